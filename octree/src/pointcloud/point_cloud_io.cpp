// PCD / PLY / XYZ point-cloud readers and writers. Every malformed input ends in a FileError
// naming the file and what is wrong; non-finite points are skipped and counted (see header).
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "octomotion/error.h"
#include "octomotion/input_limits.h"
#include "octomotion/pointcloud/point_cloud_io.h"

namespace octomotion::pointcloud {

namespace {

std::string readWhole(const std::string& path) {
  return readWholeFile(path, "point cloud file", kMaxDataFileBytes);
}

// Sequential line reader over a buffer; tracks the byte offset and the 1-based line number.
class Lines {
 public:
  explicit Lines(const std::string& data) : data_(data) {}
  bool next(std::string* line) {
    if (pos_ >= data_.size()) return false;
    const std::size_t end = data_.find('\n', pos_);
    const std::size_t stop = end == std::string::npos ? data_.size() : end;
    *line = data_.substr(pos_, stop - pos_);
    if (!line->empty() && line->back() == '\r') line->pop_back();
    pos_ = end == std::string::npos ? data_.size() : end + 1;
    ++number_;
    return true;
  }
  std::size_t offset() const { return pos_; }
  int number() const { return number_; }

 private:
  const std::string& data_;
  std::size_t pos_ = 0;
  int number_ = 0;
};

std::vector<std::string> split(const std::string& line, bool commas = false) {
  std::vector<std::string> out;
  std::size_t i = 0;
  auto sep = [&](char c) {
    return std::isspace(static_cast<unsigned char>(c)) != 0 || (commas && c == ',');
  };
  while (i < line.size()) {
    while (i < line.size() && sep(line[i])) ++i;
    std::size_t j = i;
    while (j < line.size() && !sep(line[j])) ++j;
    if (j > i) out.push_back(line.substr(i, j - i));
    i = j;
  }
  return out;
}

bool parseDouble(const std::string& token, double* value) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  *value = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size();
}

bool parseCount(const std::string& token, std::uint64_t* value) {
  if (token.empty() || !std::isdigit(static_cast<unsigned char>(token[0]))) return false;
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(token.c_str(), &end, 10);
  if (end != token.c_str() + token.size() || errno == ERANGE) return false;
  *value = v;
  return true;
}

std::string lineRef(int line) {
  return "line " + std::to_string(line) + ": ";
}

void addPoint(PointCloud* cloud, double x, double y, double z) {
  // Beyond float's range a coordinate would become infinite (and the conversion is undefined
  // behaviour): such points are skipped like the non-finite ones. !(<=) also catches NaN.
  constexpr double kFloatMax = std::numeric_limits<float>::max();
  if (!(std::abs(x) <= kFloatMax) || !(std::abs(y) <= kFloatMax) || !(std::abs(z) <= kFloatMax)) {
    ++cloud->skipped_non_finite;
    return;
  }
  cloud->points.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
}

double readFloating(const char* p, int size) {
  if (size == 4) {
    float f;
    std::memcpy(&f, p, 4);
    return f;
  }
  double d;
  std::memcpy(&d, p, 8);
  return d;
}

bool littleEndianHost() {
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

// ------------------------------------------------------------------------------------- PCD --

PointCloud loadPcd(const std::string& path) {
  const std::string data = readWhole(path);
  Lines lines(data);
  std::vector<std::string> fields, sizes, types, counts;
  std::uint64_t width = 0, height = 0, points = 0;
  bool have_width = false, have_height = false, have_points = false;
  std::string encoding;
  std::string line;
  while (encoding.empty()) {
    if (!lines.next(&line)) throw FileError(path, "header ends before the DATA line");
    const std::vector<std::string> t = split(line);
    if (t.empty() || t[0][0] == '#') continue;
    const std::string key = t[0];
    const std::vector<std::string> values(t.begin() + 1, t.end());
    auto count = [&](std::uint64_t* v) {
      if (values.size() != 1 || !parseCount(values[0], v))
        throw FileError(path, lineRef(lines.number()) + key + " needs one non-negative integer");
    };
    if (key == "VERSION" || key == "VIEWPOINT") {
      continue;
    } else if (key == "FIELDS") {
      fields = values;
    } else if (key == "SIZE") {
      sizes = values;
    } else if (key == "TYPE") {
      types = values;
    } else if (key == "COUNT") {
      counts = values;
    } else if (key == "WIDTH") {
      count(&width);
      have_width = true;
    } else if (key == "HEIGHT") {
      count(&height);
      have_height = true;
    } else if (key == "POINTS") {
      count(&points);
      have_points = true;
    } else if (key == "DATA") {
      if (values.size() != 1)
        throw FileError(path, lineRef(lines.number()) + "DATA needs one value");
      encoding = values[0];
    } else {
      throw FileError(path, lineRef(lines.number()) + "unknown header keyword '" + key + "'");
    }
  }
  if (fields.empty()) throw FileError(path, "header has no FIELDS");
  if (counts.empty()) counts.assign(fields.size(), "1");
  if (sizes.size() != fields.size() || types.size() != fields.size() ||
      counts.size() != fields.size())
    throw FileError(path, "FIELDS, SIZE, TYPE and COUNT have different lengths");
  if (!have_points) {
    if (!have_width) throw FileError(path, "header has neither POINTS nor WIDTH");
    points = width * (have_height ? height : 1);
  } else if (have_width && have_height && width * height != points) {
    throw FileError(path, "WIDTH x HEIGHT (" + std::to_string(width * height) +
                              ") differs from POINTS (" + std::to_string(points) + ")");
  }
  // Byte and value offsets of every field; positions of x, y, z.
  std::size_t record = 0, values_per_point = 0;
  int xyz_size[3] = {0, 0, 0};
  std::size_t xyz_byte[3] = {0, 0, 0}, xyz_value[3] = {0, 0, 0};
  bool found[3] = {false, false, false};
  for (std::size_t i = 0; i < fields.size(); ++i) {
    std::uint64_t size = 0, cnt = 0;
    if (!parseCount(sizes[i], &size) || (size != 1 && size != 2 && size != 4 && size != 8))
      throw FileError(path, "field '" + fields[i] + "' has SIZE '" + sizes[i] + "' (not 1/2/4/8)");
    if (types[i] != "F" && types[i] != "I" && types[i] != "U")
      throw FileError(path, "field '" + fields[i] + "' has TYPE '" + types[i] + "' (not F/I/U)");
    if (!parseCount(counts[i], &cnt) || cnt == 0 || cnt > 1000000)
      throw FileError(path, "field '" + fields[i] + "' has a bad COUNT '" + counts[i] + "'");
    const char* axes[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
      if (fields[i] != axes[a]) continue;
      if (found[a]) throw FileError(path, std::string("field ") + axes[a] + " appears twice");
      if (types[i] != "F" || (size != 4 && size != 8) || cnt != 1)
        throw FileError(path, std::string("field ") + axes[a] +
                                  " must be one FLOAT of SIZE 4 (or 8), not TYPE " + types[i] +
                                  " SIZE " + sizes[i] + " COUNT " + counts[i]);
      found[a] = true;
      xyz_size[a] = static_cast<int>(size);
      xyz_byte[a] = record;
      xyz_value[a] = values_per_point;
    }
    record += static_cast<std::size_t>(size * cnt);
    values_per_point += static_cast<std::size_t>(cnt);
  }
  if (!found[0] || !found[1] || !found[2]) throw FileError(path, "FIELDS lacks x, y or z");

  PointCloud cloud;
  if (encoding == "ascii") {
    cloud.points.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(points, 1u << 24)));
    std::uint64_t read = 0;
    while (read < points && lines.next(&line)) {
      const std::vector<std::string> t = split(line);
      if (t.empty()) continue;
      if (t.size() != values_per_point)
        throw FileError(path, lineRef(lines.number()) + "expected " +
                                  std::to_string(values_per_point) + " values, found " +
                                  std::to_string(t.size()));
      double v[3];
      for (int a = 0; a < 3; ++a) {
        if (!parseDouble(t[xyz_value[a]], &v[a]))
          throw FileError(path, lineRef(lines.number()) + "bad number '" + t[xyz_value[a]] + "'");
      }
      addPoint(&cloud, v[0], v[1], v[2]);
      ++read;
    }
    if (read < points)
      throw FileError(path, "truncated: header promises " + std::to_string(points) +
                                " points, data has " + std::to_string(read));
  } else if (encoding == "binary") {
    if (!littleEndianHost()) throw FileError(path, "binary PCD needs a little-endian host");
    const std::size_t start = lines.offset();
    const std::size_t available = data.size() - std::min(start, data.size());
    if (record == 0 || points > available / record)
      throw FileError(path, "truncated: header promises " + std::to_string(points) + " points of " +
                                std::to_string(record) + " bytes, data has " +
                                std::to_string(available) + " bytes");
    cloud.points.reserve(static_cast<std::size_t>(points));
    const char* base = data.data() + start;
    for (std::uint64_t i = 0; i < points; ++i) {
      const char* r = base + i * record;
      addPoint(&cloud, readFloating(r + xyz_byte[0], xyz_size[0]),
               readFloating(r + xyz_byte[1], xyz_size[1]),
               readFloating(r + xyz_byte[2], xyz_size[2]));
    }
  } else if (encoding == "binary_compressed") {
    throw FileError(path,
                    "DATA binary_compressed is not supported; convert the file to binary or ascii "
                    "(e.g. pcl_convert_pcd_ascii_binary)");
  } else {
    throw FileError(path, "unknown DATA encoding '" + encoding + "'");
  }
  return cloud;
}

