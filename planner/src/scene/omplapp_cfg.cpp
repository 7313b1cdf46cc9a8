// OMPL.app rigid-body problems (`.cfg`): docs/scenes.md, "OMPL.app .cfg problems".
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include "internal/scene_paths.h"
#include "octomotion/error.h"
#include "octomotion/input_limits.h"
#include "octomotion/planner/scene/scene.h"

namespace octomotion {

namespace fs = std::filesystem;

SceneSpec parseOmplAppCfg(const std::string& text, const std::string& path) {
  // INI sections; later keys override earlier ones except in [planner] (a list).
  std::map<std::string, std::string> problem;
  std::vector<std::string> planners;
  std::optional<std::string> time_limit;  // [benchmark] time_limit
  std::string section;
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t\r");
    const auto e = s.find_last_not_of(" \t\r");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  while (std::getline(lines, line)) {
    ++number;
    line = trim(line);
    if (line.empty() || line[0] == '#' || line[0] == ';') continue;
    if (line.front() == '[') {
      if (line.back() != ']') {
        throw FileError(path, "line " + std::to_string(number) + ": unterminated section");
      }
      section = trim(line.substr(1, line.size() - 2));
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos) {
      throw FileError(path, "line " + std::to_string(number) + ": expected key = value");
    }
    const std::string key = trim(line.substr(0, eq));
    const std::string value = trim(line.substr(eq + 1));
    if (section == "problem") problem[key] = value;
    if (section == "planner" && key.find('.') == std::string::npos) planners.push_back(key);
    if (section == "benchmark" && key == "time_limit") time_limit = value;
  }
  auto get = [&](const std::string& key) -> const std::string& {
    const auto it = problem.find(key);
    if (it == problem.end()) throw FileError(path, "[problem] " + key + ": missing");
    return it->second;
  };
  // A finite number; `field` is how the error names the key.
  auto parse = [&](const std::string& v, const std::string& field) {
    char* end = nullptr;
    const double d = std::strtod(v.c_str(), &end);
    if (v.empty() || *end != '\0' || !std::isfinite(d)) {
      throw FileError(path, field + ": expected a finite number, got '" + v + "'");
    }
    return d;
  };
  auto num = [&](const std::string& key) { return parse(get(key), "[problem] " + key); };
  // A file name: an empty one would resolve to the .cfg's directory.
  auto file = [&](const std::string& key) {
    const std::string& v = get(key);
    if (v.empty()) throw FileError(path, "[problem] " + key + ": empty, expected a file name");
    return resolvePath(path, v);
  };
  SceneSpec scene;
  scene.path = path;
  scene.name = problem.count("name") ? problem["name"] : fs::path(path).stem().string();
  scene.robot.mesh = file("robot");
  scene.robot.keep_mesh_root_transform = true;  // OMPL.app keeps the Collada root transform
  scene.robot.center_mesh_vertices = true;      // and centres the robot on its vertex mean
  EnvironmentObject world;
  world.name = "world";
  world.kind = EnvironmentObject::Kind::kMesh;
  world.file = file("world");
  world.keep_mesh_root_transform = true;
  scene.environment.push_back(world);
  auto pose = [&](const std::string& prefix) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    // One at a time: a missing key must be reported in x, y, z order.
    const double x = num(prefix + ".x");
    const double y = num(prefix + ".y");
    const double z = num(prefix + ".z");
    X.translation() = Eigen::Vector3d(x, y, z);
    if (problem.count(prefix + ".theta")) {
      Eigen::Vector3d axis;
      axis.x() = num(prefix + ".axis.x");
      axis.y() = num(prefix + ".axis.y");
      axis.z() = num(prefix + ".axis.z");
      const auto unit = scaledUnitVector(axis);
      if (!unit) throw FileError(path, "[problem] " + prefix + ".axis: zero");
      X.linear() = Eigen::AngleAxisd(num(prefix + ".theta"), *unit).toRotationMatrix();
    }
    StateSpec s;
    s.pose = X;
    return s;
  };
  scene.problem.start = pose("start");
  scene.problem.goal = pose("goal");
  // All six volume keys or none: a missing one must not drop the others silently.
  bool any_volume_key = false;
  for (const auto& kv : problem) any_volume_key |= kv.first.rfind("volume.", 0) == 0;
  if (any_volume_key) {
    Eigen::Vector3d lo, hi;
    for (int a = 0; a < 3; ++a) {
      const std::string axis(1, "xyz"[a]);
      lo[a] = num("volume.min." + axis);
      hi[a] = num("volume.max." + axis);
    }
    if (!(lo.array() < hi.array()).all()) {
      throw FileError(path, "[problem] volume: min must be < max");
    }
    scene.problem.bounds = Eigen::AlignedBox3d(lo, hi);
  }
  if (time_limit) {
    const double t = parse(*time_limit, "[benchmark] time_limit");
    if (!(t > 0)) throw FileError(path, "[benchmark] time_limit: must be > 0");
    if (t > kMaxPlanningSeconds) {
      throw FileError(path, "[benchmark] time_limit: " + planningTimeTooLong(t));
    }
    scene.problem.time = t;
  }
  return scene;
}

}  // namespace octomotion
