// Writing configuration structs back to YAML: the counterpart of MapReader with the same key
// functions, so that one function per config section (`template <class Keys> void xKeys(Keys,
// Config&)`) both reads a file and writes the effective configuration with every default.
// Numbers are written in their shortest exact form: reading them back gives the same bits.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <type_traits>

#include "core/common/config_fields.h"
#include "core/common/types.h"

namespace msb {

/// The shortest text of `v` that reads back to exactly `v` (std::to_chars).
std::string exactNumberText(double v);

/// The value d, as close to rad / deg_per_unit as possible, for which d * deg_per_unit == rad
/// exactly (so that a value stored in radians and written in degrees reads back bit-identical).
double exactDegrees(double rad);

// Writer of one YAML map, with MapReader's key interface: field() writes, has() is always true
// (every optional section is written), finish() and refuse() do nothing. A NaN number is a
// config's "unset" (e.g. a render condition that keeps the world's own value) and is not written.
class MapWriter {
 public:
  /// True for MapReader, false here: sections that only a reader can do (presets, refusals) check it.
  static constexpr bool kReading = false;

  explicit MapWriter(YAML::Node node) : node_(std::move(node)) {}

  /// What one key accepts: the rule's text ("> 0", "in [1, 50]", "klt or oracle") and a YAML
  /// value it refuses ("" if it refuses none of its type).
  struct KeyRule {
    std::string accepts;
    std::string refused_value;
  };
  /// Each key's rule by its dotted path ("method.map.r_max_m").
  using KeyLog = std::map<std::string, KeyRule>;
  /// A writer that also logs the accepted values of the keys written through key tables.
  MapWriter(YAML::Node node, std::shared_ptr<KeyLog> log, std::string path = "")
      : node_(std::move(node)), log_(std::move(log)), path_(std::move(path)) {}

  bool has(const std::string&) const { return true; }
  template <class T>
  bool field(const std::string& key, const T& value) {
    if constexpr (std::is_same_v<T, double>)
      if (std::isnan(value)) return false;
    node_[key] = encode(value);
    return true;
  }
  /// The writer of the nested map at `key` (created).
  MapWriter sub(const std::string& key) {
    node_[key] = YAML::Node(YAML::NodeType::Map);
    return MapWriter(node_[key], log_, path_ + key + ".");
  }
  /// True if this writer keeps a key log.
  bool keepsLog() const { return log_ != nullptr; }
  /// Logs what `key` accepts (a key table's Limits or Choices), if this writer keeps a log.
  void noteRule(const std::string& key, KeyRule rule) {
    if (log_) (*log_)[path_ + key] = std::move(rule);
  }
  void refuse(const std::string&, const std::string&) const {}
  /// The key as named in messages (a writer has no path prefix).
  std::string keyName(const std::string& key) const { return key; }
  void finish() const {}
  YAML::Node& node() { return node_; }

  static YAML::Node encode(double v) { return YAML::Node(exactNumberText(v)); }
  static YAML::Node encode(int v) { return YAML::Node(std::to_string(v)); }
  static YAML::Node encode(uint64_t v) { return YAML::Node(std::to_string(v)); }
  static YAML::Node encode(bool v) { return YAML::Node(v ? "true" : "false"); }
  static YAML::Node encode(const std::string& v) { return YAML::Node(v); }
  static YAML::Node encode(const MapText& v) { return YAML::Load(v.text); }
  template <WordEnum E>
  static YAML::Node encode(E v) {
    return YAML::Node(std::string(wordOf(v)));
  }
  static YAML::Node encode(const Vec2& v) { return numbers(v.data(), 2); }
  static YAML::Node encode(const Vec3& v) { return numbers(v.data(), 3); }
  template <size_t N>
  static YAML::Node encode(const std::array<double, N>& v) {
    return numbers(v.data(), N);
  }

 private:
  static YAML::Node numbers(const double* v, size_t n);
  YAML::Node node_;
  std::shared_ptr<KeyLog> log_;  // null: no log
  std::string path_;             // "a.b." of this map, for the log
};

/// The text of a written tree (block style, lists of numbers in flow style).
std::string yamlText(const YAML::Node& root);

}  // namespace msb
