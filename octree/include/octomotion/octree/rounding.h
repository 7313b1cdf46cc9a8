// How a voxel that an object only partly fills is coloured.
#pragma once

namespace octomotion {

enum class Rounding {
  // Black if the object touches the (closed) voxel at all: never under-approximates, so a
  // collision is never missed.
  kConservative,
  // Black iff the voxel centre is on or inside the object (Weng & Ahuja 1987 §3): keeps volume
  // roughly unchanged, may miss thin contacts.
  kCenter,
};

const char* toString(Rounding r);
// Parses "conservative" or "center"/"centre"; throws InvalidArgument naming the value otherwise.
Rounding roundingFromString(const char* name);

}  // namespace octomotion
