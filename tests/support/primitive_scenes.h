// Random scenes of primitives for the planner tests: thin boards and thick blocks, 12 mm rods,
// posts and balls, upright and tilted, with objects reaching out of a small robot's universe.
#pragma once

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/planner/scene/scene.h"

namespace octomotion::test {

// Within 40 cm of the origin, turned at random when `tilt`.
inline void placeAtRandom(EnvironmentObject& o, std::mt19937_64& rng, bool tilt) {
  std::uniform_real_distribution<double> u(-1, 1);
  if (tilt) {
    o.X_WO.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().matrix();
  }
  o.X_WO.translation() = 0.4 * Eigen::Vector3d(u(rng), u(rng), u(rng));
}

inline std::vector<EnvironmentObject> boards(std::uint64_t seed, bool rotated) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<EnvironmentObject> objects;
  for (int i = 0; i < 12; ++i) {
    EnvironmentObject box;
    box.name = "board" + std::to_string(i);
    // Thin boards (3 mm to 2 cm) up to 40 cm wide, and a few thick blocks.
    const double thick =
        i % 4 == 0 ? 0.05 + 0.05 * std::abs(u(rng)) : 0.0015 + 0.0085 * std::abs(u(rng));
    box.primitive =
        Box{Eigen::Vector3d(0.05 + 0.15 * std::abs(u(rng)), 0.05 + 0.15 * std::abs(u(rng)), thick)};
    placeAtRandom(box, rng, rotated);
    objects.push_back(box);
  }
  // Two reaching beyond the robot, so out of the universe (fit to the reach): the axis-aligned
  // one is clipped to it, the rotated one is left out.
  EnvironmentObject wall;
  wall.name = "wall";
  wall.primitive = Box{Eigen::Vector3d(0.2, 2.0, 2.0)};
  wall.X_WO.translation() = Eigen::Vector3d(0.65, 0, 0);
  objects.push_back(wall);
  wall.name = "tilted_wall";
  wall.X_WO = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()) *
              Eigen::Translation3d(Eigen::Vector3d(-0.7, 0, 0));
  objects.push_back(wall);
  return objects;
}

// Rods (12 mm bars like the cage's, thicker posts) and balls, upright or tilted, with an
// upright pole leaving the universe (clipped to it) and a tilted one (left out): their
// inscribed boxes are the solids.
inline std::vector<EnvironmentObject> rodsAndBalls(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<EnvironmentObject> objects;
  for (int i = 0; i < 14; ++i) {
    EnvironmentObject o;
    o.name = "solid" + std::to_string(i);
    if (i % 5 == 4) {
      o.primitive = Sphere{0.01 + 0.05 * std::abs(u(rng))};
    } else {
      o.primitive = Cylinder{i % 2 == 0 ? 0.012 : 0.012 + 0.04 * std::abs(u(rng)),
                             0.1 + 0.5 * std::abs(u(rng))};
    }
    placeAtRandom(o, rng, i % 3 != 0);
    objects.push_back(o);
  }
  EnvironmentObject pole;
  pole.name = "pole";
  pole.primitive = Cylinder{0.02, 4.0};
  pole.X_WO.translation() = Eigen::Vector3d(0.25, 0.1, 0);
  objects.push_back(pole);
  pole.name = "tilted_pole";
  pole.X_WO = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()) *
              Eigen::Translation3d(Eigen::Vector3d(-0.2, 0.05, 0));
  objects.push_back(pole);
  return objects;
}

}  // namespace octomotion::test
