#include "octomotion/tools/building_scene.h"

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/error.h"

namespace octomotion::tools {
namespace {

struct Box {
  Eigen::Vector3d min, max;
};

// Binary STL: each box as 12 outward-facing triangles (a closed shell).
void writeStl(const std::string& path, const std::vector<Box>& boxes) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw FileError(path, "cannot be written");
  char header[80] = {};
  std::strncpy(header, "octomotion make-building", sizeof(header) - 1);
  out.write(header, sizeof(header));
  const auto count = static_cast<std::uint32_t>(boxes.size() * 12);
  out.write(reinterpret_cast<const char*>(&count), sizeof(count));  // little-endian hosts
  auto put = [&](const Eigen::Vector3d& v) {
    const std::array<float, 3> f = {static_cast<float>(v.x()), static_cast<float>(v.y()),
                                    static_cast<float>(v.z())};
    out.write(reinterpret_cast<const char*>(f.data()), sizeof(f));
  };
  // Faces as corner indices (bit 0 = x max, bit 1 = y max, bit 2 = z max), counter-clockwise
  // seen from outside.
  static constexpr int kFaces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                       {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const Box& b : boxes) {
    auto corner = [&](int c) {
      return Eigen::Vector3d((c & 1) ? b.max.x() : b.min.x(), (c & 2) ? b.max.y() : b.min.y(),
                             (c & 4) ? b.max.z() : b.min.z());
    };
    for (const auto& f : kFaces) {
      const Eigen::Vector3d p0 = corner(f[0]), p1 = corner(f[1]), p2 = corner(f[2]),
                            p3 = corner(f[3]);
      const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0).normalized();
      for (const auto& tri : {std::array<Eigen::Vector3d, 3>{p0, p1, p2},
                              std::array<Eigen::Vector3d, 3>{p0, p2, p3}}) {
        put(n);
        for (const Eigen::Vector3d& v : tri) put(v);
        const std::uint16_t attribute = 0;
        out.write(reinterpret_cast<const char*>(&attribute), sizeof(attribute));
      }
    }
  }
  if (!out) throw FileError(path, "write failed");
}

// splitmix64: the same sequence on every platform (std distributions are not).
struct Rng {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
};

// A wall between pillars on a grid line, from `a` to `b` along `axis` (0: x, 1: y) at `across`
// on the other axis, with a door at [door, door + width] when `door` >= 0.
void addWall(std::vector<Box>& boxes, const BuildingOptions& o, int axis, double a, double b,
             double across, double door) {
  const double h = o.wall_thickness / 2;
  auto box = [&](double from, double to, double z0, double z1) {
    Box w;
    w.min[axis] = from;
    w.max[axis] = to;
    w.min[1 - axis] = across - h;
    w.max[1 - axis] = across + h;
    w.min.z() = z0;
    w.max.z() = z1;
    boxes.push_back(w);
  };
  if (door < 0) {
    box(a, b, 0, o.wall_height);
    return;
  }
  box(a, door, 0, o.wall_height);
  box(door + o.door_width, b, 0, o.wall_height);
  box(door, door + o.door_width, o.door_height, o.wall_height);  // the lintel
}

std::string number(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

void check(const BuildingOptions& o) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw InvalidArgument("make-building: " + what);
  };
  require(o.rooms_x >= 1 && o.rooms_y >= 1 && o.rooms_x * o.rooms_y >= 2 && o.rooms_x <= 64 &&
              o.rooms_y <= 64,
          "expected 2 to 4096 rooms, 1 to 64 a side");
  for (double v : {o.room_size, o.wall_height, o.wall_thickness, o.door_width, o.door_height,
                   o.body_long_leg, o.body_short_leg, o.body_section, o.time}) {
    require(std::isfinite(v) && v > 0, "every size and the time must be positive and finite");
  }
  require(o.door_width + o.wall_thickness + 0.2 <= o.room_size, "the door does not fit its wall");
  require(o.door_height < o.wall_height, "the door must be lower than the wall");
  require(o.body_short_leg + o.body_section < o.door_height && o.body_section < o.door_width,
          "the body does not pass a door standing up");
  require(std::hypot(o.body_long_leg, o.body_short_leg) + o.wall_thickness < o.room_size &&
              o.body_short_leg < o.wall_height,
          "the body does not turn in a room");
}

}  // namespace

