// `octomotion view` and the web viewer end to end: exports the narrow-passage scene with a
// three-state path, then opens the copied viewer in headless Chromium (viewer/test/e2e.mjs),
// which checks that the environment voxels and the robot are drawn where they project and that
// the robot moves along the path. Skipped when Chromium, node or viewer/node_modules is missing.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

const std::string kSource = OCTOMOTION_SOURCE_DIR;
const std::string kCli = OCTOMOTION_CLI;

struct CommandResult {
  int status = -1;
  std::string output;
};

// Runs a shell command, returning its exit status and its stdout + stderr.
CommandResult run(const std::string& command, const fs::path& log) {
  const int raw = std::system((command + " > '" + log.string() + "' 2>&1").c_str());
  CommandResult r;
  r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  r.output = ss.str();
  return r;
}

fs::path workDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "octomotion_viewer_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The L piece upright before the wall, half turned, and through the slot (x y z qx qy qz qw).
fs::path writePath(const fs::path& dir) {
  const fs::path path = dir / "narrow_passage.path";
  std::ofstream out(path);
  out << "-0.7 0 0.6 0.70710678118654757 0 0 0.70710678118654757\n"
      << "-0.2 0 0.6 0.5 0 0 0.8660254037844386\n"
      << "0.4 -0.12 0.57 0 0 0 1\n";
  return path;
}

std::string viewCommand(const fs::path& dir, const std::string& extra = "") {
  return "'" + kCli + "' view '" + kSource +
         "/robots/scenes/narrow_passage.yaml' --resolution 0.02 --path '" +
         writePath(dir).string() + "' --state-index 1 --out-dir '" + dir.string() +
         "' --viewer-dir '" + kSource + "/viewer' " + extra;
}

TEST(Viewer, ViewWritesTheModelAndTheViewerFiles) {
  const fs::path dir = workDir("files");
  const CommandResult r = run(viewCommand(dir), dir / "view.log");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::is_regular_file(dir / "narrow_passage.glb"));
  EXPECT_GT(fs::file_size(dir / "narrow_passage.glb"), 1000u);
  EXPECT_TRUE(fs::is_regular_file(dir / "index.html"));
  EXPECT_TRUE(fs::is_regular_file(dir / "viewer.js"));
  EXPECT_NE(r.output.find("python3 -m http.server 8000 -d " + dir.string()), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("http://localhost:8000/?model=narrow_passage.glb&state=1"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("l_piece"), std::string::npos) << r.output;  // the per-tree summary
}

TEST(Viewer, ViewRejectsBadOptions) {
  const fs::path dir = workDir("bad");
  CommandResult r = run(viewCommand(dir, "--state-index 3"), dir / "a.log");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--state-index 3"), std::string::npos) << r.output;
  r = run(viewCommand(dir, "--max-boxes 0"), dir / "b.log");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--max-boxes"), std::string::npos) << r.output;
  r = run(viewCommand(dir, "--frobnicate"), dir / "c.log");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("--frobnicate"), std::string::npos) << r.output;
  std::ofstream(dir / "bad.path") << "1 2 3\n";
  r = run("'" + kCli + "' view '" + kSource +
              "/robots/scenes/narrow_passage.yaml' --resolution 0.05 --path '" +
              (dir / "bad.path").string() + "' --out-dir '" + dir.string() + "'",
          dir / "d.log");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("bad.path"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("line 1"), std::string::npos) << r.output;
}

TEST(Viewer, DrawsTheRobotAndTheVoxelsInChromium) {
  const char* chromium_env = std::getenv("CHROMIUM");
  const std::string chromium = chromium_env ? chromium_env : "/usr/bin/chromium";
  if (!fs::exists(chromium)) {
    GTEST_SKIP() << "Chromium is not installed (" << chromium
                 << "): apt-get install -y chromium chromium-driver";
  }
  if (std::system("node --version > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "node is not installed";
  }
  const fs::path modules = fs::path(kSource) / "viewer" / "node_modules";
  if (!fs::exists(modules / "three" / "build" / "three.module.js") ||
      !fs::exists(modules / "playwright-core" / "package.json")) {
    GTEST_SKIP() << "the viewer's npm packages are not installed: npm ci --prefix " << kSource
                 << "/viewer";
  }
  const fs::path dir = workDir("e2e");
  const CommandResult view = run(viewCommand(dir), dir / "view.log");
  ASSERT_EQ(view.status, 0) << view.output;
  // node resolves playwright-core from the script's directory (viewer/node_modules).
  const CommandResult e2e =
      run("node '" + kSource + "/viewer/test/e2e.mjs' --dir '" + dir.string() +
              "' --model narrow_passage.glb --state 1 --screenshot '" +
              (dir / "viewer.png").string() + "'",
          dir / "e2e.log");
  EXPECT_EQ(e2e.status, 0) << e2e.output;
  EXPECT_NE(e2e.output.find("PASS"), std::string::npos) << e2e.output;
  EXPECT_TRUE(fs::is_regular_file(dir / "viewer.png"));
}

}  // namespace
