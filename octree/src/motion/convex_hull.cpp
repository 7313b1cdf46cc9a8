#include "octomotion/motion/convex_hull.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include <Eigen/Geometry>

namespace octomotion {

namespace {

std::uint64_t edgeKey(std::uint32_t from, std::uint32_t to) {
  return std::uint64_t{from} << 32 | to;
}

// The points' extent from their centroid, 0 for none.
double extentOf(const std::vector<Eigen::Vector3d>& points) {
  if (points.empty()) return 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) centre += p;
  centre /= static_cast<double>(points.size());
  double extent = 0.0;
  for (const Eigen::Vector3d& p : points) extent = std::max(extent, (p - centre).norm());
  return extent;
}

struct Face {
  std::array<std::uint32_t, 3> v;
  Eigen::Vector3d normal;  // unit, outward
  double offset;           // normal . p of the face's points
  bool alive;
};

}  // namespace

bool isClosedConvexSurface(const std::vector<Eigen::Vector3d>& points,
                           const std::vector<std::array<std::uint32_t, 3>>& triangles,
                           double tolerance) {
  if (triangles.size() < 4 || !(tolerance >= 0)) return false;
  std::unordered_map<std::uint64_t, int> directed;
  std::vector<char> used(points.size(), 0);
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = t[static_cast<std::size_t>(k)];
      const std::uint32_t j = t[static_cast<std::size_t>((k + 1) % 3)];
      if (i >= points.size() || i == j) return false;
      used[i] = 1;
      if (++directed[edgeKey(i, j)] != 1) return false;  // an edge twice the same way
    }
  }
  // Closed and consistently turned: every edge is met once each way.
  for (const auto& [key, count] : directed) {
    const auto from = static_cast<std::uint32_t>(key >> 32);
    const auto to = static_cast<std::uint32_t>(key & 0xffffffffu);
    if (directed.find(edgeKey(to, from)) == directed.end()) return false;
  }
  for (const auto& t : triangles) {
    const Eigen::Vector3d& a = points[t[0]];
    const Eigen::Vector3d n = (points[t[1]] - a).cross(points[t[2]] - a);
    const double length = n.norm();
    if (!(length > 0) || !std::isfinite(length)) return false;
    const Eigen::Vector3d unit = n / length;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (used[i] && unit.dot(points[i] - a) > tolerance) return false;
    }
  }
  return true;
}

