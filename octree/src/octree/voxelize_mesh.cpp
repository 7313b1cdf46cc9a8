// Mesh builder. Same top-down descent as the primitives (Weng & Ahuja 1987 §4), but a cube is
// "partial" when a triangle touches its test box (Akenine-Moeller separating axes); a cube no
// triangle touches lies wholly inside or wholly outside the solid. Which one is decided by ray
// parity, but rarely by a ray of its own: two points joined by a box no triangle touches are on
// the same side, so a cube inherits the answer found for its parent's centre (class Status).
// Each cube only tests the triangles that touched its parent.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "internal/mesh.h"
#include "internal/voxelize.h"
#include "octomotion/octree/voxelize.h"

namespace octomotion {
namespace detail {
namespace {

// A triangle in grid coordinates, with what the separating-axis test against cubes needs
// precomputed: for each of the nine axes a = e_i x f_j (f_j the edges) the interval of the
// corners' projections and |a|_1, so that testing a cube of centre c and half side h on that
// axis costs one dot product with c.
struct GridTriangle {
  Eigen::Vector3d v0, v1, v2;  // corners
  Eigen::Vector3d lo, hi;      // bounding box
  Eigen::Vector3d normal;      // (v1 - v0) x (v2 - v1), not normalised
  double plane, normal_l1;     // normal . v0, |normal|_1
  struct Axis {
    Eigen::Vector3d a;
    double min, max, l1;
  };
  std::array<Axis, 9> axes;
};

GridTriangle makeTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c) {
  GridTriangle t;
  t.v0 = a;
  t.v1 = b;
  t.v2 = c;
  t.lo = a.cwiseMin(b).cwiseMin(c);
  t.hi = a.cwiseMax(b).cwiseMax(c);
  const Eigen::Vector3d edges[3] = {b - a, c - b, a - c};
  t.normal = edges[0].cross(edges[1]);
  t.plane = t.normal.dot(a);
  t.normal_l1 = t.normal.cwiseAbs().sum();
  std::size_t k = 0;
  for (const Eigen::Vector3d& f : edges) {
    for (int i = 0; i < 3; ++i) {
      GridTriangle::Axis& axis = t.axes[k++];
      axis.a = Eigen::Vector3d::Unit(i).cross(f);
      const double p0 = axis.a.dot(a), p1 = axis.a.dot(b), p2 = axis.a.dot(c);
      axis.min = std::min({p0, p1, p2});
      axis.max = std::max({p0, p1, p2});
      axis.l1 = axis.a.cwiseAbs().sum();
    }
  }
  return t;
}

// Does the triangle meet the closed cube of centre c and half side h >= 0? Separating axes
// (Akenine-Moeller): the cube's face normals, the triangle's normal, and the nine edge-by-axis
// cross products. Exact also for h = 0 (a point), where it is the point-on-triangle test.
bool touches(const GridTriangle& t, const Eigen::Vector3d& c, double h) {
  for (int i = 0; i < 3; ++i) {
    if (t.lo[i] > c[i] + h || t.hi[i] < c[i] - h) return false;
  }
  if (std::abs(t.normal.dot(c) - t.plane) > h * t.normal_l1) return false;
  for (const GridTriangle::Axis& axis : t.axes) {
    const double centre = axis.a.dot(c), r = h * axis.l1;
    if (axis.min - centre > r || axis.max - centre < -r) return false;
  }
  return true;
}

// touches() for a cube and for the same cube grown by `grow`, in one pass: 2 when the triangle
// touches the cube, 1 when it only touches the grown cube, 0 when it misses both.
int touchLevel(const GridTriangle& t, const Eigen::Vector3d& c, double h, double grow) {
  const double hg = h + grow;
  bool exact = true;
  for (int i = 0; i < 3; ++i) {
    const double gap = std::max(t.lo[i] - c[i], c[i] - t.hi[i]);
    if (gap > hg) return 0;
    exact &= gap <= h;
  }
  {
    const double gap = std::abs(t.normal.dot(c) - t.plane);
    if (gap > hg * t.normal_l1) return 0;
    exact &= gap <= h * t.normal_l1;
  }
  for (const GridTriangle::Axis& axis : t.axes) {
    const double centre = axis.a.dot(c);
    const double gap = std::max(axis.min - centre, centre - axis.max);
    if (gap > hg * axis.l1) return 0;
    exact &= gap <= h * axis.l1;
  }
  return exact ? 2 : 1;
}

// Point-in-solid by the parity of crossings of the ray from the point towards +z. Triangles are
// binned by their xy bounding boxes, so a query looks at one bin. Rays through edges and
// vertices: the point is moved by an infinitesimal (eps, eps^2) in xy (simulation of
// simplicity), decided exactly from the edge's direction; every edge function is evaluated with
// its endpoints in one canonical order, so the two triangles sharing an edge always get exactly
// opposite signs and the ray crosses exactly one of them.
class ParityCaster {
 public:
  explicit ParityCaster(const std::vector<GridTriangle>& triangles) {
    lo_ = Eigen::Vector2d::Constant(INFINITY);
    hi_ = Eigen::Vector2d::Constant(-INFINITY);
    flats_.reserve(triangles.size());
    for (const GridTriangle& t : triangles) {
      const Eigen::Vector2d a = t.v0.head<2>(), b = t.v1.head<2>(), c = t.v2.head<2>();
      // A triangle whose projection has a repeated corner has no area: no ray crosses it.
      if (a == b || b == c || c == a || t.normal.z() == 0.0) continue;
      Flat f;
      f.lo = t.lo.head<2>();
      f.hi = t.hi.head<2>();
      f.zmax = t.hi.z();
      f.edge[0] = Edge::of(a, b);
      f.edge[1] = Edge::of(b, c);
      f.edge[2] = Edge::of(c, a);
      f.anchor = t.v0;
      f.gx = -t.normal.x() / t.normal.z();
      f.gy = -t.normal.y() / t.normal.z();
      lo_ = lo_.cwiseMin(f.lo);
      hi_ = hi_.cwiseMax(f.hi);
      flats_.push_back(f);
    }
    if (flats_.empty()) return;
    // About one triangle per bin along a typical column.
    const Eigen::Vector2d extent = (hi_ - lo_).cwiseMax(1e-9);
    const double bin = std::sqrt(extent.x() * extent.y() / static_cast<double>(flats_.size()));
    nx_ = std::clamp(static_cast<int>(std::ceil(extent.x() / bin)), 1, 4096);
    ny_ = std::clamp(static_cast<int>(std::ceil(extent.y() / bin)), 1, 4096);
    scale_ = Eigen::Vector2d(nx_ / extent.x(), ny_ / extent.y());
    std::vector<std::uint32_t> count(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    auto forBins = [&](const Flat& f, auto&& visit) {
      const int x0 = binX(f.lo.x()), x1 = binX(f.hi.x()), y0 = binY(f.lo.y()), y1 = binY(f.hi.y());
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) visit(static_cast<std::size_t>(y) * nx_ + x);
    };
    for (const Flat& f : flats_) forBins(f, [&](std::size_t b) { ++count[b + 1]; });
    for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
    start_ = count;
    items_.resize(count.back());
    for (std::uint32_t i = 0; i < flats_.size(); ++i) {
      forBins(flats_[i], [&](std::size_t b) { items_[count[b]++] = i; });
    }
  }

