#include "octomotion/motion/rotate90.h"

#include <sstream>
#include <string>
#include <vector>

#include "octomotion/error.h"
#include "octomotion/octree/bits.h"

namespace octomotion {

namespace {
int determinant(const Eigen::Matrix3i& m) {
  return m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1)) -
         m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0)) +
         m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
}
}  // namespace

AxisRotation::AxisRotation() : AxisRotation({0, 1, 2}, {1, 1, 1}) {}

AxisRotation::AxisRotation(const std::array<std::int8_t, 3>& axis,
                           const std::array<std::int8_t, 3>& sign)
    : axis_(axis), sign_(sign) {
  // Bit i of the image label is bit axis(i) of the label, flipped where the axis is reversed:
  // about the centre of a cube, R maps its octant with offsets b to the octant with offsets R b.
  for (int k = 0; k < 8; ++k) {
    int image = 0;
    for (int i = 0; i < 3; ++i) {
      const int b = (k >> axis_[static_cast<std::size_t>(i)]) & 1;
      image |= (sign_[static_cast<std::size_t>(i)] < 0 ? 1 - b : b) << i;
    }
    label_map_[static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(image);
  }
  for (int m = 0; m < 256; ++m) {
    int image = 0;
    for (int k = 0; k < 8; ++k) {
      if (m & (1 << k)) image |= 1 << label_map_[static_cast<std::size_t>(k)];
    }
    mask_map_[static_cast<std::size_t>(m)] = static_cast<std::uint8_t>(image);
  }
}

AxisRotation AxisRotation::fromMatrix(const Eigen::Matrix3i& R) {
  std::array<std::int8_t, 3> axis{}, sign{};
  int columns_used = 0;
  bool ok = true;
  for (int i = 0; i < 3 && ok; ++i) {
    int nonzero = 0;
    for (int j = 0; j < 3; ++j) {
      if (R(i, j) == 0) continue;
      if (R(i, j) != 1 && R(i, j) != -1) ok = false;
      ++nonzero;
      axis[static_cast<std::size_t>(i)] = static_cast<std::int8_t>(j);
      sign[static_cast<std::size_t>(i)] = static_cast<std::int8_t>(R(i, j));
      columns_used |= 1 << j;
    }
    if (nonzero != 1) ok = false;
  }
  if (!ok || columns_used != 7 || determinant(R) != 1) {
    std::ostringstream text;
    text << R.format(
        Eigen::IOFormat(Eigen::FullPrecision, Eigen::DontAlignCols, " ", "; ", "", "", "[", "]"));
    throw InvalidArgument("AxisRotation::fromMatrix: " + text.str() +
                          " is not a signed permutation matrix with determinant +1");
  }
  return AxisRotation(axis, sign);
}

AxisRotation AxisRotation::about(int axis, int quarter_turns) {
  if (axis < 0 || axis > 2) {
    throw InvalidArgument("AxisRotation::about: axis must be 0, 1 or 2, got " +
                          std::to_string(axis));
  }
  // A quarter turn about `axis` sends axis u to axis v and v to -u, (axis, u, v) right-handed.
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  Eigen::Matrix3i quarter = Eigen::Matrix3i::Zero();
  quarter(axis, axis) = 1;
  quarter(v, u) = 1;
  quarter(u, v) = -1;
  const AxisRotation step = fromMatrix(quarter);
  AxisRotation r;
  for (int t = ((quarter_turns % 4) + 4) % 4; t > 0; --t) r = step * r;
  return r;
}

const std::array<AxisRotation, 24>& AxisRotation::all() {
  static const std::array<AxisRotation, 24> rotations = [] {
    std::array<AxisRotation, 24> out;
    std::size_t n = 0;
    const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (const auto& p : perms) {
      for (int s = 0; s < 8; ++s) {
        Eigen::Matrix3i m = Eigen::Matrix3i::Zero();
        for (int i = 0; i < 3; ++i) m(i, p[i]) = (s >> i) & 1 ? -1 : 1;
        if (determinant(m) == 1) out[n++] = fromMatrix(m);
      }
    }
    return out;
  }();
  return rotations;
}

Eigen::Matrix3i AxisRotation::matrix() const {
  Eigen::Matrix3i m = Eigen::Matrix3i::Zero();
  for (int i = 0; i < 3; ++i) m(i, axis(i)) = sign(i);
  return m;
}

Voxel AxisRotation::apply(const Voxel& v, int depth) const {
  const std::uint32_t last = (std::uint32_t{1} << depth) - 1u;
  const std::uint32_t in[3] = {v.x, v.y, v.z};
  std::uint32_t out[3];
  for (int i = 0; i < 3; ++i) {
    const std::uint32_t c = in[axis(i)];
    out[i] = sign(i) > 0 ? c : last - c;
  }
  return {out[0], out[1], out[2]};
}

Cube AxisRotation::apply(const Cube& c, int depth) const {
  // The image's minimum corner is the image of the corner voxel with the reversed axes at max.
  const std::uint32_t far = c.side() - 1u;
  const std::uint32_t in[3] = {c.origin.x, c.origin.y, c.origin.z};
  const std::uint32_t last = (std::uint32_t{1} << depth) - 1u;
  std::uint32_t out[3];
  for (int i = 0; i < 3; ++i) {
    const std::uint32_t x = in[axis(i)];
    out[i] = sign(i) > 0 ? x : last - (x + far);
  }
  return {c.level, {out[0], out[1], out[2]}};
}

AxisRotation operator*(const AxisRotation& a, const AxisRotation& b) {
  // (AB)(i, j) = A(i, a.axis(i)) B(a.axis(i), j): one nonzero at j = b.axis(a.axis(i)).
  std::array<std::int8_t, 3> axis{}, sign{};
  for (int i = 0; i < 3; ++i) {
    const int mid = a.axis(i);
    axis[static_cast<std::size_t>(i)] = static_cast<std::int8_t>(b.axis(mid));
    sign[static_cast<std::size_t>(i)] = static_cast<std::int8_t>(a.sign(i) * b.sign(mid));
  }
  return AxisRotation(axis, sign);
}

AxisRotation AxisRotation::inverse() const {
  // R^-1 = R^T: row axis(i) of the transpose has sign(i) in column i.
  std::array<std::int8_t, 3> axis{}, sign{};
  for (int i = 0; i < 3; ++i) {
    axis[static_cast<std::size_t>(this->axis(i))] = static_cast<std::int8_t>(i);
    sign[static_cast<std::size_t>(this->axis(i))] = static_cast<std::int8_t>(this->sign(i));
  }
  return AxisRotation(axis, sign);
}

namespace {

// Lays out the rotated copy of source node `from` at `to`, its gray children in one block in
// the order of their new labels (depth-first, like OctreeBuilder::build).
void emitRotated(const std::vector<OctreeNode>& source, std::uint32_t from, std::uint32_t to,
                 const AxisRotation& R, const std::array<std::uint8_t, 8>& preimage,
                 std::vector<OctreeNode>& out) {
  const OctreeNode n = source[from];
  const std::uint8_t gray = R.mapMask(n.gray);
  const std::uint32_t first = static_cast<std::uint32_t>(out.size());
  out[to] = OctreeNode{gray ? first : 0u, R.mapMask(n.black), gray};
  out.resize(out.size() + static_cast<std::size_t>(popcount8(gray)));
  std::uint32_t j = 0;
  for (std::uint8_t g = gray; g; g &= static_cast<std::uint8_t>(g - 1), ++j) {
    const int k = preimage[static_cast<std::size_t>(lowestBit(g))];
    emitRotated(source, n.childIndex(k), first + j, R, preimage, out);
  }
}

}  // namespace

Octree rotate90(const Octree& source, const AxisRotation& R) {
  if (source.rootColor() != Color::kGray) return source;  // uniform universes are symmetric
  std::array<std::uint8_t, 8> preimage{};
  for (int k = 0; k < 8; ++k) {
    preimage[static_cast<std::size_t>(R.mapLabel(k))] = static_cast<std::uint8_t>(k);
  }
  std::vector<OctreeNode> nodes(1);
  nodes.reserve(source.internalNodeCount());
  emitRotated(source.nodes(), 0, 0, R, preimage, nodes);
  return Octree::fromNodes(source.grid(), Color::kGray, std::move(nodes));
}

}  // namespace octomotion
