// RefineMode::kExact (internal/refine.h): the octree certifies freedom, FCL decides the links and
// pairs whose voxels meet.
#include "internal/refine.h"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>

#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/distance.h>

#include "internal/collision_model_parts.h"
#include "octomotion/error.h"

namespace octomotion {

RefineScratchHolder::RefineScratchHolder() noexcept = default;
RefineScratchHolder::RefineScratchHolder(const RefineScratchHolder&) {}
RefineScratchHolder::RefineScratchHolder(RefineScratchHolder&&) noexcept = default;
RefineScratchHolder& RefineScratchHolder::operator=(const RefineScratchHolder& other) {
  if (this != &other) scratch_.reset();
  return *this;
}
RefineScratchHolder& RefineScratchHolder::operator=(RefineScratchHolder&&) noexcept = default;
RefineScratchHolder::~RefineScratchHolder() = default;
void RefineScratchHolder::reset(std::unique_ptr<detail::RefineScratch> scratch) {
  scratch_ = std::move(scratch);
}

namespace detail {

namespace {

void extend(fcl::AABBd& box, const fcl::AABBd& other, bool first) {
  if (first) {
    box = other;
  } else {
    box += other;
  }
}

}  // namespace

RefineData::RefineData(const RobotModel& model, const EnvironmentGeometry& environment,
                       const WorldGrid& grid, const CollisionModelOptions& options)
    : robot(std::make_unique<const fcl_internal::RobotGeometry>(
          model, options.keep_mesh_root_transform, options.center_mesh_vertices)),
      link_elements(static_cast<std::size_t>(model.linkCount())) {
  for (std::size_t e = 0; e < robot->elementCount(); ++e) {
    link_elements[static_cast<std::size_t>(robot->elementLink(e))].push_back(e);
  }
  for (std::size_t i = 0; i < environment.size(); ++i) {
    const EnvironmentGeometry::Item& item = environment.items()[i];
    RefineObject object;
    auto add = [&](const fcl_internal::Geom& g, const Eigen::Isometry3d& X_WO) {
      object.shapes.emplace_back(g, X_WO.rotation(), X_WO.translation());
      fcl_internal::setTightAabb(object.shapes.back());
    };
    if (item.spec.kind == EnvironmentObject::Kind::kPrimitive) {
      add(fcl_internal::shapeOf(item.spec.primitive), item.spec.X_WO);
    } else if (item.spec.kind == EnvironmentObject::Kind::kMesh) {
      add(fcl_internal::meshOf(item.mesh), item.spec.X_WO);
    } else {
      // Point clouds and OctoMaps are voxels by definition: their exact geometry is their black
      // voxels on the model's grid, as the environment tree holds them.
      environment.voxelizeObject(i, grid, options.rounding).forEachBlackLeaf([&](const Cube& c) {
        const Eigen::Vector3d lo = grid.cubeMin(c), hi = grid.cubeMax(c);
        const Eigen::Vector3d size = hi - lo;
        add(std::make_shared<fcl::Boxd>(size.x(), size.y(), size.z()),
            Eigen::Isometry3d(Eigen::Translation3d((lo + hi) / 2)));
      });
    }
    for (std::size_t k = 0; k < object.shapes.size(); ++k) {
      extend(object.box_W, object.shapes[k].getAABB(), k == 0);
    }
    objects.push_back(std::move(object));
  }
}

fcl_internal::RobotScratch& posedRefineScratch(const RefineData& data, const RobotModel& model,
                                               std::uint64_t owner, const RobotData& robot,
                                               RefineScratchHolder& h) {
  if (h.get() == nullptr || h.get()->owner != owner) {
    auto scratch = std::make_unique<RefineScratch>();
    scratch->owner = owner;
    data.robot->initScratch(model, scratch->fcl);
    h.reset(std::move(scratch));
  }
  fcl_internal::RobotScratch& s = h.get()->fcl;
  data.robot->poseElements(robot, s);
  return s;
}

bool refineLinkHits(const RefineData& data, fcl_internal::RobotScratch& s, int link) {
  for (std::size_t e : data.link_elements[static_cast<std::size_t>(link)]) {
    const fcl::CollisionObjectd& element = s.objects[e];
    for (const RefineObject& object : data.objects) {
      if (object.shapes.empty() || !object.box_W.overlap(element.getAABB())) continue;
      for (const fcl::CollisionObjectd& shape : object.shapes) {
        if (fcl_internal::collidePair(element, shape, s.request, s.result)) return true;
      }
    }
  }
  return false;
}

bool refinePairHits(const RefineData& data, fcl_internal::RobotScratch& s, int link_a, int link_b) {
  for (std::size_t a : data.link_elements[static_cast<std::size_t>(link_a)]) {
    for (std::size_t b : data.link_elements[static_cast<std::size_t>(link_b)]) {
      if (fcl_internal::collidePair(s.objects[a], s.objects[b], s.request, s.result)) return true;
    }
  }
  return false;
}

double refineEnvironmentDistance(const RefineData& data, fcl_internal::RobotScratch& s) {
  double best = std::numeric_limits<double>::infinity();
  fcl::DistanceRequestd request;
  fcl::DistanceResultd result;
  for (const fcl::CollisionObjectd& element : s.objects) {
    for (const RefineObject& object : data.objects) {
      if (object.shapes.empty() || object.box_W.distance(element.getAABB()) >= best) continue;
      for (const fcl::CollisionObjectd& shape : object.shapes) {
        if (shape.getAABB().distance(element.getAABB()) >= best) continue;
        result.clear();
        fcl::distance(&element, &shape, request, result);
        best = std::min(best, std::max(0.0, result.min_distance));
        if (best <= 0) return 0;
      }
    }
  }
  return best;
}

}  // namespace detail

bool OctreeCollisionModel::refinedEnvironmentInCollision(CheckerPath path,
                                                         CheckScratch& scratch) const {
  const detail::EnvironmentModel& environment = parts_->environment;
  const detail::LinkModels& links = parts_->links;
  fcl_internal::RobotScratch* exact = nullptr;  // posed on the first link the octree cannot clear
  for (const detail::EnvironmentLinkTest& t : links.environment_tests) {
    const Eigen::Isometry3d& X_WL = scratch.robot.linkPose(t.link);
    if (detail::sphereMeetsBox(t, X_WL, environment.box_W) &&
        environment.linkHits(t, links.links[t.slot].voxels, X_WL, path, scratch.fused)) {
      if (exact == nullptr) {
        exact = &detail::posedRefineScratch(*refine_, robot_, id_, scratch.robot, scratch.refine);
      }
      if (detail::refineLinkHits(*refine_, *exact, t.link)) return true;
    }
  }
  return false;
}

bool OctreeCollisionModel::refinedSelfInCollision(CheckerPath path, CheckScratch& scratch) const {
  const detail::LinkModels& links = parts_->links;
  fcl_internal::RobotScratch* exact = nullptr;
  return parts_->self.confirmedInCollision(links, path, scratch, [&](const detail::SelfPair& p) {
    if (exact == nullptr) {
      exact = &detail::posedRefineScratch(*refine_, robot_, id_, scratch.robot, scratch.refine);
    }
    return detail::refinePairHits(*refine_, *exact, links.links[p.a].link, links.links[p.b].link);
  });
}

double OctreeCollisionModel::refinedClearance(const CheckScratch& scratch, double margin) const {
  const double bound = options_.clearance == ClearanceMethod::kPointOctree
                           ? clearanceLowerBoundPoints(scratch)
                           : clearanceLowerBoundTree(scratch);
  if (!refine_ || bound >= margin) return bound;
  return detail::refineEnvironmentDistance(
      *refine_, detail::posedRefineScratch(*refine_, robot_, id_, scratch.robot, scratch.refine));
}

}  // namespace octomotion