  bool inside(const Eigen::Vector3d& p) const {
    if (items_.empty()) return false;
    // Outside the xy extent the ray meets nothing. (Same comparisons as the binning.)
    if (!(p.x() >= lo_.x() && p.x() <= hi_.x() && p.y() >= lo_.y() && p.y() <= hi_.y())) {
      return false;
    }
    const std::size_t b = static_cast<std::size_t>(binY(p.y())) * nx_ + binX(p.x());
    const Eigen::Vector2d q = p.head<2>();
    bool odd = false;
    for (std::uint32_t i = start_[b]; i < start_[b + 1]; ++i) {
      const Flat& f = flats_[items_[i]];
      // The moved point q + (eps, eps^2) is in the bounding box iff lo <= q < hi.
      if (!(f.zmax > p.z()) || q.x() < f.lo.x() || q.x() >= f.hi.x() || q.y() < f.lo.y() ||
          q.y() >= f.hi.y()) {
        continue;
      }
      const bool s = f.edge[0].positive(q);
      if (f.edge[1].positive(q) != s || f.edge[2].positive(q) != s) continue;
      const double z = f.anchor.z() + f.gx * (q.x() - f.anchor.x()) + f.gy * (q.y() - f.anchor.y());
      if (z > p.z()) odd = !odd;
    }
    return odd;
  }

