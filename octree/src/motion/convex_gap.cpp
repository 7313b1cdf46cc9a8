#include "octomotion/motion/convex_gap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "octomotion/error.h"
#include "octomotion/motion/convex_hull.h"

namespace octomotion {

ConvexPoints::ConvexPoints(const std::vector<Eigen::Vector3d>& points, double radius)
    : radius_(radius) {
  store(points);
}

namespace {

// Point sets larger than this are split into clusters of at most kClusterPoints.
constexpr std::size_t kClusteredFrom = 64;
constexpr std::size_t kClusterPoints = 16;

}  // namespace

std::vector<std::uint32_t> ConvexPoints::store(const std::vector<Eigen::Vector3d>& points) {
  if (points.empty()) throw InvalidArgument("ConvexPoints: no points");
  if (!(radius_ >= 0) || !std::isfinite(radius_)) {
    throw InvalidArgument("ConvexPoints: the radius must be finite and >= 0");
  }
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) throw InvalidArgument("ConvexPoints: a point is not finite");
    centroid_ += p;
  }
  centroid_ /= static_cast<double>(points.size());
  for (const Eigen::Vector3d& p : points) reach_ = std::max(reach_, (p - centroid_).norm());
  // order[k]: the given index of stored point k.
  std::vector<std::uint32_t> order;
  if (points.size() >= kClusteredFrom) {
    clusters_ = clusterPoints(points, kClusterPoints, order);
    // Far above rounding in the bound, so no skipped cluster holds a higher point.
    for (PointCluster& c : clusters_) c.radius += 1e-12 * (c.radius + c.centre.norm());
  } else {
    order.resize(points.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<std::uint32_t>(i);
  }
  x_.reserve(points.size());
  y_.reserve(points.size());
  z_.reserve(points.size());
  std::vector<std::uint32_t> index(points.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Eigen::Vector3d& p = points[order[k]];
    x_.push_back(p.x());
    y_.push_back(p.y());
    z_.push_back(p.z());
    index[order[k]] = static_cast<std::uint32_t>(k);
  }
  return index;
}

ConvexPoints::ConvexPoints(const std::vector<Eigen::Vector3d>& points,
                           const std::vector<std::array<std::uint32_t, 3>>& triangles,
                           double radius)
    : radius_(radius) {
  const std::vector<std::uint32_t> index = store(points);
  std::vector<std::vector<std::uint32_t>> adjacent(points.size());
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = t[static_cast<std::size_t>(k)];
      const std::uint32_t j = t[static_cast<std::size_t>((k + 1) % 3)];
      if (i >= points.size() || j >= points.size()) {
        throw InvalidArgument("ConvexPoints: a triangle's index is out of range");
      }
      if (i == j) continue;
      adjacent[index[i]].push_back(index[j]);
      adjacent[index[j]].push_back(index[i]);
    }
  }
  if (triangles.empty()) return;
  first_.push_back(0);
  for (auto& list : adjacent) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    neighbours_.insert(neighbours_.end(), list.begin(), list.end());
    first_.push_back(static_cast<std::uint32_t>(neighbours_.size()));
  }
  // Each cell's support point at the direction through its centre.
  for (int face = 0; face < 6; ++face) {
    const int k = face / 2;
    for (int u = 0; u < kStartCells; ++u) {
      for (int v = 0; v < kStartCells; ++v) {
        Eigen::Vector3d d;
        d[k] = face % 2 ? -1.0 : 1.0;
        d[(k + 1) % 3] = -1.0 + (2.0 * u + 1.0) / kStartCells;
        d[(k + 2) % 3] = -1.0 + (2.0 * v + 1.0) / kStartCells;
        start_[static_cast<std::size_t>((face * kStartCells + u) * kStartCells + v)] =
            static_cast<std::uint32_t>(supportIndex(d));
      }
    }
  }
}

