#include <chrono>
#include <iostream>

#include "commands.h"
#include "octomotion/error.h"

namespace octomotion::cli {

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
            << " s, checker " << checkerKindName(scene.checker) << ", rounding "
            << toString(scene.spec.octree.rounding) << "\n";
  return scene;
}

}  // namespace octomotion::cli
