// How a voxel that an object only partly fills is coloured.
#pragma once

namespace octomotion {

enum class Rounding {
  // Black if the object reaches into the voxel at all (primitives: into its interior, by more
  // than a 1e-6-voxel tie; meshes: touches the closed voxel): never under-approximates beyond
  // that tie, so a collision is never missed.
  kConservative,
  // Black iff the voxel centre is on or inside the object (Weng & Ahuja 1987 §3): keeps volume
  // roughly unchanged, may miss thin contacts.
  kCenter,
};

const char* toString(Rounding r);
// Parses "conservative" or "center"/"centre"; throws InvalidArgument naming the value otherwise.
Rounding roundingFromString(const char* name);

}  // namespace octomotion
