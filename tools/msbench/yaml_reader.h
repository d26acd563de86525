// Strict reading of YAML maps into typed fields for the configuration layer (tools/ only):
// unknown keys and wrong types become ConfigError with the full key path.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/common/config_check.h"
#include "core/common/types.h"

namespace msb {

/// A configuration problem in a named file (message: "FILE: key 'k': reason").
class FileConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Loads a YAML file and converts it with `read(MapReader&, Spec&)`, then validates the
/// result. A missing file, a syntax error, an unknown key, a wrong type or a bad value all
/// throw FileConfigError naming the file (and the key).
template <class Spec, class Read>
Spec parseConfigFile(const std::string& path, Read read);

// Strict reader of one YAML map: reads optional keys into typed fields and rejects unknown ones.
class MapReader {
 public:
  MapReader(const YAML::Node& node, std::string prefix) : node_(node), prefix_(std::move(prefix)) {
    if (!node_.IsMap()) throw ConfigError(keyName(""), "expected a map of keys");
  }

  bool has(const std::string& key) const { return bool(node_[key]); }

  // Reads `key` into `out` if present (marks it used); type errors name the key.
  template <class T>
  bool read(const std::string& key, T& out) {
    const YAML::Node n = node_[key];
    if (!n) return false;
    used_.insert(key);
    convert(n, key, out);
    return true;
  }

  // Reader for the nested map at `key` (the map must exist: call has() first).
  MapReader sub(const std::string& key) {
    used_.insert(key);
    return MapReader(node_[key], keyName(key) + ".");
  }

  // The raw node of `key` (marked used).
  YAML::Node raw(const std::string& key) {
    used_.insert(key);
    return node_[key];
  }

  // Calls item(MapReader&) for each map of the list at `key` (keys named "key[i].…").
  template <class Item>
  void forEachInList(const std::string& key, Item item) {
    const YAML::Node n = raw(key);
    if (!n.IsSequence()) throw ConfigError(keyName(key), "expected a list");
    for (size_t i = 0; i < n.size(); ++i) {
      MapReader m(n[i], keyName(key) + "[" + std::to_string(i) + "].");
      item(m);
    }
  }

  // Rejects keys that were never read.
  void finish() const {
    std::vector<ConfigIssue> issues;
    for (const auto& kv : node_) {
      const auto k = kv.first.as<std::string>();
      if (!used_.count(k)) issues.push_back({keyName(k), "unknown key"});
    }
    if (!issues.empty()) throw ConfigError(issues);
  }

  std::string keyName(const std::string& key) const {
    return key.empty() ? (prefix_.empty() ? "<root>" : prefix_.substr(0, prefix_.size() - 1))
                       : prefix_ + key;
  }

 private:
  [[noreturn]] void typeError(const YAML::Node& n, const std::string& key, const char* want) const {
    std::string got = n.IsScalar() ? "'" + n.Scalar() + "'" : n.IsSequence() ? "a list" : "a map";
    throw ConfigError(keyName(key), std::string("expected ") + want + ", got " + got);
  }
  void convert(const YAML::Node& n, const std::string& key, double& out) const {
    if (!n.IsScalar() || !YAML::convert<double>::decode(n, out) || !std::isfinite(out))
      typeError(n, key, "a number");
  }
  void convert(const YAML::Node& n, const std::string& key, int& out) const {
    if (!n.IsScalar() || !YAML::convert<int>::decode(n, out)) typeError(n, key, "an integer");
  }
  void convert(const YAML::Node& n, const std::string& key, uint64_t& out) const {
    long long v;
    if (!n.IsScalar() || !YAML::convert<long long>::decode(n, v) || v < 0)
      typeError(n, key, "a non-negative integer");
    out = static_cast<uint64_t>(v);
  }
  void convert(const YAML::Node& n, const std::string& key, bool& out) const {
    if (!n.IsScalar() || !YAML::convert<bool>::decode(n, out)) typeError(n, key, "true or false");
  }
  void convert(const YAML::Node& n, const std::string& key, std::string& out) const {
    if (!n.IsScalar()) typeError(n, key, "a string");
    out = n.Scalar();
  }
  void convert(const YAML::Node& n, const std::string& key, Vec3& out) const {
    if (!n.IsSequence() || n.size() != 3) typeError(n, key, "a list of 3 numbers");
    for (int i = 0; i < 3; ++i)
      if (!n[i].IsScalar() || !YAML::convert<double>::decode(n[i], out[i]))
        typeError(n, key, "a list of 3 numbers");
  }
  void convert(const YAML::Node& n, const std::string& key, std::array<double, 4>& out) const {
    if (!n.IsSequence() || n.size() != 4) typeError(n, key, "a list of 4 numbers");
    for (int i = 0; i < 4; ++i)
      if (!n[i].IsScalar() || !YAML::convert<double>::decode(n[i], out[i]))
        typeError(n, key, "a list of 4 numbers");
  }

  YAML::Node node_;
  std::string prefix_;
  std::set<std::string> used_;
};


/// Loads a YAML file; a missing file or a syntax error throws FileConfigError naming the file.
inline YAML::Node loadYamlFile(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw FileConfigError(path + ": file not found");
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw FileConfigError(path + ": YAML syntax error at line " + std::to_string(e.mark.line + 1) +
                          ", column " + std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
}

/// Converts an already loaded tree (errors are reported against `label`, usually the file).
template <class Spec, class Read>
Spec parseConfigNode(const std::string& label, const YAML::Node& root, Read read) {
  Spec spec;
  try {
    MapReader reader(root, "");
    read(reader, spec);
    checkValid(spec);
  } catch (const ConfigError& e) {
    throw FileConfigError(label + ": " + e.what());
  }
  return spec;
}

template <class Spec, class Read>
Spec parseConfigFile(const std::string& path, Read read) {
  return parseConfigNode<Spec>(path, loadYamlFile(path), read);
}

/// Reads a 2-vector ([x, y]).
inline void readVec2(MapReader& r, const std::string& key, Vec2& out) {
  YAML::Node n = r.raw(key);
  if (!n.IsSequence() || n.size() != 2 || !n[0].IsScalar() || !n[1].IsScalar())
    throw ConfigError(r.keyName(key), "expected a list of 2 numbers");
  double a, b;
  if (!YAML::convert<double>::decode(n[0], a) || !YAML::convert<double>::decode(n[1], b))
    throw ConfigError(r.keyName(key), "expected a list of 2 numbers");
  out = Vec2(a, b);
}

}  // namespace msb
