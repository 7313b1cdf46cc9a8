#include "octomotion/octree/mesh.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include "internal/collada_check.h"
#include "internal/mesh.h"
#include "octomotion/error.h"
#include "octomotion/input_limits.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;

Eigen::Matrix4d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return out;
}

void appendNode(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& X_parent,
                bool is_root, const MeshLoadOptions& options, TriangleMesh* out) {
  const Eigen::Matrix4d X = (is_root && !options.keep_root_transform)
                                ? X_parent
                                : X_parent * toEigen(node.mTransformation);
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const std::uint32_t base = static_cast<std::uint32_t>(out->vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      const Eigen::Vector4d q = X * Eigen::Vector4d(p.x, p.y, p.z, 1.0);
      out->vertices.push_back(q.head<3>().cwiseProduct(options.scale));
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no surface
      out->triangles.push_back(
          {base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    appendNode(scene, *node.mChildren[c], X, false, options, out);
  }
}

// Exact-position key for welding duplicated vertices (STL stores each triangle's own corners).
struct PositionHash {
  std::size_t operator()(const Eigen::Vector3d& p) const {
    std::size_t h = 1469598103934665603ull;
    for (int i = 0; i < 3; ++i) {
      const double v = p[i] == 0.0 ? 0.0 : p[i];  // -0 and +0 weld
      std::uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
      h ^= h >> 29;
    }
    return h;
  }
};

struct PositionEqual {
  bool operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const { return a == b; }
};

// assimp's Collada importer copies memory without end when an <accessor> (or <input>) names a
// source id that the file does not define (fuzz/known/README.md), so every local reference
// `source="#id"` must name an element's id. The scan is textual: attributes inside comments
// count too, which can only refuse more, never let a dangling reference through.
std::string attributeValue(const std::string& text, std::size_t at) {
  const std::size_t close = text.find(text[at], at + 1);
  const std::size_t end = close == std::string::npos ? text.size() : close;
  return text.substr(at + 1, end - at - 1);
}

// Offsets just past `name=` followed by a quote, for each attribute `name` preceded by space.
template <class F>
void forEachAttribute(const std::string& text, const char* name, F&& f) {
  const std::size_t n = std::strlen(name);
  for (std::size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
    if (at == 0 || !std::isspace(static_cast<unsigned char>(text[at - 1]))) continue;
    std::size_t q = at + n;
    while (q < text.size() && std::isspace(static_cast<unsigned char>(text[q]))) ++q;
    if (q >= text.size() || text[q] != '=') continue;
    ++q;
    while (q < text.size() && std::isspace(static_cast<unsigned char>(text[q]))) ++q;
    if (q >= text.size() || (text[q] != '"' && text[q] != '\'')) continue;
    f(q);
  }
}

void requireLocalSourcesDefined(const std::string& text, const std::string& path) {
  std::unordered_set<std::string> ids;
  forEachAttribute(text, "id", [&](std::size_t q) { ids.insert(attributeValue(text, q)); });
  forEachAttribute(text, "source", [&](std::size_t q) {
    const std::string value = attributeValue(text, q);
    if (value.empty() || value[0] != '#') return;
    if (ids.count(value.substr(1)) != 0) return;
    std::string shown = value.substr(0, 64);
    for (char& c : shown) {
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
    }
    const auto line =
        1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(q), '\n');
    throw FileError(path, "source=\"" + shown + "\" (line " + std::to_string(line) +
                              ") names no element of the file");
  });
}

// assimp's Collada importer loops without end on a primitive's index list (<p>, <vcount>, <v>,
// <h>, <int_array>) holding anything but integers, so those lists are checked first.
void requireIntegerIndexLists(const std::string& text, const std::string& path) {
  for (const char* tag : {"<p", "<vcount", "<v", "<h", "<int_array"}) {
    const std::size_t n = std::strlen(tag);
    for (std::size_t at = text.find(tag); at != std::string::npos; at = text.find(tag, at + 1)) {
      const char after = at + n < text.size() ? text[at + n] : '\0';
      if (after != '>' && !std::isspace(static_cast<unsigned char>(after))) continue;
      const std::size_t open_end = text.find('>', at);
      if (open_end == std::string::npos || text[open_end - 1] == '/') continue;
      for (std::size_t i = open_end + 1; i < text.size() && text[i] != '<'; ++i) {
        const unsigned char c = static_cast<unsigned char>(text[i]);
        if (std::isdigit(c) || std::isspace(c) || c == '-' || c == '+') continue;
        const auto line =
            1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(i), '\n');
        throw FileError(path, std::string(tag + 1) + " (line " + std::to_string(line) +
                                  ") holds a character that is not part of an integer");
      }
    }
  }
}

