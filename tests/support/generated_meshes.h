// Meshes and mesh files the project writes itself, for tests and the differential validation
// program: closed solids, open sheets, double-sided faces (each face written twice, once
// reversed, as SketchUp exports them), triangle soups; written as ASCII STL, OBJ or COLLADA.
// The COLLADA writer reproduces what real exported models carry: a node hierarchy with rotations
// and large translations, Z-up or X-up, a unit other than the metre, <lines> beside the
// triangles, and non-triangle polygons (<polylist>).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "octomotion/octree/mesh.h"

namespace octomotion::test {

// A polygon mesh: faces of 3 or more corners (convex, in order), and loose line segments.
struct PolyMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::vector<std::uint32_t>> faces;
  std::vector<std::array<std::uint32_t, 2>> lines;
};

inline PolyMesh fromTriangles(const TriangleMesh& mesh) {
  PolyMesh out;
  out.vertices = mesh.vertices;
  for (const auto& t : mesh.triangles) out.faces.push_back({t[0], t[1], t[2]});
  return out;
}

// Every face a second time with its corners reversed (a two-sided sheet has no inside).
inline PolyMesh doubleSided(PolyMesh mesh) {
  const std::size_t n = mesh.faces.size();
  for (std::size_t f = 0; f < n; ++f) {
    std::vector<std::uint32_t> reversed(mesh.faces[f].rbegin(), mesh.faces[f].rend());
    mesh.faces.push_back(std::move(reversed));
  }
  return mesh;
}

// An axis-aligned box from lo to hi as six quads (outward).
inline PolyMesh boxQuads(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  PolyMesh m;
  for (int k = 0; k < 8; ++k) {
    m.vertices.emplace_back((k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(),
                            (k & 4) ? hi.z() : lo.z());
  }
  m.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  // Edges of the box as lines too, as SketchUp writes them beside the faces.
  m.lines = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3}, {4, 6}, {5, 7}};
  return m;
}

// Several meshes in one (vertex indices shifted).
inline PolyMesh merged(const std::vector<PolyMesh>& parts) {
  PolyMesh out;
  for (const PolyMesh& p : parts) {
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), p.vertices.begin(), p.vertices.end());
    for (auto f : p.faces) {
      for (auto& i : f) i += base;
      out.faces.push_back(std::move(f));
    }
    for (auto l : p.lines) out.lines.push_back({l[0] + base, l[1] + base});
  }
  return out;
}

// An open square sheet in the plane z = 0 (one quad per cell of an n x n grid).
inline PolyMesh sheet(double half, int n) {
  PolyMesh m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      m.vertices.emplace_back(half * (2.0 * i / n - 1), half * (2.0 * j / n - 1), 0.0);
    }
  }
  auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i)
      m.faces.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
  }
  return m;
}

// A closed star-shaped blob: a tessellated unit sphere with each vertex pushed out by a random
// factor in [1 - bump, 1 + bump].
inline TriangleMesh blobMesh(double radius, double bump, std::mt19937_64& rng) {
  TriangleMesh m = sphereMesh(1.0, 12, 8);
  std::uniform_real_distribution<double> u(1 - bump, 1 + bump);
  for (Eigen::Vector3d& v : m.vertices) v *= radius * u(rng);
  return m;
}

inline TriangleMesh triangulated(const PolyMesh& mesh) {
  TriangleMesh out;
  out.vertices = mesh.vertices;
  for (const auto& f : mesh.faces) {
    for (std::size_t k = 1; k + 1 < f.size(); ++k) out.triangles.push_back({f[0], f[k], f[k + 1]});
  }
  return out;
}

