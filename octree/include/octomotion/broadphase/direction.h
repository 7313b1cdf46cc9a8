// The 26 directions of a cubical lattice (6 faces, 12 edges, 8 vertices) and Samet's four
// constant-time neighbour-finding primitives ADJ, REFLECT, COMMON_FACE and COMMON_EDGE, as used by
// the N-objects octree report (§2.1, Fig. 1 and the appendix "Low-Level Neighbor-Finding
// Operations"). Names follow the report: L/R = -x/+x, D/U = -y/+y, B/F = -z/+z.
//
// Octant labels are the project's (Ahuja & Nash Fig. 1): bit 0 = +x, bit 1 = +y, bit 2 = +z, so
// octant label o is the vertex direction whose x/y/z letters are R/U/F where o has the bit set
// (label 0 = LDB, label 7 = RUF). Every primitive is one lookup in a table built at compile time.
#pragma once

#include <array>
#include <cstdint>

namespace octomotion::broadphase {

enum class Direction : std::uint8_t {
  // Faces.
  L,
  R,
  D,
  U,
  B,
  F,
  // Edges.
  LD,
  LU,
  LB,
  LF,
  RD,
  RU,
  RB,
  RF,
  DB,
  DF,
  UB,
  UF,
  // Vertices.
  LDB,
  LDF,
  LUB,
  LUF,
  RDB,
  RDF,
  RUB,
  RUF,
  // Undefined (Samet's Omega).
  kOmega
};
inline constexpr int kDirectionCount = 26;

enum class DirectionKind : std::uint8_t { kFace, kEdge, kVertex, kNone };

// Per-axis step (-1, 0 or +1) of a direction; kOmega is (0,0,0).
struct Offset {
  int dx = 0, dy = 0, dz = 0;
};

namespace detail {

constexpr std::array<Offset, 27> kOffsets = {{
    {-1, 0, 0},   {1, 0, 0},   {0, -1, 0},  {0, 1, 0},  {0, 0, -1},  {0, 0, 1},   // faces
    {-1, -1, 0},  {-1, 1, 0},  {-1, 0, -1}, {-1, 0, 1}, {1, -1, 0},  {1, 1, 0},   // edges
    {1, 0, -1},   {1, 0, 1},   {0, -1, -1}, {0, -1, 1}, {0, 1, -1},  {0, 1, 1},   // edges
    {-1, -1, -1}, {-1, -1, 1}, {-1, 1, -1}, {-1, 1, 1}, {1, -1, -1}, {1, -1, 1},  // vertices
    {1, 1, -1},   {1, 1, 1},   {0, 0, 0}                                          // ..., Omega
}};

constexpr int offsetKey(int dx, int dy, int dz) {
  return (dx + 1) + 3 * (dy + 1) + 9 * (dz + 1);
}

constexpr std::array<std::uint8_t, 27> makeDirectionOfOffset() {
  std::array<std::uint8_t, 27> t{};
  for (int i = 0; i < 27; ++i) {
    const Offset& o = kOffsets[static_cast<std::size_t>(i)];
    t[static_cast<std::size_t>(offsetKey(o.dx, o.dy, o.dz))] = static_cast<std::uint8_t>(i);
  }
  return t;
}
constexpr std::array<std::uint8_t, 27> kDirectionOfOffset = makeDirectionOfOffset();

// Sign (+1/-1) of octant `label` along axis a.
constexpr int octantSign(int label, int axis) {
  return (label >> axis) & 1 ? 1 : -1;
}
constexpr int component(const Offset& o, int axis) {
  return axis == 0 ? o.dx : (axis == 1 ? o.dy : o.dz);
}

// Axes along which a step in direction d leaves octant `label`'s parent block: the non-zero
// components of d that point the same way as the octant lies in its parent.
constexpr int crossingAxes(int d, int label) {
  int mask = 0;
  for (int a = 0; a < 3; ++a) {
    const int c = component(kOffsets[static_cast<std::size_t>(d)], a);
    if (c != 0 && c == octantSign(label, a)) mask |= 1 << a;
  }
  return mask;
}

// The direction made of d's components on the axes in `mask` only.
constexpr std::uint8_t restrictTo(int d, int mask) {
  const Offset& o = kOffsets[static_cast<std::size_t>(d)];
  return kDirectionOfOffset[static_cast<std::size_t>(
      offsetKey(mask & 1 ? o.dx : 0, mask & 2 ? o.dy : 0, mask & 4 ? o.dz : 0))];
}

constexpr int nonZero(int d) {
  const Offset& o = kOffsets[static_cast<std::size_t>(d)];
  return (o.dx != 0) + (o.dy != 0) + (o.dz != 0);
}

struct Tables {
  bool adj[27][8]{};
  std::uint8_t reflect[27][8]{};
  std::uint8_t common_face[27][8]{};
  std::uint8_t common_edge[27][8]{};
};

constexpr Tables makeTables() {
  Tables t{};
  const auto omega = static_cast<std::uint8_t>(Direction::kOmega);
  for (int d = 0; d < 27; ++d) {
    for (int o = 0; o < 8; ++o) {
      const int n = nonZero(d);
      const int crossing = crossingAxes(d, o);
      const int crossing_count =
          ((crossing & 1) != 0) + ((crossing & 2) != 0) + ((crossing & 4) != 0);
      // ADJ: octant o touches the d-th face/edge/vertex of its parent iff every step crosses.
      t.adj[d][o] = d < kDirectionCount && crossing_count == n;
      // REFLECT: the equal-size neighbour's label flips o's bits on the stepped axes.
      int flip = 0;
      for (int a = 0; a < 3; ++a)
        if (component(kOffsets[static_cast<std::size_t>(d)], a) != 0) flip |= 1 << a;
      t.reflect[d][o] = static_cast<std::uint8_t>(d < kDirectionCount ? (o ^ flip) : o);
      // COMMON_FACE / COMMON_EDGE: the parent's face (one crossing axis) or edge (two) through
      // which the neighbour of an edge/vertex direction lies; Omega otherwise.
      t.common_face[d][o] = (n >= 2 && crossing_count == 1) ? restrictTo(d, crossing) : omega;
      t.common_edge[d][o] = (n == 3 && crossing_count == 2) ? restrictTo(d, crossing) : omega;
    }
  }
  return t;
}
inline constexpr Tables kTables = makeTables();

}  // namespace detail

constexpr Offset offset(Direction d) {
  return detail::kOffsets[static_cast<std::size_t>(d)];
}
// The direction with the given per-axis steps (each -1, 0 or +1); (0,0,0) gives kOmega.
constexpr Direction directionOf(int dx, int dy, int dz) {
  return static_cast<Direction>(
      detail::kDirectionOfOffset[static_cast<std::size_t>(detail::offsetKey(dx, dy, dz))]);
}
constexpr DirectionKind kindOf(Direction d) {
  const int i = static_cast<int>(d);
  return i < 6 ? DirectionKind::kFace
               : (i < 18 ? DirectionKind::kEdge
                         : (i < kDirectionCount ? DirectionKind::kVertex : DirectionKind::kNone));
}
// The vertex direction naming octant `label` of its parent (label 0 = LDB ... 7 = RUF).
constexpr Direction octantDirection(int label) {
  return directionOf(label & 1 ? 1 : -1, label & 2 ? 1 : -1, label & 4 ? 1 : -1);
}

// ADJ(I, O): octant `label` is adjacent to the I-th face, edge or vertex of its parent block.
constexpr bool adj(Direction i, int label) {
  return detail::kTables.adj[static_cast<int>(i)][label];
}
// REFLECT(I, O): label of the equal-size block sharing octant `label`'s I-th face/edge/vertex.
constexpr int reflect(Direction i, int label) {
  return detail::kTables.reflect[static_cast<int>(i)][label];
}
// COMMON_FACE(I, O): for an edge or vertex direction I, the face of the parent block shared by
// octant `label` and its I-neighbour; kOmega when the neighbour is a sibling or lies across an
// edge/vertex of the parent.
constexpr Direction commonFace(Direction i, int label) {
  return static_cast<Direction>(detail::kTables.common_face[static_cast<int>(i)][label]);
}
// COMMON_EDGE(I, O): for a vertex direction I, the edge of the parent block shared by octant
// `label` and its I-neighbour; kOmega otherwise.
constexpr Direction commonEdge(Direction i, int label) {
  return static_cast<Direction>(detail::kTables.common_edge[static_cast<int>(i)][label]);
}

// "L", "RUF", ... ("Omega" for kOmega).
const char* directionName(Direction d);

}  // namespace octomotion::broadphase
