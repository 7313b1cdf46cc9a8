// problem.range: the planner's extension range (planning_scene.h, setPlannerRange).
#include <cmath>
#include <sstream>
#include <string>

#include <ompl/base/Planner.h>

#include "octomotion/error.h"
#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion {

void setPlannerRange(ompl::base::Planner& planner, std::optional<double> range) {
  if (!range) return;
  if (!(*range > 0) || !std::isfinite(*range)) {
    throw InvalidArgument("the planner's range must be positive and finite");
  }
  if (!planner.params().hasParam("range")) {
    throw InvalidArgument("planner " + planner.getName() +
                          " has no range (it does not extend by steps); leave the range out");
  }
  std::ostringstream value;
  value.precision(17);
  value << *range;
  if (!planner.params().setParam("range", value.str())) {
    throw InvalidArgument("planner " + planner.getName() + " refused the range " + value.str());
  }
}

}  // namespace octomotion
