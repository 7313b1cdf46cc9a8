// `octomotion view SCENE`: exports the scene's octrees, the robot and a path to a .glb file
// (gltf_export.h) and copies the static three.js viewer (viewer/, docs/viewer.md) next to it,
// so that `python3 -m http.server -d DIR` serves a self-contained page.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <system_error>

#include "commands.h"
#include "octomotion/error.h"
#include "octomotion/tools/gltf_export.h"

namespace octomotion::cli {

namespace {

namespace fs = std::filesystem;

const char* kViewUsage = R"(usage: octomotion view SCENE [--path PATH] [view options] [options]
Writes DIR/<scene>.glb (the environment tree, each link's tree moved to the chosen state, the
robot's collision meshes and the path as an animation) and the web viewer's files to DIR, then
prints how to open them (docs/viewer.md).
view options:
  --path PATH          a path as written by `octomotion plan --out` (default: the scene's start)
  --state-index I      the path state whose link trees are written: 0-based, or `last`
                       (default 0)
  --out-dir DIR        where the files go (default out/view)
  --max-boxes N        at most N boxes per tree; bigger trees are drawn coarsened
                       (default 150000)
  --no-link-trees      leave out the links' voxel trees
  --viewer-dir DIR     the viewer's sources (default: $OCTOMOTION_VIEWER_DIR, else the
                       installed PREFIX/share/octomotion/viewer, else viewer/ next to the
                       build tree or in the current directory)
options: the scene options of `octomotion --help` (--resolution, --rounding, ...)
)";

std::size_t parseIndex(const std::string& flag, const std::string& value) {
  const double v = parseNumber(flag, value);
  if (v < 0 || v != std::floor(v) || v > 1e12) {
    throw InvalidArgument(flag + ": expected a whole number >= 0, got '" + value + "'");
  }
  return static_cast<std::size_t>(v);
}

bool isViewerDir(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "index.html", ec) && fs::is_regular_file(dir / "files.txt", ec);
}

// The viewer's sources: the flag, the environment, then places relative to the executable
// (installed: <prefix>/share/octomotion/viewer; in a build tree: build-*/planner/octomotion ->
// viewer/) and the current directory.
std::optional<fs::path> findViewerDir(const std::string& flag_value) {
  if (!flag_value.empty()) {
    if (!isViewerDir(flag_value)) {
      throw FileError(flag_value, "--viewer-dir: not a viewer directory (no index.html/files.txt)");
    }
    return fs::path(flag_value);
  }
  if (const char* env = std::getenv("OCTOMOTION_VIEWER_DIR"); env && *env) {
    if (!isViewerDir(env)) {
      throw FileError(env, "OCTOMOTION_VIEWER_DIR: not a viewer directory (no index.html)");
    }
    return fs::path(env);
  }
  std::vector<fs::path> candidates;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path bin = exe.parent_path();
    // The installed viewer first (cmake --install puts it under <prefix>/share/octomotion), so
    // an installed command never picks up a stray viewer/ next to its prefix.
    candidates = {bin / "../share/octomotion/viewer", bin / "../../viewer", bin / "../viewer"};
  }
  candidates.push_back(fs::current_path(ec) / "viewer");
  for (const fs::path& c : candidates) {
    if (isViewerDir(c)) return fs::weakly_canonical(c, ec);
  }
  return std::nullopt;
}

// Copies the files viewer/files.txt lists (relative paths, three.js's modules under
// node_modules/ among them) into out_dir. Returns the files that are missing.
std::vector<std::string> copyViewer(const fs::path& viewer, const fs::path& out_dir) {
  std::ifstream list(viewer / "files.txt");
  if (!list) throw FileError((viewer / "files.txt").string(), "cannot read the viewer's file list");
  std::vector<std::string> missing;
  std::string line;
  while (std::getline(list, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const fs::path from = viewer / line, to = out_dir / line;
    std::error_code ec;
    if (!fs::is_regular_file(from, ec)) {
      missing.push_back(line);
      continue;
    }
    fs::create_directories(to.parent_path(), ec);
    fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
    if (ec) throw FileError(to.string(), "cannot copy the viewer file: " + ec.message());
  }
  return missing;
}

RobotState toRobotState(const StateSpec& spec) {
  RobotState s;
  s.q = spec.joints;
  if (spec.pose) s.X_WB = *spec.pose;
  return s;
}

}  // namespace

