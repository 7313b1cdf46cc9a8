// Fused move-and-intersect query (see collides.h).
#include "octomotion/motion/collides.h"

#include <algorithm>
#include <cmath>

#include "internal/kernel.h"
#include "octomotion/error.h"
#include "octomotion/octree/bits.h"

namespace octomotion {

namespace {

using detail::CollisionItem;
using detail::MotionFrame;
using Node = MovableSource::Node;

class Query {
 public:
  Query(MotionFrame& f, const MovableSource& src, const Octree& env, Rounding rounding,
        CollisionScratch& scratch, Cube* witness, const BlackCellGrid* solid,
        const ClearanceGrid* clear)
      : f_(f),
        nodes_(src.nodes().data()),
        env_(env.nodes().data()),
        env_root_(env.rootColor()),
        depth_(env.grid().depth()),
        rounding_(rounding),
        margin_(detail::rejectMargin(rounding)),
        scratch_(scratch),
        witness_(witness),
        src_(src),
        solid_(solid),
        clear_(clear) {}

  bool run() {
    if (env_root_ == Color::kWhite) return false;
    const CollisionItem root = nodeItem(0);
    // Integer box of target voxels the moved source can reach (one voxel of slack).
    const double side = f_.side;
    std::uint32_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      const double l = root.g[a] - root.rt[a] - 1.0, h = root.g[a] + root.rt[a] + 1.0;
      if (!(h >= 0.0 && l < side)) return false;
      lo[a] = static_cast<std::uint32_t>(std::max(0.0, std::floor(l)));
      hi[a] = static_cast<std::uint32_t>(std::min(side - 1.0, std::floor(h)));
    }
    // Anchor level: the smallest cells of which at most 2 x 2 x 2 cover the box; reach them
    // by following the environment's path (no geometry on the way down).
    int la = 0;
    while (la < depth_ && ((hi[0] >> la) - (lo[0] >> la) > 1 || (hi[1] >> la) - (lo[1] >> la) > 1 ||
                           (hi[2] >> la) - (lo[2] >> la) > 1)) {
      ++la;
    }
    std::uint32_t cells[3][2];
    int count[3];
    for (int a = 0; a < 3; ++a) {
      cells[a][0] = lo[a] >> la;
      cells[a][1] = hi[a] >> la;
      count[a] = cells[a][1] != cells[a][0] ? 2 : 1;
    }
    // Cheapest guess: points of the source in entirely black environment cells. Conservative:
    // the voxel holding a moved leaf's centre is black in the moved tree (see inside()), so one
    // landing in a black cell is a shared voxel (needs the smallest leaf's moved half to pass
    // inside()). Centre: that voxel is black only if its centre lies in a moved black leaf,
    // which centreProbe looks up in the source tree and confirms with the colour rule.
    if (solid_ && (rounding_ == Rounding::kCenter || detail::movedHalf(f_, 0) >= kInsideMinHalf)) {
      for (const std::array<double, 3>& u : src_.gridProbes()) {
        double g[3];
        detail::movePoint(f_, u.data(), g);
        if (!solid_->black(g)) continue;
        const Voxel v{static_cast<std::uint32_t>(g[0]), static_cast<std::uint32_t>(g[1]),
                      static_cast<std::uint32_t>(g[2])};
        if (rounding_ == Rounding::kCenter && !centreProbe(v)) continue;
        if (witness_) *witness_ = Cube{0, v};
        return true;
      }
    }
    // Drop the parts of the moved source that are clear of the environment; none left: free.
    std::vector<CollisionItem>& pieces = scratch_.pieces;
    pieces.clear();
    if (clear_) {
      splitByClearance(root);
      if (pieces.empty()) return false;
    } else {
      pieces.push_back(root);
    }
    // Cheap first guess: the voxel at the moved centre of each of the largest leaves.
    for (const Cube& leaf : src_.coreLeaves()) {
      double u[3], g[3];
      detail::cubeCentre(leaf, u);
      detail::movePoint(f_, u, g);
      if (!(g[0] >= 0 && g[1] >= 0 && g[2] >= 0 && g[0] < side && g[1] < side && g[2] < side)) {
        continue;
      }
      const Voxel v{static_cast<std::uint32_t>(g[0]), static_cast<std::uint32_t>(g[1]),
                    static_cast<std::uint32_t>(g[2])};
      if (locate(Cube{0, v}) == kBlackCell &&
          probe(g, detail::movedHalf(f_, leaf.level), Cube{0, v})) {
        return true;
      }
    }
    out_ = &scratch_.items;
    out_->clear();
    for (int iz = 0; iz < count[2]; ++iz) {
      for (int iy = 0; iy < count[1]; ++iy) {
        for (int ix = 0; ix < count[0]; ++ix) {
          const Cube cell{la, {cells[0][ix] << la, cells[1][iy] << la, cells[2][iz] << la}};
          const std::uint32_t env = locate(cell);
          if (env == kWhiteCell) continue;
          const std::size_t b = out_->size();
          for (const CollisionItem& piece : pieces) {
            if (reaches(piece, cell)) pushRefined(piece, cell);
          }
          if (out_->size() == b) continue;
          const bool hit = visit(cell, env, b, out_->size());
          out_->resize(b);
          if (hit) return true;
        }
      }
    }
    return false;
  }

