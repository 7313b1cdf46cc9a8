// The human-readable summary of what a collision model modelled.
#include <cmath>
#include <sstream>
#include <string>

#include "octomotion/planner/model/collision_model.h"

namespace octomotion {

const char* selfBroadPhaseName(SelfBroadPhase strategy) {
  switch (strategy) {
    case SelfBroadPhase::kAuto:
      return "auto";
    case SelfBroadPhase::kPairs:
      return "all checked pairs";
    case SelfBroadPhase::kNObjectsOctree:
      return "N-objects octree";
  }
  return "?";
}

std::string CollisionModelReport::toString() const {
  std::ostringstream out;
  out << "universe: depth " << grid.depth() << ", " << grid.voxelSize() << " m voxels, side "
      << grid.sideMetres() << " m, origin [" << grid.origin().transpose() << "]\n";
  out << "environment: " << environment.internal_nodes << " internal nodes, " << environment.bytes
      << " bytes, built in " << environment.build_seconds << " s\n";
  if (environment_cell_grid_level >= 0) {
    out << "environment black-cell grid: level " << environment_cell_grid_level << " ("
        << (1u << environment_cell_grid_level) << "-voxel cells), " << environment_cell_grid_bytes
        << " bytes\n";
  }
  if (environment_clearance_grid_level >= 0) {
    out << "environment clearance grid: level " << environment_clearance_grid_level << " ("
        << (1u << environment_clearance_grid_level) << "-voxel cells), "
        << environment_clearance_grid_bytes << " bytes\n";
  }
  for (const auto& o : environment.objects) {
    out << "  " << o.name << ": " << o.black_leaves << " black leaves, " << o.internal_nodes
        << " internal nodes, " << o.build_seconds << " s\n";
  }
  out << "links (source voxels " << link_resolution << " m";
  if (self_link_resolution != link_resolution) {
    out << "; self-collision trees " << self_link_resolution << " m";
  }
  out << "):\n";
  for (const LinkReport& l : links) {
    out << "  " << l.name << ": ";
    if (!l.modelled) {
      out << "not modelled\n";
      continue;
    }
    out << l.source_internal_nodes << " internal nodes, " << l.source_black_leaves
        << " black leaves, " << l.source_bytes << " bytes, depth " << l.source_depth << ", radius "
        << l.radius << " m, " << l.core_boxes << " core boxes, " << l.build_seconds << " s";
    if (l.self_source_bytes > 0) out << "; self-collision tree " << l.self_source_bytes << " bytes";
    out << "\n";
  }
  out << "environment pre-test: "
      << (environment_pre_test == EnvironmentPreTest::kObjectBoxes
              ? "object boxes (" + std::to_string(environment_object_boxes) + ")"
              : std::string("environment box"))
      << "; certain contacts: links' core boxes against " << environment_solid_boxes
      << " primitives' inscribed boxes\n";
  if (exact_primitives > 0) {
    out << "exact primitives: the links' source voxels tested against " << exact_primitives
        << " primitives' exact shapes (not the environment tree)";
    if (exact_primitives_other_objects > 0) {
      out << "; the " << exact_primitives_other_objects << " other objects in a tree of their own";
    }
    out << "\n";
  }
  out << "environment tested in the order (share of sampled states hitting):";
  for (const std::string& name : environment_order) {
    out << " " << name;
    for (const LinkReport& l : links) {
      if (l.name == name && l.environment_hit_share >= 0) {
        out << " (" << std::round(1000 * l.environment_hit_share) / 10 << " %)";
      }
    }
  }
  out << "\n";
  out << "self-collision pairs checked: " << self_pairs << " among " << self_links
      << " links; broad phase: " << selfBroadPhaseName(self_broad_phase);
  if (self_links >= 2) {
    out << " (auto picks the N-objects octree from " << kSelfBroadPhaseAutoLinks << " links)";
  }
  if (!self_pair_tables.empty()) {
    out << "\nself-pair tables (joint space, FCL-certified cells): " << self_pair_tables.size();
  }
  for (const SelfPairTableReport& t : self_pair_tables) {
    out << "\n  " << t.link_a << "-" << t.link_b << ": " << t.variables << " variable"
        << (t.variables == 1 ? "" : "s") << ", depth " << t.depth << ", " << t.nodes << " nodes, "
        << t.bytes << " bytes, certified free " << 100 * t.free_fraction << " %, colliding "
        << 100 * t.colliding_fraction << " % (" << t.classified << " FCL cells, " << t.build_seconds
        << " s)";
  }
  if (!static_links.empty()) {
    out << "\nstatic links (no joint moves them; tested against the environment once):";
    for (const std::string& name : static_links) out << " " << name;
  }
  if (!constant_pairs.empty()) {
    out << "\nconstant self pairs (no joint between them; tested once, dropped): "
        << constant_pairs.size();
    for (const auto& [a, b] : constant_pairs) out << " " << a << "-" << b;
  }
  for (const std::string& what : static_collisions) {
    out << "\nEVERY STATE IS IN COLLISION: " << what;
  }
  if (refine == RefineMode::kExact) {
    out << "\nrefine: exact (FCL decides each link-object and link-link pair whose voxels meet; "
           "its geometry built in "
        << refine_build_seconds << " s)";
  } else {
    out << "\nrefine: none (the voxels decide)";
  }
  out << "\nmodel built in " << build_seconds << " s\n";
  return out.str();
}

}  // namespace octomotion
