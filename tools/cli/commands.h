// The octomotion command's pieces: options every command shares, and the commands that live in
// their own files (bench, view). Each command takes the arguments after its name.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "octomotion/planner/ompl/planning_scene.h"
#include "octomotion/tools/option_table.h"

namespace octomotion::cli {

using tools::parseNumber;  // a finite number, or InvalidArgument naming the flag

// The scene options shared by every command (tools::sceneOptions()). Returns false when `arg` is
// not one of them; `value` returns the option's value (and throws when it is missing).
inline bool parseSceneOption(const std::string& arg, const std::function<std::string()>& value,
                             SceneOverrides& overrides) {
  return tools::sceneOptions().parse(arg, value, overrides);
}

// Loads a scene with warnings and the load time on stderr.
// Flushes standard output and throws Error if anything written to it was lost (a full disk, a
// closed pipe); returns `status` otherwise.
int finishStdout(int status);

PlanningScene loadSceneVerbose(const std::string& path, const SceneOverrides& overrides);

// `octomotion bench SCENE ...`: the speed/accuracy trade study of one scene.
int benchCommand(const std::vector<std::string>& args);
// `octomotion bench-set DIR ...`: the planning benchmark over a folder of problems.
int benchSetCommand(const std::vector<std::string>& args);
// `octomotion view SCENE ...`: writes the glTF file and the viewer page.
int viewCommand(const std::vector<std::string>& args);
// `octomotion make-building DIR ...`: writes the generated building scene.
int makeBuildingCommand(const std::vector<std::string>& args);

}  // namespace octomotion::cli
