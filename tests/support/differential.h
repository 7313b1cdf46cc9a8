// Randomised differential validation against FCL (docs/validation.md §6): scenes the project did
// not author, generated from a seed, checked state by state by the octree model and by exact FCL.
// Each case draws a robot — a generated rigid body (closed, double-sided, open or soup meshes of
// 1 cm to 100 m, written as STL, OBJ or COLLADA with node transforms, units and up axes), a
// shipped arm, or the real Panda when its folder is given — an environment of generated meshes,
// primitives and point clouds scaled to it, a resolution, link-tree ratios, a rounding, a checker
// path, exact primitives or not and self-pair tables or not; then uniform random states. It counts,
// per path, the states FCL finds in contact that the octree calls free (false negatives: none
// allowed with conservative rounding) and the distances of the states it rejects that FCL calls
// free, against the margin docs/validation.md derives for that path (none allowed beyond it, either
// rounding). Used by bench/validation_differential_bench (millions of states) and by a bounded
// test.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <ompl/util/Console.h>

#include "fcl_reference.h"
#include "generated_meshes.h"
#include "octomotion/octree/mesh.h"
#include "octomotion/octree/shapes.h"
#include "octomotion/planner/robot/collision_meshes.h"

namespace octomotion::validation {

struct DifferentialOptions {
  std::uint64_t seed = 1;
  std::size_t states = 1000000;  // in all, over as many cases as it takes
  std::size_t states_per_case = 2000;
  std::string work_dir;         // where each case's files are written (case_N/)
  std::string source_dir;       // the repository (robots/ for the shipped arms)
  std::string panda_dir;        // a folder with panda.urdf and panda.srdf; empty: no Panda cases
  std::ostream* log = nullptr;  // one line per case when set
};

// What one checker path (rounding, path, exact primitives) saw over all its cases.
struct PathTally {
  std::size_t cases = 0, states = 0;
  std::size_t fcl_env = 0, fcl_self = 0;        // FCL's contacts
  std::size_t missed_env = 0, missed_self = 0;  // false negatives
  std::size_t extra_env = 0, extra_self = 0;    // false positives
  std::size_t beyond = 0;                       // false positives farther than the margin
  std::size_t inside_solid = 0;  // ... where one solid lies wholly inside another (FCL: surfaces)
  std::vector<double> ratio;     // false positive's FCL distance / margin
};

struct DifferentialReport {
  std::size_t cases = 0, states = 0;
  std::map<std::string, PathTally> paths;
  std::vector<std::string> failures;  // the first few, each naming its case's scene file
};

namespace differential_detail {

using test::PolyMesh;

inline double logUniform(std::mt19937_64& rng, double lo, double hi) {
  return std::exp(std::uniform_real_distribution<double>(std::log(lo), std::log(hi))(rng));
}

inline Eigen::Isometry3d randomRigid(std::mt19937_64& rng, double translation) {
  std::normal_distribution<double> gauss;
  Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = translation * Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
  return X;
}

// A mesh of about unit size, of a random kind.
inline PolyMesh randomShape(std::mt19937_64& rng, std::string* kind) {
  std::uniform_int_distribution<int> pick(0, 6);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto side = [&] { return 0.1 + 0.4 * unit(rng); };
  switch (pick(rng)) {
    case 0:
      *kind = "blob";
      return test::fromTriangles(test::blobMesh(0.5, 0.4, rng));
    case 1:
      *kind = "double-sided box";
      return test::doubleSided(
          test::boxQuads({-side(), -side(), -side()}, {side(), side(), side()}));
    case 2:
      *kind = "L of two double-sided boxes";
      return test::doubleSided(
          test::merged({test::boxQuads({-0.5, -0.1, -0.1}, {0.5, 0.1, 0.1}),
                        test::boxQuads({-0.5, -0.1, -0.1}, {-0.3, 0.5, 0.1})}));
    case 3: {
      *kind = "open box";
      PolyMesh m = test::boxQuads({-side(), -side(), -side()}, {side(), side(), side()});
      m.faces.pop_back();
      return m;
    }
    case 4:
      *kind = "torus";
      return test::fromTriangles(torusMesh(0.35, 0.1 + 0.1 * unit(rng), 16, 8));
    case 5:
      *kind = "sheet";
      return test::sheet(0.5, 2);
    default: {
      *kind = "triangle soup";
      PolyMesh m;
      for (int t = 0; t < 10; ++t) {
        const auto base = static_cast<std::uint32_t>(m.vertices.size());
        for (int c = 0; c < 3; ++c) {
          m.vertices.emplace_back(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5);
        }
        m.faces.push_back({base, base + 1, base + 2});
      }
      return m;
    }
  }
}

// Writes the shape, scaled to `size` and moved off its origin, as STL, OBJ or COLLADA (random
// unit, up axis and node hierarchy); returns the file name (relative to dir) and what it is.
// `units`: COLLADA files may carry a unit other than the metre (the reader then applies it only
// where the root transform is kept, so URDF meshes, which drop it, are written in metres).
inline std::string writeShape(std::mt19937_64& rng, const std::string& dir, const std::string& stem,
                              double size, std::string* what, bool units = true) {
  std::string kind;
  PolyMesh m = randomShape(rng, &kind);
  for (Eigen::Vector3d& v : m.vertices) v *= size;
  // Half of them axis-aligned, as authored models mostly are: their extreme faces then lie on
  // voxel boundaries of the grids fitted to them.
  Eigen::Isometry3d authored = randomRigid(rng, size);
  const bool aligned = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
  if (aligned) authored.linear().setIdentity();
  m = test::transformedPoly(m, authored);
  std::uniform_int_distribution<int> format(0, 3);
  std::ostringstream out;
  out << (aligned ? "aligned " : "") << kind << " " << size << " m";
  const int f = format(rng);
  std::string file;
  if (f == 0) {
    file = stem + ".stl";
    test::writeStl(dir + "/" + file, test::triangulated(m));
  } else if (f == 1) {
    file = stem + ".obj";
    test::writeObj(dir + "/" + file, m);
  } else {
    file = stem + ".dae";
    test::ColladaDocument doc;
    const char* axes[] = {"Y_UP", "Z_UP", "X_UP"};
    doc.up_axis = axes[std::uniform_int_distribution<int>(0, 2)(rng)];
    const double unit_choices[] = {1.0, 0.01, 0.0254};
    doc.unit_metres = units ? unit_choices[std::uniform_int_distribution<int>(0, 2)(rng)] : 1.0;
    for (Eigen::Vector3d& v : m.vertices) v /= doc.unit_metres;  // about `size` once read
    doc.geometries.push_back(m);
    // One to three nested nodes with rotations and translations of up to 100 sizes; the
    // geometry is moved back by their inverse so that it stays near the origin.
    const int depth = std::uniform_int_distribution<int>(1, 3)(rng);
    Eigen::Isometry3d total = Eigen::Isometry3d::Identity();
    std::vector<Eigen::Isometry3d> chain;
    for (int k = 0; k < depth; ++k) {
      chain.push_back(randomRigid(rng, 100 * size / doc.unit_metres));
      total = total * chain.back();
    }
    doc.geometries[0] = test::transformedPoly(m, total.inverse());
    test::ColladaNode leaf;
    leaf.matrix = chain.back().matrix();
    leaf.geometries = {0};
    for (int k = depth - 2; k >= 0; --k) {
      test::ColladaNode parent;
      parent.matrix = chain[static_cast<std::size_t>(k)].matrix();
      parent.children.push_back(leaf);
      leaf = parent;
    }
    doc.nodes.push_back(leaf);
    test::writeCollada(dir + "/" + file, doc);
    out << " (COLLADA " << doc.up_axis << ", unit " << doc.unit_metres << ", " << depth
        << " nodes)";
  }
  *what = out.str() + " as " + file;
  return file;
}

struct Case {
  std::string scene_file;
  std::string description;
  SceneOverrides overrides;
  // Some mesh is not closed, so it is voxelized as a shell whatever the rounding (voxelize.h):
  // the centre path's margin is then that of a touching voxel (docs/validation.md §3).
  bool shells = false;
};

// Whether writeShape's description names a shape that is not closed.
inline bool isShell(const std::string& shape) {
  return shape.find("open box") != std::string::npos || shape.find("sheet") != std::string::npos ||
         shape.find("soup") != std::string::npos;
}

inline std::string yamlVector(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out.precision(17);
  out << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return out.str();
}

inline Case makeCase(std::mt19937_64& rng, const DifferentialOptions& options, std::size_t index) {
  namespace fs = std::filesystem;
  const std::string dir = options.work_dir + "/case_" + std::to_string(index);
  fs::create_directories(dir);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Case c;
  std::ostringstream yaml, what;
  yaml.precision(17);
  // The robot, by turns: generated rigid bodies (two cases in five, three in ten), a generated
  // serial arm (one in ten), a shipped arm, the Panda (or a shipped arm without it).
  double size = 1.0;  // the robot's scale, for the environment and the resolution
  bool arm = false, generated_arm = false;
  const int kind = static_cast<int>(index % 5);
  if (kind == 2 && (index / 5) % 2 == 0) {
    arm = generated_arm = true;
    // Two to five links, each a generated mesh along its length, revolute or prismatic joints
    // about random axes, joint frames turned now and then; 2 cm to 20 m per link.
    const int links = std::uniform_int_distribution<int>(2, 5)(rng);
    const double length = logUniform(rng, 0.02, 20.0);
    std::ostringstream urdf;
    urdf.precision(17);
    urdf << "<robot name=\"generated_arm\">\n";
    std::string shapes;
    for (int l = 0; l < links; ++l) {
      std::string shape;
      const std::string file =
          writeShape(rng, dir, "link" + std::to_string(l), length / 2, &shape, false);
      shapes += (l ? ", " : "") + shape;
      c.shells |= isShell(shape);
      urdf << "  <link name=\"l" << l << "\"><collision><origin xyz=\"0 0 " << length / 2
           << "\"/><geometry><mesh filename=\"" << file << "\"/></geometry></collision></link>\n";
      if (l == 0) continue;
      const bool prismatic = unit(rng) < 0.2;
      const char* axes[] = {"1 0 0", "0 1 0", "0 0 1"};
      urdf << "  <joint name=\"j" << l << "\" type=\"" << (prismatic ? "prismatic" : "revolute")
           << "\"><parent link=\"l" << l - 1 << "\"/><child link=\"l" << l
           << "\"/><origin xyz=\"0 0 " << length << "\" rpy=\""
           << (unit(rng) < 0.5 ? 0.0 : M_PI / 2) << " 0 " << (unit(rng) < 0.5 ? 0.0 : 0.7)
           << "\"/><axis xyz=\"" << axes[std::uniform_int_distribution<int>(0, 2)(rng)]
           << "\"/><limit lower=\"" << (prismatic ? -0.3 * length : -2.5) << "\" upper=\""
           << (prismatic ? 0.3 * length : 2.5) << "\" effort=\"1\" velocity=\"1\"/></joint>\n";
    }
    urdf << "</robot>\n";
    std::ofstream(dir + "/arm.urdf") << urdf.str();
    yaml << "robot:\n  urdf: arm.urdf\n";
    size = links * length;
    what << "generated arm of " << links << " links (" << shapes << ")";
  } else if (kind == 4 || kind == 3) {
    arm = true;
    std::string urdf, srdf;
    if (kind == 4 && !options.panda_dir.empty()) {
      urdf = options.panda_dir + "/panda.urdf";
      srdf = options.panda_dir + "/panda.srdf";
    } else {
      const std::string name = index % 2 ? "octo6" : "octo7";
      urdf = options.source_dir + "/robots/" + name + "/" + name + ".urdf";
      srdf = options.source_dir + "/robots/" + name + "/" + name + ".srdf";
      c.overrides.package_paths = {options.source_dir};
    }
    yaml << "robot:\n  urdf: " << urdf << "\n  srdf: " << srdf << "\n";
    what << fs::path(urdf).stem().string();
  } else {
    size = logUniform(rng, 0.01, 100.0);
    std::string shape;
    const std::string file = writeShape(rng, dir, "robot", size, &shape);
    c.shells |= isShell(shape);
    const bool center = unit(rng) < 0.5, keep_root = unit(rng) < 0.7;
    yaml << "robot:\n  mesh: " << file << "\n  center_vertices: " << (center ? "true" : "false")
         << "\n  keep_root_transform: " << (keep_root ? "true" : "false") << "\n";
    // The body as the scene will read it, to place the environment around it.
    MeshLoadOptions load;
    load.keep_root_transform = keep_root;
    TriangleMesh body = loadMesh(dir + "/" + file, load);
    if (center) centerOnVertexMean(body);
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& v : body.vertices) box.extend(v);
    size = std::max(box.sizes().maxCoeff(), 1e-3);
    what << "rigid " << shape;
  }
  // The environment: objects of a tenth to one robot size, in a cube of four robot sizes (arms:
  // in front of them, within a metre).
  const bool shipped_arm = arm && !generated_arm;
  const double half = shipped_arm ? 0.8 : (generated_arm ? 0.7 : 2.0) * size;
  const Eigen::Vector3d centre =
      shipped_arm ? Eigen::Vector3d(0.3, 0.0, 0.5) : Eigen::Vector3d::Zero();
  yaml << "environment:\n";
  const int objects = std::uniform_int_distribution<int>(2, 6)(rng);
  const double scale = shipped_arm ? 0.5 : (generated_arm ? 0.3 : 1.0) * size;
  int clouds = 0, meshes = 0, primitives = 0;
  for (int k = 0; k < objects; ++k) {
    const Eigen::Vector3d at =
        centre + half * Eigen::Vector3d(2 * unit(rng) - 1, 2 * unit(rng) - 1, 2 * unit(rng) - 1);
    Eigen::Quaterniond q(randomRigid(rng, 0).linear());
    if (unit(rng) < 0.5) q.setIdentity();
    std::ostringstream pose_text;
    pose_text.precision(17);
    pose_text << "    pose: {xyz: " << yamlVector(at) << ", quat: [" << q.x() << ", " << q.y()
              << ", " << q.z() << ", " << q.w() << "]}\n";  // [qx, qy, qz, qw]
    const std::string pose = pose_text.str();
    const double s = scale * (0.1 + 0.9 * unit(rng));
    const double draw = unit(rng);
    yaml << "  - name: object" << k << "\n";
    if (draw < 0.45) {
      ++primitives;
      const int p = std::uniform_int_distribution<int>(0, 2)(rng);
      if (p == 0) {
        yaml << "    box: {size: "
             << yamlVector(s *
                           Eigen::Vector3d(unit(rng) + 0.05, unit(rng) + 0.05, unit(rng) + 0.05))
             << "}\n";
      } else if (p == 1) {
        yaml << "    sphere: {radius: " << s / 2 << "}\n";
      } else {
        yaml << "    cylinder: {radius: " << s / 4 << ", length: " << s << "}\n";
      }
      yaml << pose;
    } else if (draw < 0.9 || clouds > 0) {
      ++meshes;
      std::string shape;
      const std::string file = writeShape(rng, dir, "object" + std::to_string(k), s, &shape);
      c.shells |= isShell(shape);
      yaml << "    mesh: {file: " << file
           << ", keep_root_transform: " << (unit(rng) < 0.5 ? "true" : "false") << "}\n"
           << pose;
    } else {
      ++clouds;
      // Points on a random plane patch (a scanned surface).
      const std::string file = "cloud" + std::to_string(k) + ".xyz";
      std::ofstream points(dir + "/" + file);
      points.precision(9);
      const Eigen::Isometry3d X = randomRigid(rng, 0);
      for (int i = 0; i < 400; ++i) {
        const Eigen::Vector3d p =
            at + X.linear() * Eigen::Vector3d(s * (unit(rng) - 0.5), s * (unit(rng) - 0.5), 0);
        points << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
      }
      yaml << "    pointcloud: {file: " << file << "}\n";
    }
  }
  what << "; " << primitives << " primitives, " << meshes << " meshes, " << clouds << " clouds";
  // The octree settings.
  const double resolution = shipped_arm ? std::vector<double>{0.01, 0.02, 0.04}[index % 3]
                                        : size / logUniform(rng, 6.0, 40.0);
  // The path by turns, independently of the robot's kind (index % 5): conservative fused,
  // conservative moveTree, centre (fused or moveTree), conservative fused, conservative moveTree.
  const std::size_t turn = (index / 5 + index) % 5;
  const bool centre_rounding = turn == 2;
  const bool fused = turn == 0 || turn == 3 || (turn == 2 && index % 2 == 0);
  // Link trees from the environment's voxel down to an eighth of it; the moveTree path, which
  // builds a world tree per link and state, to half of it (finer ones take minutes a case).
  const double link_ratio = std::vector<double>{
      1.0, 0.5, 0.25, 0.125}[std::uniform_int_distribution<int>(0, fused ? 3 : 1)(rng)];
  const bool exact = !centre_rounding && primitives > 0 && unit(rng) < 0.3;
  c.overrides.resolution = resolution;
  c.overrides.link_resolution = resolution * link_ratio;
  if (arm && unit(rng) < 0.4) c.overrides.self_link_resolution = resolution * link_ratio;
  c.overrides.rounding = centre_rounding ? Rounding::kCenter : Rounding::kConservative;
  c.overrides.checker = fused ? CheckerKind::kOctreeFused : CheckerKind::kOctree;
  c.overrides.exact_primitives = exact;
  // The voxels' own answers (their margins are what is scored), not the default exact refine.
  c.overrides.refine = RefineMode::kNone;
  // Self-pair tables where they are cheap to build (octo7: one small table, in well under a
  // second), conservative rounding only.
  const bool octo7 = what.str().rfind("octo7", 0) == 0;
  c.overrides.self_pair_tables = octo7 && !centre_rounding && unit(rng) < 0.5;
  if (!arm) {
    const Eigen::Vector3d lo = centre - Eigen::Vector3d::Constant(half + size);
    const Eigen::Vector3d hi = centre + Eigen::Vector3d::Constant(half + size);
    yaml << "problem:\n  bounds: {min: " << yamlVector(lo) << ", max: " << yamlVector(hi) << "}\n";
  }
  c.scene_file = dir + "/scene.yaml";
  std::ofstream(c.scene_file) << yaml.str();
  what << "; resolution " << resolution << " m, link x" << link_ratio;
  c.description = what.str();
  return c;
}

inline std::string pathName(const Case& c, bool exact_applied) {
  std::string name = *c.overrides.rounding == Rounding::kCenter ? "center" : "conservative";
  name += *c.overrides.checker == CheckerKind::kOctree ? " moveTree" : " fused";
  if (exact_applied) name += " exact-primitives";
  if (c.overrides.self_pair_tables.value_or(false)) name += " self-pair-tables";
  return name;
}

// FCL's meshes are surfaces (docs/validation.md, "The reference"): a body wholly inside a closed
// mesh, or a closed mesh wholly inside a body, does not collide for FCL although the solids
// overlap, and the octree fills closed meshes. Such a state is neither a missed contact nor a
// margin violation; it is told apart by testing one point of each body against the other
// body's solids (primitives, and meshes that are closed manifolds, by ray parity).
class Solids {
 public:
  Solids(const PlanningScene& scene) : robot_(scene.model->robot()) {
    CollisionMeshes meshes(scene.spec.robot.keep_mesh_root_transform,
                           scene.spec.robot.center_mesh_vertices);
    links_.resize(static_cast<std::size_t>(robot_.linkCount()));
    for (int l = 0; l < robot_.linkCount(); ++l) {
      for (const CollisionElement& e : robot_.link(l).collision) {
        Part part;
        part.X = e.X_LE;
        if (const auto* prim = std::get_if<Primitive>(&e.geometry)) {
          part.primitive = *prim;
        } else {
          const TriangleMesh& mesh = meshes.get(std::get<MeshRef>(e.geometry));
          part.mesh = std::make_shared<TriangleMesh>(mesh);
          part.solid = isClosedManifold(mesh);
        }
        links_[static_cast<std::size_t>(l)].push_back(std::move(part));
      }
    }
    for (const auto& item : scene.environment->items()) {
      Part part;
      part.X = item.spec.X_WO;
      if (item.spec.kind == EnvironmentObject::Kind::kPrimitive) {
        part.primitive = item.spec.primitive;
      } else if (item.spec.kind == EnvironmentObject::Kind::kMesh) {
        part.mesh = std::make_shared<TriangleMesh>(item.mesh);
        part.solid = isClosedManifold(item.mesh);
      } else {
        for (const Eigen::Vector3f& p : item.points_W) cloud_points_.push_back(p.cast<double>());
        continue;
      }
      objects_.push_back(std::move(part));
    }
  }

