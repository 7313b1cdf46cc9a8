// The certified motion validator's per-state values (internal/certified_scratch.h): the posed
// rates, computed per evaluated state for the links and pairs its interval's halves will test
// (those not proven over the interval are all that its descendants test); the nearest
// obstacles' slabs and the parts of an interval they prove; the remembered ends' places.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "internal/certified_scratch.h"

namespace octomotion {

void CertifiedMotionValidator::Scratch::setRates(const LinkMotionBound& bound,
                                                 const RobotData* posed, std::size_t slot,
                                                 std::size_t stride, const Interval* in) {
  const std::size_t pairs = bound.pairs().size();
  double* links = link_rate.data() + slot * stride;
  double* pair_values = pair_rate.data() + slot * pairs;
  double* link_speeds = link_speed.data() + slot * stride;
  double* pair_speeds = pair_speed.data() + slot * pairs;
  // An end's arms are every link's (remembered with the end).
  if (posed && !in) bound.posedArms(*posed, arms.data());
  armed.assign(stride, posed && in ? 0 : 1);
  auto arm = [&](int link) {
    if (armed[static_cast<std::size_t>(link)]) return;
    bound.posedArms(*posed, link, arms.data());
    armed[static_cast<std::size_t>(link)] = 1;
  };
  // A link's speed sums, made once per state for the link and every pair it is in.
  speed_sums.resize(arms.size() / LinkMotionBound::kArmValues * LinkMotionBound::kSumValues);
  summed.assign(stride, 0);
  auto sum = [&](int link) {
    if (summed[static_cast<std::size_t>(link)]) return;
    arm(link);
    bound.speedSums(link, terms, arms.data(), speed_sums.data());
    summed[static_cast<std::size_t>(link)] = 1;
  };
  const std::uint64_t links_done = in ? in->links_done : 0;
  const std::uint64_t pairs_done = in ? in->pairs_done : 0;
  for (std::size_t k = 0; k < active_links.size(); ++k) {
    if (k < 64 && (links_done >> k & 1)) continue;
    const int l = static_cast<int>(active_links[k]);
    sum(l);
    links[l] = bound.linkRate(l, terms, arms.data());
    link_speeds[l] = bound.linkSpeedFromSums(l, speed_sums.data());
  }
  for (std::size_t k = 0; k < active_pairs.size(); ++k) {
    if (k < 64 && (pairs_done >> k & 1)) continue;
    const std::size_t p = active_pairs[k];
    sum(bound.pairs()[p].first);
    sum(bound.pairs()[p].second);
    pair_values[p] = bound.pairRate(p, terms, arms.data());
    pair_speeds[p] = bound.pairSpeedFromSums(p, speed_sums.data());
  }
}

// A slot's kNear values per link: gap[k], then others, then toward_W[k] (3 each), then per
// slab its approach rate forwards and backwards.
void CertifiedMotionValidator::Scratch::setSlabs(const LinkMotionBound& bound, std::size_t slot,
                                                 std::size_t stride, const Interval* in) {
  const std::uint64_t links_done = in ? in->links_done : 0;
  for (std::size_t k = 0; k < active_links.size(); ++k) {
    if (k < 64 && (links_done >> k & 1)) continue;
    const std::size_t l = active_links[k];
    const NearestObstacle& o = nearest[l];
    double* v = link_near.data() + (slot * stride + l) * kNear;
    for (std::size_t j = 0; j < kSlabs; ++j) {
      v[j] = o.valid(j) ? o.gap[j] : std::numeric_limits<double>::quiet_NaN();
      if (!o.valid(j)) continue;
      std::copy_n(o.toward_W[j].data(), 3, v + kSlabs + 1 + 3 * j);
      double* rates = v + kNearKept + 2 * j;
      bound.linkApproach(static_cast<int>(l), speed_sums.data(), o.toward_W[j], rates[0], rates[1]);
    }
    v[kSlabs] = o.others;
  }
}

void CertifiedMotionValidator::Scratch::keepSlabs(Remembered& r, std::size_t slot,
                                                  std::size_t stride) const {
  r.near.clear();
  if (!slabs) return;
  for (std::size_t l = 0; l < stride; ++l) {
    const double* v = link_near.data() + (slot * stride + l) * kNear;
    r.near.insert(r.near.end(), v, v + kNearKept);
  }
}

void CertifiedMotionValidator::Scratch::restoreSlabs(const LinkMotionBound& bound,
                                                     const Remembered& r, std::size_t slot,
                                                     std::size_t stride) {
  if (r.near.size() < kNearKept * stride) return;  // kept without slabs: the slot keeps none
  for (std::size_t l : active_links) {
    const double* v = r.near.data() + kNearKept * l;
    NearestObstacle& o = nearest[l];
    for (std::size_t j = 0; j < kSlabs; ++j) {
      o.gap[j] = v[j];
      o.toward_W[j] = Eigen::Map<const Eigen::Vector3d>(v + kSlabs + 1 + 3 * j);
    }
    o.others = v[kSlabs];
  }
  setSlabs(bound, slot, stride, nullptr);
}

CertifiedMotionValidator::Scratch::Remembered& CertifiedMotionValidator::Scratch::rememberedPlace(
    bool at_start, bool free_flying) {
  const std::vector<double>& end = at_start ? q1 : q2;
  key.assign(end.begin(), end.end());
  if (free_flying) {
    const double* X = (at_start ? X_WB1 : X_WB2).matrix().data();
    key.insert(key.end(), X, X + 12);
  }
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a over the values' bytes
  for (double v : key) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    hash = (hash ^ bits) * 1099511628211ull;
  }
  return remembered[(hash ^ (hash >> 29)) % kRemembered];
}

namespace {

// The longest part s from a posed end over which an advance of at most rate * s + growth * s^2
// / 2 (growth >= 0; the rate may be negative: moving away) stays below d.
double partBelow(double rate, double growth, double d) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!(d > 0) || !(rate < kInfinity)) return 0.0;
  if (d == kInfinity) return kInfinity;
  const double root = std::sqrt(rate * rate + 2 * growth * d);
  if (rate >= 0) return rate + root > 0 ? 2 * d / (rate + root) : kInfinity;
  return growth > 0 ? (root - rate) / growth : kInfinity;
}

}  // namespace

double CertifiedMotionValidator::Scratch::stretch(std::size_t i, std::size_t slot, bool forwards,
                                                  double clear, std::size_t stride) const {
  const double rate = link_rate[slot * stride + i];
  const double speed = link_speed[slot * stride + i];
  const double growth = terms.link_growth[i];
  const double speed_growth = terms.link_speed_growth[i];
  // No point travels as far as d: the posed bounds (Scratch::posedBound) from this end alone.
  auto travelBelow = [&](double d) {
    return std::max(partBelow(rate, growth, d), partBelow(speed, speed_growth, d));
  };
  const double plain = travelBelow(clear);
  if (!slabs) return plain;
  const double* v = link_near.data() + (slot * stride + i) * kNear;
  if (!(v[0] > 0)) return plain;
  // Per slab, the link's points advance along its direction at most at the approach rate, which
  // changes no faster than a point's velocity (the speed growth); the other objects are held
  // off by the travel bound.
  double part = travelBelow(v[kSlabs]);
  for (std::size_t j = 0; j < kSlabs && v[j] > 0; ++j) {
    const double* rates = v + kNearKept + 2 * j;
    part = std::min(part, partBelow(forwards ? rates[0] : rates[1], speed_growth, v[j]));
  }
  return std::max(plain, part);
}

}  // namespace octomotion
