#include "internal/environment_boxes.h"

#include <algorithm>
#include <cmath>
#include <variant>

#include "octomotion/motion/pose.h"
#include "octomotion/octree/shapes.h"

namespace octomotion::detail {

namespace {

// Every entry 0 or ±1: the rotation only permutes and flips the axes, so boxes along them are
// exactly axis-aligned in the world.
bool isAxisPermutation(const Eigen::Matrix3d& R) {
  return (R.array() == 0 || R.array().abs() == 1).all();
}

bool isPrimitive(const EnvironmentGeometry::Item& item) {
  return item.spec.kind == EnvironmentObject::Kind::kPrimitive;
}

}  // namespace

Eigen::AlignedBox3d blackBox(const Octree& tree) {
  const WorldGrid& grid = tree.grid();
  const auto b = tree.bounds();
  return b ? Eigen::AlignedBox3d(grid.cubeMin(Cube{0, b->min}), grid.cubeMax(Cube{0, b->max}))
           : Eigen::AlignedBox3d();
}

// Object boxes for the environment pre-test: every voxel an object marks (any rounding, any
// kind) overlaps the object's box, so it lies within one voxel of it. With exact primitives a
// link leaf's bounding sphere that meets the object reaches past the link's box by less than a
// link voxel: the boxes grow by the larger of the two voxels and keep the parts outside the
// universe.
void buildObjectBoxes(EnvironmentModel& environment_, const EnvironmentGeometry& scene_,
                      const WorldGrid& grid_, double link_res_, bool exact_) {
  const double growth = exact_ ? std::max(grid_.voxelSize(), link_res_) : grid_.voxelSize();
  const Eigen::Vector3d one_voxel = Eigen::Vector3d::Constant(growth * (1 + 1e-9));
  const Eigen::AlignedBox3d universe_W(grid_.origin(), grid_.origin().array() + grid_.sideMetres());
  for (const EnvironmentGeometry::Item& item : scene_.items()) {
    if (item.bounds_W.isEmpty()) continue;
    const Eigen::AlignedBox3d box(item.bounds_W.min() - one_voxel, item.bounds_W.max() + one_voxel);
    if (!exact_ && box.intersection(universe_W).isEmpty()) continue;
    environment_.object_boxes_W.push_back(box);
    ObjectFrameBox frame_box;
    const Eigen::Matrix3d& R_WO = item.spec.X_WO.linear();
    if (isPrimitive(item) && !std::holds_alternative<Sphere>(item.spec.primitive) &&
        !isAxisPermutation(R_WO)) {
      frame_box.tilted = true;
      frame_box.centre_W = item.spec.X_WO.translation();
      frame_box.R_OW = R_WO.transpose();
      frame_box.half =
          boxHalfSides(item.spec.primitive) + Eigen::Vector3d::Constant(std::sqrt(3.0) * growth);
    }
    environment_.object_frame_boxes.push_back(frame_box);
  }
}

// kAuto picks the object boxes for 2 ... kObjectBoxesMaxObjects objects; the environment box
// drops them. The kept boxes' per-axis arrays are precomputed for the pre-test's first stage.
EnvironmentPreTest resolveEnvironmentPreTest(EnvironmentModel& environment_,
                                             EnvironmentPreTest option, const WorldGrid& grid_) {
  EnvironmentPreTest resolved = EnvironmentPreTest::kEnvironmentBox;
  std::vector<Eigen::AlignedBox3d>& boxes = environment_.object_boxes_W;
  switch (option) {
    case EnvironmentPreTest::kAuto:
      resolved = boxes.size() >= 2 && boxes.size() <= kObjectBoxesMaxObjects
                     ? EnvironmentPreTest::kObjectBoxes
                     : EnvironmentPreTest::kEnvironmentBox;
      break;
    default:
      resolved = option;
  }
  if (resolved != EnvironmentPreTest::kObjectBoxes) {
    boxes.clear();
    environment_.object_frame_boxes.clear();
  }
  const double tie_margin = kMotionTieTolerance * grid_.voxelSize();
  for (const Eigen::AlignedBox3d& box : boxes) {
    for (std::size_t a = 0; a < 3; ++a) {
      const auto axis = static_cast<Eigen::Index>(a);
      environment_.object_centre_W[a].push_back(0.5 * (box.min()[axis] + box.max()[axis]));
      environment_.object_reach_W[a].push_back(0.5 * (box.max()[axis] - box.min()[axis]) +
                                               tie_margin);
    }
  }
  return resolved;
}

// Solid boxes for the links' core boxes (conservative rounding): each primitive's inscribed
// box, its part inside the universe (a moved link voxel outside it is dropped), shrunk like the
// cores.
void buildSolidBoxes(EnvironmentModel& environment_, const EnvironmentGeometry& scene_,
                     const WorldGrid& grid_, const CollisionModelOptions& options_,
                     double link_res_) {
  if (!options_.core_boxes || options_.rounding != Rounding::kConservative) return;
  const double shrink = kSolidShrink * std::max(options_.resolution, link_res_);
  const Eigen::AlignedBox3d inner_universe_W(grid_.origin().array() + shrink,
                                             grid_.origin().array() + grid_.sideMetres() - shrink);
  for (const EnvironmentGeometry::Item& item : scene_.items()) {
    if (!isPrimitive(item)) continue;
    const Eigen::Vector3d half_O = inscribedBoxHalfSides(item.spec.primitive);
    const Eigen::Matrix3d& R_WO = item.spec.X_WO.linear();
    const Eigen::Vector3d extent_W = R_WO.cwiseAbs() * half_O;
    const Eigen::AlignedBox3d aabb_W(item.spec.X_WO.translation() - extent_W,
                                     item.spec.X_WO.translation() + extent_W);
    SolidBox solid;
    if (inner_universe_W.contains(aabb_W)) {
      solid.centre_W = item.spec.X_WO.translation();
      solid.R_OW = R_WO.transpose();
      solid.half = half_O - Eigen::Vector3d::Constant(shrink);
      solid.extent_W = extent_W;
    } else if (isAxisPermutation(R_WO)) {
      // Exactly axis-aligned (a box crossing the universe's side, e.g. a floor beyond the
      // robot's reach): the part inside the universe, which is its own world box.
      const Eigen::AlignedBox3d inside = aabb_W.intersection(inner_universe_W);
      if (inside.isEmpty()) continue;
      solid.centre_W = inside.center();
      solid.R_OW = Eigen::Matrix3d::Identity();
      solid.half = inside.sizes() / 2 - Eigen::Vector3d::Constant(shrink);
      solid.extent_W = inside.sizes() / 2;
    } else {
      continue;  // rotated and leaving the universe
    }
    if (!(solid.half.array() > 0).all()) continue;
    environment_.solid_boxes_W.push_back(solid);
  }
}

}  // namespace octomotion::detail
