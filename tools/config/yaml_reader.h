// Strict reading of YAML maps into typed fields for the configuration layer (tools/ only):
// unknown keys and wrong types become ConfigError with the full key path.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/common/config_check.h"
#include "core/common/config_fields.h"
#include "core/common/strict_number.h"
#include "core/common/types.h"

namespace msb {

/// Loads a YAML file and converts it with `read(MapReader&, Spec&)`, then validates the
/// result. A missing file, a syntax error, an unknown key, a wrong type or a bad value all
/// throw FileConfigError naming the file (and the key).
template <class Spec, class Read>
Spec parseConfigFile(const std::string& path, Read read);

/// The name among `names` closest to `typo` (edit distance at most 2, or a third of its length for
/// long names), "" if none is that close: the "did you mean" of unknown keys and method types.
std::string closestName(const std::string& typo, const std::set<std::string>& names);

// Strict reader of one YAML map: reads optional keys into typed fields and rejects unknown ones.
class MapReader {
 public:
  MapReader(const YAML::Node& node, std::string prefix) : node_(node), prefix_(std::move(prefix)) {
    if (!node_.IsMap()) throw ConfigError(keyName(""), "expected a map of keys");
  }

  /// True here, false for MapWriter: sections only a reader can do (presets, refusals) check it.
  static constexpr bool kReading = true;

  bool has(const std::string& key) const {
    asked_.insert(key);
    return bool(node_[key]);
  }

  /// read() under the name the key functions shared with MapWriter use.
  template <class T>
  bool field(const std::string& key, T& out) {
    return read(key, out);
  }

  /// Throws ConfigError(key, reason) if `key` is present (a key that is not one, e.g. moved).
  void refuse(const std::string& key, const std::string& reason) const {
    if (has(key)) throw ConfigError(keyName(key), reason);
  }

  // Reads `key` into `out` if present (marks it used); type errors name the key.
  template <class T>
  bool read(const std::string& key, T& out) {
    asked_.insert(key);
    const YAML::Node n = node_[key];
    if (!n) return false;
    used_.insert(key);
    convert(n, key, out);
    return true;
  }

  // Converts `n`, which is not a key of this map (e.g. a list element), with the same strictness;
  // errors name it `key` after this reader's prefix.
  template <class T>
  void value(const YAML::Node& n, const std::string& key, T& out) const {
    convert(n, key, out);
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
    size_t i = 0;
    for (const YAML::Node& element : n) {  // iterators: indexing a yaml-cpp sequence is linear
      MapReader m(element, keyName(key) + "[" + std::to_string(i++) + "].");
      item(m);
    }
  }

  // Rejects keys that were never read.
  void finish() const {
    std::vector<ConfigIssue> issues;
    for (const auto& kv : node_) {
      const std::string k = kv.first.IsScalar() ? kv.first.Scalar() : "<a non-text key>";
      if (used_.count(k)) continue;
      const std::string near = closestName(k, asked_);
      issues.push_back(
          {keyName(k), near.empty() ? "unknown key" : "unknown key (did you mean '" + keyName(near) + "'?)"});
    }
    if (!issues.empty()) throw ConfigError(issues);
  }

  std::string keyName(const std::string& key) const {
    return key.empty() ? (prefix_.empty() ? "<root>" : prefix_.substr(0, prefix_.size() - 1)) : prefix_ + key;
  }