  // With the link poses of `data`: is a link inside an object's solid or the reverse?
  bool environmentNested(const RobotData& data) const {
    for (int l = 0; l < robot_.linkCount(); ++l) {
      const Eigen::Isometry3d& X_WL = data.linkPose(l);
      for (const Part& link_part : links_[static_cast<std::size_t>(l)]) {
        const Eigen::Isometry3d X_W = X_WL * link_part.X;
        for (const Part& object : objects_) {
          if (inside(object, object.X, point(link_part, X_W))) return true;
          if (inside(link_part, X_W, point(object, object.X))) return true;
        }
        for (const Eigen::Vector3d& p : cloud_points_) {
          if (inside(link_part, X_W, p)) return true;
        }
      }
    }
    return false;
  }

  bool selfNested(const RobotData& data) const {
    for (const auto& [a, b] : robot_.checkedPairs()) {
      for (const Part& pa : links_[static_cast<std::size_t>(a)]) {
        for (const Part& pb : links_[static_cast<std::size_t>(b)]) {
          const Eigen::Isometry3d Xa = data.linkPose(a) * pa.X, Xb = data.linkPose(b) * pb.X;
          if (inside(pa, Xa, point(pb, Xb)) || inside(pb, Xb, point(pa, Xa))) return true;
        }
      }
    }
    return false;
  }

