// Viewing a scene: exports the collision model's octrees, the robot's collision meshes and a
// path to one glTF binary (.glb) file through assimp, for viewer/ (three.js) or any glTF viewer.
//
// File layout (node names are what viewer/ relies on; units are metres):
//   octomotion            root; rotates the robot's Z-up world W into glTF's Y-up
//     environment_voxels  the environment tree's black leaves as boxes (voxels_environment)
//     link_voxels         the modelled links' trees at the chosen state (movedLinkTree)
//       voxels_<link>
//     robot
//       link_<link>       pose X_WL at the chosen state; the link's collision meshes, in L
//   animation "path"      one key per path state (state i at time i seconds) for every
//                         link_<link> node: translation + rotation, linear (slerp)
// Voxel boxes carry no normals (glTF viewers then shade flat); materials are coloured per tree.
#pragma once

#include <array>
#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/planner/model/collision_model.h"

namespace octomotion {

// One configuration of the robot: joint values q (fixed base: the base stays at the model's
// mount) or, for a free-flying robot, the base pose X_WB (q empty).
struct RobotState {
  std::vector<double> q;
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
};

// Reads a path in OMPL's format, as writePath (planning_scene.h) writes it: one state per line,
// "x y z qx qy qz qw" for free-flying robots, the joint values in variables() order otherwise.
// Blank lines and lines starting with '#' are skipped. Throws FileError naming `source_name`
// and the line for a wrong number of values, a non-number, a non-finite value or a zero
// quaternion (quaternions are normalised), and for a path without states.
std::vector<RobotState> readPath(const RobotModel& robot, std::istream& in,
                                 const std::string& source_name);
std::vector<RobotState> readPathFile(const RobotModel& robot, const std::string& path);

// The world poses of every link at a state (fixed-base robots use model.baseMount()).
std::vector<Eigen::Isometry3d, Eigen::aligned_allocator<Eigen::Isometry3d>> linkPoses(
    const OctreeCollisionModel& model, const RobotState& state);

// A link's source tree moved to pose X_WL onto the model's voxel lattice (the same voxel size,
// the origin shifted by whole voxels) but on a universe fitted to the moved link, so that all of
// it is drawn: moveTree onto model.grid() drops what lies outside the model's universe (where
// the checker models no environment). Inside that universe both trees have the same black
// voxels. `outside_universe` tells whether part of the link is outside it.
Octree movedLinkTree(const OctreeCollisionModel& model, const Octree& source,
                     const Eigen::Isometry3d& X_WL, bool* outside_universe = nullptr);

struct GltfExportOptions {
  // The state whose link poses and moved link trees are written (the animation covers all).
  std::size_t state_index = 0;
  // At most this many boxes per tree: a tree with more black leaves is drawn coarsened, every
  // cube of the coarsest level L that keeps the count under the cap drawn whole when it holds
  // any black voxel (a conservative outline; the report says which level was used).
  std::size_t max_boxes_per_tree = 150000;
  bool link_trees = true;  // export the moved link trees
  // How the robot's mesh files are read (SceneSpec::robot's conventions).
  bool keep_mesh_root_transform = false;
  bool center_mesh_vertices = false;
};

// Colours (linear RGBA) of the trees and the robot, also documented in docs/viewer.md.
inline constexpr std::array<float, 4> kEnvironmentColor{0.20f, 0.45f, 0.90f, 1.0f};  // blue
inline constexpr std::array<float, 4> kRobotColor{1.00f, 0.45f, 0.05f, 1.0f};        // orange
// Link trees cycle through these (translucent, so the robot inside them stays visible).
inline constexpr std::array<std::array<float, 4>, 4> kLinkTreeColors{{
    {0.15f, 0.80f, 0.25f, 0.35f},  // green
    {0.80f, 0.20f, 0.75f, 0.35f},  // magenta
    {0.10f, 0.75f, 0.80f, 0.35f},  // cyan
    {0.85f, 0.80f, 0.10f, 0.35f},  // yellow
}};

struct GltfTreeReport {
  std::string name;  // "environment" or the link's name
  std::size_t black_leaves = 0;
  std::size_t boxes = 0;          // written
  int drawn_level = 0;            // 0: every leaf exactly; L > 0: coarsened to cubes of 2^L voxels
  bool outside_universe = false;  // a link tree reaching out of the model's universe
};

struct GltfExportReport {
  std::vector<GltfTreeReport> trees;
  std::size_t link_meshes = 0;  // links with collision meshes written
  std::size_t path_states = 0;
  std::size_t state_index = 0;
  std::string toString() const;
};

// Writes the .glb. Throws InvalidArgument for an empty path, a state index out of range or a
// state of the wrong size; FileError naming `glb_path` when assimp cannot write it.
GltfExportReport exportGlb(const OctreeCollisionModel& model, const std::vector<RobotState>& path,
                           const GltfExportOptions& options, const std::string& glb_path);

}  // namespace octomotion
