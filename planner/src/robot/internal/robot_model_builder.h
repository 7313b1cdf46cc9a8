// Internal: assembles a RobotModel from links and joints already in depth-first order.
#pragma once

#include <string>
#include <vector>

#include "octomotion/planner/robot/robot_model.h"

namespace octomotion {

class RobotModelBuilder {
 public:
  // `links` and `joints` follow the conventions of robot_model.h (link 0 is the root, joint j is
  // the parent joint of link j + 1, mimic masters resolved to non-mimic joints).
  static RobotModel build(std::string name, std::string source, BaseMotion base,
                          std::vector<Link> links, std::vector<Joint> joints) {
    RobotModel model;
    model.name_ = std::move(name);
    model.source_ = std::move(source);
    model.base_ = base;
    model.links_ = std::move(links);
    model.joints_ = std::move(joints);
    model.finalize();
    return model;
  }

  // What holdJoints keeps of the model it reduces: the self-collision filter (finalize reset it to
  // the adjacent pairs), the SRDF groups; and the joints it holds.
  static void keepSemantics(const RobotModel& from, RobotModel& to, std::vector<HeldJoint> held) {
    to.disabled_ = from.disabled_;
    to.rebuildCheckedPairs();
    to.groups_ = from.groups_;
    to.group_states_ = from.group_states_;
    to.held_ = std::move(held);
  }
};

}  // namespace octomotion