// ------------------------------------------------------------------------------------- PLY --

namespace {

struct PlyProperty {
  std::string name;
  int size = 0;  // scalar size, or list item size
  bool floating = false;
  bool is_signed = false;
  bool list = false;
  int count_size = 0;  // list length type size
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

bool plyType(const std::string& t, int* size, bool* floating, bool* is_signed) {
  static const struct {
    const char* name;
    int size;
    bool floating, is_signed;
  } kTypes[] = {
      {"char", 1, false, true},    {"uchar", 1, false, false},  {"short", 2, false, true},
      {"ushort", 2, false, false}, {"int", 4, false, true},     {"uint", 4, false, false},
      {"float", 4, true, true},    {"double", 8, true, true},   {"int8", 1, false, true},
      {"uint8", 1, false, false},  {"int16", 2, false, true},   {"uint16", 2, false, false},
      {"int32", 4, false, true},   {"uint32", 4, false, false}, {"float32", 4, true, true},
      {"float64", 8, true, true}};
  for (const auto& k : kTypes) {
    if (t == k.name) {
      *size = k.size;
      *floating = k.floating;
      *is_signed = k.is_signed;
      return true;
    }
  }
  return false;
}

std::uint64_t readUnsigned(const char* p, int size) {
  std::uint64_t v = 0;
  if (size == 1) {
    std::uint8_t x;
    std::memcpy(&x, p, 1);
    v = x;
  } else if (size == 2) {
    std::uint16_t x;
    std::memcpy(&x, p, 2);
    v = x;
  } else if (size == 4) {
    std::uint32_t x;
    std::memcpy(&x, p, 4);
    v = x;
  } else {
    std::memcpy(&v, p, 8);
  }
  return v;
}

}  // namespace

PointCloud loadPly(const std::string& path) {
  const std::string data = readWhole(path);
  Lines lines(data);
  std::string line;
  if (!lines.next(&line) || line != "ply") throw FileError(path, "not a PLY file (no 'ply' magic)");
  bool ascii = false, have_format = false;
  std::vector<PlyElement> elements;
  for (;;) {
    if (!lines.next(&line)) throw FileError(path, "header ends before end_header");
    const std::vector<std::string> t = split(line);
    if (t.empty()) continue;
    if (t[0] == "end_header") break;
    if (t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "format") {
      if (t.size() != 3) throw FileError(path, lineRef(lines.number()) + "bad format line");
      if (t[1] == "ascii") {
        ascii = true;
      } else if (t[1] == "binary_little_endian") {
        ascii = false;
      } else if (t[1] == "binary_big_endian") {
        throw FileError(path, "binary_big_endian PLY is not supported");
      } else {
        throw FileError(path, lineRef(lines.number()) + "unknown format '" + t[1] + "'");
      }
      have_format = true;
    } else if (t[0] == "element") {
      PlyElement e;
      if (t.size() != 3 || !parseCount(t[2], &e.count))
        throw FileError(path, lineRef(lines.number()) + "bad element line");
      e.name = t[1];
      elements.push_back(e);
    } else if (t[0] == "property") {
      if (elements.empty())
        throw FileError(path, lineRef(lines.number()) + "property before any element");
      PlyProperty p;
      bool ok;
      if (t.size() == 5 && t[1] == "list") {
        int count_size = 0;
        bool count_floating = false, count_signed = false;
        ok = plyType(t[2], &count_size, &count_floating, &count_signed) && !count_floating &&
             plyType(t[3], &p.size, &p.floating, &p.is_signed);
        p.list = true;
        p.count_size = count_size;
        p.name = t[4];
      } else {
        ok = t.size() == 3 && plyType(t[1], &p.size, &p.floating, &p.is_signed);
        if (ok) p.name = t[2];
      }
      if (!ok) throw FileError(path, lineRef(lines.number()) + "bad property line '" + line + "'");
      elements.back().properties.push_back(p);
    } else {
      throw FileError(path, lineRef(lines.number()) + "unknown header line '" + line + "'");
    }
  }
  if (!have_format) throw FileError(path, "header has no format line");
  if (!ascii && !littleEndianHost()) throw FileError(path, "binary PLY needs a little-endian host");
  const auto vertex_it = std::find_if(elements.begin(), elements.end(),
                                      [](const PlyElement& e) { return e.name == "vertex"; });
  if (vertex_it == elements.end()) throw FileError(path, "no vertex element");
  const PlyElement& vertex = *vertex_it;
  int xyz[3] = {-1, -1, -1};
  for (std::size_t i = 0; i < vertex.properties.size(); ++i) {
    const PlyProperty& p = vertex.properties[i];
    const char* axes[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
      if (p.name != axes[a]) continue;
      if (p.list || !p.floating)
        throw FileError(path,
                        std::string("vertex property ") + axes[a] + " must be float or double");
      xyz[a] = static_cast<int>(i);
    }
    if (p.list) throw FileError(path, "list property '" + p.name + "' in the vertex element");
  }
  if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0) throw FileError(path, "vertex lacks x, y or z");

