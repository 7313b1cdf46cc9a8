// A CollisionBackend of the user's own: it forwards the queries to another backend and overrides
// nothing else, so the library knows neither its type nor how it names contacts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>

#include "octomotion/planner/model/collision_backend.h"

namespace octomotion::test {

struct ForwardingBackend final : CollisionBackend {
  explicit ForwardingBackend(std::shared_ptr<const CollisionBackend> b) : inner(std::move(b)) {}
  std::unique_ptr<BackendScratch> makeBackendScratch() const override {
    return inner->makeBackendScratch();
  }
  bool inCollision(const double* q, std::size_t n, const Eigen::Isometry3d& X,
                   BackendScratch& s) const override {
    return inner->inCollision(q, n, X, s);
  }
  bool environmentInCollision(const double* q, std::size_t n, const Eigen::Isometry3d& X,
                              BackendScratch& s) const override {
    return inner->environmentInCollision(q, n, X, s);
  }
  bool selfInCollision(const double* q, std::size_t n, const Eigen::Isometry3d& X,
                       BackendScratch& s) const override {
    return inner->selfInCollision(q, n, X, s);
  }
  double clearance(BackendScratch& s) const override { return inner->clearance(s); }
  ClearanceBound clearanceBound() const override { return inner->clearanceBound(); }
  const RobotModel& robot() const override { return inner->robot(); }
  std::uint64_t id() const override { return inner->id(); }
  CheckerKind kind() const override { return inner->kind(); }
  std::shared_ptr<const CollisionBackend> inner;
};

}  // namespace octomotion::test
