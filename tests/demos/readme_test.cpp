// The README must not lie: its OMPL example is the code that demos/readme_example.cpp compiles
// and runs (ctest demo_readme_example), line for line.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace {

std::vector<std::string> readLines(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot open " << path;
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Lines strictly between the first line containing `begin` and the next containing `end`.
std::vector<std::string> between(const std::vector<std::string>& lines, const std::string& begin,
                                 const std::string& end) {
  std::vector<std::string> out;
  bool inside = false;
  for (const std::string& l : lines) {
    if (!inside && l.find(begin) != std::string::npos) {
      inside = true;
    } else if (inside && l.find(end) != std::string::npos) {
      return out;
    } else if (inside) {
      out.push_back(l);
    }
  }
  ADD_FAILURE() << "no '" << begin << "' ... '" << end << "' block";
  return {};
}

TEST(Readme, OmplExampleIsTheCompiledDemo) {
  const std::string root = OCTOMOTION_SOURCE_DIR;
  const auto demo = between(readLines(root + "/demos/readme_example.cpp"),
                            "// README example begin", "// README example end");
  const auto readme_section =
      between(readLines(root + "/README.md"), "## Plugging it into OMPL", "## ");
  const auto readme_code = between(readme_section, "```cpp", "```");
  ASSERT_GT(demo.size(), 10u);
  EXPECT_EQ(readme_code, demo) << "README.md's OMPL example differs from demos/readme_example.cpp";
}

// The "Your own robot" commands work as written: each line runs from the repository root (this
// build's folder standing in for build/) and exits 0.
TEST(Readme, OwnRobotCommandsRun) {
  const std::string root = OCTOMOTION_SOURCE_DIR;
  if (!std::filesystem::exists(root + "/../shared/data/panda/panda.urdf") ||
      !std::filesystem::exists(root + "/../shared/data/mbm_panda/problems.tar.bz2")) {
    GTEST_SKIP() << "no ../shared/data";
  }
  const auto block = between(
      between(readLines(root + "/README.md"), "<!-- own-robot-commands", "## "), "```sh", "```");
  ASSERT_GE(block.size(), 5u);
  // build/ stands for this build's folder (the CLI is <build>/planner/octomotion).
  const std::string build =
      std::filesystem::path(OCTOMOTION_CLI).parent_path().parent_path().string();
  std::size_t run = 0;
  for (std::string line : block) {
    if (line.empty() || line[0] == '#') continue;
    if (line.rfind("build/", 0) == 0) line = build + line.substr(5);
    const std::string command = "cd '" + root + "' && (" + line + ") > /dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << line;
    ++run;
  }
  EXPECT_GE(run, 5u);
}

}  // namespace
