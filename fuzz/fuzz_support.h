// Shared by the libFuzzer targets in fuzz/. The contract every target checks: for any input, the
// code under test returns or throws octomotion::Error. Any other exception escapes
// LLVMFuzzerTestOneInput and libFuzzer reports it ("deadly signal" after std::terminate), just as
// it reports crashes, hangs (-timeout), leaks and sanitizer findings.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "octomotion/error.h"

namespace octomotion::fuzz {

// The loaders that only take a path read the input from this file: one per process (libFuzzer
// -jobs/-fork runs several processes), named with the extension the loader dispatches on.
inline std::string writeInput(const std::uint8_t* data, std::size_t size, const std::string& ext) {
  static const std::string dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    return std::string(tmp && *tmp ? tmp : "/tmp");
  }();
  const std::string path =
      dir + "/octomotion_fuzz_" + std::to_string(static_cast<long long>(::getpid())) + ext;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz harness: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

// Reports a broken property (an oracle mismatch) as a crash, with a message.
[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "fuzz oracle failed: %s\n", what);
  std::abort();
}

// Reads fixed-size values from the front of the input (zeros once it runs out).
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::uint16_t u16() { return static_cast<std::uint16_t>(byte() | byte() << 8); }
  // A value in [lo, hi] from one byte.
  double unit(double lo, double hi) { return lo + (hi - lo) * byte() / 255.0; }
  bool empty() const { return pos_ >= size_; }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace octomotion::fuzz