std::optional<std::vector<std::array<std::uint32_t, 3>>> convexHullTriangles(
    const std::vector<Eigen::Vector3d>& points) {
  const std::size_t n = points.size();
  if (n < 4 || n > kMaxHullPoints) return std::nullopt;
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) return std::nullopt;
  }
  const double extent = extentOf(points);
  // Far above the rounding of a plane's distance, far below any length that matters.
  const double eps = 1e-12 * std::max(extent, 1e-300);
  if (!(extent > 0)) return std::nullopt;

  // A first tetrahedron from far-apart points: the lowest x, the farthest from it, the farthest
  // from their line, the farthest from their plane.
  std::array<std::uint32_t, 4> s{};
  for (std::uint32_t i = 1; i < n; ++i) {
    if (points[i].x() < points[s[0]].x()) s[0] = i;
  }
  auto farthest = [&](auto&& distance) {
    std::uint32_t best = 0;
    double far = -1;
    for (std::uint32_t i = 0; i < n; ++i) {
      const double d = distance(points[i]);
      if (d > far) {
        far = d;
        best = i;
      }
    }
    return std::make_pair(best, far);
  };
  const Eigen::Vector3d& p0 = points[s[0]];
  auto [i1, d1] = farthest([&](const Eigen::Vector3d& p) { return (p - p0).norm(); });
  if (!(d1 > 1e3 * eps)) return std::nullopt;
  s[1] = i1;
  const Eigen::Vector3d axis = (points[s[1]] - p0).normalized();
  auto [i2, d2] = farthest([&](const Eigen::Vector3d& p) { return axis.cross(p - p0).norm(); });
  if (!(d2 > 1e3 * eps)) return std::nullopt;
  s[2] = i2;
  const Eigen::Vector3d across = axis.cross(points[s[2]] - p0).normalized();
  auto [i3, d3] = farthest([&](const Eigen::Vector3d& p) { return std::abs(across.dot(p - p0)); });
  if (!(d3 > 1e3 * eps)) return std::nullopt;
  s[3] = i3;

  std::vector<Face> faces;
  std::unordered_map<std::uint64_t, std::size_t> face_of;  // directed edge -> its face
  auto addFace = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const Eigen::Vector3d cross = (points[b] - points[a]).cross(points[c] - points[a]);
    const double length = cross.norm();
    if (!(length > eps * extent)) return false;  // too thin to have a plane
    const Eigen::Vector3d unit = cross / length;
    faces.push_back({{a, b, c}, unit, unit.dot(points[a]), true});
    const std::size_t f = faces.size() - 1;
    face_of[edgeKey(a, b)] = f;
    face_of[edgeKey(b, c)] = f;
    face_of[edgeKey(c, a)] = f;
    return true;
  };
  const Eigen::Vector3d inside = (points[s[0]] + points[s[1]] + points[s[2]] + points[s[3]]) / 4;
  const std::array<std::array<int, 3>, 4> tetra = {{{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}};
  for (const auto& corners : tetra) {
    std::uint32_t a = s[static_cast<std::size_t>(corners[0])];
    std::uint32_t b = s[static_cast<std::size_t>(corners[1])];
    const std::uint32_t c = s[static_cast<std::size_t>(corners[2])];
    if ((points[b] - points[a]).cross(points[c] - points[a]).dot(inside - points[a]) > 0) {
      std::swap(a, b);  // turned to face away from the inside
    }
    if (!addFace(a, b, c)) return std::nullopt;
  }

  // The faces still on the hull (the others stay in `faces`, dead, so indices hold).
  std::vector<std::size_t> alive(faces.size());
  for (std::size_t f = 0; f < alive.size(); ++f) alive[f] = f;
  std::vector<std::size_t> visible;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> horizon;
  std::unordered_set<std::size_t> seen;
  for (std::uint32_t p = 0; p < n; ++p) {
    if (p == s[0] || p == s[1] || p == s[2] || p == s[3]) continue;
    visible.clear();
    for (const std::size_t f : alive) {
      if (faces[f].normal.dot(points[p]) - faces[f].offset > eps) visible.push_back(f);
    }
    if (visible.empty()) continue;  // inside, or within eps of the hull
    seen.clear();
    seen.insert(visible.begin(), visible.end());
    // The horizon: edges of visible faces whose other face is not visible.
    horizon.clear();
    for (const std::size_t f : visible) {
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = faces[f].v[static_cast<std::size_t>(k)];
        const std::uint32_t b = faces[f].v[static_cast<std::size_t>((k + 1) % 3)];
        const auto other = face_of.find(edgeKey(b, a));
        if (other == face_of.end()) return std::nullopt;
        if (seen.count(other->second) == 0) horizon.emplace_back(a, b);
      }
    }
    for (const std::size_t f : visible) {
      faces[f].alive = false;
      for (int k = 0; k < 3; ++k) {
        face_of.erase(edgeKey(faces[f].v[static_cast<std::size_t>(k)],
                              faces[f].v[static_cast<std::size_t>((k + 1) % 3)]));
      }
    }
    const std::size_t first_new = faces.size();
    for (const auto& [a, b] : horizon) {
      if (!addFace(a, b, p)) return std::nullopt;
    }
    alive.erase(
        std::remove_if(alive.begin(), alive.end(), [&](std::size_t f) { return !faces[f].alive; }),
        alive.end());
    for (std::size_t f = first_new; f < faces.size(); ++f) alive.push_back(f);
  }
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (const Face& f : faces) {
    if (f.alive) triangles.push_back(f.v);
  }
  if (!isClosedConvexSurface(points, triangles, 64 * eps)) return std::nullopt;
  return triangles;
}

}  // namespace octomotion