std::string writeBuildingScene(const std::string& dir, const BuildingOptions& o) {
  check(o);
  std::filesystem::create_directories(dir);
  const int nx = o.rooms_x, ny = o.rooms_y;
  const double s = o.room_size, t = o.wall_thickness, h = t / 2;

  // The doors: a random spanning tree of the room grid (Kruskal over shuffled walls).
  struct Edge {
    int axis;  // 0: the wall runs along x (between rooms (i, j-1) and (i, j)); 1: along y
    int i, j;
  };
  std::vector<Edge> walls;
  for (int j = 1; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) walls.push_back({0, i, j});
  }
  for (int i = 1; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) walls.push_back({1, i, j});
  }
  Rng rng{o.seed};
  for (std::size_t k = walls.size(); k > 1; --k) {
    std::swap(walls[k - 1], walls[static_cast<std::size_t>(rng.next() % k)]);
  }
  std::vector<int> parent(static_cast<std::size_t>(nx * ny));
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int r) {
    while (parent[static_cast<std::size_t>(r)] != r) r = parent[static_cast<std::size_t>(r)];
    return r;
  };
  std::vector<Box> boxes;
  const double margin = 0.1;  // between a door and a pillar
  for (const Edge& e : walls) {
    const int a = e.axis == 0 ? (e.j - 1) * nx + e.i : e.j * nx + e.i - 1;
    const int b = e.j * nx + e.i;
    const int ra = root(a), rb = root(b);
    double door = -1;
    if (ra != rb) {
      parent[static_cast<std::size_t>(ra)] = rb;
      const double start = (e.axis == 0 ? e.i : e.j) * s + h + margin;
      door = start + rng.uniform() * (s - t - 2 * margin - o.door_width);
    }
    if (e.axis == 0) {
      addWall(boxes, o, 0, e.i * s + h, (e.i + 1) * s - h, e.j * s, door);
    } else {
      addWall(boxes, o, 1, e.j * s + h, (e.j + 1) * s - h, e.i * s, door);
    }
  }
  // The outer walls and the pillars at every grid node.
  for (int i = 0; i < nx; ++i) {
    addWall(boxes, o, 0, i * s + h, (i + 1) * s - h, 0, -1);
    addWall(boxes, o, 0, i * s + h, (i + 1) * s - h, ny * s, -1);
  }
  for (int j = 0; j < ny; ++j) {
    addWall(boxes, o, 1, j * s + h, (j + 1) * s - h, 0, -1);
    addWall(boxes, o, 1, j * s + h, (j + 1) * s - h, nx * s, -1);
  }
  for (int i = 0; i <= nx; ++i) {
    for (int j = 0; j <= ny; ++j) {
      boxes.push_back({{i * s - h, j * s - h, 0}, {i * s + h, j * s + h, o.wall_height}});
    }
  }
  const double slab = 0.2;
  boxes.push_back({{-h, -h, -slab}, {nx * s + h, ny * s + h, 0}});
  boxes.push_back({{-h, -h, o.wall_height}, {nx * s + h, ny * s + h, o.wall_height + slab}});
  const std::filesystem::path folder(dir);
  writeStl((folder / "building.stl").string(), boxes);

  // The L: the long leg along x, the short one along y, centred on its bounding box.
  const double c = o.body_section;
  const Eigen::Vector3d centre(o.body_long_leg / 2, o.body_short_leg / 2, c / 2);
  std::vector<Box> body = {
      {Eigen::Vector3d(0, 0, 0) - centre, Eigen::Vector3d(o.body_long_leg, c, c) - centre},
      {Eigen::Vector3d(0, c, 0) - centre, Eigen::Vector3d(c, o.body_short_leg, c) - centre}};
  writeStl((folder / "l_body.stl").string(), body);

  const std::string scene = (folder / "building.yaml").string();
  std::ofstream out(scene);
  if (!out) throw FileError(scene, "cannot be written");
  const double z = c / 2 + 0.3;
  out << "# Generated by octomotion make-building (tools/src/building_scene.cpp), seed " << o.seed
      << ": " << nx << " x " << ny << " rooms of " << number(s)
      << " m, doors of a random spanning tree.\n"
      << "name: building\n"
      << "robot:\n  mesh: l_body.stl\n"
      << "environment:\n  - {name: building, mesh: {file: building.stl}}\n"
      << "octree:\n  resolution: auto\n  rounding: conservative\n  checker: octree-fused\n"
      << "problem:\n"
      << "  start: {xyz: [" << number(s / 2) << ", " << number(s / 2) << ", " << number(z)
      << "], rpy: [0, 0, 0]}\n"
      << "  goal: {xyz: [" << number((nx - 0.5) * s) << ", " << number((ny - 0.5) * s) << ", "
      << number(z) << "], rpy: [0, 0, 1.5707963267948966]}\n"
      << "  bounds: {min: [0, 0, 0], max: [" << number(nx * s) << ", " << number(ny * s) << ", "
      << number(o.wall_height) << "]}\n"
      << "  planner: RRTConnect\n  time: " << number(o.time) << "\n  seed: 1\n";
  if (!out) throw FileError(scene, "write failed");
  return scene;
}

}  // namespace octomotion::tools
