// The certified motion validator's counts (certified_motion_validator.h, counts, resetCounts).
#include <atomic>
#include <cstddef>

#include "internal/certified_scratch.h"

namespace octomotion {

CertifiedMotionValidator::Counts CertifiedMotionValidator::counts() const {
  auto load = [](const AtomicCounts::Edges& e) {
    EdgeCounts c;
    c.edges = e.edges.load(std::memory_order_relaxed);
    c.screen_checks = e.screen_checks.load(std::memory_order_relaxed);
    c.proof_checks = e.proof_checks.load(std::memory_order_relaxed);
    c.clearance_states = e.clearance_states.load(std::memory_order_relaxed);
    c.pair_distances = e.pair_distances.load(std::memory_order_relaxed);
    c.table_pairs = e.table_pairs.load(std::memory_order_relaxed);
    c.depth = e.depth.load(std::memory_order_relaxed);
    c.seconds = 1e-9 * static_cast<double>(e.nanoseconds.load(std::memory_order_relaxed));
    c.travel = 1e-6 * static_cast<double>(e.micrometres.load(std::memory_order_relaxed));
    return c;
  };
  Counts c;
  c.accepted = load(counts_->accepted);
  c.rejected = load(counts_->rejected);
  c.rejected_by_screen = counts_->rejected_by_screen.load(std::memory_order_relaxed);
  c.remembered_ends = counts_->remembered_ends.load(std::memory_order_relaxed);
  return c;
}

void CertifiedMotionValidator::resetCounts() const {
  state_checks_ = 0;
  self_checks_ = 0;
  for (AtomicCounts::Edges* e : {&counts_->accepted, &counts_->rejected}) {
    e->edges = 0;
    e->screen_checks = 0;
    e->proof_checks = 0;
    e->clearance_states = 0;
    e->pair_distances = 0;
    e->table_pairs = 0;
    e->depth = 0;
    e->nanoseconds = 0;
    e->micrometres = 0;
  }
  counts_->rejected_by_screen = 0;
  counts_->remembered_ends = 0;
}

}  // namespace octomotion
