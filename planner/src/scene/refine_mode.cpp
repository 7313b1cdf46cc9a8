// RefineMode's names in scene files and on command lines (scene/scene.h).
#include <string>

#include "octomotion/error.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

const char* refineModeName(RefineMode mode) {
  return mode == RefineMode::kExact ? "exact" : "none";
}

RefineMode parseRefineMode(const std::string& name) {
  if (name == "none") return RefineMode::kNone;
  if (name == "exact") return RefineMode::kExact;
  throw InvalidArgument("refine mode '" + name + "': expected none or exact");
}

}  // namespace octomotion
