// The one exception family users catch: every user-facing failure (bad file, bad field, bad pose)
// is an octomotion::Error whose message names the file or field and what is wrong.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

namespace octomotion {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// A value outside what the library accepts (NaN pose, depth > kMaxDepth, zero voxel size...).
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

// A file that is missing, truncated, corrupt or of the wrong kind. The message starts with the
// path.
class FileError : public Error {
 public:
  FileError(const std::string& path, const std::string& what) : Error(path + ": " + what) {}
};

// Where non-fatal warnings go (e.g. "mesh is open: voxelized as a surface shell"). An empty sink
// means the default: one line on stderr.
using WarningSink = std::function<void(const std::string&)>;
void warn(const WarningSink& sink, const std::string& message);

}  // namespace octomotion