 private:
  static constexpr std::uint32_t kWhiteCell = 0xfffffffeu;
  static constexpr std::uint32_t kBlackCell = 0xffffffffu;

  // Fills scratch_.pieces with pieces covering the moved source's black voxels. Breadth first
  // from `root`: a piece whose bounding sphere lies within the clearance at its centre is
  // dropped (every black voxel of the moved tree touches a moved piece, every point of a black
  // environment voxel is at least the clearance away); a gray node is split into its children
  // while the budget (kClearanceSplits) lasts and its sphere is wider than a clearance cell
  // (smaller ones are below the grid's resolution); the rest are kept.
  void splitByClearance(const CollisionItem& root) {
    std::vector<CollisionItem>& todo = scratch_.items;  // free until the descent
    std::vector<CollisionItem>& pieces = scratch_.pieces;
    todo.clear();
    todo.push_back(root);
    const double cell = clear_->cellVoxels();
    int splits = 0;
    for (std::size_t next = 0; next < todo.size(); ++next) {
      const CollisionItem it = todo[next];  // the pushes below may reallocate
      const double r2 = it.rs[0] * it.rs[0] + it.rs[1] * it.rs[1] + it.rs[2] * it.rs[2];
      const double c = clear_->clearance(it.g);
      // Clearances are whole quarters of a cell (exact); the margin covers rounding in g and r.
      if (r2 * (1.0 + 1e-9) + 1e-6 < c * c) continue;
      if (it.leaf >= 0 || splits == kClearanceSplits || r2 < cell * cell) {
        pieces.push_back(it);
        continue;
      }
      ++splits;
      const Node& n = nodes_[it.node];
      for (std::uint8_t m = n.black; m; m &= static_cast<std::uint8_t>(m - 1)) {
        todo.push_back(leafItem(it.node, lowestBit(m)));
      }
      for (std::uint8_t m = n.gray; m; m &= static_cast<std::uint8_t>(m - 1)) {
        todo.push_back(nodeItem(n.childIndex(lowestBit(m))));
      }
    }
  }

  // The environment node of an anchor cell, kBlackCell or kWhiteCell.
  std::uint32_t locate(const Cube& cell) const {
    if (env_root_ == Color::kBlack) return kBlackCell;
    std::uint32_t idx = 0;
    for (int lvl = depth_ - 1; lvl >= cell.level; --lvl) {
      const int k =
          static_cast<int>(((cell.origin.x >> lvl) & 1u) | (((cell.origin.y >> lvl) & 1u) << 1) |
                           (((cell.origin.z >> lvl) & 1u) << 2));
      const OctreeNode& n = env_[idx];
      if (n.black & (1u << k)) return kBlackCell;
      if (!(n.gray & (1u << k))) return kWhiteCell;
      idx = envChild(n, k);
    }
    return idx;
  }

  static std::uint32_t envChild(const OctreeNode& n, int k) {
    return n.first_child + static_cast<std::uint32_t>(childRank(n.gray, k));
  }

