// The OMPL plugin: a StateValidityChecker over any CollisionBackend (model/collision_backend.h).
// A thin layer in the manner of OMPL's VAMP checker: the backend is constant and shared, every
// thread gets its own scratch, and isValid never throws (a NaN or out-of-bounds state is simply
// invalid).
//
// ValidityChecker<Backend> is instantiated over the concrete (final) backends, so a check calls
// the backend without a virtual call; ValidityChecker<CollisionBackend> takes any backend, for
// code that does not know which one it has. makeValidityChecker picks the concrete one. The
// named checkers below are those instantiations with the constructors and accessors their users
// know.
#pragma once

#include <cstdint>
#include <exception>
#include <memory>
#include <type_traits>
#include <vector>

#include <ompl/base/StateValidityChecker.h>
#include <Eigen/Geometry>

#include "octomotion/error.h"
#include "octomotion/planner/model/collision_backend.h"
#include "octomotion/planner/model/collision_model.h"
#include "octomotion/planner/model/octree_backend.h"
#include "octomotion/planner/ompl/state_space.h"
#include "octomotion/planner/reference/fcl_collision_model.h"
#include "octomotion/planner/reference/fcl_octomap_collision_model.h"

namespace octomotion {

template <class Backend>
class ValidityChecker : public ompl::base::StateValidityChecker {
  static_assert(std::is_base_of_v<CollisionBackend, Backend>, "Backend must be a CollisionBackend");

 public:
  // Throws InvalidArgument for a null backend.
  ValidityChecker(const ompl::base::SpaceInformationPtr& si, std::shared_ptr<const Backend> backend)
      : ompl::base::StateValidityChecker(si), backend_(std::move(backend)), in_bounds_(si) {
    if (!backend_) throw InvalidArgument("ValidityChecker: no collision backend");
    switch (backend_->clearanceBound()) {
      case ClearanceBound::kNone:
        break;
      case ClearanceBound::kLowerBound:
        specs_.clearanceComputationType =
            ompl::base::StateValidityCheckerSpecs::BOUNDED_APPROXIMATE;
        break;
      case ClearanceBound::kExact:
        specs_.clearanceComputationType = ompl::base::StateValidityCheckerSpecs::EXACT;
        break;
    }
  }

  // Invalid when outside the space's bounds, non-finite, or in collision (environment or
  // self-collision between checked pairs). Const and thread-safe.
  bool isValid(const ompl::base::State* state) const override {
    try {
      return check(state) != nullptr;
    } catch (const std::exception&) {
      return false;  // never throw into OMPL: an unusable state is an invalid one
    }
  }
  // The backend's clearance (ClearanceBound) at a valid state; 0 when invalid.
  double clearance(const ompl::base::State* state) const override {
    if (backend_->clearanceBound() == ClearanceBound::kNone) return 0.0;
    try {
      BackendScratch* scratch = check(state);
      return scratch ? backend_->clearance(*scratch) : 0.0;
    } catch (const std::exception&) {
      return 0.0;
    }
  }

  const Backend& backend() const { return *backend_; }
  const std::shared_ptr<const Backend>& sharedBackend() const { return backend_; }

 private:
  // Per thread, rebuilt only when the thread switches to another backend (by id: addresses may
  // be reused).
  struct ThreadScratch {
    std::uint64_t owner = 0;
    std::unique_ptr<BackendScratch> backend;
    std::vector<double> q;
    Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  };
  static ThreadScratch& threadScratch(const Backend& backend) {
    thread_local ThreadScratch scratch;
    if (scratch.owner != backend.id()) {
      scratch.backend = backend.makeBackendScratch();
      scratch.q.assign(static_cast<std::size_t>(backend.robot().variableCount()), 0.0);
      scratch.owner = backend.id();
    }
    return scratch;
  }
  // Bounds, finiteness and the backend's check in this thread's scratch: the scratch (posed at
  // the state) when valid, else null.
  BackendScratch* check(const ompl::base::State* state) const {
    if (!in_bounds_(state)) return nullptr;
    const Backend& backend = *backend_;
    ThreadScratch& t = threadScratch(backend);
    if (!stateToConfiguration(backend.robot(), state, t.q, t.X_WB)) return nullptr;
    if (backend.inCollision(t.q.data(), t.q.size(), t.X_WB, *t.backend)) return nullptr;
    return t.backend.get();
  }

  std::shared_ptr<const Backend> backend_;
  BoundsCheck in_bounds_;
};

// Compiled once, in the library.
extern template class ValidityChecker<CollisionBackend>;
extern template class ValidityChecker<OctreeBackend>;
extern template class ValidityChecker<FclCollisionModel>;
extern template class ValidityChecker<FclOctomapCollisionModel>;

// The octree model on one query path; clearance is OctreeCollisionModel::clearanceLowerBound.
class OctreeValidityChecker final : public ValidityChecker<OctreeBackend> {
 public:
  OctreeValidityChecker(const ompl::base::SpaceInformationPtr& si,
                        std::shared_ptr<const OctreeCollisionModel> model, CheckerPath path)
      : ValidityChecker(si, std::make_shared<const OctreeBackend>(std::move(model), path)) {}
  OctreeValidityChecker(const ompl::base::SpaceInformationPtr& si,
                        std::shared_ptr<const OctreeBackend> backend)
      : ValidityChecker(si, std::move(backend)) {}

  const OctreeCollisionModel& model() const { return backend().model(); }
  CheckerPath path() const { return backend().path(); }
};

// The exact FCL reference; clearance is the exact distance to the environment.
class FclValidityChecker final : public ValidityChecker<FclCollisionModel> {
 public:
  using ValidityChecker::ValidityChecker;
  const FclCollisionModel& model() const { return backend(); }
};

// FCL on an OctoMap of the environment; no clearance.
class FclOctomapValidityChecker final : public ValidityChecker<FclOctomapCollisionModel> {
 public:
  using ValidityChecker::ValidityChecker;
  const FclOctomapCollisionModel& model() const { return backend(); }
};

// The checker of the backend's concrete type (one of the named checkers above), or
// ValidityChecker<CollisionBackend> for any other backend. Throws InvalidArgument for null.
ompl::base::StateValidityCheckerPtr makeValidityChecker(
    const ompl::base::SpaceInformationPtr& si,
    const std::shared_ptr<const CollisionBackend>& backend);

}  // namespace octomotion
