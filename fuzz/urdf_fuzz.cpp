// Fuzzes the URDF loader (urdfdom + our checks) on text: a RobotModel or an octomotion::Error.
// What is accepted must be usable: forward kinematics at the middle of every joint range gives
// finite link poses.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "octomotion/planner/robot/robot_model.h"

namespace {
const std::string kDataDir = std::string(OCTOMOTION_SOURCE_DIR) + "/tests/data/urdf";
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace octomotion;
  const std::string text(reinterpret_cast<const char*>(data), size);
  RobotModelOptions options;
  options.package_paths = {kDataDir + "/packages"};
  options.use_environment_package_paths = false;
  options.warnings = [](const std::string&) {};
  // The first byte (when it is not the '<' of an XML document) picks a free-flying base.
  if (size > 0 && data[0] == 'F') options.base = BaseMotion::kFreeFlying;
  std::optional<RobotModel> robot;
  try {
    robot.emplace(RobotModel::fromUrdfString(text, "fuzz.urdf", kDataDir, options));
  } catch (const Error&) {
    return 0;
  }
  std::vector<double> q;
  for (const Variable& v : robot->variables()) q.push_back(0.5 * v.lower + 0.5 * v.upper);
  RobotData robot_data = robot->makeData();
  // forwardKinematics throws for a non-finite link pose: for an accepted model at mid-range,
  // that is a finding, not an answer.
  try {
    robot->forwardKinematics(q.data(), q.size(), robot_data);
  } catch (const Error&) {
    fuzz::fail("non-finite link pose");
  }
  for (int l = 0; l < robot->linkCount(); ++l) {
    if (!robot_data.linkPose(l).matrix().allFinite()) fuzz::fail("non-finite link pose");
  }
  for (const auto& [a, b] : robot->checkedPairs()) {
    if (robot->collisionAllowed(a, b)) fuzz::fail("checked pair is allowed");
  }
  return 0;
}
