// Scenes made of COLLADA files the tests generate themselves, shaped like the OMPL.app models
// (SketchUp exports) on which conservative rounding once missed contacts (docs/validation.md,
// "Surfaces on voxel boundaries"): double-sided faces, so the solids have no inside by ray
// parity; node hierarchies with rotations and translations of hundreds of metres; Z-up and X-up;
// an inch unit; <lines> beside the faces; quads and pentagons as <polylist>; open sheets on the
// planes where the grid puts voxel boundaries (the environment's lowest faces).
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "generated_meshes.h"

namespace octomotion::test {

// Writes the scenes into `dir` (created if needed) and returns their files: an OMPL.app .cfg
// problem and two YAML scenes.
inline std::vector<std::string> writeColladaScenes(const std::string& dir) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  const Eigen::Vector3d ex = Eigen::Vector3d::UnitX(), ez = Eigen::Vector3d::UnitZ();
  std::vector<std::string> scenes;

  // 1. A body in a building, like OMPL.app's "Easy" (both in inches, Z-up): an L of two
  // double-sided boxes (about 55 x 48 x 54 inches), placed by a node turned half a turn about a
  // tilted axis and moved by (275, 297, 165); the building's floor, walls and a pillar are
  // double-sided slabs, some under a node moved by (101, 294, 0), some at the top level.
  {
    ColladaDocument robot;
    robot.unit_metres = 0.0254;
    robot.geometries.push_back(
        doubleSided(merged({boxQuads({-22.75, -24.5, 11.0}, {32.25, -12.75, 22.75}),
                            boxQuads({-22.75, -24.5, -31.25}, {-11.0, 23.5, 22.75})})));
    ColladaNode top;
    ColladaNode placed;
    placed.matrix = rigidMatrix(Eigen::Vector3d(0.9997, -0.0239, 0), M_PI, {274.97, 297.10, 165.5});
    placed.geometries = {0};
    top.children.push_back(placed);
    robot.nodes.push_back(top);
    writeCollada(dir + "/easy_like_robot.dae", robot);

    ColladaDocument building;
    building.unit_metres = 0.0254;
    const PolyMesh floor = doubleSided(boxQuads({-41.25, 0, -24.25}, {354, 10.25, 320.75}));
    const PolyMesh wall_a = doubleSided(boxQuads({-41.25, 10.25, -24.25}, {-31, 150, 320.75}));
    const PolyMesh wall_b = doubleSided(boxQuads({120, 10.25, 100}, {130, 150, 320.75}));
    const PolyMesh pillar = doubleSided(boxQuads({200, 10.25, 20}, {240, 150, 60}));
    building.geometries = {floor, wall_a, wall_b, pillar};
    ColladaNode scene_top;
    scene_top.geometries = {0, 1};
    ColladaNode moved;
    moved.matrix = rigidMatrix(ez, 0, {101.2104496, 293.8550907, 0});
    moved.geometries = {2, 3};
    scene_top.children.push_back(moved);
    building.nodes.push_back(scene_top);
    writeCollada(dir + "/easy_like_env.dae", building);

    std::ofstream cfg(dir + "/easy_like.cfg");
    cfg << "[problem]\nname=easy_like\nworld=easy_like_env.dae\nrobot=easy_like_robot.dae\n"
           "start.x=2.7\nstart.y=1.6\nstart.z=-2.0\nstart.axis.x=1\nstart.axis.y=0\n"
           "start.axis.z=0\nstart.theta=0\ngoal.x=2.7\ngoal.y=1.6\ngoal.z=-4.0\n"
           "goal.axis.x=0\ngoal.axis.y=1\ngoal.axis.z=0\ngoal.theta=3.14159\n"
           "volume.min.x=-1\nvolume.min.y=-0.5\nvolume.min.z=-11\nvolume.max.x=11.5\n"
           "volume.max.y=8\nvolume.max.z=0\n";
    scenes.push_back(dir + "/easy_like.cfg");
  }