  PointCloud cloud;
  const auto truncated = [&](const std::string& element) {
    return FileError(path, "truncated: data ends inside element '" + element + "'");
  };
  if (ascii) {
    for (const PlyElement& e : elements) {
      const bool is_vertex = &e == &vertex;
      if (is_vertex)
        cloud.points.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(e.count, 1u << 24)));
      for (std::uint64_t i = 0; i < e.count; ++i) {
        std::vector<std::string> t;
        do {
          if (!lines.next(&line)) throw truncated(e.name);
          t = split(line);
        } while (t.empty());
        if (!is_vertex) continue;
        if (t.size() != vertex.properties.size())
          throw FileError(path, lineRef(lines.number()) + "expected " +
                                    std::to_string(vertex.properties.size()) + " values, found " +
                                    std::to_string(t.size()));
        double v[3];
        for (int a = 0; a < 3; ++a) {
          if (!parseDouble(t[static_cast<std::size_t>(xyz[a])], &v[a]))
            throw FileError(path, lineRef(lines.number()) + "bad number '" +
                                      t[static_cast<std::size_t>(xyz[a])] + "'");
        }
        addPoint(&cloud, v[0], v[1], v[2]);
      }
      if (is_vertex) break;  // later elements are not needed
    }
    return cloud;
  }
  std::size_t pos = lines.offset();
  for (const PlyElement& e : elements) {
    const bool is_vertex = &e == &vertex;
    if (is_vertex) {
      std::size_t record = 0, offset[3] = {0, 0, 0};
      for (std::size_t i = 0; i < e.properties.size(); ++i) {
        for (int a = 0; a < 3; ++a)
          if (static_cast<int>(i) == xyz[a]) offset[a] = record;
        record += static_cast<std::size_t>(e.properties[i].size);
      }
      if (e.count > (data.size() - pos) / record) throw truncated(e.name);
      cloud.points.reserve(static_cast<std::size_t>(e.count));
      const int s[3] = {e.properties[static_cast<std::size_t>(xyz[0])].size,
                        e.properties[static_cast<std::size_t>(xyz[1])].size,
                        e.properties[static_cast<std::size_t>(xyz[2])].size};
      for (std::uint64_t i = 0; i < e.count; ++i) {
        const char* r = data.data() + pos + i * record;
        addPoint(&cloud, readFloating(r + offset[0], s[0]), readFloating(r + offset[1], s[1]),
                 readFloating(r + offset[2], s[2]));
      }
      break;
    }
    // Skip an element before the vertices (lists make records variable-length).
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const PlyProperty& p : e.properties) {
        if (!p.list) {
          if (data.size() - pos < static_cast<std::size_t>(p.size)) throw truncated(e.name);
          pos += static_cast<std::size_t>(p.size);
          continue;
        }
        if (data.size() - pos < static_cast<std::size_t>(p.count_size)) throw truncated(e.name);
        const std::uint64_t n = readUnsigned(data.data() + pos, p.count_size);
        pos += static_cast<std::size_t>(p.count_size);
        if (n > (data.size() - pos) / static_cast<std::size_t>(p.size)) throw truncated(e.name);
        pos += static_cast<std::size_t>(n) * static_cast<std::size_t>(p.size);
      }
    }
  }
  return cloud;
}

