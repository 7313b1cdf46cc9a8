// Fuzzes the OMPL.app .cfg problem parser: a SceneSpec or an octomotion::Error.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "octomotion/planner/scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const octomotion::SceneSpec spec = octomotion::parseOmplAppCfg(text, "/fuzz/problem.cfg");
    // Accepted problems have finite poses and a positive time limit.
    if (!spec.problem.start || !spec.problem.start->pose || !spec.problem.goal ||
        !spec.problem.goal->pose) {
      octomotion::fuzz::fail("cfg accepted without a start and goal pose");
    }
    if (!spec.problem.start->pose->matrix().allFinite() ||
        !spec.problem.goal->pose->matrix().allFinite()) {
      octomotion::fuzz::fail("cfg accepted a non-finite pose");
    }
    if (!(spec.problem.time > 0)) octomotion::fuzz::fail("cfg accepted a time limit <= 0");
  } catch (const octomotion::Error&) {
  }
  return 0;
}