 private:
  [[noreturn]] void typeError(const YAML::Node& n, const std::string& key, const char* want) const {
    std::string got = n.IsScalar()     ? "'" + n.Scalar() + "'"
                      : n.IsSequence() ? "a list of " + std::to_string(n.size())
                      : n.IsMap()      ? "a map"
                                       : "nothing (null)";
    throw ConfigError(keyName(key), std::string("expected ") + want + ", got " + got);
  }
  // Every number goes through the strict reader (finite, in range, whole text).
  double number(const YAML::Node& n, const std::string& key, const char* want) const {
    if (!n.IsScalar()) typeError(n, key, want);
    double v;
    std::string why;
    if (!parseNumber(n.Scalar(), &v, &why))
      throw ConfigError(keyName(key), std::string("expected ") + want + ": " + why);
    return v;
  }
  void convert(const YAML::Node& n, const std::string& key, double& out) const { out = number(n, key, "a number"); }
  void convert(const YAML::Node& n, const std::string& key, int& out) const {
    if (!n.IsScalar()) typeError(n, key, "an integer");
    int64_t v;
    std::string why;
    if (!parseInteger(n.Scalar(), &v, &why)) throw ConfigError(keyName(key), "expected an integer: " + why);
    if (v < INT32_MIN || v > INT32_MAX)
      throw ConfigError(keyName(key), "expected an integer: '" + n.Scalar() + "' is out of range");
    out = int(v);
  }
  void convert(const YAML::Node& n, const std::string& key, uint64_t& out) const {
    if (!n.IsScalar()) typeError(n, key, "a non-negative integer");
    std::string why;
    if (!parseUnsigned(n.Scalar(), &out, &why))
      throw ConfigError(keyName(key), "expected a non-negative integer: " + why);
  }
  // One rule for every boolean key: the words true or false (YAML 1.2's; yes/no/on/off/y/n, 1/0
  // and other spellings YAML 1.1 read as booleans are refused, quoted or not).
  void convert(const YAML::Node& n, const std::string& key, bool& out) const {
    if (!n.IsScalar()) typeError(n, key, "true or false");
    const std::string& v = n.Scalar();
    if (v == "true" || v == "True" || v == "TRUE")
      out = true;
    else if (v == "false" || v == "False" || v == "FALSE")
      out = false;
    else
      throw ConfigError(keyName(key), "expected true or false, got '" + v + "'");
  }
  void convert(const YAML::Node& n, const std::string& key, std::string& out) const {
    if (!n.IsScalar()) typeError(n, key, "a string");
    out = n.Scalar();
  }
  // A mode key: one of its enum's words (core/common/word_enum.h).
  template <WordEnum E>
  void convert(const YAML::Node& n, const std::string& key, E& out) const {
    if (!n.IsScalar()) typeError(n, key, "a word");
    if (!parseWord(n.Scalar(), out))
      throw ConfigError(keyName(key), "must be " + Choices::of<E>().text() + " (got '" + n.Scalar() + "')");
  }
  // A map kept as its one-line text (MapText).
  void convert(const YAML::Node& n, const std::string& key, MapText& out) const {
    if (!n.IsMap()) typeError(n, key, "a map");
    YAML::Emitter e;
    e << YAML::Flow << n;
    out.text = e.c_str();
  }
  // A list of exactly N numbers, each through the strict reader.
  template <size_t N, class Out>
  void numbers(const YAML::Node& n, const std::string& key, Out& out) const {
    const std::string want = "a list of " + std::to_string(N) + " numbers";
    if (!n.IsSequence()) typeError(n, key, want.c_str());
    if (n.size() != N)
      throw ConfigError(keyName(key), "expected " + want + ", got a list of " + std::to_string(n.size()));
    size_t i = 0;
    for (const YAML::Node& element : n) {
      out[i] = number(element, key + "[" + std::to_string(i) + "]", "a number");
      ++i;
    }
  }
  void convert(const YAML::Node& n, const std::string& key, Vec2& out) const { numbers<2>(n, key, out); }
  void convert(const YAML::Node& n, const std::string& key, Vec3& out) const { numbers<3>(n, key, out); }
  void convert(const YAML::Node& n, const std::string& key, std::array<double, 3>& out) const {
    numbers<3>(n, key, out);
  }
  void convert(const YAML::Node& n, const std::string& key, std::array<double, 4>& out) const {
    numbers<4>(n, key, out);
  }

  YAML::Node node_;
  std::string prefix_;
  std::set<std::string> used_;
  mutable std::set<std::string> asked_;  // every key looked for: the names a typo is compared with
};

/// The largest YAML input msbench reads (a scenario, base, flight, sweep or world spec).
inline constexpr std::uintmax_t kMaxYamlFileBytes = 8u << 20;
/// The most nodes a YAML input may expand to, aliases counted at every use: a bound on every
/// later traversal, so that an alias bomb (a few KB that expand to 10^10 nodes) is refused at
/// once instead of hanging every reader.
inline constexpr size_t kMaxYamlNodes = 1'000'000;

/// Throws FileConfigError (naming `label` and both lines) if a map anywhere in `node` holds
/// the same key twice (YAML forbids it; yaml-cpp keeps both and lookups would pick one), or if
/// `node` expands to more than kMaxYamlNodes nodes. Every loaded YAML input passes here first.
void rejectDuplicateKeys(const YAML::Node& node, const std::string& label, const std::string& prefix = "");

/// Loads a YAML file; a missing file, one larger than kMaxYamlFileBytes, a syntax error, a
/// duplicate key or an expansion beyond kMaxYamlNodes throws FileConfigError naming the file.
YAML::Node loadYamlFile(const std::string& path);

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
  } catch (const YAML::Exception& e) {
    throw FileConfigError(label + ": unreadable YAML value: " + e.msg);
  }
  return spec;
}

template <class Spec, class Read>
Spec parseConfigFile(const std::string& path, Read read) {
  return parseConfigNode<Spec>(path, loadYamlFile(path), read);
}

/// Reads a 2-vector ([x, y]) through the strict number reader (finite, in range; errors name the
/// element, e.g. `objects[2].at[1]`).
inline void readVec2(MapReader& r, const std::string& key, Vec2& out) {
  if (!r.read(key, out)) throw ConfigError(r.keyName(key), "expected a list of 2 numbers, got nothing");
}

}  // namespace msb