  // 2. Open and one-sided geometry on voxel boundaries: a robot that is an open box (no lid,
  // single-sided quads) with a pentagon fin, three nodes deep (translate, quarter turn, 30
  // degrees); an X-up environment whose floor is an open sheet at its lowest plane, with a
  // double-sided wall and a closed box, plus a primitive.
  {
    ColladaDocument robot;
    robot.up_axis = "Y_UP";
    PolyMesh open_box = boxQuads({-0.2, -0.1, -0.15}, {0.2, 0.1, 0.15});
    open_box.faces.pop_back();  // no lid: not closed
    PolyMesh fin;
    fin.vertices = {{0.2, 0, 0}, {0.35, 0.05, 0}, {0.4, 0.15, 0}, {0.3, 0.2, 0}, {0.2, 0.1, 0}};
    fin.faces = {{0, 1, 2, 3, 4}};
    robot.geometries = {open_box, fin};
    ColladaNode a, b, c;
    a.matrix = rigidMatrix(ex, 0, {3.0, -2.0, 1.0});
    b.matrix = rigidMatrix(ez, M_PI / 2, {0, 0, 0});
    c.matrix = rigidMatrix(ex, M_PI / 6, {0.05, 0, 0});
    c.geometries = {0, 1};
    b.children.push_back(c);
    a.children.push_back(b);
    robot.nodes.push_back(a);
    writeCollada(dir + "/open_robot.dae", robot);

    ColladaDocument env;
    env.up_axis = "X_UP";
    env.geometries = {sheet(1.0, 4), doubleSided(boxQuads({-1, -1, 0}, {-0.9, 1, 0.8})),
                      fromTriangles(boxMesh(Eigen::Vector3d(0.15, 0.15, 0.15), 1))};
    ColladaNode floor;
    floor.geometries = {0, 1};
    ColladaNode block;
    block.matrix = rigidMatrix(ez, 0, {0.4, 0.3, 0.15});
    block.geometries = {2};
    floor.children.push_back(block);
    env.nodes.push_back(floor);
    writeCollada(dir + "/sheets_env.dae", env);

    std::ofstream yaml(dir + "/open_sheets.yaml");
    yaml << "name: open_sheets\nrobot:\n  mesh: open_robot.dae\n  center_vertices: true\n"
            "environment:\n  - name: sheets\n    mesh: {file: sheets_env.dae, keep_root_transform: "
            "false}\n  - name: post\n    box: {size: [0.1, 0.1, 0.6]}\n    pose: {xyz: [0.5, -0.5, "
            "0.3]}\noctree:\n  resolution: 0.05\nproblem:\n  start: {xyz: [-0.5, 0.5, 0.5]}\n"
            "  goal: {xyz: [0.5, 0.5, 0.5]}\n  bounds: {min: [-1.2, -1.2, -0.3], max: [1.2, 1.2, "
            "1.2]}\n";
    scenes.push_back(dir + "/open_sheets.yaml");
  }

  // 3. Thin double-sided panels at round coordinates, in metres, Z-up, a polylist robot of a
  // double-sided blob; resolution 2 cm, so the panels' faces fall on voxel boundaries.
  {
    ColladaDocument robot;
    std::mt19937_64 rng(7);
    robot.geometries = {doubleSided(fromTriangles(blobMesh(0.12, 0.3, rng))),
                        boxQuads({-0.02, -0.02, 0.1}, {0.02, 0.02, 0.3})};
    ColladaNode n;
    n.matrix = rigidMatrix(Eigen::Vector3d(1, 2, 3), 0.7, {120.0, -40.0, 15.0});
    n.geometries = {0, 1};
    robot.nodes.push_back(n);
    writeCollada(dir + "/blob_robot.dae", robot);

    ColladaDocument env;
    env.geometries = {doubleSided(sheet(0.5, 2)),
                      doubleSided(boxQuads({0.2, -0.5, 0}, {0.22, 0.5, 0.6}))};
    ColladaNode root;
    root.geometries = {0, 1};
    env.nodes.push_back(root);
    writeCollada(dir + "/panels_env.dae", env);

    std::ofstream yaml(dir + "/panels.yaml");
    yaml << "name: panels\nrobot:\n  mesh: blob_robot.dae\n  keep_root_transform: false\n"
            "  center_vertices: true\nenvironment:\n  - name: panels\n    mesh: {file: "
            "panels_env.dae, keep_root_transform: false}\noctree:\n  resolution: 0.02\n"
            "problem:\n  start: {xyz: [-0.3, 0, 0.3]}\n  goal: {xyz: [0.4, 0, 0.3]}\n"
            "  bounds: {min: [-0.6, -0.6, -0.2], max: [0.6, 0.6, 0.8]}\n";
    scenes.push_back(dir + "/panels.yaml");
  }
  return scenes;
}

// The scenes written once per process into a folder of the system's temporary directory.
inline const std::vector<std::string>& colladaSceneFiles() {
  static const std::vector<std::string> files = [] {
    const std::string dir = (std::filesystem::temp_directory_path() /
                             ("octomotion_collada_scenes_" + std::to_string(::getpid())))
                                .string();
    return writeColladaScenes(dir);
  }();
  return files;
}

}  // namespace octomotion::test