std::size_t ConvexPoints::climbStart(const Eigen::Vector3d& d) const {
  // The face of the cube of directions that d crosses (its largest component), then the cell
  // there: the other two components over the largest, from -1 to 1, in kStartCells steps.
  const double ax = std::abs(d.x()), ay = std::abs(d.y()), az = std::abs(d.z());
  int k = 2;
  double most = az;
  if (ax >= ay && ax >= az) {
    k = 0;
    most = ax;
  } else if (ay >= az) {
    k = 1;
    most = ay;
  }
  // Zero, NaN, or so small or large that the scale below would overflow: any point starts
  // (where the climb starts does not change what it finds on a hull).
  if (!(most > 1e-300) || !(most < 1e300)) return start_[0];
  // c + most is within [0, 2 most], so the cell's index is within [0, kStartCells]; a NaN
  // component falls in cell 0.
  const double over = kStartCells / (2 * most);
  auto cell = [&](double c) {
    const double at = (c + most) * over;
    return at >= 1.0 ? std::min(static_cast<int>(at), kStartCells - 1) : 0;
  };
  const int face = 2 * k + (d[k] < 0 ? 1 : 0);
  const int u = cell(d[(k + 1) % 3]), v = cell(d[(k + 2) % 3]);
  return start_[static_cast<std::size_t>((face * kStartCells + u) * kStartCells + v)];
}

std::size_t ConvexPoints::climbSupport(const Eigen::Vector3d& d) const {
  if (neighbours_.empty()) return supportIndex(d);
  const double dx = d.x(), dy = d.y(), dz = d.z();
  std::size_t at = climbStart(d);
  double value = x_[at] * dx + y_[at] * dy + z_[at] * dz;
  // Each step strictly increases the value, so the climb ends.
  for (;;) {
    std::size_t next = at;
    for (std::uint32_t k = first_[at]; k < first_[at + 1]; ++k) {
      const std::uint32_t j = neighbours_[k];
      const double v = x_[j] * dx + y_[j] * dy + z_[j] * dz;
      if (v > value) {
        value = v;
        next = j;
      }
    }
    if (next == at) return at;
    at = next;
  }
}

std::size_t ConvexPoints::supportIndexIn(const Eigen::Vector3d& d, std::size_t begin,
                                         std::size_t end, double& value) const {
  const double dx = d.x(), dy = d.y(), dz = d.z();
  std::size_t best = begin;
  for (std::size_t i = begin; i < end; ++i) {
    const double v = x_[i] * dx + y_[i] * dy + z_[i] * dz;
    if (v > value) {
      value = v;
      best = i;
    }
  }
  return best;
}

std::size_t ConvexPoints::supportIndex(const Eigen::Vector3d& d) const {
  if (box_corners_) {
    // The corner on the side of each positive component: the highest of the eight (either
    // corner of an axis along which d is 0).
    return static_cast<std::size_t>((d.x() > 0 ? 1 : 0) | (d.y() > 0 ? 2 : 0) |
                                    (d.z() > 0 ? 4 : 0));
  }
  double value = -std::numeric_limits<double>::infinity();
  if (clusters_.empty()) return supportIndexIn(d, 0, x_.size(), value);
  // The cluster whose centre is highest first: its best point makes most bounds fall short.
  std::size_t start = 0;
  double start_value = -std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < clusters_.size(); ++k) {
    const double v = d.dot(clusters_[k].centre);
    if (v > start_value) {
      start_value = v;
      start = k;
    }
  }
  std::size_t best = supportIndexIn(d, clusters_[start].begin, clusters_[start].end, value);
  const double norm = d.norm();
  for (std::size_t k = 0; k < clusters_.size(); ++k) {
    const PointCluster& c = clusters_[k];
    if (k == start || d.dot(c.centre) + norm * c.radius <= value) continue;
    const double before = value;
    const std::size_t i = supportIndexIn(d, c.begin, c.end, value);
    if (value > before) best = i;
  }
  return best;
}

namespace {

// GJK's simplex on the Minkowski difference a - b: its corners, newest last.
struct Simplex {
  std::array<Eigen::Vector3d, 4> p = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                      Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  int n = 0;
};

// The point of triangle (a, b, c) closest to the origin, and the corners of the feature it lies
// on (Ericson, Real-Time Collision Detection §5.1.5, with the query point at the origin).
Eigen::Vector3d closestOnTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c, Simplex& feature) {
  const Eigen::Vector3d ab = b - a, ac = c - a;
  const double d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= 0 && d2 <= 0) {
    feature.p[0] = a;
    feature.n = 1;
    return a;
  }
  const double d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= 0 && d4 <= d3) {
    feature.p[0] = b;
    feature.n = 1;
    return b;
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    feature.p[0] = a;
    feature.p[1] = b;
    feature.n = 2;
    return a + d1 / (d1 - d3) * ab;
  }
  const double d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= 0 && d5 <= d6) {
    feature.p[0] = c;
    feature.n = 1;
    return c;
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    feature.p[0] = a;
    feature.p[1] = c;
    feature.n = 2;
    return a + d2 / (d2 - d6) * ac;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    feature.p[0] = b;
    feature.p[1] = c;
    feature.n = 2;
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  }
  const double denom = 1 / (va + vb + vc);
  feature.p[0] = a;
  feature.p[1] = b;
  feature.p[2] = c;
  feature.n = 3;
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// The origin and `opposite` lie strictly on different sides of the plane through a, b, c.
bool originOutsideFace(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                       const Eigen::Vector3d& opposite) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  return (-a).dot(n) * (opposite - a).dot(n) < 0;
}

