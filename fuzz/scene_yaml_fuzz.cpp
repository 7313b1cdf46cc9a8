// Fuzzes the YAML scene parser (docs/scenes.md): any text is either a SceneSpec or an
// octomotion::Error naming the file; yaml-cpp's own exceptions must not escape.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "octomotion/planner/scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const octomotion::SceneSpec spec = octomotion::parseSceneYaml(text, "/fuzz/scene.yaml");
    // What was accepted is usable: the checker name is one of the known ones.
    octomotion::checkerKindName(spec.octree.checker);
  } catch (const octomotion::Error&) {
  }
  return 0;
}
