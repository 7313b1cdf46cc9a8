// Resolves the resource URIs URDF files use (package://, file://, relative paths) to files.
#pragma once

#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace octomotion {

// Finds ROS-style packages in a list of search directories. The search list is the explicit
// directories first, then (when `use_environment`) the colon-separated OCTOMOTION_PACKAGE_PATH,
// then ROS_PACKAGE_PATH. In each directory D, in order, package NAME is:
//   1. D itself when D/package.xml declares <name>NAME</name>;
//   2. D/NAME when that is a directory;
//   3. the shallowest directory below D whose package.xml declares <name>NAME</name>
//      (breadth-first, siblings in name order, depth <= 4, at most 20000 directories listed,
//      hidden directories skipped, packages not descended into, as rospack does).
// The first search directory that has the package wins. Lookups are cached; thread-safe.
class PackageLocator {
 public:
  explicit PackageLocator(std::vector<std::string> search_paths = {}, bool use_environment = true);
  PackageLocator(const PackageLocator& other);
  PackageLocator& operator=(const PackageLocator& other);

  // The colon-separated entries of OCTOMOTION_PACKAGE_PATH then ROS_PACKAGE_PATH (empty
  // entries dropped).
  static std::vector<std::string> environmentSearchPaths();

  const std::vector<std::string>& searchPaths() const { return search_paths_; }

  // The package's directory, or nullopt when no search directory has it.
  std::optional<std::string> findPackage(const std::string& name) const;

  // The absolute path a URI names: "package://NAME/rest", "file:///abs/path", an absolute path,
  // or a path relative to `base_dir`. Does not check that the file exists. Throws Error saying
  // what is wrong (unknown package with the directories searched, unsupported scheme, empty
  // URI); callers prefix the file and field.
  std::string resolve(const std::string& uri, const std::string& base_dir) const;

 private:
  std::vector<std::string> search_paths_;
  mutable std::mutex cache_mutex_;
  mutable std::map<std::string, std::optional<std::string>> cache_;
};

}  // namespace octomotion