 private:
  struct Part {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();  // link or world frame of the part
    std::optional<Primitive> primitive;
    std::shared_ptr<const TriangleMesh> mesh;
    bool solid = false;
  };

  static Eigen::Vector3d point(const Part& part, const Eigen::Isometry3d& X_W) {
    return part.mesh ? Eigen::Vector3d(X_W * part.mesh->vertices.front()) : X_W.translation();
  }

  // Parity of the crossings of a ray in a fixed generic direction (Moeller-Trumbore).
  static bool inside(const Part& part, const Eigen::Isometry3d& X_W, const Eigen::Vector3d& p_W) {
    const Eigen::Vector3d p = X_W.inverse() * p_W;
    if (part.primitive) return containsPoint(*part.primitive, p);
    if (!part.solid) return false;
    const Eigen::Vector3d d = Eigen::Vector3d(0.5477, 0.3211, 0.7734).normalized();
    bool odd = false;
    const TriangleMesh& m = *part.mesh;
    for (const auto& t : m.triangles) {
      const Eigen::Vector3d& a = m.vertices[t[0]];
      const Eigen::Vector3d e1 = m.vertices[t[1]] - a, e2 = m.vertices[t[2]] - a;
      const Eigen::Vector3d h = d.cross(e2);
      const double det = e1.dot(h);
      if (std::abs(det) < 1e-300) continue;
      const Eigen::Vector3d sv = p - a;
      const double u = sv.dot(h) / det;
      if (u < 0 || u > 1) continue;
      const Eigen::Vector3d qv = sv.cross(e1);
      const double v = d.dot(qv) / det;
      if (v < 0 || u + v > 1) continue;
      if (e2.dot(qv) / det > 0) odd = !odd;
    }
    return odd;
  }

