// Text checks before a document reaches TinyXML (our scans, urdfdom). TinyXML 2.6 reads a UTF-8
// lead byte as "the next 1-3 bytes belong to this character" without checking them, so a lead
// byte just before the terminating NUL makes it step past the end of the buffer (a heap overflow
// the URDF fuzzer found). Well-formed UTF-8 without NUL bytes cannot trigger that. TinyXML also
// recurses once per nested element (and takes time quadratic in the depth), so the nesting depth
// is bounded too.
#pragma once

#include <cstddef>
#include <string>

#include "octomotion/error.h"
#include "octomotion/input_limits.h"

namespace octomotion::detail {

// Throws FileError naming `source_name`, the line and the byte offset when `text` holds a NUL
// byte or is not well-formed UTF-8 (truncated or stray continuation bytes, invalid lead bytes),
// or when its elements nest deeper than kMaxXmlDepth.
inline void requireXmlText(const std::string& text, const std::string& source_name) {
  int line = 1;
  auto fail = [&](std::size_t offset, const char* what) {
    throw FileError(source_name, std::string(what) + " at line " + std::to_string(line) +
                                     " (byte offset " + std::to_string(offset) +
                                     "); XML files must be UTF-8 text");
  };
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == 0) fail(i, "NUL byte");
    if (c < 0x80) {
      line += c == '\n';
      ++i;
      continue;
    }
    std::size_t length = 0;
    if (c >= 0xC2 && c <= 0xDF) {
      length = 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
      length = 3;
    } else if (c >= 0xF0 && c <= 0xF4) {
      length = 4;
    } else {
      fail(i, "invalid UTF-8 byte");
    }
    if (n - i < length) fail(i, "truncated UTF-8 sequence");
    for (std::size_t k = 1; k < length; ++k) {
      if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) {
        fail(i, "truncated UTF-8 sequence");
      }
    }
    i += length;
  }
  requireXmlDepth(text, source_name);
}

}  // namespace octomotion::detail