 private:
  // A projected edge kept with its endpoints in one canonical (x, then y) order, so that the
  // two triangles sharing it compute the very same number and differ only in `flip`.
  struct Edge {
    Eigen::Vector2d u, d;  // canonical first endpoint, and second minus first (d.x >= 0)
    bool flip;             // the triangle runs the edge from the second endpoint to the first
    static Edge of(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
      const bool swap = b.x() < a.x() || (b.x() == a.x() && b.y() < a.y());
      const Eigen::Vector2d& u = swap ? b : a;
      const Eigen::Vector2d& v = swap ? a : b;
      return {u, v - u, swap};
    }
    // Is q + (eps, eps^2) strictly left of the directed edge? Never on it.
    bool positive(const Eigen::Vector2d& q) const {
      const double w = d.x() * (q.y() - u.y()) - d.y() * (q.x() - u.x());
      // On the line: w(q + (eps, eps^2)) = -d.y eps + d.x eps^2, and d.x >= 0.
      const bool left = w > 0.0 || (w == 0.0 && (d.y() < 0.0 || (d.y() == 0.0 && d.x() > 0.0)));
      return left != flip;
    }
  };
  struct Flat {
    Eigen::Vector2d lo, hi;  // projected bounding box
    double zmax;
    std::array<Edge, 3> edge;
    Eigen::Vector3d anchor;  // a corner; plane z = anchor.z + gx (x - anchor.x) + gy (...)
    double gx, gy;
  };

  int binX(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - lo_.x()) * scale_.x())), 0, nx_ - 1);
  }
  int binY(double y) const {
    return std::clamp(static_cast<int>(std::floor((y - lo_.y()) * scale_.y())), 0, ny_ - 1);
  }

  Eigen::Vector2d lo_, hi_, scale_;
  int nx_ = 0, ny_ = 0;
  std::vector<Flat> flats_;
  std::vector<std::uint32_t> start_;  // items of bin b: items_[start_[b] .. start_[b + 1])
  std::vector<std::uint32_t> items_;  // indices into flats_
};

// Whether a point is in the solid, found out at most once: by ray parity, or inherited from a
// point joined to it by a box no triangle touches (no surface between them, so same side).
class Status {
 public:
  enum State : std::int8_t { kUnknown, kOut, kIn };
  Status() = default;
  explicit Status(State state) : state_(state) {}
  State state() const { return state_; }
  bool inside(const ParityCaster& caster, const Eigen::Vector3d& p) {
    if (state_ == kUnknown) state_ = caster.inside(p) ? kIn : kOut;
    return state_ == kIn;
  }

 private:
  State state_ = kUnknown;
};

class MeshDescent {
 public:
  // caster == nullptr: a surface shell (voxels the triangles touch), whatever the rounding.
  MeshDescent(const std::vector<GridTriangle>& triangles, const ParityCaster* caster,
              Rounding rounding, int depth)
      : triangles_(triangles),
        caster_(caster),
        conservative_(caster == nullptr || rounding == Rounding::kConservative),
        shrink_(conservative_ ? 0.0 : 0.5),
        side_voxels_(std::ldexp(1.0, depth)),
        lists_(static_cast<std::size_t>(depth) + 1) {}

  Octree build(const WorldGrid& grid) {
    const Cube universe = grid.universe();
    std::vector<std::uint32_t> all(triangles_.size());
    for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
    std::vector<std::uint32_t>& top = lists_[static_cast<std::size_t>(universe.level)];
    filter(all, testBox(universe, shrink_, kInternalMargin), top);
    if (top.empty()) {
      Status status;
      return caster_ != nullptr && status.inside(*caster_, centreOf(universe)) ? Octree::full(grid)
                                                                               : Octree(grid);
    }
    OctreeBuilder builder(grid);
    Status status;
    descend(builder, OctreeBuilder::kRoot, universe, top, status);
    return builder.build();
  }

 private:
  static Eigen::Vector3d centreOf(const Cube& cube) {
    const double h = 0.5 * static_cast<double>(cube.side());
    return Eigen::Vector3d(cube.origin.x + h, cube.origin.y + h, cube.origin.z + h);
  }