// Replaces the simplex by the smallest feature holding its point closest to the origin and
// returns that point; false when the origin is inside a tetrahedron or the simplex is
// degenerate (GJK then stops: not proven apart).
bool reduce(Simplex& s, Eigen::Vector3d& v) {
  if (s.n == 1) {
    v = s.p[0];
    return true;
  }
  if (s.n == 2) {
    const Eigen::Vector3d a = s.p[0], ab = s.p[1] - s.p[0];
    const double len2 = ab.squaredNorm();
    if (!(len2 > 0)) return false;
    const double t = -a.dot(ab) / len2;
    if (t <= 0) {
      s.n = 1;
    } else if (t >= 1) {
      s.p[0] = s.p[1];
      s.n = 1;
    }
    v = t <= 0 ? a : t >= 1 ? s.p[0] : Eigen::Vector3d(a + t * ab);
    return true;
  }
  if (s.n == 3) {
    Simplex feature;
    v = closestOnTriangle(s.p[0], s.p[1], s.p[2], feature);
    s = feature;
    return true;
  }
  // Tetrahedron: the best of the faces the origin lies outside of; none means inside.
  const Eigen::Vector3d &a = s.p[0], &b = s.p[1], &c = s.p[2], &d = s.p[3];
  const std::array<std::array<const Eigen::Vector3d*, 4>, 4> faces = {
      {{&a, &b, &c, &d}, {&a, &c, &d, &b}, {&a, &d, &b, &c}, {&b, &d, &c, &a}}};
  double best = std::numeric_limits<double>::infinity();
  Simplex best_feature;
  for (const auto& f : faces) {
    if (!originOutsideFace(*f[0], *f[1], *f[2], *f[3])) continue;
    Simplex feature;
    const Eigen::Vector3d q = closestOnTriangle(*f[0], *f[1], *f[2], feature);
    if (q.squaredNorm() < best) {
      best = q.squaredNorm();
      best_feature = feature;
      v = q;
    }
  }
  if (best_feature.n == 0) return false;
  s = best_feature;
  return true;
}

constexpr int kMaxIterations = 32;

}  // namespace

bool convexApart(const ConvexPoints& a, const ConvexPoints& b, const Eigen::Isometry3d& X_AB,
                 double gap, Eigen::Vector3d* direction_A) {
  if (a.empty() || b.empty()) return false;
  const Eigen::Matrix3d R_AB = X_AB.linear();
  const Eigen::Matrix3d R_BA = R_AB.transpose();
  const Eigen::Vector3d p_AB = X_AB.translation();
  // Apart along v (not unit) when min over a, b of v . (a - b) exceeds margin * |v|.
  const double margin = gap + a.radius() + b.radius();
  Eigen::Vector3d v = a.centroid() - (R_AB * b.centroid() + p_AB);
  if (direction_A != nullptr && direction_A->allFinite() && direction_A->squaredNorm() > 0) {
    v = *direction_A;
  }
  if (!(v.squaredNorm() > 0)) v = Eigen::Vector3d::UnitX();
  Simplex s;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    // w: the point of a - b that is lowest along v, from each set's support point.
    std::size_t ia = a.climbSupport(-v);
    std::size_t ib = b.climbSupport(R_BA * v);
    Eigen::Vector3d w = a.point(ia) - (R_AB * b.point(ib) + p_AB);
    double vw = v.dot(w);
    const double v2 = v.squaredNorm();
    if (vw > 0 && vw * vw > margin * margin * v2 && !(a.exactClimb() && b.exactClimb())) {
      // A climb may stop short of the support: the answer rests on every point.
      ia = a.exactSupport(-v);
      ib = b.exactSupport(R_BA * v);
      w = a.point(ia) - (R_AB * b.point(ib) + p_AB);
      vw = v.dot(w);
    }
    if (vw > 0 && vw * vw > margin * margin * v2) {
      if (direction_A != nullptr) *direction_A = v;
      return true;
    }
    // No progress left: |v| is the hulls' distance up to rounding, and it is not enough.
    if (v2 - vw <= 1e-9 * v2 || s.n == 4) return false;
    s.p[static_cast<std::size_t>(s.n++)] = w;
    // |v| bounds the distance from above: at most the margin, they cannot be apart by it.
    if (!reduce(s, v) || !(v.squaredNorm() > margin * margin)) return false;
  }
  return false;
}

