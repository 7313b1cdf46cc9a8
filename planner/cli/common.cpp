#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include "commands.h"
#include "octomotion/error.h"

namespace octomotion::cli {

double parseNumber(const std::string& flag, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v)) {
    throw InvalidArgument(flag + ": expected a number, got '" + value + "'");
  }
  return v;
}

namespace {

// An on|off switch's value.
bool onOff(const std::string& flag, const std::string& v) {
  if (v != "on" && v != "off") throw InvalidArgument(flag + ": expected on or off");
  return v == "on";
}

}  // namespace

bool parseSceneOption(const std::string& arg, const std::function<std::string()>& value,
                      SceneOverrides& overrides) {
  if (arg == "--planner") {
    overrides.planner = value();
  } else if (arg == "--time") {
    const double t = parseNumber(arg, value());
    if (!(t > 0)) throw InvalidArgument("--time: must be > 0");
    if (t > kMaxPlanningSeconds) throw InvalidArgument("--time: " + planningTimeTooLong(t));
    overrides.time = t;
  } else if (arg == "--seed") {
    const std::string text = value();
    const double s = parseNumber(arg, text);
    if (s < 0 || s != std::floor(s) || s > kMaxSeed) {
      // A larger double would not convert to the seed's integer type.
      throw InvalidArgument("--seed: expected an integer from 0 to 9e15, got '" + text + "'");
    }
    overrides.seed = static_cast<std::uint64_t>(s);
  } else if (arg == "--resolution") {
    const std::string v = value();
    if (v == "auto") {
      overrides.auto_resolution = true;
    } else {
      const double r = parseNumber(arg, v);
      if (!(r > 0)) throw InvalidArgument("--resolution: must be > 0");
      overrides.resolution = r;
    }
  } else if (arg == "--rounding") {
    overrides.rounding = roundingFromString(value().c_str());
  } else if (arg == "--checker") {
    overrides.checker = checkerName(value());
  } else if (arg == "--max-surface-voxels") {
    const double n = parseNumber(arg, value());
    if (!(n > 0)) throw InvalidArgument("--max-surface-voxels: must be > 0");
    overrides.max_surface_voxels = n;
  } else if (arg == "--link-resolution") {
    const double r = parseNumber(arg, value());
    if (!(r > 0)) throw InvalidArgument("--link-resolution: must be > 0");
    overrides.link_resolution = r;
  } else if (arg == "--self-link-resolution") {
    const double r = parseNumber(arg, value());
    if (!(r > 0)) throw InvalidArgument("--self-link-resolution: must be > 0");
    overrides.self_link_resolution = r;
  } else if (arg == "--self-pair-tables") {
    overrides.self_pair_tables = onOff(arg, value());
  } else if (arg == "--exact-primitives") {
    overrides.exact_primitives = onOff(arg, value());
  } else if (arg == "--package-path") {
    overrides.package_paths.push_back(value());
  } else {
    return false;
  }
  return true;
}

int finishStdout(int status) {
  std::cout.flush();
  if (!std::cout) throw Error("standard output: write error (disk full or closed?)");
  return status;
}

PlanningScene loadSceneVerbose(const std::string& path, const SceneOverrides& overrides) {
  const auto t0 = std::chrono::steady_clock::now();
  PlanningScene scene = loadPlanningScene(path, overrides, [](const std::string& m) {
    std::cerr << "octomotion: warning: " << m << "\n";
  });
  std::cerr << "octomotion: loaded " << path << " in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
            << " s, checker " << scene.checker << ", rounding "
            << toString(scene.spec.octree.rounding) << "\n";
  return scene;
}

}  // namespace octomotion::cli
