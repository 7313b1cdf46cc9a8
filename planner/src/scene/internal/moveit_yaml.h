// Reading ROS messages written as YAML (MoveIt's PlanningScene and MotionPlanRequest): fields
// that may be absent (ROS then means zero or empty), vectors and quaternions given as lists
// ([x, y, z, w]) or as mappings ({x, y, z, w}), message constants given as numbers or names.
// Every problem is a FileError "<file>: <field path>: <what> (line L)".
#pragma once

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <Eigen/Geometry>

#include "octomotion/error.h"
#include "octomotion/input_limits.h"

namespace octomotion::detail {

class MessageYaml {
 public:
  explicit MessageYaml(std::string path) : path_(std::move(path)) {}

  const std::string& path() const { return path_; }

  YAML::Node parse(const std::string& text) const {
    YAML::Node root;
    try {
      root = YAML::Load(text);
    } catch (const YAML::ParserException& e) {
      throw FileError(
          path_, "YAML syntax error at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
    }
    if (!root.IsMap()) throw FileError(path_, "expected a YAML mapping (a ROS message)");
    return root;
  }

  [[noreturn]] void fail(const std::string& field, const YAML::Node& node,
                         const std::string& what) const {
    std::string where;
    if (node.IsDefined() && node.Mark().line >= 0) {
      where = " (line " + std::to_string(node.Mark().line + 1) + ")";
    }
    throw FileError(path_, field + ": " + what + where);
  }

  // map[key], or an undefined node when the key is absent (or null); `map` must be a mapping.
  YAML::Node child(const YAML::Node& map, const std::string& field, const char* key) const {
    if (!map.IsMap()) fail(field, map, "expected a mapping");
    const YAML::Node node = map[key];
    return node && !node.IsNull() ? node : YAML::Node(YAML::NodeType::Undefined);
  }
  YAML::Node required(const YAML::Node& map, const std::string& field, const char* key) const {
    const YAML::Node node = child(map, field, key);
    if (!node) fail(join(field, key), map, "missing");
    return node;
  }
  // A list (absent: empty).
  std::vector<YAML::Node> list(const YAML::Node& node, const std::string& field) const {
    std::vector<YAML::Node> out;
    if (!node) return out;
    if (!node.IsSequence()) fail(field, node, "expected a list");
    for (std::size_t i = 0; i < node.size(); ++i) out.push_back(node[i]);
    return out;
  }
  // Rejects keys the message does not have: a typo must not be silently ignored.
  void allowOnly(const YAML::Node& map, const std::string& field,
                 std::initializer_list<const char*> keys) const {
    if (!map.IsMap()) fail(field, map, "expected a mapping");
    for (const auto& kv : map) {
      const std::string key = kv.first.Scalar();
      if (std::none_of(keys.begin(), keys.end(), [&](const char* k) { return key == k; })) {
        fail(join(field, key), kv.first, "unknown field");
      }
    }
  }

  double number(const YAML::Node& node, const std::string& field) const {
    if (!node) fail(field, node, "missing");
    if (!node.IsScalar()) fail(field, node, "expected a number");
    double v = 0;
    try {
      v = node.as<double>();
    } catch (const YAML::Exception&) {
      fail(field, node, "expected a number, got '" + node.Scalar() + "'");
    }
    if (!std::isfinite(v)) fail(field, node, "must be finite");
    return v;
  }
  std::vector<double> numbers(const YAML::Node& node, const std::string& field) const {
    std::vector<double> out;
    const std::vector<YAML::Node> items = list(node, field);
    for (std::size_t i = 0; i < items.size(); ++i) out.push_back(number(items[i], index(field, i)));
    return out;
  }
  // A string that may be empty (ROS strings default to "").
  std::string text(const YAML::Node& node, const std::string& field) const {
    if (!node) return "";
    if (!node.IsScalar()) fail(field, node, "expected a string");
    return node.Scalar();
  }
  std::string name(const YAML::Node& node, const std::string& field) const {
    const std::string s = text(node, field);
    if (s.empty()) fail(field, node, node ? "expected a non-empty name" : "missing");
    return s;
  }

  // A message constant: its number, or its name in any case (e.g. type: box or type: 1).
  int constant(const YAML::Node& node, const std::string& field,
               std::initializer_list<std::pair<const char*, int>> names) const {
    if (!node || !node.IsScalar())
      fail(field, node, node ? "expected a name or number" : "missing");
    std::string v = node.Scalar();
    for (char& c : v) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    std::string known;
    for (const auto& [n, value] : names) {
      if (v == n || v == std::to_string(value)) return value;
      known += (known.empty() ? "" : ", ") + std::string(n) + " (" + std::to_string(value) + ")";
    }
    fail(field, node, "unknown value '" + node.Scalar() + "' (known: " + known + ")");
  }

  // geometry_msgs/Point or Vector3: [x, y, z] or {x, y, z} (absent components are 0, as in ROS).
  Eigen::Vector3d vector3(const YAML::Node& node, const std::string& field) const {
    return Eigen::Vector3d(components<3>(node, field, {"x", "y", "z"}).data());
  }
  // geometry_msgs/Quaternion: [x, y, z, w] or {x, y, z, w}, normalised (after scaling by its
  // largest component, so huge ones do not overflow). All zeros is refused, unless
  // `zero_is_identity`: MoveIt reads an all-zero orientation in a collision object as the
  // identity (a message whose pose was never filled in has one).
  Eigen::Quaterniond quaternion(const YAML::Node& node, const std::string& field,
                                bool zero_is_identity = false) const {
    const std::array<double, 4> c = components<4>(node, field, {"x", "y", "z", "w"});
    const Eigen::Vector4d v(c[0], c[1], c[2], c[3]);
    if (zero_is_identity && v.isZero(0)) return Eigen::Quaterniond::Identity();
    const auto unit = scaledUnitVector(v);
    if (!unit) fail(field, node, "quaternion of zero length");
    return Eigen::Quaterniond((*unit)[3], (*unit)[0], (*unit)[1], (*unit)[2]);
  }
  // geometry_msgs/Pose: position and orientation, both required.
  Eigen::Isometry3d pose(const YAML::Node& node, const std::string& field,
                         bool zero_is_identity = false) const {
    allowOnly(node, field, {"position", "orientation"});
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = vector3(required(node, field, "position"), join(field, "position"));
    X.linear() = quaternion(required(node, field, "orientation"), join(field, "orientation"),
                            zero_is_identity)
                     .toRotationMatrix();
    return X;
  }
  // geometry_msgs/Transform: translation and rotation, both required.
  Eigen::Isometry3d transform(const YAML::Node& node, const std::string& field) const {
    allowOnly(node, field, {"translation", "rotation"});
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = vector3(required(node, field, "translation"), join(field, "translation"));
    X.linear() =
        quaternion(required(node, field, "rotation"), join(field, "rotation")).toRotationMatrix();
    return X;
  }

  static std::string join(const std::string& field, const std::string& key) {
    return field.empty() ? key : field + "." + key;
  }
  static std::string index(const std::string& field, std::size_t i) {
    return field + "[" + std::to_string(i) + "]";
  }

 private:
  template <std::size_t N>
  std::array<double, N> components(const YAML::Node& node, const std::string& field,
                                   std::initializer_list<const char*> keys) const {
    std::array<double, N> out{};
    if (node.IsSequence()) {
      if (node.size() != N) {
        fail(field, node,
             "expected " + std::to_string(N) + " numbers, got " + std::to_string(node.size()));
      }
      for (std::size_t i = 0; i < N; ++i) out[i] = number(node[i], index(field, i));
      return out;
    }
    if (!node.IsMap()) fail(field, node, "expected a list or a mapping of " + std::to_string(N));
    allowOnly(node, field, keys);
    std::size_t i = 0;
    for (const char* k : keys) {
      const YAML::Node c = child(node, field, k);
      out[i++] = c ? number(c, join(field, k)) : 0.0;
    }
    return out;
  }

  std::string path_;
};

}  // namespace octomotion::detail
