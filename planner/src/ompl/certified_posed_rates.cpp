// The certified motion validator's posed rates (internal/certified_scratch.h): computed per
// evaluated state for the links and pairs its interval's halves will test, as those not proven
// over the interval are all that its descendants test.
#include <cstddef>
#include <cstdint>

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

}  // namespace octomotion
