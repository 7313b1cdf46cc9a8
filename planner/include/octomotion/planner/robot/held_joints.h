// Planning some of a robot's joints: every other movable joint is held at a value, which makes
// it a fixed joint of a smaller model (Pinocchio's buildReducedModel). The reduced model keeps
// the links (indices, names, collision geometry), the joints' indices and names, the
// self-collision filter and the SRDF groups; only its variables() shrink to the planned joints.
#pragma once

#include <vector>

#include "octomotion/error.h"
#include "octomotion/planner/robot/robot_model.h"

namespace octomotion {

// `planned_variables`: indices into robot.variables() to keep, in any order; `values`: one per
// variable of `robot` (the entries of planned ones are ignored), the value each held joint keeps.
// A held joint's motion at its value is folded into its X_PJ; a mimic joint whose master is held
// is held at multiplier * value + offset, one whose master is planned stays a mimic joint.
// A held value outside the joint's limits is allowed (MotionBenchMaker holds the Panda's fingers
// beyond theirs) with a warning through `warnings`. Throws InvalidArgument for an index out of
// range or given twice, a wrong number of values or a non-finite one.
RobotModel holdJoints(const RobotModel& robot, const std::vector<int>& planned_variables,
                      const std::vector<double>& values, const WarningSink& warnings = {});

// The configuration of `full` (the model holdJoints reduced) that `q` (one value per variable of
// `reduced`) stands for: planned values from q, held ones from reduced.heldJoints(). Throws
// InvalidArgument when `reduced` is not a reduction of `full` or q has the wrong size.
std::vector<double> expandConfiguration(const RobotModel& full, const RobotModel& reduced,
                                        const std::vector<double>& q);

}  // namespace octomotion
