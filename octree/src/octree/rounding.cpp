#include "octomotion/octree/rounding.h"

#include <cstring>
#include <string>

#include "octomotion/error.h"

namespace octomotion {

const char* toString(Rounding r) {
  return r == Rounding::kCenter ? "center" : "conservative";
}

Rounding roundingFromString(const char* name) {
  if (std::strcmp(name, "conservative") == 0) return Rounding::kConservative;
  if (std::strcmp(name, "center") == 0 || std::strcmp(name, "centre") == 0) {
    return Rounding::kCenter;
  }
  throw InvalidArgument(std::string("rounding: expected 'conservative' or 'center', got '") + name +
                        "'");
}

}  // namespace octomotion