// assimp's Collada (and other XML) importers recurse once per nested element, so a deeply
// nested file overflows the stack: XML mesh files are pre-scanned for their nesting depth.
// assimp takes a file for Collada by its extension or by "<collada" near its start, whatever
// precedes it (its XML parser skips leading junk), so every such file is validated, and one
// that does not start with an element is refused rather than left unchecked.
void requireShallowXml(const std::string& path, std::uintmax_t max_bytes) {
  std::string head(4096, '\0');
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FileError(path, "cannot open mesh file");
    in.read(&head[0], static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
  }
  std::string lower_head = head;
  for (char& c : lower_head) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".zae") {
    throw FileError(path, "zipped COLLADA (.zae) is not supported: unzip it and load the .dae");
  }
  const bool collada = ext == ".dae" || lower_head.find("<collada") != std::string::npos;
  std::size_t i = 0;
  if (head.compare(0, 3, "\xEF\xBB\xBF") == 0) i = 3;  // a UTF-8 byte-order mark
  while (i < head.size() && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
  if (i >= head.size() || head[i] != '<') {
    if (collada) throw FileError(path, "a COLLADA file must start with an XML element ('<')");
    return;
  }
  const std::string text = readWholeFile(path, "mesh file", max_bytes);
  requireXmlDepth(text, path);
  if (collada || text.find("<COLLADA") != std::string::npos) {
    requireLocalSourcesDefined(text, path);
    requireIntegerIndexLists(text, path);
    detail::validateCollada(text, path);
  }
}

}  // namespace

TriangleMesh loadMesh(const std::string& path, const MeshLoadOptions& options) {
  if (!options.scale.allFinite() || options.scale.x() == 0.0 || options.scale.y() == 0.0 ||
      options.scale.z() == 0.0) {
    throw InvalidArgument("loadMesh: MeshLoadOptions.scale must be finite and non-zero (" + path +
                          ")");
  }
  requireRegularFile(path, "mesh file", options.max_file_bytes);
  requireShallowXml(path, options.max_file_bytes);
  Assimp::Importer importer;
  // Only triangles matter; drop point and line primitives instead of failing on them.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw FileError(path, std::string("cannot read mesh: ") + importer.GetErrorString());
  }
  TriangleMesh mesh;
  appendNode(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), true, options, &mesh);
  if (mesh.triangles.empty()) throw FileError(path, "mesh file contains no triangles");
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite()) {
      throw FileError(path, "vertex " + std::to_string(i) + " is not finite");
    }
  }
  return mesh;
}

void validateMesh(const TriangleMesh& mesh, const std::string& what) {
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (!mesh.vertices[i].allFinite()) {
      throw InvalidArgument(what + ": vertices[" + std::to_string(i) + "] is not finite");
    }
  }
  const std::size_t n = mesh.vertices.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::uint32_t index : mesh.triangles[t]) {
      if (index >= n) {
        throw InvalidArgument(what + ": triangles[" + std::to_string(t) + "] refers to vertex " +
                              std::to_string(index) + " of " + std::to_string(n));
      }
    }
  }
}

