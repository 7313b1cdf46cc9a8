// The octomotion command's pieces: options every command shares, and the commands that live in
// their own files (bench, view). Each command takes the arguments after its name.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "octomotion/planner/ompl/planning_scene.h"

namespace octomotion::cli {

// A finite number, or InvalidArgument naming the flag.
double parseNumber(const std::string& flag, const std::string& value);

// The scene options shared by every command (--resolution, --rounding, --checker, --planner,
// --time, --seed, --package-path). Returns false when `arg` is not one of them; `value` returns
// the option's value (and throws when it is missing).
bool parseSceneOption(const std::string& arg, const std::function<std::string()>& value,
                      SceneOverrides& overrides);

// Loads a scene with warnings and the load time on stderr.
// Flushes standard output and throws Error if anything written to it was lost (a full disk, a
// closed pipe); returns `status` otherwise.
int finishStdout(int status);

PlanningScene loadSceneVerbose(const std::string& path, const SceneOverrides& overrides);

// `octomotion bench SCENE ...`: the speed/accuracy trade study of one scene.
int benchCommand(const std::vector<std::string>& args);
// `octomotion view SCENE ...`: writes the glTF file and the viewer page.
int viewCommand(const std::vector<std::string>& args);

}  // namespace octomotion::cli
