#include "octomotion/planner/robot/package_locator.h"

#include <algorithm>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include <tinyxml.h>

#include "internal/xml_text.h"
#include "octomotion/error.h"

namespace octomotion {
namespace {

namespace fs = std::filesystem;

// How deep below a search directory the package.xml crawl goes and how many directories it lists
// at most: bounds the cost of a search path like $HOME and guarantees termination through symlink
// loops.
constexpr int kMaxCrawlDepth = 4;
constexpr std::size_t kMaxCrawlDirectories = 20000;

void appendColonList(const char* value, std::vector<std::string>* out) {
  if (value == nullptr) return;
  std::stringstream stream(value);
  std::string entry;
  while (std::getline(stream, entry, ':')) {
    if (!entry.empty()) out->push_back(entry);
  }
}

// The <name> a package.xml declares, or "" when the file is absent or unreadable.
std::string declaredPackageName(const fs::path& dir) {
  std::error_code ec;
  const fs::path manifest = dir / "package.xml";
  if (!fs::exists(manifest, ec)) return "";
  // A manifest that is not a small regular file of UTF-8 text nested no deeper than
  // kMaxXmlDepth is treated as unreadable (xml_text.h says why it must not reach TinyXML).
  std::string manifest_text;
  try {
    manifest_text = readWholeFile(manifest.string(), "package manifest", kMaxXmlFileBytes);
    detail::requireXmlText(manifest_text, manifest.string());
  } catch (const FileError&) {
    return "";
  }
  TiXmlDocument doc;
  doc.Parse(manifest_text.c_str());
  if (doc.Error()) return "";
  const TiXmlElement* root = doc.RootElement();
  if (root == nullptr) return "";
  const TiXmlElement* name = root->FirstChildElement("name");
  if (name == nullptr || name->GetText() == nullptr) return "";
  std::string text = name->GetText();
  const auto first = text.find_first_not_of(" \t\r\n");
  const auto last = text.find_last_not_of(" \t\r\n");
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

// Breadth-first, so the shallowest match wins: a copy of a package deep inside a build or install
// tree below the search directory does not shadow the real one near the top.
std::optional<fs::path> crawl(const fs::path& top, const std::string& name) {
  std::deque<std::pair<fs::path, int>> queue{{top, 0}};
  std::size_t visited = 0;
  while (!queue.empty() && visited < kMaxCrawlDirectories) {
    const auto [dir, depth] = queue.front();
    queue.pop_front();
    ++visited;
    std::error_code ec;
    fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
    if (ec) continue;
    std::vector<fs::path> subdirs;
    for (; it != fs::directory_iterator(); it.increment(ec)) {
      if (ec) break;
      const std::string leaf = it->path().filename().string();
      if (leaf.empty() || leaf[0] == '.') continue;
      std::error_code dir_ec;
      if (it->is_directory(dir_ec)) subdirs.push_back(it->path());
    }
    // Sorted so that the answer does not depend on the file system's listing order.
    std::sort(subdirs.begin(), subdirs.end());
    for (const fs::path& sub : subdirs) {
      const std::string declared = declaredPackageName(sub);
      if (declared == name) return sub;
      if (!declared.empty()) continue;  // a package: rospack does not look inside
      if (depth + 1 < kMaxCrawlDepth) queue.emplace_back(sub, depth + 1);
    }
  }
  return std::nullopt;
}

std::optional<fs::path> findIn(const fs::path& dir, const std::string& name) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return std::nullopt;
  if (declaredPackageName(dir) == name) return dir;
  if (fs::is_directory(dir / name, ec)) return dir / name;
  return crawl(dir, name);
}

}  // namespace

PackageLocator::PackageLocator(std::vector<std::string> search_paths, bool use_environment)
    : search_paths_(std::move(search_paths)) {
  if (use_environment) {
    for (std::string& p : environmentSearchPaths()) search_paths_.push_back(std::move(p));
  }
}

PackageLocator::PackageLocator(const PackageLocator& other) : search_paths_(other.search_paths_) {
  std::lock_guard<std::mutex> lock(other.cache_mutex_);
  cache_ = other.cache_;
}

PackageLocator& PackageLocator::operator=(const PackageLocator& other) {
  if (this == &other) return *this;
  std::scoped_lock lock(cache_mutex_, other.cache_mutex_);
  search_paths_ = other.search_paths_;
  cache_ = other.cache_;
  return *this;
}

std::vector<std::string> PackageLocator::environmentSearchPaths() {
  std::vector<std::string> paths;
  appendColonList(std::getenv("OCTOMOTION_PACKAGE_PATH"), &paths);
  appendColonList(std::getenv("ROS_PACKAGE_PATH"), &paths);
  return paths;
}

std::optional<std::string> PackageLocator::findPackage(const std::string& name) const {
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos) {
    return std::nullopt;
  }
  {
    std::lock_guard<std::mutex> lock(cache_mutex_);
    auto it = cache_.find(name);
    if (it != cache_.end()) return it->second;
  }
  std::optional<std::string> result;
  for (const std::string& dir : search_paths_) {
    if (auto found = findIn(fs::path(dir), name)) {
      std::error_code ec;
      const fs::path absolute = fs::absolute(*found, ec);
      result = (ec ? *found : absolute).lexically_normal().string();
      break;
    }
  }
  std::lock_guard<std::mutex> lock(cache_mutex_);
  cache_.emplace(name, result);
  return result;
}

std::string PackageLocator::resolve(const std::string& uri, const std::string& base_dir) const {
  if (uri.empty()) throw Error("empty file name");
  fs::path path;
  const std::string package_scheme = "package://";
  const std::string file_scheme = "file://";
  if (uri.compare(0, package_scheme.size(), package_scheme) == 0) {
    const std::string rest = uri.substr(package_scheme.size());
    const auto slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    if (package.empty()) throw Error("URI '" + uri + "' names no package");
    const auto dir = findPackage(package);
    if (!dir) {
      std::string searched;
      for (const std::string& p : search_paths_) searched += (searched.empty() ? "" : ":") + p;
      throw Error("package '" + package + "' of URI '" + uri +
                  "' was not found (search path: " + (searched.empty() ? "empty" : searched) +
                  "; set OCTOMOTION_PACKAGE_PATH or RobotModelOptions::package_paths)");
    }
    path = fs::path(*dir);
    if (slash != std::string::npos) path /= rest.substr(slash + 1);
  } else if (uri.compare(0, file_scheme.size(), file_scheme) == 0) {
    path = fs::path(uri.substr(file_scheme.size()));
    if (path.empty()) throw Error("URI '" + uri + "' names no file");
    if (path.is_relative()) path = fs::path(base_dir) / path;
  } else if (uri.find("://") != std::string::npos) {
    throw Error("URI '" + uri + "' has an unsupported scheme (use package://, file:// or a path)");
  } else {
    path = fs::path(uri);
    if (path.is_relative()) path = fs::path(base_dir) / path;
  }
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  return (ec ? path : absolute).lexically_normal().string();
}

}  // namespace octomotion
