// A configuration struct's key table (core/common/config_fields.h) read from YAML or written to
// it: `fieldKeys(k, config)` with k a MapReader (reads each key present, refuses wrong types) or
// a MapWriter (writes every key; with a key log it also records each key's accepted values, for
// `msbench keys`). A nested group is read by its own table, unless the caller names a reader of
// its own for it (FieldKeys::custom: a section that also takes a preset name, or a list).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <type_traits>

#include "core/common/config_fields.h"
#include "tools/config/yaml_reader.h"
#include "tools/config/yaml_writer.h"

namespace msb {

/// The key-table visitor over a MapReader or MapWriter.
template <class Keys>
class FieldKeys {
 public:
  explicit FieldKeys(Keys& k) : k_(k) {}

  /// A key: read or written as its type; its accepted values (a Limits or Choices) are logged.
  template <class T, class... Rule>
  void key(const char* name, T& value, const Rule&... rule) {
    k_.field(name, value);
    // The rule's texts are made only for a writer that keeps a log (`msbench keys`).
    if constexpr (sizeof...(Rule) == 1 && !Keys::kReading)
      if (k_.keepsLog()) k_.noteRule(name, {rule.text()..., refused<T>(rule...)});
    // A mode key's rule is its words.
    if constexpr (WordEnum<T> && !Keys::kReading)
      if (k_.keepsLog()) k_.noteRule(name, {Choices::of<T>().text(), Choices::of<T>().outside()});
  }
  /// A nested group: its own table under its key (read if present, written always; unknown keys
  /// refused), or the reader given by custom().
  template <class Sub>
  void group(const char* name, Sub& sub) {
    if (auto it = custom_.find(name); it != custom_.end()) return it->second(k_);
    if (!k_.has(name)) return;
    auto k = k_.sub(name);
    FieldKeys<Keys> v(k);
    Sub::fields(sub, v);
    k.finish();
  }
  /// A name that is not a key here: refused by the reader, naming the key that holds the value.
  void moved(const char* name, const char* where) {
    k_.refuse(name, std::string("not a key of its own: the value is ") + where);
  }
  /// Reads and writes the group `name` with `section(parent keys)` instead of its table (a
  /// section that also takes a preset name, or a list).
  void custom(const std::string& name, std::function<void(Keys&)> section) { custom_[name] = std::move(section); }

 private:
  // A YAML value of type T that `rule` refuses ("" if none): a list for vector keys.
  template <class T>
  static std::string refused(const Choices& rule) {
    return rule.outside();
  }
  template <class T>
  static std::string refused(const Limits& rule) {
    const double v = rule.outside();
    if (std::isnan(v)) return "";
    const std::string one = exactNumberText(v);
    if constexpr (std::is_same_v<T, Vec2>) return "[" + one + ", " + one + "]";
    if constexpr (std::is_same_v<T, Vec3> || std::is_same_v<T, std::array<double, 3>>)
      return "[" + one + ", " + one + ", " + one + "]";
    if constexpr (std::is_same_v<T, std::array<double, 4>>)
      return "[" + one + ", " + one + ", " + one + ", " + one + "]";
    return one;
  }
  Keys& k_;
  std::map<std::string, std::function<void(Keys&)>> custom_;
};

/// Reads (MapReader) or writes (MapWriter) every key of `config`'s table in `k` (the caller
/// finishes `k`).
template <class Keys, class Config>
void fieldKeys(Keys& k, Config& config) {
  FieldKeys<Keys> v(k);
  Config::fields(config, v);
}

}  // namespace msb
