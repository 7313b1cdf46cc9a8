// Fuzzes octomotion's own octree file (.omt, octree/io.h): a valid tree or an octomotion::Error.
// Most mutations break the FNV-1a checksum, so each input is also tried with its last 8 bytes
// replaced by the right checksum: that reaches the header, count and node validation. Accepted
// trees satisfy the invariants and survive a write/read round trip unchanged.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "fuzz_support.h"
#include "octomotion/octree/io.h"

namespace {

void readOne(const std::string& bytes) {
  using namespace octomotion;
  try {
    std::istringstream in(bytes);
    const Octree tree = readOctree(in, "<fuzz>");
    if (!tree.checkInvariants()) fuzz::fail("accepted tree breaks the invariants");
    std::stringstream round_trip;
    writeOctree(tree, round_trip);
    if (!(readOctree(round_trip, "<round trip>") == tree))
      fuzz::fail("round trip changed the tree");
  } catch (const Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  readOne(bytes);
  if (bytes.size() >= 8) {
    // FNV-1a 64 over everything before the checksum, stored little-endian.
    std::uint64_t h = 14695981039346656037ull;
    for (std::size_t i = 0; i + 8 < bytes.size(); ++i) {
      h = (h ^ static_cast<unsigned char>(bytes[i])) * 1099511628211ull;
    }
    for (int i = 0; i < 8; ++i) {
      bytes[bytes.size() - 8 + static_cast<std::size_t>(i)] = static_cast<char>(h >> (8 * i));
    }
    readOne(bytes);
  }
  return 0;
}