// ------------------------------------------------------------------------------------- XYZ --

PointCloud loadXyz(const std::string& path) {
  const std::string data = readWhole(path);
  Lines lines(data);
  std::string line;
  PointCloud cloud;
  while (lines.next(&line)) {
    const std::vector<std::string> t = split(line, /*commas=*/true);
    if (t.empty() || t[0][0] == '#') continue;
    if (t.size() < 3)
      throw FileError(path, lineRef(lines.number()) + "expected x y z, found " +
                                std::to_string(t.size()) + " values");
    double v[3];
    for (int a = 0; a < 3; ++a) {
      if (!parseDouble(t[static_cast<std::size_t>(a)], &v[a]))
        throw FileError(
            path, lineRef(lines.number()) + "bad number '" + t[static_cast<std::size_t>(a)] + "'");
    }
    addPoint(&cloud, v[0], v[1], v[2]);
  }
  return cloud;
}

PointCloud loadPointCloud(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::string ext = dot == std::string::npos ? "" : lower(path.substr(dot + 1));
  if (ext == "pcd") return loadPcd(path);
  if (ext == "ply") return loadPly(path);
  if (ext == "xyz" || ext == "txt" || ext == "pts") return loadXyz(path);
  throw FileError(path, "unknown point-cloud extension (expected .pcd, .ply, .xyz, .txt or .pts)");
}