  // Depth-first parallel descent. The pieces [b, e) of the stack reach `cell`; the callee's
  // pieces go on top of the stack and are popped before returning.
  bool visit(const Cube& cell, std::uint32_t env, std::size_t b, std::size_t e) {
    const std::size_t top = out_->size();
    if (env == kBlackCell) {
      // Settle the black cell as far as probes go: every leaf under the pieces that reaches it
      // tries the cell's voxel nearest to its centre. Only leaves whose probe failed go on, to
      // be settled exactly on the cell's children (down to voxels, where the probe is the
      // colour rule itself).
      bool hit = false;
      for (std::size_t i = b; i < e && !hit; ++i) {
        const CollisionItem it = (*out_)[i];
        hit = it.leaf >= 0 ? probeOrDefer(it, cell) : probeBelow(it, cell);
      }
      if (!hit && cell.level > 0 && out_->size() > top) {
        hit = blackChildren(cell, top, out_->size());
      }
      out_->resize(top);
      return hit;
    }
    const OctreeNode n = env_[env];
    const unsigned reach = childMasks(b, e, cell);
    // Gather every reached child, then visit black ones first (a shared voxel there is found by
    // a probe), each group deepest inside the moved source first; a free pose visits them all.
    struct Pending {
      std::uint32_t b, e;
      int k;
      double score;
    } pending[8];
    int count = 0;
    for (unsigned m = reach & n.occupied(); m; m &= m - 1) {
      const int k = lowestBit(m);
      const std::size_t base = out_->size();
      const Cube child = cell.child(k);
      if (!gather(b, e, child, k)) continue;
      const double score =
          depthOutside(child, base, out_->size()) + ((n.black >> k) & 1u ? -1e300 : 0.0);
      int at = count++;
      while (at > 0 && pending[at - 1].score > score) {
        pending[at] = pending[at - 1];
        --at;
      }
      pending[at] = {static_cast<std::uint32_t>(base), static_cast<std::uint32_t>(out_->size()), k,
                     score};
    }
    bool hit = false;
    for (int i = 0; i < count && !hit; ++i) {
      const int k = pending[i].k;
      hit = visit(cell.child(k), (n.black >> k) & 1u ? kBlackCell : envChild(n, k), pending[i].b,
                  pending[i].e);
    }
    out_->resize(top);
    return hit;
  }

  // How far the cell's centre is outside the nearest piece's box, in its own axes (negative:
  // inside); the ordering heuristic of visit().
  double depthOutside(const Cube& cell, std::size_t b, std::size_t e) const {
    double c[3];
    detail::cubeCentre(cell, c);
    double best = 1e300;
    for (std::size_t i = b; i < e; ++i) {
      const CollisionItem& it = (*out_)[i];
      const double d[3] = {c[0] - it.g[0], c[1] - it.g[1], c[2] - it.g[2]};
      double worst = -1e300;
      for (int j = 0; j < 3; ++j) {
        const double q = f_.R[0][j] * d[0] + f_.R[1][j] * d[1] + f_.R[2][j] * d[2];
        worst = std::max(worst, std::fabs(q) - it.rs[j]);
      }
      best = std::min(best, worst);
    }
    return best;
  }

  // The eight children of a black cell with the (leaf) pieces [b, e) that reach each.
  bool blackChildren(const Cube& cell, std::size_t b, std::size_t e) {
    const std::size_t top = out_->size();
    for (unsigned m = childMasks(b, e, cell); m; m &= m - 1) {
      const int k = lowestBit(m);
      const Cube child = cell.child(k);
      const bool hit = gather(b, e, child, k) && visit(child, kBlackCell, top, out_->size());
      out_->resize(top);
      if (hit) return true;
    }
    return false;
  }

  // For each piece of [b, e), the children of `cell` it may reach by the target-axis tests
  // (two half-planes per axis instead of eight cubes); returns their union.
  unsigned childMasks(std::size_t b, std::size_t e, const Cube& cell) {
    const double s = detail::halfSide(cell.level);  // a child's side
    const double q = detail::halfSide(cell.level - 1);
    const double hc = detail::cellReach(rounding_, cell.level - 1) + margin_;
    const double lo[3] = {static_cast<double>(cell.origin.x) + q,
                          static_cast<double>(cell.origin.y) + q,
                          static_cast<double>(cell.origin.z) + q};
    static constexpr unsigned kLow[3] = {0x55, 0x33, 0x0f}, kHigh[3] = {0xaa, 0xcc, 0xf0};
    unsigned all = 0;
    for (std::size_t i = b; i < e; ++i) {
      CollisionItem& it = (*out_)[i];
      unsigned mask = 0xff;
      for (int a = 0; a < 3; ++a) {
        const double lim = hc + it.rt[a];
        const double d = lo[a] - it.g[a];
        mask &= (std::fabs(d) <= lim ? kLow[a] : 0u) | (std::fabs(d + s) <= lim ? kHigh[a] : 0u);
      }
      it.mask = static_cast<std::uint8_t>(mask);
      all |= mask;
    }
    return all;
  }

