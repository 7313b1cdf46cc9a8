// RefineMode's names in scene files and on command lines, and what kAuto resolves to
// (scene/scene.h).
#include <string>

#include "octomotion/error.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

const char* refineModeName(RefineMode mode) {
  switch (mode) {
    case RefineMode::kNone:
      return "none";
    case RefineMode::kExact:
      return "exact";
    case RefineMode::kAuto:
      return "auto";
  }
  return "none";
}

RefineMode parseRefineMode(const std::string& name) {
  if (name == "none") return RefineMode::kNone;
  if (name == "exact") return RefineMode::kExact;
  if (name == "auto") return RefineMode::kAuto;
  throw InvalidArgument("refine mode '" + name + "': expected none, exact or auto");
}

RefineMode resolveRefineMode(RefineMode mode, Rounding rounding, bool world_updates) {
  if (mode != RefineMode::kAuto) return mode;
  return rounding == Rounding::kConservative && !world_updates ? RefineMode::kExact
                                                               : RefineMode::kNone;
}

}  // namespace octomotion