  const RobotModel& robot_;
  std::vector<std::vector<Part>> links_;
  std::vector<Part> objects_;
  std::vector<Eigen::Vector3d> cloud_points_;
};

}  // namespace differential_detail

inline DifferentialReport runDifferential(const DifferentialOptions& options) {
  using namespace differential_detail;
  ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
  DifferentialReport report;
  std::mt19937_64 rng(options.seed);
  for (std::size_t index = 0; report.states < options.states; ++index) {
    const Case c = makeCase(rng, options, index);
    PlanningScene scene;
    try {
      // Warnings (open meshes voxelized as shells, ...) are expected of generated input.
      scene = loadPlanningScene(c.scene_file, c.overrides, [](const std::string&) {});
    } catch (const Error& e) {
      // A generated case the library refuses (e.g. a resolution too fine for the universe) is
      // no answer to check; the refusal itself is the robustness tests' business.
      if (options.log) *options.log << "case " << index << " refused: " << e.what() << "\n";
      continue;
    }
    const OctreeCollisionModel& octree = *scene.model;
    const std::shared_ptr<const FclCollisionModel> reference = exactReference(scene);
    const FclCollisionModel& fcl = *reference;
    const bool exact_applied = octree.report().exact_primitives > 0;
    const bool only_primitives =
        exact_applied && octree.report().exact_primitives_other_objects == 0;
    const bool centre = octree.rounding() == Rounding::kCenter;
    const Resolutions r = resolutionsOf(octree);
    // docs/validation.md §2-3: the margin of each path.
    const double s3 = std::sqrt(3.0);
    const double centre_env = c.shells ? s3 / 2 * r.environment + s3 * r.link : s3 / 2 * r.link;
    const double centre_self = c.shells ? 1.5 * s3 * r.self_link : s3 / 2 * r.self_link;
    const double delta_env =
        (centre ? centre_env : s3 * ((only_primitives ? 0.0 : r.environment) + r.link)) +
        kTieSlack * std::max(1.0, r.environment);
    const double delta_self =
        (centre ? centre_self : 2 * s3 * r.self_link) + kTieSlack * std::max(1.0, r.environment);
    const CheckerPath path = octreeCheckerPath(*c.overrides.checker);
    PathTally& tally = report.paths[pathName(c, exact_applied)];
    ++tally.cases;
    ++report.cases;
    const OctreeBackend checked(scene.model, path);
    const std::unique_ptr<BackendScratch> scratch = checked.makeBackendScratch();
    const std::unique_ptr<BackendScratch> exact = fcl.makeBackendScratch();
    const RobotData& poses = checked.scratchOf(*scratch).check.robot;
    const std::vector<Sample> samples = uniformSamples(scene, options.states_per_case, rng());
    const Solids solids(scene);
    std::size_t case_missed = 0, case_beyond = 0;
    std::string first;  // the first failing state of the case
    auto note = [&](const Sample& s, const std::string& what) {
      if (first.empty()) first = what + " at " + describe(s);
    };
    for (const Sample& s : samples) {
      const auto [fe, fs, oe, os] = answersAt(s, fcl, *exact, checked, *scratch);
      tally.fcl_env += fe;
      tally.fcl_self += fs;
      if (fe && !oe) {
        ++tally.missed_env;
        if (!centre) ++case_missed, note(s, "missed environment contact");
      }
      if (fs && !os) {
        ++tally.missed_self;
        if (!centre) ++case_missed, note(s, "missed self contact");
      }
      if (oe && !fe) {
        ++tally.extra_env;
        const double d = fcl.environmentDistance(fcl.scratchOf(*exact), 2 * delta_env);
        if (d <= delta_env) tally.ratio.push_back(d / delta_env);
        if (d > delta_env && solids.environmentNested(poses)) {
          ++tally.inside_solid;
        } else if (d > delta_env) {
          ++tally.beyond, ++case_beyond;
          note(s, "environment rejected at FCL distance " + std::to_string(d) + " > " +
                      std::to_string(delta_env));
        }
      }
      if (os && !fs) {
        ++tally.extra_self;
        const double d = fcl.selfDistance(fcl.scratchOf(*exact), 2 * delta_self);
        if (d <= delta_self) tally.ratio.push_back(d / delta_self);
        if (d > delta_self && solids.selfNested(poses)) {
          ++tally.inside_solid;
        } else if (d > delta_self) {
          ++tally.beyond, ++case_beyond;
          note(s, "self pair rejected at FCL distance " + std::to_string(d) + " > " +
                      std::to_string(delta_self));
        }
      }
    }
    tally.states += samples.size();
    report.states += samples.size();
    if ((case_missed || case_beyond) && report.failures.size() < 10) {
      report.failures.push_back(c.scene_file + " (" + pathName(c, exact_applied) + "; " +
                                c.description + "): " + std::to_string(case_missed) +
                                " missed contacts, " + std::to_string(case_beyond) +
                                " rejections beyond the margin; first: " + first);
    }
    if (options.log) {
      *options.log << "case " << index << " " << pathName(c, exact_applied) << ": " << c.description
                   << "; " << case_missed << " missed, " << case_beyond << " beyond\n";
    }
  }
  return report;
}

