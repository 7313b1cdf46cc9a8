// The boundary of a point set's convex hull as triangles, and the check that makes a climb along
// its edges an exact support search: on a closed convex surface whose planes hold every point,
// a vertex no neighbour beats along a direction is the highest of all (ConvexPoints::hullOf).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

namespace octomotion {

// Point sets larger than this get no hull (the incremental build is quadratic).
inline constexpr std::size_t kMaxHullPoints = 4096;

// The hull's boundary as triangles over indices into `points`, each counter-clockwise seen
// from outside, built incrementally (points within a trillionth of the set's size of a face
// are left inside it). Nothing when the points span no volume, are more than kMaxHullPoints or
// not finite, or when the triangles fail isClosedConvexSurface.
std::optional<std::vector<std::array<std::uint32_t, 3>>> convexHullTriangles(
    const std::vector<Eigen::Vector3d>& points);

// True when `triangles` (indices into `points`) form a closed surface, every edge in exactly two
// of them and in opposite directions, none degenerate, and every point whose index they use
// lies on the inner side of every triangle's plane, up to `tolerance` (a distance).
bool isClosedConvexSurface(const std::vector<Eigen::Vector3d>& points,
                           const std::vector<std::array<std::uint32_t, 3>>& triangles,
                           double tolerance);

}  // namespace octomotion