  // Pushes the pieces of [b, e) that reach child k `cell` (refined to its size); true if any.
  // The target-axis half of the test was done by childMasks.
  bool gather(std::size_t b, std::size_t e, const Cube& cell, int k) {
    const std::size_t base = out_->size();
    double c[3];
    detail::cubeCentre(cell, c);
    const double hc = detail::cellReach(rounding_, cell.level);
    for (std::size_t i = b; i < e; ++i) {
      if (((*out_)[i].mask >> k & 1u) && reachesInSource((*out_)[i], c, hc)) {
        const CollisionItem it = (*out_)[i];  // the push below may reallocate
        pushRefined(it, cell);
      }
    }
    return out_->size() > base;
  }

  // The source-axis half of reaches().
  bool reachesInSource(const CollisionItem& it, const double e[3], double hc) const {
    const double d[3] = {e[0] - it.g[0], e[1] - it.g[1], e[2] - it.g[2]};
    for (int j = 0; j < 3; ++j) {
      const double q = f_.R[0][j] * d[0] + f_.R[1][j] * d[1] + f_.R[2][j] * d[2];
      if (std::fabs(q) > it.rs[j] + hc * f_.colsum[j] + margin_) return false;
    }
    return true;
  }

  CollisionItem nodeItem(std::uint32_t i) const {
    const Node& n = nodes_[i];
    CollisionItem it;
    detail::movePoint(f_, n.centre, it.g);
    for (int a = 0; a < 3; ++a) {
      it.rs[a] = f_.s * n.half[a];
      it.rt[a] = f_.absA[a][0] * n.half[0] + f_.absA[a][1] * n.half[1] + f_.absA[a][2] * n.half[2];
    }
    it.split = f_.s * n.split_half;
    it.node = i;
    it.leaf = -1;
    it.level = n.level;
    return it;
  }

  CollisionItem leafItem(std::uint32_t i, int k) const {
    const Node& n = nodes_[i];
    const Cube cube = Cube{n.level, n.origin}.child(k);
    double u[3];
    detail::cubeCentre(cube, u);
    CollisionItem it;
    detail::movePoint(f_, u, it.g);  // the same expression moveTree evaluates
    const double hs = detail::movedHalf(f_, cube.level);
    for (int a = 0; a < 3; ++a) {
      it.rs[a] = hs;
      it.rt[a] = hs * f_.rowsum[a];
    }
    it.split = 0.0;  // leaves are never split
    it.node = i;
    it.leaf = static_cast<std::int8_t>(k);
    it.level = static_cast<std::int8_t>(cube.level);
    return it;
  }

  // Relation B's "outside" (both ways, exact face-axis projections, safe margin): false when no
  // voxel of `cell` can be turned black by the moved piece.
  bool reaches(const CollisionItem& it, const Cube& cell) const {
    double e[3];
    detail::cubeCentre(cell, e);
    return reaches(it, e, detail::cellReach(rounding_, cell.level));
  }
  // The same with the cell's centre e and reach hc (see cellReach) precomputed.
  bool reaches(const CollisionItem& it, const double e[3], double hc) const {
    const double d[3] = {e[0] - it.g[0], e[1] - it.g[1], e[2] - it.g[2]};
    for (int i = 0; i < 3; ++i) {
      if (std::fabs(d[i]) > hc + it.rt[i] + margin_) return false;
    }
    for (int j = 0; j < 3; ++j) {
      const double q = f_.R[0][j] * d[0] + f_.R[1][j] * d[1] + f_.R[2][j] * d[2];
      if (std::fabs(q) > it.rs[j] + hc * f_.colsum[j] + margin_) return false;
    }
    return true;
  }