namespace detail {

std::vector<std::uint32_t> weldByPosition(const TriangleMesh& mesh) {
  std::unordered_map<Eigen::Vector3d, std::uint32_t, PositionHash, PositionEqual> first;
  first.reserve(mesh.vertices.size());
  std::vector<std::uint32_t> canonical(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    canonical[i] = first.emplace(mesh.vertices[i], static_cast<std::uint32_t>(i)).first->second;
  }
  return canonical;
}

EdgeCensus edgeCensus(const TriangleMesh& mesh) {
  const std::vector<std::uint32_t> canonical = weldByPosition(mesh);
  // Directed edge (a, b) -> number of triangles traversing it a to b.
  std::unordered_map<std::uint64_t, std::uint32_t> directed;
  directed.reserve(mesh.triangles.size() * 3);
  EdgeCensus census;
  for (const auto& tri : mesh.triangles) {
    const std::uint32_t v[3] = {canonical[tri[0]], canonical[tri[1]], canonical[tri[2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;  // no area, no surface
    ++census.triangles;
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t key = std::uint64_t{v[k]} << 32 | v[(k + 1) % 3];
      ++directed[key];
    }
  }
  for (const auto& [key, count] : directed) {
    const std::uint32_t a = static_cast<std::uint32_t>(key >> 32);
    const std::uint32_t b = static_cast<std::uint32_t>(key);
    const auto reverse = directed.find(std::uint64_t{b} << 32 | a);
    const std::uint32_t back = reverse == directed.end() ? 0u : reverse->second;
    if (count != 1 || back != 1) census.manifold = false;
    // Each undirected edge is seen from both of its directions when both exist; count it once.
    if (back != 0 && b < a) continue;
    if ((count + back) % 2 != 0) ++census.odd_edges;
  }
  return census;
}

}  // namespace detail

bool isClosedManifold(const TriangleMesh& mesh) {
  validateMesh(mesh, "isClosedManifold");
  const detail::EdgeCensus census = detail::edgeCensus(mesh);
  return census.triangles > 0 && census.manifold;
}

}  // namespace octomotion

namespace octomotion {
namespace {

void requireCount(int value, int minimum, const char* field) {
  if (value < minimum) {
    throw InvalidArgument(std::string(field) + " must be >= " + std::to_string(minimum) + ", got " +
                          std::to_string(value));
  }
}

void requireLength(double value, const char* field) {
  if (!std::isfinite(value) || !(value > 0.0)) {
    throw InvalidArgument(std::string(field) + " must be finite and > 0");
  }
}

std::uint32_t index(std::size_t i) {
  return static_cast<std::uint32_t>(i);
}

}  // namespace

TriangleMesh boxMesh(const Eigen::Vector3d& half_extents, int n) {
  requireCount(n, 1, "boxMesh: n");
  for (int i = 0; i < 3; ++i) requireLength(half_extents[i], "boxMesh: half_extents");
  TriangleMesh mesh;
  // Each face: normal axis a, sign s; (u, v) axes chosen so that u x v = s * e_a (outward).
  for (int a = 0; a < 3; ++a) {
    for (int s = -1; s <= 1; s += 2) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;  // e_u x e_v = e_a
      const std::size_t base = mesh.vertices.size();
      for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) {
          Eigen::Vector3d p;
          p[a] = s * half_extents[a];
          p[u] = half_extents[u] * (2.0 * i / n - 1.0);
          p[v] = half_extents[v] * (2.0 * j / n - 1.0);
          mesh.vertices.push_back(p);
        }
      }
      auto at = [&](int i, int j) {
        return index(base + static_cast<std::size_t>(j * (n + 1) + i));
      };
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const std::uint32_t p00 = at(i, j), p10 = at(i + 1, j), p01 = at(i, j + 1),
                              p11 = at(i + 1, j + 1);
          if (s > 0) {
            mesh.triangles.push_back({p00, p10, p11});
            mesh.triangles.push_back({p00, p11, p01});
          } else {
            mesh.triangles.push_back({p00, p11, p10});
            mesh.triangles.push_back({p00, p01, p11});
          }
        }
      }
    }
  }
  return mesh;
}

TriangleMesh sphereMesh(double radius, int segments, int rings) {
  requireLength(radius, "sphereMesh: radius");
  requireCount(segments, 3, "sphereMesh: segments");
  requireCount(rings, 2, "sphereMesh: rings");
  TriangleMesh mesh;
  mesh.vertices.emplace_back(0.0, 0.0, radius);  // north pole
  for (int r = 1; r < rings; ++r) {
    const double theta = M_PI * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2.0 * M_PI * s / segments;
      mesh.vertices.emplace_back(radius * std::sin(theta) * std::cos(phi),
                                 radius * std::sin(theta) * std::sin(phi),
                                 radius * std::cos(theta));
    }
  }
  mesh.vertices.emplace_back(0.0, 0.0, -radius);  // south pole
  const std::uint32_t south = index(mesh.vertices.size() - 1);
  auto ring = [&](int r, int s) {
    return index(1 + static_cast<std::size_t>((r - 1) * segments + s % segments));
  };
  for (int s = 0; s < segments; ++s) mesh.triangles.push_back({0, ring(1, s), ring(1, s + 1)});
  for (int r = 1; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      mesh.triangles.push_back({ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      mesh.triangles.push_back({ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
  }
  for (int s = 0; s < segments; ++s) {
    mesh.triangles.push_back({south, ring(rings - 1, s + 1), ring(rings - 1, s)});
  }
  return mesh;
}

TriangleMesh torusMesh(double R, double r, int segments, int sides) {
  requireLength(r, "torusMesh: r");
  if (!std::isfinite(R) || !(R > r)) throw InvalidArgument("torusMesh: R must be finite and > r");
  requireCount(segments, 3, "torusMesh: segments");
  requireCount(sides, 3, "torusMesh: sides");
  TriangleMesh mesh;
  for (int i = 0; i < segments; ++i) {
    const double u = 2.0 * M_PI * i / segments;
    for (int j = 0; j < sides; ++j) {
      const double v = 2.0 * M_PI * j / sides;
      const double rho = R + r * std::cos(v);
      mesh.vertices.emplace_back(rho * std::cos(u), rho * std::sin(u), r * std::sin(v));
    }
  }
  auto at = [&](int i, int j) {
    return index(static_cast<std::size_t>((i % segments) * sides + j % sides));
  };
  for (int i = 0; i < segments; ++i) {
    for (int j = 0; j < sides; ++j) {
      mesh.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      mesh.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return mesh;
}

Eigen::Vector3d centerOnVertexMean(TriangleMesh& mesh) {
  if (mesh.vertices.empty()) return Eigen::Vector3d::Zero();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : mesh.vertices) mean += v;
  mean /= static_cast<double>(mesh.vertices.size());
  for (Eigen::Vector3d& v : mesh.vertices) v -= mean;
  return mean;
}

}  // namespace octomotion
