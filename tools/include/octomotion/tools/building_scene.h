// A generated building-sized rigid-body problem (`octomotion make-building`, docs/scenes.md,
// "Large rigid scenes"): a floor of square rooms behind walls with doors, one mesh tens of
// metres across, and a large L-shaped body (metres) that has to stand one leg up to pass a
// door. OMPL.app's `cubicles` plays this part there; this one is generated at test or bench time
// instead of being shipped.
//
// The rooms form a grid; the doors are those of a random spanning tree of the rooms (seeded), so
// there is exactly one way from room to room and the start and goal rooms, at opposite corners,
// are several doors apart. Every wall, pillar, lintel, the floor and the ceiling is a closed box
// shell in one STL file; the boxes touch but do not overlap, so the voxelizer fills them solid.
#pragma once

#include <cstdint>
#include <string>

namespace octomotion::tools {

struct BuildingOptions {
  int rooms_x = 4;  // rooms along x and along y
  int rooms_y = 3;
  double room_size = 8.0;  // metres, wall axis to wall axis
  double wall_height = 3.0;
  double wall_thickness = 0.2;
  double door_width = 1.4;  // narrower than the body's long legs: it turns one upright
  double door_height = 2.4;
  double body_long_leg = 2.0;   // the L's legs (metres) and their square section
  double body_short_leg = 1.8;  //
  double body_section = 0.3;    //
  std::uint64_t seed = 1;       // the doors' rooms and places
  double time = 30;             // problem.time, seconds
};

// Writes DIR/building.stl (the environment), DIR/l_body.stl (the robot, centred on its bounding
// box) and DIR/building.yaml (the scene: resolution auto, the RRTConnect problem from the first
// room's middle, lying flat, to the last room's, turned a quarter) and returns the scene's path.
// Creates DIR if needed. Throws InvalidArgument for options that give no building (fewer than
// one room, a door that does not fit its wall, a body that does not fit a door standing up) and
// FileError when a file cannot be written.
std::string writeBuildingScene(const std::string& dir, const BuildingOptions& options = {});

}  // namespace octomotion::tools