int viewCommand(const std::vector<std::string>& args) {
  SceneOverrides overrides;
  GltfExportOptions options;
  std::string path_file, out_dir = "out/view", viewer_flag;
  bool state_last = false;  // --state-index last
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&] { return tools::flagValue(args, i); };
    if (parseSceneOption(arg, value, overrides)) {
      continue;
    } else if (arg == "--path") {
      path_file = value();
    } else if (arg == "--state-index") {
      const std::string v = value();
      state_last = v == "last";
      if (!state_last) options.state_index = parseIndex(arg, v);
    } else if (arg == "--out-dir") {
      out_dir = value();
    } else if (arg == "--max-boxes") {
      options.max_boxes_per_tree = parseIndex(arg, value());
      if (options.max_boxes_per_tree == 0) throw InvalidArgument("--max-boxes: must be > 0");
    } else if (arg == "--no-link-trees") {
      options.link_trees = false;
    } else if (arg == "--viewer-dir") {
      viewer_flag = value();
    } else if (arg == "-h" || arg == "--help") {
      std::cout << kViewUsage;
      return 0;
    } else if (!arg.empty() && arg[0] == '-') {
      throw InvalidArgument("view: unknown option " + arg + " (octomotion view --help)");
    } else {
      positional.push_back(arg);
    }
  }
  if (positional.size() != 1) throw InvalidArgument("view: expected one scene (see view --help)");
  const std::string scene_path = positional[0];
  // Find the viewer before the (possibly slow) scene load, so a bad --viewer-dir fails fast.
  const std::optional<fs::path> viewer = findViewerDir(viewer_flag);

  overrides.require_free_start_goal = false;  // a colliding start is worth a look
  const PlanningScene scene = loadSceneVerbose(scene_path, overrides);
  const RobotModel& robot = scene.model->robot();
  std::vector<RobotState> path;
  if (!path_file.empty()) {
    path = readPathFile(robot, path_file);
  } else if (scene.spec.problem.start) {
    path.push_back(toRobotState(*scene.spec.problem.start));
  } else {
    RobotState s;  // joints at zero (clamped to their limits), or the base at the origin
    for (const Variable& v : robot.variables()) s.q.push_back(std::clamp(0.0, v.lower, v.upper));
    path.push_back(s);
  }
  if (state_last) options.state_index = path.size() - 1;
  if (options.state_index >= path.size()) {
    throw InvalidArgument("--state-index " + std::to_string(options.state_index) +
                          ": the path has " + std::to_string(path.size()) + " states");
  }
  options.keep_mesh_root_transform = scene.spec.robot.keep_mesh_root_transform;
  options.center_mesh_vertices = scene.spec.robot.center_mesh_vertices;

  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw FileError(out_dir, "cannot create the output directory: " + ec.message());
  const std::string stem = fs::path(scene_path).stem().string();
  const std::string glb_name = (stem.empty() ? "scene" : stem) + ".glb";
  const std::string glb = (fs::path(out_dir) / glb_name).string();
  const GltfExportReport report = exportGlb(*scene.model, path, options, glb);
  std::cerr << "octomotion: wrote " << glb << "\n" << report.toString();

  if (!viewer) {
    std::cerr << "octomotion: warning: the viewer's sources (viewer/) were not found; open " << glb
              << " in any glTF viewer, or pass --viewer-dir\n";
    return 0;
  }
  const std::vector<std::string> missing = copyViewer(*viewer, out_dir);
  if (!missing.empty()) {
    std::cerr << "octomotion: warning: " << missing.size()
              << " viewer file(s) missing (first: " << missing.front()
              << "); install three.js with `npm ci --prefix " << viewer->string() << "`\n";
  }
  std::cout << "octomotion: to view, run\n  python3 -m http.server 8000 -d " << out_dir
            << "\nand open http://localhost:8000/?model=" << glb_name
            << "&state=" << options.state_index << "\n";
  return 0;
}

}  // namespace octomotion::cli
