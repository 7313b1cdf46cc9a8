// Kept for existing includes: the state-space glue is in ompl/state_space.h, the checkers
// (OctreeValidityChecker among them) in ompl/validity_checker.h.
#pragma once

#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/ompl/validity_checker.h"
