// Shared by the scene parsers (scene.cpp, omplapp_cfg.cpp).
#pragma once

#include <string>

namespace octomotion {

// `file` made absolute against the directory of the scene file `scene_path` (a scene named
// without a directory lives in the current one).
std::string resolvePath(const std::string& scene_path, const std::string& file);

}  // namespace octomotion