// The report as text: per path, the counts and the distribution of the false positives' FCL
// distance as a fraction of the margin.
inline std::string formatReport(DifferentialReport report) {
  std::ostringstream out;
  out << report.cases << " cases, " << report.states << " states\n"
      << "| path | cases | states | FCL contacts env / self | missed env / self | rejected free "
         "env / self | within the margin: distance / margin, median, p90, p99, max | beyond the "
         "margin | one solid inside another |\n"
      << "|---|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  out.precision(3);
  for (auto& [name, t] : report.paths) {
    std::sort(t.ratio.begin(), t.ratio.end());
    auto q = [&](double p) {
      return t.ratio.empty() ? 0.0 : t.ratio[static_cast<std::size_t>(p * (t.ratio.size() - 1))];
    };
    out << "| " << name << " | " << t.cases << " | " << t.states << " | " << t.fcl_env << " / "
        << t.fcl_self << " | " << t.missed_env << " / " << t.missed_self << " | " << t.extra_env
        << " / " << t.extra_self << " | " << q(0.5) << ", " << q(0.9) << ", " << q(0.99) << ", "
        << q(1.0) << " | " << t.beyond << " | " << t.inside_solid << " |\n";
  }
  for (const std::string& f : report.failures) out << "FAILURE: " << f << "\n";
  return out.str();
}

}  // namespace octomotion::validation
