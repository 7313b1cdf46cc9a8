#include "octomotion/tools/study_options.h"

#include "octomotion/error.h"

namespace octomotion::tools {

namespace {

double ratio(const std::string& flag, const std::string& value) {
  const double r = parseNumber(flag, value);
  if (!(r > 0 && r <= 1)) throw InvalidArgument(flag + ": must be in (0, 1]");
  return r;
}

}  // namespace

const OptionTable<StudyCommandOptions>& studyOptions() {
  static const OptionTable<StudyCommandOptions> table = [] {
    using O = StudyCommandOptions;
    OptionTable<O> t({
        {"--states", "N", "uniform states checked by every checker (default 20000)",
         [](const std::string& flag, const std::string& v, O& o) {
           o.study.states = parseCount(flag, v);
           if (o.study.states == 0) throw InvalidArgument(flag + ": must be > 0");
         }},
        {"--move-tree-states", "N",
         "the moveTree path checks only the first N of the states (it is\nslow at fine "
         "resolutions; default: all)",
         [](const std::string& flag, const std::string& v, O& o) {
           o.study.move_tree_states = parseCount(flag, v);
         }},
        {"--runs", "N", "planning runs per planner and setting (default 20; 0: no planning)",
         [](const std::string& flag, const std::string& v, O& o) {
           o.study.runs = static_cast<unsigned>(parseCount(flag, v));
         }},
        {"--resolutions", "A,B,...",
         "voxel sizes in metres (default: 8 cm .. 5 mm for arms, 16 .. 1 x\nthe scene's "
         "resolution for rigid bodies)",
         [](const std::string& flag, const std::string& v, O& o) {
           o.study.resolutions.clear();
           for (const std::string& r : parseList(flag, v)) {
             const double x = parseNumber(flag, r);
             if (!(x > 0)) throw InvalidArgument(flag + ": " + r + " must be > 0");
             o.study.resolutions.push_back(x);
           }
         }},
        {"--roundings", "LIST", "conservative,center (default both)",
         [](const std::string& flag, const std::string& v, O& o) {
           o.study.roundings.clear();
           for (const std::string& r : parseList(flag, v)) {
             o.study.roundings.push_back(roundingFromString(r.c_str()));
           }
         }},
        {"--refine-exact", nullptr,
         "also conservative rounding refined with FCL (--refine exact; rows\n"
         "\"conservative+exact\")",
         [](const std::string&, const std::string&, O& o) { o.study.refine_exact = true; }},
        {"--paths", "LIST", "octree,octree-fused (default both)",
         [](const std::string& flag, const std::string& v, O& o) {
           o.study.octree_checkers.clear();
           for (const std::string& p : parseList(flag, v)) {
             if (p == checkerKindName(CheckerKind::kOctree)) {
               o.study.octree_checkers.push_back(CheckerKind::kOctree);
             } else if (p == checkerKindName(CheckerKind::kOctreeFused)) {
               o.study.octree_checkers.push_back(CheckerKind::kOctreeFused);
             } else {
               throw InvalidArgument(flag + ": expected octree or octree-fused, got '" + p + "'");
             }
           }
         }},
        {"--planners", "NAME[:S],...",
         "OMPL planners, each with an optional time limit in seconds\n(default RRTConnect,RRTstar "
         "with the scene's --time)",
         [](const std::string& flag, const std::string& v, O& o) {
           o.study.planners.clear();
           for (const std::string& p : parseList(flag, v)) {
             StudyPlanner planner;
             const auto colon = p.find(':');
             planner.name = p.substr(0, colon);
             if (colon != std::string::npos) {
               planner.time = parseNumber(flag, p.substr(colon + 1));
               if (!(planner.time > 0)) {
                 throw InvalidArgument(flag + ": " + p + ": time must be > 0");
               }
               if (planner.time > kMaxPlanningSeconds) {
                 throw InvalidArgument(flag + ": " + p + ": " + planningTimeTooLong(planner.time));
               }
             }
             o.study.planners.push_back(planner);
           }
         }},
        {"--plan-every-setting", nullptr,
         "plan with every setting (default: the fused conservative octree at\nevery resolution, "
         "the others at the scene's resolution, FCL)",
         [](const std::string&, const std::string&, O& o) { o.study.plan_every_setting = true; }},
        {"--no-fcl-octomap", nullptr, "leave out FCL+OctoMap",
         [](const std::string&, const std::string&, O& o) { o.study.fcl_octomap = false; }},
        {"--link-ratio", "R",
         "octree link trees at R x each resolution (default 0.25, the library's)",
         [](const std::string& flag, const std::string& v, O& o) {
           o.study.link_resolution_ratio = ratio(flag, v);
         }},
        {"--self-link-ratio", "R",
         "self-collision trees at R x each resolution (default: --link-ratio if\ngiven, else 1, "
         "the library's defaults)",
         [](const std::string& flag, const std::string& v, O& o) {
           o.study.self_link_resolution_ratio = ratio(flag, v);
         }},
        {"--out-dir", "DIR", "where the CSV, markdown, plot data and logs go (default .)",
         [](const std::string&, const std::string& v, O& o) { o.out_dir = v; }},
    });
    // The scene options that the study's own flags replace are parsed, so that
    // finishStudyOptions can name the replacement, but not listed.
    t.append(sceneOptions(), [](O& o) -> SceneOverrides& { return o.study.overrides; },
             {"--resolution", "--rounding", "--checker", "--planner", "--link-resolution",
              "--self-link-resolution", "--refine"});
    return t;
  }();
  return table;
}

void finishStudyOptions(StudyCommandOptions& options) {
  const SceneOverrides& o = options.study.overrides;
  if (o.resolution || o.auto_resolution || o.checker || o.rounding || o.planner ||
      o.link_resolution || o.self_link_resolution) {
    throw InvalidArgument(
        "bench: --resolution/--rounding/--checker/--planner/--link-resolution/"
        "--self-link-resolution do not apply; use --resolutions, --roundings, --paths, "
        "--planners, --link-ratio, --self-link-ratio");
  }
  if (o.refine) throw InvalidArgument("bench: --refine does not apply; use --refine-exact");
  if (o.seed) options.study.seed = *o.seed;
}

}  // namespace octomotion::tools
