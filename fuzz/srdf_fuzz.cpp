// Fuzzes the SRDF reader (allowed collision pairs) on a fixed robot, tests/data/urdf/arm.urdf: the
// filter changes or an octomotion::Error leaves it unchanged (robot_model.h promises that).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "octomotion/planner/robot/robot_model.h"

namespace {
const std::string kDataDir = std::string(OCTOMOTION_SOURCE_DIR) + "/tests/data/urdf";

const octomotion::RobotModel& arm() {
  static const octomotion::RobotModel robot = [] {
    octomotion::RobotModelOptions options;
    options.package_paths = {kDataDir + "/packages"};
    options.use_environment_package_paths = false;
    return octomotion::RobotModel::fromUrdfFile(kDataDir + "/arm.urdf", options);
  }();
  return robot;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace octomotion;
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const SrdfMode mode : {SrdfMode::kReplace, SrdfMode::kMerge}) {
    RobotModel robot = arm();
    try {
      robot.loadSrdfString(text, "fuzz.srdf", mode);
    } catch (const Error&) {
      if (robot.disabledPairs() != arm().disabledPairs()) {
        fuzz::fail("a rejected SRDF changed the collision filter");
      }
    }
  }
  return 0;
}