namespace {

// The gap between a and b along v (not 0) over every point: min over a of u . a less max over
// b of u . (X_AB b), u = v / |v|, less the radii (the supports found exactly: exactSupport).
double gapOverEveryPoint(const ConvexPoints& a, const ConvexPoints& b, const Eigen::Matrix3d& R_AB,
                         const Eigen::Vector3d& p_AB, const Eigen::Vector3d& v) {
  const Eigen::Vector3d u = v.normalized();
  const Eigen::Vector3d w =
      a.point(a.exactSupport(-u)) - (R_AB * b.point(b.exactSupport(R_AB.transpose() * u)) + p_AB);
  return u.dot(w) - a.radius() - b.radius();
}

// Far above rounding in a support value, far below any distance that matters.
constexpr double kRounding = 1e-9;

}  // namespace

double convexDistanceBelow(const ConvexPoints& a, const ConvexPoints& b,
                           const Eigen::Isometry3d& X_AB, double cap, Eigen::Vector3d* direction_A,
                           double tolerance) {
  if (a.empty() || b.empty()) return 0.0;
  const Eigen::Matrix3d R_AB = X_AB.linear();
  const Eigen::Matrix3d R_BA = R_AB.transpose();
  const Eigen::Vector3d p_AB = X_AB.translation();
  const double radii = a.radius() + b.radius();
  // A given direction (an earlier answer's) is tried first: its gap over every point is a bound,
  // the answer when it reaches the cap. GJK itself starts from the centroids' difference, a
  // point of a - b (its length bounds the distance from above, which the stopping test needs).
  if (direction_A != nullptr && direction_A->allFinite() && direction_A->squaredNorm() > 0) {
    const double given = gapOverEveryPoint(a, b, R_AB, p_AB, *direction_A) - kRounding;
    if (given >= cap) return std::max(0.0, given);
  }
  Eigen::Vector3d v = a.centroid() - (R_AB * b.centroid() + p_AB);
  if (!(v.squaredNorm() > 0)) v = Eigen::Vector3d::UnitX();
  // The last non-zero direction, and the best gap found with the supports of every point and
  // its direction.
  Eigen::Vector3d last = v, best = v;
  double bound = -std::numeric_limits<double>::infinity();
  bool exact_supports = a.exactClimb() && b.exactClimb();
  Simplex s;
  for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
    last = v;
    std::size_t ia = exact_supports ? a.exactSupport(-v) : a.climbSupport(-v);
    std::size_t ib = exact_supports ? b.exactSupport(R_BA * v) : b.climbSupport(R_BA * v);
    Eigen::Vector3d w = a.point(ia) - (R_AB * b.point(ib) + p_AB);
    double vw = v.dot(w);
    const double len = v.norm();
    if (vw / len - radii >= cap && !exact_supports) {
      // A climb may stop short of the support: from here on every point is searched.
      exact_supports = true;
      ia = a.exactSupport(-v);
      ib = b.exactSupport(R_BA * v);
      w = a.point(ia) - (R_AB * b.point(ib) + p_AB);
      vw = v.dot(w);
    }
    if (exact_supports && vw / len - radii - kRounding > bound) {
      bound = vw / len - radii - kRounding;
      best = v;
    }
    if (bound >= cap) break;
    // No progress left (the distance found) or a full simplex: stop.
    if (len * len - vw <= tolerance * len * len || s.n == 4) break;
    s.p[static_cast<std::size_t>(s.n++)] = w;
    // The origin inside the simplex (the hulls overlap) or a degenerate simplex: stop.
    if (!reduce(s, v) || !(v.squaredNorm() > 0)) break;
  }
  if (!exact_supports) {
    bound = gapOverEveryPoint(a, b, R_AB, p_AB, last) - kRounding;
    best = last;
  }
  if (direction_A != nullptr) *direction_A = best;
  return std::max(0.0, bound);
}

