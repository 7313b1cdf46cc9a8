// `octomotion make-building DIR`: writes the generated building-sized rigid-body problem
// (tools/building_scene.h; docs/scenes.md, "Large rigid scenes").
#include <cstdint>
#include <iostream>

#include "commands.h"
#include "octomotion/error.h"
#include "octomotion/tools/building_scene.h"

namespace octomotion::cli {

namespace {

const char* kMakeBuildingUsage = R"(usage: octomotion make-building DIR [options]
Writes DIR/building.yaml, DIR/building.stl and DIR/l_body.stl: a floor of square rooms whose
doors form a random spanning tree, and a large L-shaped body to fly from the first room to the
last (docs/scenes.md, "Large rigid scenes").
options:
  --rooms NX NY            rooms along x and y (default: 4 3)
  --room-size METRES       wall axis to wall axis (default: 8)
  --door WIDTH HEIGHT      metres (default: 1.4 2.4)
  --body LONG SHORT SECTION  the L's legs and section, metres (default: 2 1.8 0.3)
  --seed N                 the doors' rooms and places (default: 1)
  --time SECONDS           the scene's planning time (default: 30)
)";

int count(const std::string& flag, const std::string& v) {
  const double n = parseNumber(flag, v);
  if (n != static_cast<int>(n)) throw InvalidArgument(flag + ": expected an integer, got " + v);
  return static_cast<int>(n);
}

}  // namespace

int makeBuildingCommand(const std::vector<std::string>& args) {
  tools::BuildingOptions o;
  std::string dir;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&] { return tools::flagValue(args, i); };
    if (arg == "-h" || arg == "--help") {
      std::cout << kMakeBuildingUsage;
      return 0;
    } else if (arg == "--rooms") {
      o.rooms_x = count(arg, value());
      o.rooms_y = count(arg, value());
    } else if (arg == "--room-size") {
      o.room_size = parseNumber(arg, value());
    } else if (arg == "--door") {
      o.door_width = parseNumber(arg, value());
      o.door_height = parseNumber(arg, value());
    } else if (arg == "--body") {
      o.body_long_leg = parseNumber(arg, value());
      o.body_short_leg = parseNumber(arg, value());
      o.body_section = parseNumber(arg, value());
    } else if (arg == "--seed") {
      const double s = parseNumber(arg, value());
      if (s < 0 || s != static_cast<double>(static_cast<std::uint64_t>(s))) {
        throw InvalidArgument(arg + ": expected a non-negative integer");
      }
      o.seed = static_cast<std::uint64_t>(s);
    } else if (arg == "--time") {
      o.time = parseNumber(arg, value());
    } else if (!arg.empty() && arg[0] == '-') {
      throw InvalidArgument("make-building: unknown option " + arg);
    } else if (dir.empty()) {
      dir = arg;
    } else {
      throw InvalidArgument("make-building: one folder expected, got " + dir + " and " + arg);
    }
  }
  if (dir.empty()) throw InvalidArgument("make-building: no folder given (see --help)");
  std::cout << tools::writeBuildingScene(dir, o) << "\n";
  return 0;
}

}  // namespace octomotion::cli