// ----------------------------------------------------------------------------------- write --

namespace {

void writeAll(const std::string& path, const std::string& header, const std::string& body) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw FileError(path, "cannot open file for writing");
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  out.write(body.data(), static_cast<std::streamsize>(body.size()));
  if (!out) throw FileError(path, "write error");
}

std::string asciiBody(const std::vector<Eigen::Vector3f>& points) {
  std::string body;
  char buf[96];
  for (const Eigen::Vector3f& p : points) {
    // %.9g round-trips every float exactly.
    const int n = std::snprintf(buf, sizeof(buf), "%.9g %.9g %.9g\n", static_cast<double>(p.x()),
                                static_cast<double>(p.y()), static_cast<double>(p.z()));
    body.append(buf, static_cast<std::size_t>(n));
  }
  return body;
}

std::string binaryBody(const std::vector<Eigen::Vector3f>& points) {
  std::string body(points.size() * 12, '\0');
  for (std::size_t i = 0; i < points.size(); ++i) {
    const float xyz[3] = {points[i].x(), points[i].y(), points[i].z()};
    std::memcpy(&body[i * 12], xyz, 12);
  }
  return body;
}

}  // namespace

void savePcd(const std::string& path, const std::vector<Eigen::Vector3f>& points,
             Encoding encoding) {
  const std::string n = std::to_string(points.size());
  const std::string header =
      "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH " +
      n + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + n + "\nDATA " +
      (encoding == Encoding::kAscii ? "ascii" : "binary") + "\n";
  writeAll(path, header, encoding == Encoding::kAscii ? asciiBody(points) : binaryBody(points));
}

void savePly(const std::string& path, const std::vector<Eigen::Vector3f>& points,
             Encoding encoding) {
  const std::string header = std::string("ply\nformat ") +
                             (encoding == Encoding::kAscii ? "ascii" : "binary_little_endian") +
                             " 1.0\ncomment written by octomotion\nelement vertex " +
                             std::to_string(points.size()) +
                             "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  writeAll(path, header, encoding == Encoding::kAscii ? asciiBody(points) : binaryBody(points));
}

void saveXyz(const std::string& path, const std::vector<Eigen::Vector3f>& points) {
  writeAll(path, "", asciiBody(points));
}

}  // namespace octomotion::pointcloud