ConvexPoints ConvexPoints::hullOf(const std::vector<Eigen::Vector3d>& points, double radius) {
  const std::optional<std::vector<std::array<std::uint32_t, 3>>> triangles =
      convexHullTriangles(points);
  if (!triangles) return ConvexPoints(points, radius);
  // The surface's vertices, renumbered; the other points lie inside but for rounding.
  std::vector<std::uint32_t> kept_index(points.size(), std::numeric_limits<std::uint32_t>::max());
  std::vector<Eigen::Vector3d> kept;
  std::vector<std::array<std::uint32_t, 3>> surface;
  for (const auto& t : *triangles) {
    std::array<std::uint32_t, 3> renumbered{};
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint32_t& i = kept_index[t[k]];
      if (i == std::numeric_limits<std::uint32_t>::max()) {
        i = static_cast<std::uint32_t>(kept.size());
        kept.push_back(points[t[k]]);
      }
      renumbered[k] = i;
    }
    surface.push_back(renumbered);
  }
  // A dropped point outside a face's plane (by rounding) is outside the hull by at most its
  // distance to the surface, which the radius takes up: the grown hull still holds it.
  std::vector<Eigen::Vector3d> normals;  // not unit: only their signs are read
  for (const auto& t : surface) {
    normals.push_back((kept[t[1]] - kept[t[0]]).cross(kept[t[2]] - kept[t[0]]));
  }
  double outside = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (kept_index[i] != std::numeric_limits<std::uint32_t>::max()) continue;
    const Eigen::Vector3d& p = points[i];
    bool out = false;
    for (std::size_t f = 0; f < surface.size() && !out; ++f) {
      out = normals[f].dot(p - kept[surface[f][0]]) > 0;
    }
    if (!out) continue;
    double nearest = std::numeric_limits<double>::infinity();
    Simplex feature;
    for (const auto& t : surface) {
      const Eigen::Vector3d q =
          closestOnTriangle(kept[t[0]] - p, kept[t[1]] - p, kept[t[2]] - p, feature);
      nearest = std::min(nearest, q.norm());
    }
    outside = std::max(outside, nearest);
  }
  // Twice the distance: far above the rounding of the distance and of the sum.
  const double grown = radius + 2 * outside;
  ConvexPoints hull(kept, surface, grown);
  hull.exact_climb_ = true;
  return hull;
}

ConvexPoints boxHull(const Eigen::Vector3d& half_extents) {
  if (!half_extents.allFinite() || !(half_extents.minCoeff() >= 0)) {
    throw InvalidArgument("boxHull: the half extents must be finite and >= 0");
  }
  const std::array<Eigen::Vector3d, 8> corners = boxCorners(half_extents);
  ConvexPoints hull(std::vector<Eigen::Vector3d>(corners.begin(), corners.end()));
  hull.box_corners_ = true;
  return hull;
}

std::array<Eigen::Vector3d, 8> boxCorners(const Eigen::Vector3d& half_extents) {
  std::array<Eigen::Vector3d, 8> corners;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d sign((k & 1) ? 1 : -1, (k & 2) ? 1 : -1, (k & 4) ? 1 : -1);
    corners[static_cast<std::size_t>(k)] = half_extents.cwiseProduct(sign);
  }
  return corners;
}

ConvexPoints ballHull(double radius) {
  return ConvexPoints({Eigen::Vector3d::Zero()}, radius);
}

ConvexPoints cylinderHull(double radius, double length, int sides) {
  if (!(radius >= 0) || !(length >= 0) || !std::isfinite(radius) || !std::isfinite(length)) {
    throw InvalidArgument("cylinderHull: the radius and length must be finite and >= 0");
  }
  if (sides < 3) throw InvalidArgument("cylinderHull: fewer than 3 sides");
  // A regular polygon whose edges touch the circle: its corners at radius / cos(pi / sides).
  const double corner = radius / std::cos(M_PI / sides);
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < sides; ++k) {
    const double angle = 2 * M_PI * k / sides;
    for (double z : {-length / 2, length / 2}) {
      points.emplace_back(corner * std::cos(angle), corner * std::sin(angle), z);
    }
  }
  return ConvexPoints::hullOf(points);  // a climb around the prism (flat ones: every point)
}

}  // namespace octomotion