  // Pushes a piece known to reach `cell`; a gray source node larger than the cell is replaced
  // by its children that reach it (the source side of the parallel descent).
  void pushRefined(const CollisionItem& it, const Cube& cell) {
    if (it.leaf >= 0 || it.split <= detail::halfSide(cell.level)) {
      out_->push_back(it);
      return;
    }
    const Node& n = nodes_[it.node];
    for (std::uint8_t m = n.black; m; m &= static_cast<std::uint8_t>(m - 1)) {
      const CollisionItem c = leafItem(it.node, lowestBit(m));
      if (reaches(c, cell)) out_->push_back(c);
    }
    for (std::uint8_t m = n.gray; m; m &= static_cast<std::uint8_t>(m - 1)) {
      const CollisionItem c = nodeItem(n.childIndex(lowestBit(m)));
      if (reaches(c, cell)) pushRefined(c, cell);
    }
  }

  bool probeOrDefer(const CollisionItem& leaf, const Cube& cell) {
    if (probe(leaf, cell)) return true;
    if (cell.level > 0) out_->push_back(leaf);
    return false;
  }

  // Depth-first through a gray piece's descendants that reach `cell`, probing each leaf. A
  // leaf's full piece is only built when its probe fails and it must be deferred.
  bool probeBelow(const CollisionItem& it, const Cube& cell) {
    const Node& n = nodes_[it.node];
    if (n.black) {
      double e[3];
      detail::cubeCentre(cell, e);
      const double hc = detail::cellReach(rounding_, cell.level);
      const double hs = detail::movedHalf(f_, n.level - 1);
      const Cube parent{n.level, n.origin};
      for (std::uint8_t m = n.black; m; m &= static_cast<std::uint8_t>(m - 1)) {
        const int k = lowestBit(m);
        double u[3], g[3];
        detail::cubeCentre(parent.child(k), u);
        detail::movePoint(f_, u, g);
        if (!leafReaches(g, hs, e, hc)) continue;
        if (probe(g, hs, cell)) return true;
        if (cell.level > 0) out_->push_back(leafItem(it.node, k));
      }
    }
    for (std::uint8_t m = n.gray; m; m &= static_cast<std::uint8_t>(m - 1)) {
      const CollisionItem c = nodeItem(n.childIndex(lowestBit(m)));
      if (reaches(c, cell) && probeBelow(c, cell)) return true;
    }
    return false;
  }

  // reaches() for a moved leaf cube of centre g and half side hs.
  bool leafReaches(const double g[3], double hs, const double e[3], double hc) const {
    const double d[3] = {e[0] - g[0], e[1] - g[1], e[2] - g[2]};
    for (int i = 0; i < 3; ++i) {
      if (std::fabs(d[i]) > hc + hs * f_.rowsum[i] + margin_) return false;
    }
    for (int j = 0; j < 3; ++j) {
      const double q = f_.R[0][j] * d[0] + f_.R[1][j] * d[1] + f_.R[2][j] * d[2];
      if (std::fabs(q) > hs + hc * f_.colsum[j] + margin_) return false;
    }
    return true;
  }

  // Conservative rounding accepts a voxel that holds the moved cube's centre g, whatever the
  // rotation: on every separating axis the voxel's half-projection already covers the offset of
  // g, and the cube adds at least hs (the edge axes' cS is >= 1), far above the tie tolerance.
  // The shortcut skips the 15-axis test (and forming the edge axes) for most hits.
  bool inside(const Voxel& v, const double g[3], double hs) const {
    return rounding_ == Rounding::kConservative && hs >= kInsideMinHalf &&
           static_cast<double>(v.x) <= g[0] && g[0] < static_cast<double>(v.x) + 1.0 &&
           static_cast<double>(v.y) <= g[1] && g[1] < static_cast<double>(v.y) + 1.0 &&
           static_cast<double>(v.z) <= g[2] && g[2] < static_cast<double>(v.z) + 1.0;
  }
  static constexpr double kInsideMinHalf = 1e-3;  // >> kMotionTieTolerance and rounding noise