  // The smallest box holding the box and the point p, grown by the internal margin so that a
  // triangle grazing it within rounding counts as touching. Every use here has p at a corner
  // of a cube-shaped result. An untouched link box means no surface between its points.
  static TestBox link(const TestBox& box, const Eigen::Vector3d& p) {
    return {box.lo.cwiseMin(p).array() - kInternalMargin,
            box.hi.cwiseMax(p).array() + kInternalMargin};
  }
  static TestBox link(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return link(TestBox{a, a}, b);
  }

  bool anyTouches(const std::vector<std::uint32_t>& candidates, const TestBox& box) const {
    const Eigen::Vector3d c = 0.5 * (box.lo + box.hi);
    const double h = 0.5 * (box.hi - box.lo).maxCoeff();
    for (std::uint32_t i : candidates) {
      if (touches(triangles_[i], c, h)) return true;
    }
    return false;
  }

  void filter(const std::vector<std::uint32_t>& in, const TestBox& box,
              std::vector<std::uint32_t>& out) const {
    const Eigen::Vector3d c = 0.5 * (box.lo + box.hi);
    const double h = 0.5 * (box.hi - box.lo).maxCoeff();
    out.clear();
    for (std::uint32_t i : in) {
      if (touches(triangles_[i], c, h)) out.push_back(i);
    }
  }

  // Whether triangle t, which grazes voxel v without reaching into it, is held by a black voxel
  // next to v. t lies beyond some of v's faces (within the tie), so its part of v's closure lies
  // on the face, edge or corner where those face planes meet, and every voxel around that part
  // holds it in its closure; one of them inside the universe with its centre in the solid is
  // black.
  bool coveredAcross(const GridTriangle& t, const Cube& v) const {
    if (caster_ == nullptr) return false;
    const double tol = kFaceTie + kInternalMargin;
    const Eigen::Vector3d lo(v.origin.x, v.origin.y, v.origin.z);
    int step[3] = {0, 0, 0};
    for (int axis = 0; axis < 3; ++axis) {
      if (t.lo[axis] >= lo[axis] + 1.0 - tol) step[axis] = 1;
      if (t.hi[axis] <= lo[axis] + tol) step[axis] = -1;
    }
    for (int axes = 1; axes < 8; ++axes) {
      Eigen::Vector3d across = lo + Eigen::Vector3d::Constant(0.5);
      bool around = true;
      for (int axis = 0; axis < 3 && around; ++axis) {
        if ((axes >> axis & 1) == 0) continue;
        around = step[axis] != 0;
        across[axis] += step[axis];
        around &= across[axis] > 0.0 && across[axis] < side_voxels_;
      }
      if (around && caster_->inside(across)) return true;
    }
    return false;
  }

  // A voxel of the level-1 cube whose centre is `middle` (status `middle_status`), given the
  // triangles that touch the cube's test box.
  bool voxel(const Cube& v, const std::vector<std::uint32_t>& candidates,
             const Eigen::Vector3d& middle, Status& middle_status) const {
    const Eigen::Vector3d centre(v.origin.x + 0.5, v.origin.y + 0.5, v.origin.z + 0.5);
    if (conservative_) {
      // A triangle reaching into the voxel (kFaceTie) makes it black. An untouched voxel takes
      // the status of the middle, one of its corners. A voxel some triangle only grazes (it
      // passes within kFaceTie of the boundary, e.g. a face lying on a voxel face) is black when
      // its centre is in the solid, and also when a grazing triangle is held by no black voxel
      // across the face, edge or corner it lies on (coveredAcross): the surface itself must
      // always lie in a closed black voxel, also where parity sees no inside on either side of
      // it (a double-sided sheet, an open mesh).
      grazers_.clear();
      for (std::uint32_t i : candidates) {
        const int level =
            touchLevel(triangles_[i], centre, 0.5 - kFaceTie, kFaceTie + kInternalMargin);
        if (level == 2) return true;
        if (level == 1) grazers_.push_back(i);
      }
      if (grazers_.empty()) {
        return caster_ != nullptr && middle_status.inside(*caster_, middle);
      }
      if (caster_ != nullptr && caster_->inside(centre)) return true;
      for (std::uint32_t i : grazers_) {
        if (!coveredAcross(triangles_[i], v)) return true;
      }
      return false;
    }
    for (std::uint32_t i : candidates) {
      if (touches(triangles_[i], centre, 0.0)) return true;  // on the surface counts
    }
    if (!anyTouches(candidates, link(centre, middle))) {
      return middle_status.inside(*caster_, middle);
    }
    return caster_->inside(centre);
  }

