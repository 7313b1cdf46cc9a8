// Private to the planner library: classifies the joint space of one self-collision pair with
// FCL on the exact geometry (docs/planner.md, "Self-pair tables").
#pragma once

#include <optional>
#include <vector>

#include "octomotion/octree/mesh.h"
#include "octomotion/octree/octree.h"
#include "octomotion/planner/model/joint_space_table.h"
#include "octomotion/planner/robot/robot_model.h"

namespace octomotion::detail {

// One link of the pair: its collision elements' meshes (nullptr for a primitive element), its
// conservative source tree (an inside/outside oracle: a point in a white voxel is outside the
// link's solid) and how far its geometry reaches from its frame origin (exact, no voxel margin).
struct SelfPairLink {
  int link = -1;
  std::vector<const TriangleMesh*> element_mesh;
  const Octree* oracle = nullptr;
  double reach = 0;
};

struct SelfPairTableOptions {
  // Largest motion of one link relative to the other within a finest cell: the width of the
  // band around contact that the table leaves to the octree test.
  double tolerance = 5e-4;
  std::size_t max_cells = 60000;  // FCL classifications per pair
};

// The variables (indices into q) a pair's table spans: those the relative pose of links a and b
// depends on, less one whose joint only turns a or b about an axis its solid is symmetric about
// (spheres and cylinders on the axis).
std::vector<int> pairVariables(const RobotModel& robot, int link_a, int link_b);

// Every variable at the middle of its limits (continuous ones at 0): the configuration whose
// other variables a pair's table and sampling hold fixed (they do not move the pair).
std::vector<double> middleConfiguration(const RobotModel& robot);

// A table for the pair when its relative pose depends on 1 ... JointSpaceTable::kMaxDims
// variables; nullopt otherwise. A cell is kFree when FCL's distance at its centre exceeds the
// cell's motion bound (and neither link is inside the other), kColliding when a point of one link
// lies deeper inside the other than that bound.
std::optional<JointSpaceTable> buildSelfPairTable(const RobotModel& robot, const SelfPairLink& a,
                                                  const SelfPairLink& b,
                                                  const SelfPairTableOptions& options);

}  // namespace octomotion::detail
