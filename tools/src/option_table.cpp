#include "octomotion/tools/option_table.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "octomotion/error.h"

namespace octomotion::tools {

double parseNumber(const std::string& flag, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v)) {
    throw InvalidArgument(flag + ": expected a number, got '" + value + "'");
  }
  return v;
}

std::string flagValue(const std::vector<std::string>& args, std::size_t& i) {
  if (i + 1 >= args.size()) throw InvalidArgument(args[i] + ": missing value");
  return args[++i];
}

std::size_t parseCount(const std::string& flag, const std::string& value) {
  const double v = parseNumber(flag, value);
  if (v < 0 || v != std::floor(v) || v > 1e9) {
    throw InvalidArgument(flag + ": expected a whole number, got '" + value + "'");
  }
  return static_cast<std::size_t>(v);
}

bool parseOnOff(const std::string& flag, const std::string& value) {
  if (value != "on" && value != "off") throw InvalidArgument(flag + ": expected on or off");
  return value == "on";
}

std::vector<std::string> parseList(const std::string& flag, const std::string& value) {
  std::vector<std::string> items;
  std::stringstream ss(value);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) throw InvalidArgument(flag + ": empty item in '" + value + "'");
    items.push_back(item);
  }
  if (items.empty()) throw InvalidArgument(flag + ": expected a list, got '" + value + "'");
  return items;
}

namespace {

double positive(const std::string& flag, const std::string& value) {
  const double v = parseNumber(flag, value);
  if (!(v > 0)) throw InvalidArgument(flag + ": must be > 0");
  return v;
}

using SceneOption = Option<SceneOverrides>;

}  // namespace

const OptionTable<SceneOverrides>& sceneOptions() {
  static const OptionTable<SceneOverrides> table({
      {"--resolution", "METRES|auto", "voxel size of the environment (overrides the scene)",
       [](const std::string& flag, const std::string& v, SceneOverrides& o) {
         if (v == "auto") {
           o.auto_resolution = true;
         } else {
           o.resolution = positive(flag, v);
         }
       }},
      {"--rounding", "conservative|center", "voxel rounding (overrides the scene)",
       [](const std::string&, const std::string& v, SceneOverrides& o) {
         o.rounding = roundingFromString(v.c_str());
       }},
      {"--checker", "octree|octree-fused|fcl|fcl-octomap", "the validity checker",
       [](const std::string&, const std::string& v, SceneOverrides& o) {
         o.checker = parseCheckerKind(v);
       }},
      {"--motion-validator", "certified|discrete|ompl-default",
       "how edges are checked (overrides the scene's; default certified:\ndocs/validation.md §4)",
       [](const std::string&, const std::string& v, SceneOverrides& o) {
         o.motion_validator = parseMotionValidatorKind(v);
       }},
      {"--planner", "NAME", "OMPL planner (overrides the scene's, e.g. RRTConnect)",
       [](const std::string&, const std::string& v, SceneOverrides& o) { o.planner = v; }},
      {"--time", "SECONDS", "planning time limit (overrides the scene's)",
       [](const std::string& flag, const std::string& v, SceneOverrides& o) {
         const double t = positive(flag, v);
         if (t > kMaxPlanningSeconds) throw InvalidArgument(flag + ": " + planningTimeTooLong(t));
         o.time = t;
       }},
      {"--seed", "N",
       "seeds OMPL's random numbers (overrides the scene's; bench: also the\nstates, default 1; "
       "bench-set: each problem its own, made\nfrom N; docs/benchmarking.md)",
       [](const std::string& flag, const std::string& v, SceneOverrides& o) {
         const double s = parseNumber(flag, v);
         if (s < 0 || s != std::floor(s) || s > kMaxSeed) {
           // A larger double would not convert to the seed's integer type.
           throw InvalidArgument(flag + ": expected an integer from 0 to 9e15, got '" + v + "'");
         }
         o.seed = static_cast<std::uint64_t>(s);
       }},
      {"--range", "DISTANCE",
       "how far one planner step reaches, in the state space's distance\n(radians over the "
       "joints for an arm; overrides problem.range;\ndefault: 3/40 of an arm's joint-space "
       "extent, the planner's own\nfor a rigid body; docs/planner.md)",
       [](const std::string& flag, const std::string& v, SceneOverrides& o) {
         o.range = positive(flag, v);
       }},
      {"--package-path", "DIR", "extra package:// search path (repeatable)",
       [](const std::string&, const std::string& v, SceneOverrides& o) {
         o.package_paths.push_back(v);
       }},
      {"--max-surface-voxels", "N",
       "fail early when a tree would need more voxels (default: the scene's,\nelse 2e8)",
       [](const std::string& flag, const std::string& v, SceneOverrides& o) {
         o.max_surface_voxels = positive(flag, v);
       }},
      {"--link-resolution", "METRES",
       "voxel size of the links' trees for the environment queries\n(default: the resolution / "
       "4; docs/planner.md)",
       [](const std::string& flag, const std::string& v, SceneOverrides& o) {
         o.link_resolution = positive(flag, v);
       }},
      {"--self-link-resolution", "METRES",
       "link trees for self-collision pairs only (default: the\n--link-resolution if given, else "
       "the resolution; finer ones give\nfewer false positives of near self pairs; "
       "docs/trade-off.md)",
       [](const std::string& flag, const std::string& v, SceneOverrides& o) {
         o.self_link_resolution = positive(flag, v);
       }},
      {"--self-pair-tables", "on|off",
       "joint-space tables for self pairs of 1-2 variables (default: the\nscene's, else off; "
       "docs/planner.md, \"Self-pair tables\")",
       [](const std::string& flag, const std::string& v, SceneOverrides& o) {
         o.self_pair_tables = parseOnOff(flag, v);
       }},
      {"--exact-primitives", "on|off",
       "test the links against the scene's boxes, balls and cylinders\nthemselves, not their "
       "voxels (default: the scene's, else off;\ndocs/planner.md, \"Exact primitives\")",
       [](const std::string& flag, const std::string& v, SceneOverrides& o) {
         o.exact_primitives = parseOnOff(flag, v);
       }},
      {"--refine", "auto|none|exact",
       "exact: FCL decides each link-object and link-link pair whose voxels\nmeet, so the "
       "answer is FCL's (conservative rounding); none: the voxels\ndecide; auto: exact under "
       "conservative rounding, else none\n(default: the scene's, else auto; docs/planner.md, "
       "\"Exact refine mode\")",
       [](const std::string&, const std::string& v, SceneOverrides& o) {
         o.refine = parseRefineMode(v);
       }},
  });
  return table;
}

}  // namespace octomotion::tools