inline PolyMesh transformedPoly(PolyMesh mesh, const Eigen::Isometry3d& X) {
  for (Eigen::Vector3d& v : mesh.vertices) v = X * v;
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// Writers. Numbers are written with 17 significant digits, so a file read back gives the same
// doubles (COLLADA readers parse floats: assimp reads them as single precision).

inline std::string number(double v) {
  std::ostringstream out;
  out.precision(17);
  out << v;
  return out.str();
}

inline void writeStl(const std::string& path, const TriangleMesh& mesh) {
  std::ofstream out(path);
  out << "solid generated\n";
  for (const auto& t : mesh.triangles) {
    out << " facet normal 0 0 0\n  outer loop\n";
    for (std::uint32_t i : t) {
      const Eigen::Vector3d& v = mesh.vertices[i];
      out << "   vertex " << number(v.x()) << ' ' << number(v.y()) << ' ' << number(v.z()) << '\n';
    }
    out << "  endloop\n endfacet\n";
  }
  out << "endsolid generated\n";
}

inline void writeObj(const std::string& path, const PolyMesh& mesh) {
  std::ofstream out(path);
  for (const Eigen::Vector3d& v : mesh.vertices) {
    out << "v " << number(v.x()) << ' ' << number(v.y()) << ' ' << number(v.z()) << '\n';
  }
  for (const auto& f : mesh.faces) {
    out << 'f';
    for (std::uint32_t i : f) out << ' ' << i + 1;
    out << '\n';
  }
  for (const auto& l : mesh.lines) out << "l " << l[0] + 1 << ' ' << l[1] + 1 << '\n';
}

// One node of a COLLADA visual scene: its <matrix> (row-major, as COLLADA writes it), the
// geometries it instances (indices into ColladaDocument::geometries) and its children.
struct ColladaNode {
  Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
  std::vector<int> geometries;
  std::vector<ColladaNode> children;
};

struct ColladaDocument {
  std::string up_axis = "Z_UP";  // Y_UP, Z_UP or X_UP
  double unit_metres = 1.0;      // <unit meter=...>
  std::vector<PolyMesh> geometries;
  std::vector<ColladaNode> nodes;  // the visual scene's top-level nodes
};

inline std::string colladaText(const ColladaDocument& doc) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      << "<!-- Generated by octomotion's tests (tests/support/generated_meshes.h). -->\n"
      << "<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n"
      << "  <asset>\n    <unit name=\"generated\" meter=\"" << number(doc.unit_metres)
      << "\"/>\n    <up_axis>" << doc.up_axis << "</up_axis>\n  </asset>\n"
      << "  <library_geometries>\n";
  for (std::size_t g = 0; g < doc.geometries.size(); ++g) {
    const PolyMesh& m = doc.geometries[g];
    const std::string id = "g" + std::to_string(g);
    out << "    <geometry id=\"" << id << "\">\n      <mesh>\n        <source id=\"" << id
        << "-pos\">\n          <float_array id=\"" << id << "-arr\" count=\""
        << 3 * m.vertices.size() << "\">";
    for (const Eigen::Vector3d& v : m.vertices) {
      out << number(v.x()) << ' ' << number(v.y()) << ' ' << number(v.z()) << ' ';
    }
    out << "</float_array>\n          <technique_common>\n            <accessor source=\"#" << id
        << "-arr\" count=\"" << m.vertices.size()
        << "\" stride=\"3\"><param name=\"X\" type=\"float\"/><param name=\"Y\" "
           "type=\"float\"/><param name=\"Z\" type=\"float\"/></accessor>\n"
        << "          </technique_common>\n        </source>\n        <vertices id=\"" << id
        << "-vtx\"><input semantic=\"POSITION\" source=\"#" << id << "-pos\"/></vertices>\n";
    std::vector<const std::vector<std::uint32_t>*> triangles, polygons;
    for (const auto& f : m.faces) (f.size() == 3 ? triangles : polygons).push_back(&f);
    const std::string input =
        "<input semantic=\"VERTEX\" source=\"#" + id + "-vtx\" offset=\"0\"/>";
    if (!triangles.empty()) {
      out << "        <triangles count=\"" << triangles.size() << "\">" << input << "<p>";
      for (const auto* f : triangles) out << (*f)[0] << ' ' << (*f)[1] << ' ' << (*f)[2] << ' ';
      out << "</p></triangles>\n";
    }
    if (!polygons.empty()) {
      out << "        <polylist count=\"" << polygons.size() << "\">" << input << "<vcount>";
      for (const auto* f : polygons) out << f->size() << ' ';
      out << "</vcount><p>";
      for (const auto* f : polygons) {
        for (std::uint32_t i : *f) out << i << ' ';
      }
      out << "</p></polylist>\n";
    }
    if (!m.lines.empty()) {
      out << "        <lines count=\"" << m.lines.size() << "\">" << input << "<p>";
      for (const auto& l : m.lines) out << l[0] << ' ' << l[1] << ' ';
      out << "</p></lines>\n";
    }
    out << "      </mesh>\n    </geometry>\n";
  }
  out << "  </library_geometries>\n  <library_visual_scenes>\n    <visual_scene id=\"scene\">\n";
  int next_id = 0;
  auto writeNode = [&](auto&& self, const ColladaNode& node, int indent) -> void {
    const std::string pad(static_cast<std::size_t>(indent), ' ');
    out << pad << "<node id=\"n" << next_id++ << "\">\n" << pad << "  <matrix>";
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) out << number(node.matrix(r, c)) << ' ';
    }
    out << "</matrix>\n";
    for (int g : node.geometries) out << pad << "  <instance_geometry url=\"#g" << g << "\"/>\n";
    for (const ColladaNode& child : node.children) self(self, child, indent + 2);
    out << pad << "</node>\n";
  };
  for (const ColladaNode& node : doc.nodes) writeNode(writeNode, node, 6);
  out << "    </visual_scene>\n  </library_visual_scenes>\n"
      << "  <scene><instance_visual_scene url=\"#scene\"/></scene>\n</COLLADA>\n";
  return out.str();
}

inline void writeCollada(const std::string& path, const ColladaDocument& doc) {
  std::ofstream(path) << colladaText(doc);
}

inline Eigen::Matrix4d rigidMatrix(const Eigen::Vector3d& axis, double angle,
                                   const Eigen::Vector3d& translation) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  X.translation() = translation;
  return X.matrix();
}

}  // namespace octomotion::test
