// docs/robustness.md promises that no exception other than octomotion::Error escapes any entry
// point and that no bad input hangs. This holds the promise over the whole bad corpus
// (tests/data/bad/): every file goes through every loader, whatever its extension (a loader may
// accept a file meant for another, but must then return, and must never throw anything else),
// each call within a time bound; and through the command line, whose error is one line naming
// the file.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <sstream>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "octomotion/error.h"
#include "octomotion/octree/io.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/octree/octomap_io.h"
#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/planner/robot/robot_model.h"
#include "octomotion/pointcloud/point_cloud_io.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::vector<fs::path> corpus() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(std::string(OCTOMOTION_TEST_DATA_DIR) + "/bad")) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

struct Loader {
  const char* name;
  std::function<void(const std::string&)> load;
};

TEST(EntryPoints, OnlyOctomotionErrorsLeaveAnyLoaderOnTheWholeCorpus) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  RobotModelOptions options;
  options.package_paths = {OCTOMOTION_SOURCE_DIR};
  const RobotModel octo7 = RobotModel::fromUrdfFile(
      std::string(OCTOMOTION_SOURCE_DIR) + "/robots/octo7/octo7.urdf", options);
  const std::vector<Loader> loaders = {
      {"urdf", [](const std::string& p) { RobotModel::fromUrdfFile(p); }},
      {"srdf",
       [&](const std::string& p) {
         RobotModel copy = octo7;
         copy.loadSrdfFile(p);
       }},
      {"mesh", [](const std::string& p) { loadMesh(p); }},
      {"scene", [](const std::string& p) { loadScene(p); }},
      {"planning scene", [](const std::string& p) { loadPlanningScene(p); }},
      {"point cloud", [](const std::string& p) { pointcloud::loadPointCloud(p); }},
      {"octree", [](const std::string& p) { loadOctree(p); }},
      {"octomap", [](const std::string& p) { importOctoMap(p); }},
  };
  const std::vector<fs::path> files = corpus();
  ASSERT_GT(files.size(), 20u);
  for (const fs::path& file : files) {
    for (const Loader& loader : loaders) {
      auto answer = std::async(std::launch::async, [&]() -> std::string {
        try {
          loader.load(file.string());
          return "";
        } catch (const Error& e) {
          const std::string what = e.what();
          // Every message locates the problem, naming the file it was given.
          if (what.find(file.filename().string()) == std::string::npos) {
            return "an Error not naming the file: " + what;
          }
          return "";
        } catch (const std::exception& e) {
          return std::string("not an octomotion::Error: ") + e.what();
        } catch (...) {
          return "a non-std exception";
        }
      });
      ASSERT_EQ(answer.wait_for(std::chrono::seconds(20)), std::future_status::ready)
          << loader.name << " hangs on " << file.filename();
      const std::string problem = answer.get();
      EXPECT_EQ(problem, "") << loader.name << " on " << file.filename();
    }
  }
}

// Every scene in the corpus through `octomotion info`: a non-zero status and one error line that
// names the file.
TEST(EntryPoints, TheCommandLineNamesTheFileInOneLine) {
  const fs::path err_path =
      fs::temp_directory_path() / ("octomotion_entry_points_stderr_" + std::to_string(getpid()));
  for (const fs::path& file : corpus()) {
    const std::string ext = file.extension().string();
    if (ext != ".yaml" && ext != ".cfg") continue;
    const std::string cmd = std::string(OCTOMOTION_CLI) + " info " + file.string() +
                            " >/dev/null 2>" + err_path.string();
    const int raw = std::system(cmd.c_str());
    std::ifstream in(err_path);
    std::stringstream s;
    s << in.rdbuf();
    const std::string err = s.str();
    ASSERT_TRUE(WIFEXITED(raw)) << file.filename() << " killed the command";
    EXPECT_EQ(WEXITSTATUS(raw), 1) << file.filename();
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
    EXPECT_THAT(err, HasSubstr("octomotion: error: "));
    EXPECT_THAT(err, HasSubstr(file.filename().string()));
  }
  fs::remove(err_path);
}

}  // namespace
}  // namespace octomotion
