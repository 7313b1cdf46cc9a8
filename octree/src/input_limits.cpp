#include "octomotion/input_limits.h"

#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "octomotion/error.h"

namespace octomotion {

namespace fs = std::filesystem;

namespace {

std::string megabytes(std::uintmax_t bytes) {
  return std::to_string(bytes / kMiB) + " MiB";
}

}  // namespace

void requireRegularFile(const std::string& path, const std::string& what,
                        std::uintmax_t max_bytes) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw FileError(path, "cannot open the " + what + ": it does not exist");
  if (!fs::is_regular_file(status)) {
    // A FIFO would block and a device (/dev/zero) never ends.
    throw FileError(path, what + " is not a regular file");
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw FileError(path, "cannot read the " + what + ": " + ec.message());
  if (size > max_bytes) {
    throw FileError(path, what + " is " + megabytes(size) + ", more than the limit of " +
                              megabytes(max_bytes) + " (docs/robustness.md, input limits)");
  }
}

std::string readWholeFile(const std::string& path, const std::string& what,
                          std::uintmax_t max_bytes) {
  requireRegularFile(path, what, max_bytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FileError(path, "cannot open the " + what + ": " + std::strerror(errno));
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes) {
      throw FileError(
          path, what + " grew past the limit of " + megabytes(max_bytes) + " while being read");
    }
  }
  if (in.bad()) throw FileError(path, "cannot read the " + what);
  return text;
}

void requireXmlDepth(const std::string& text, const std::string& source_name, int max_depth) {
  const std::size_t n = text.size();
  int line = 1;
  int depth = 0;
  std::size_t i = 0;
  // Moves i to just past `end` (or to the end of the text), counting lines on the way.
  auto skipPast = [&](const char* end) {
    const std::size_t found = text.find(end, i);
    const std::size_t stop = found == std::string::npos ? n : found + std::strlen(end);
    for (; i < stop; ++i) line += text[i] == '\n';
  };
  // Moves i to just past the '>' closing a tag, skipping quoted values (which may hold '>');
  // returns whether the tag ended with "/>".
  auto skipTag = [&]() {
    char quote = 0;
    char previous = 0;
    for (; i < n; ++i) {
      const char c = text[i];
      line += c == '\n';
      if (quote != 0) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '>') {
        ++i;
        return previous == '/';
      }
      previous = c;
    }
    return false;
  };
  while (i < n) {
    if (text[i] != '<') {
      line += text[i] == '\n';
      ++i;
      continue;
    }
    if (text.compare(i, 4, "<!--") == 0) {
      skipPast("-->");
    } else if (text.compare(i, 9, "<![CDATA[") == 0) {
      skipPast("]]>");
    } else if (text.compare(i, 2, "<?") == 0) {
      skipPast("?>");
    } else if (text.compare(i, 2, "<!") == 0) {
      // A declaration; a DOCTYPE's internal subset is bracketed and may hold '<...>'.
      int brackets = 0;
      for (; i < n; ++i) {
        const char c = text[i];
        line += c == '\n';
        brackets += c == '[' ? 1 : c == ']' ? -1 : 0;
        if (c == '>' && brackets <= 0) {
          ++i;
          break;
        }
      }
    } else if (text.compare(i, 2, "</") == 0) {
      skipTag();
      --depth;
    } else {
      const int start_line = line;
      if (!skipTag() && ++depth > max_depth) {
        throw FileError(source_name, "XML elements nest more than " + std::to_string(max_depth) +
                                         " deep at line " + std::to_string(start_line) +
                                         " (the limit, docs/robustness.md)");
      }
    }
  }
}

}  // namespace octomotion
