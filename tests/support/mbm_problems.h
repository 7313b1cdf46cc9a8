// The MotionBenchMaker Panda problems (../shared/data/mbm_panda, see its README), extracted once
// per test program into a temporary folder. Empty when the data is absent (tests then skip).
#pragma once

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace octomotion::test {

struct MbmProblem {
  std::string set;      // e.g. box_panda
  std::string scene;    // the PlanningScene YAML
  std::string request;  // the MotionPlanRequest YAML
};

class MbmProblems {
 public:
  static std::string archive() {
    return std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/mbm_panda/problems.tar.bz2";
  }
  static std::string panda() {
    return std::string(OCTOMOTION_SOURCE_DIR) + "/../shared/data/panda";
  }

  // Writes a scene file at `path` in which the real Panda (panda()) plans problem p: its scene
  // and request; `problem_extra` adds keys to the problem map (e.g. ", seed: 1").
  static void writeScene(const std::string& path, const MbmProblem& p,
                         const std::string& problem_extra = "") {
    std::ofstream(path) << "robot: {urdf: " << panda() << "/panda.urdf, srdf: " << panda()
                        << "/panda.srdf}\nenvironment:\n  - moveit_scene: " << p.scene
                        << "\nproblem: {moveit_request: " << p.request << problem_extra << "}\n";
  }

  MbmProblems() {
    namespace fs = std::filesystem;
    if (!fs::exists(archive())) return;
    dir_ = fs::temp_directory_path() / ("octomotion_mbm_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    const std::string command = "tar -xjf '" + archive() + "' -C '" + dir_.string() + "'";
    if (std::system(command.c_str()) != 0) return;
    for (const auto& set : fs::directory_iterator(dir_ / "problems")) {
      for (const auto& f : fs::directory_iterator(set.path())) {
        const std::string name = f.path().filename().string();
        if (name.rfind("request", 0) != 0) continue;
        const std::string folder = f.path().parent_path().string();
        std::string scene = folder + "/scene" + name.substr(7);
        if (!fs::exists(scene)) scene = folder + "/scene_sensed" + name.substr(7);
        problems_.push_back({set.path().filename().string(), scene, f.path().string()});
      }
    }
    std::sort(problems_.begin(), problems_.end(),
              [](const MbmProblem& a, const MbmProblem& b) { return a.request < b.request; });
  }
  ~MbmProblems() {
    std::error_code ec;
    if (!dir_.empty()) std::filesystem::remove_all(dir_, ec);
  }
  MbmProblems(const MbmProblems&) = delete;
  MbmProblems& operator=(const MbmProblems&) = delete;

  const std::vector<MbmProblem>& problems() const { return problems_; }
  // The first problem of each set (in file order), one per set.
  std::vector<MbmProblem> firstOfEachSet() const {
    std::vector<MbmProblem> out;
    for (const MbmProblem& p : problems_) {
      if (out.empty() || out.back().set != p.set) out.push_back(p);
    }
    return out;
  }
  std::string folder() const { return dir_.string(); }

 private:
  std::filesystem::path dir_;
  std::vector<MbmProblem> problems_;
};

}  // namespace octomotion::test