  // `node` stands for the partial cube `cube` (level >= 1); `candidates` are the triangles
  // touching its test box, `status` says whether its centre is in the solid if known.
  void descend(OctreeBuilder& builder, std::uint32_t node, const Cube& cube,
               const std::vector<std::uint32_t>& candidates, Status& status) {
    const Eigen::Vector3d middle = centreOf(cube);
    if (cube.level == 1) {
      std::uint8_t mask = 0;
      for (int k = 0; k < 8; ++k) {
        if (voxel(cube.child(k), candidates, middle, status)) {
          mask = static_cast<std::uint8_t>(mask | (1u << k));
        }
      }
      builder.node(node).black = mask;
      return;
    }
    std::vector<std::uint32_t>& mine = lists_[static_cast<std::size_t>(cube.level - 1)];
    for (int k = 0; k < 8; ++k) {
      const Cube child = cube.child(k);
      const TestBox box = testBox(child, shrink_, kInternalMargin);
      filter(candidates, box, mine);
      if (mine.empty()) {
        // Uniform. Conservative: the closed child holds the middle, so it shares its status.
        bool in = false;
        if (caster_ != nullptr) {
          if (conservative_ || !anyTouches(candidates, link(box, middle))) {
            in = status.inside(*caster_, middle);
          } else {
            in = caster_->inside(centreOf(child));
          }
        }
        if (in) {
          OctreeBuilder::Node& n = builder.node(node);
          n.black = static_cast<std::uint8_t>(n.black | (1u << k));
        }
      } else {
        // Partial: across an untouched link its centre is on the same side as the middle, so
        // it shares the middle's status (whoever needs it first casts the ray).
        Status own;
        Status* child_status = &own;
        if (caster_ != nullptr && !anyTouches(candidates, link(centreOf(child), middle))) {
          child_status = &status;
        }
        const std::uint32_t c = builder.split(node, k);
        descend(builder, c, child, mine, *child_status);
        builder.condense(node, k);
      }
    }
  }

  const std::vector<GridTriangle>& triangles_;
  const ParityCaster* caster_;
  bool conservative_;
  double shrink_;
  double side_voxels_;
  std::vector<std::vector<std::uint32_t>> lists_;  // scratch candidate list per level
  mutable std::vector<std::uint32_t> grazers_;     // scratch of voxel()
};

}  // namespace
}  // namespace detail

Octree voxelizeMesh(const WorldGrid& grid, const TriangleMesh& mesh, const Eigen::Isometry3d& X_WM,
                    Rounding rounding, const WarningSink& warnings) {
  validateMesh(mesh, "voxelizeMesh: mesh");
  if (mesh.triangles.empty()) throw InvalidArgument("voxelizeMesh: mesh has no triangles");
  detail::validatePose(X_WM, "voxelizeMesh: X_WM");

  const detail::EdgeCensus census = detail::edgeCensus(mesh);
  const bool solid = census.triangles > 0 && census.odd_edges == 0;
  if (!solid) {
    warn(warnings, "voxelizeMesh: mesh is not closed (" + std::to_string(census.odd_edges) +
                       " edges are used by an odd number of triangles): voxelized as the "
                       "surface shell of voxels its triangles touch, with nothing inside");
  }

  std::vector<Eigen::Vector3d> vertices_G(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    vertices_G[i] = grid.toGrid(X_WM * mesh.vertices[i]);
    if (!vertices_G[i].allFinite()) {
      throw InvalidArgument("voxelizeMesh: mesh.vertices[" + std::to_string(i) +
                            "] is too far out for this grid");
    }
  }
  std::vector<detail::GridTriangle> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    triangles.push_back(detail::makeTriangle(vertices_G[t[0]], vertices_G[t[1]], vertices_G[t[2]]));
  }
  if (!solid) return detail::MeshDescent(triangles, nullptr, rounding, grid.depth()).build(grid);
  const detail::ParityCaster caster(triangles);
  return detail::MeshDescent(triangles, &caster, rounding, grid.depth()).build(grid);
}

}  // namespace octomotion