  // Centre rounding: is target voxel v black in the moved tree? Its centre, taken back into
  // the source grid, falls in at most one source leaf (up to ties); v is black if that leaf is
  // black and accepts v by the colour rule (the same predicate moveTree applies, so a true
  // answer is exact; a tie the lookup resolves the other way only costs a missed shortcut).
  bool centreProbe(const Voxel& v) const {
    const double d[3] = {static_cast<double>(v.x) + 0.5 - f_.b[0],
                         static_cast<double>(v.y) + 0.5 - f_.b[1],
                         static_cast<double>(v.z) + 0.5 - f_.b[2]};
    std::uint32_t u[3];
    const Node& root = nodes_[0];
    const double side = 2.0 * detail::halfSide(root.level);
    for (int j = 0; j < 3; ++j) {
      const double q = (f_.R[0][j] * d[0] + f_.R[1][j] * d[1] + f_.R[2][j] * d[2]) / f_.s;
      if (!(q >= 0.0 && q < side)) return false;
      u[j] = static_cast<std::uint32_t>(q);
    }
    for (std::uint32_t idx = 0;;) {
      const Node& n = nodes_[idx];
      const int sh = n.level - 1;
      const int k = static_cast<int>((((u[0] - n.origin.x) >> sh) & 1u) |
                                     ((((u[1] - n.origin.y) >> sh) & 1u) << 1) |
                                     ((((u[2] - n.origin.z) >> sh) & 1u) << 2));
      if ((n.black >> k) & 1u) {
        const Cube leaf = Cube{n.level, n.origin}.child(k);
        double c[3], g[3];
        detail::cubeCentre(leaf, c);
        detail::movePoint(f_, c, g);  // the same expression moveTree evaluates
        return detail::voxelAccepts(f_, rounding_, v, g, detail::movedHalf(f_, leaf.level));
      }
      if (!((n.gray >> k) & 1u)) return false;
      idx = n.childIndex(k);
    }
  }

  // Tries the voxel of `cell` (entirely black) nearest to the moved leaf's centre.
  bool probe(const CollisionItem& leaf, const Cube& cell) {
    return probe(leaf.g, leaf.rs[0], cell);
  }
  bool probe(const double g[3], double hs, const Cube& cell) {
    const double top = static_cast<double>(cell.side() - 1);
    const std::uint32_t o[3] = {cell.origin.x, cell.origin.y, cell.origin.z};
    std::uint32_t v[3];
    for (int a = 0; a < 3; ++a) {
      const double r = std::floor(g[a]) - static_cast<double>(o[a]);
      v[a] = o[a] + static_cast<std::uint32_t>(std::min(top, std::max(0.0, r)));
    }
    const Voxel voxel{v[0], v[1], v[2]};
    if (!inside(voxel, g, hs)) {
      if (f_.n_cross < 0 && rounding_ == Rounding::kConservative) detail::addEdgeAxes(f_);
      // Centre rounding: a leaf smaller than a voxel (finer link trees) seldom holds a voxel
      // centre itself, but inside the object its neighbours do; one lookup settles the voxel
      // instead of descending every leaf down to single voxels.
      if (!detail::voxelAccepts(f_, rounding_, voxel, g, hs) &&
          !(rounding_ == Rounding::kCenter && centreProbe(voxel))) {
        return false;
      }
    }
    if (witness_) *witness_ = Cube{0, voxel};
    return true;
  }

  MotionFrame& f_;  // its edge axes are added at the first probe that needs them
  const Node* nodes_;
  const OctreeNode* env_;
  Color env_root_;
  int depth_;
  Rounding rounding_;
  double margin_;
  CollisionScratch& scratch_;
  Cube* witness_;
  const MovableSource& src_;
  const BlackCellGrid* solid_;
  const ClearanceGrid* clear_;
  std::vector<CollisionItem>* out_ = nullptr;
};

}  // namespace

bool collides(const MovableSource& source, const Eigen::Isometry3d& X_WS, const Octree& environment,
              Rounding rounding, CollisionScratch& scratch, Cube* witness,
              const BlackCellGrid* solid, const ClearanceGrid* clearance) {
  if (solid && solid->sideVoxels() != static_cast<double>(environment.grid().sideVoxels())) {
    throw InvalidArgument("collides: the BlackCellGrid is not of this environment");
  }
  if (clearance &&
      clearance->sideVoxels() != static_cast<double>(environment.grid().sideVoxels())) {
    throw InvalidArgument("collides: the ClearanceGrid is not of this environment");
  }
  MotionFrame f = detail::makeMotionFrame(X_WS, source.grid(), environment.grid(), "collides");
  if (source.rootColor() == Color::kWhite) return false;
  Query q(f, source, environment, rounding, scratch, witness, solid, clearance);
  return q.run();
}

bool collides(const Octree& source, const Eigen::Isometry3d& X_WS, const Octree& environment,
              Rounding rounding, Cube* witness) {
  const MovableSource prepared(source);
  CollisionScratch scratch;
  return collides(prepared, X_WS, environment, rounding, scratch, witness);
}

}  // namespace octomotion
