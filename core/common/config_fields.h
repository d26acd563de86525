// Key tables: each configuration struct names its keys once, with the values each accepts, in
//
//   template <class Self, class V> static void fields(Self& s, V& v) {
//     v.key("max_range_m", s.max_range_m, Limits::positive());  // a number and its range
//     v.key("insertion", s.insertion, Choices{"standard", "confidence_weighted"});
//     v.key("compute", s.compute);                               // a mode (core/common/word_enum.h)
//     v.key("enabled", s.enabled);                               // a flag
//     v.group("planner", s.planner);                             // a nested config (its own table)
//     v.moved("r_min_m", "method.map.r_min_m");                  // not a key here: refused, naming where
//   }
//
// The same table validates (FieldCheck below, from the struct's validate()), reads and writes
// YAML (tools/config/field_keys.h) and lists the key reference (`msbench keys`, docs/keys.md).
// `Self` is the struct, const or not, so that one table serves checking (const) and reading.
// What a table cannot say (a value that depends on another key) stays in validate().
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/common/config_check.h"
#include "core/common/types.h"
#include "core/common/word_enum.h"

namespace msb {

/// The values a numeric key accepts: an interval, each end open or closed (or unbounded). A
/// vector key applies it to each component. NaN passes only when `unset_ok` (a key whose NaN
/// means "not given", e.g. a render condition that keeps the world's own value).
struct Limits {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  bool unset_ok = false;

  /// (0, ∞).
  static Limits positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  /// [0, ∞).
  static Limits nonNegative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  /// [lo, hi].
  static Limits range(double lo, double hi) { return {lo, hi, false, false}; }
  /// Any finite value (the reader refuses non-finite numbers).
  static Limits any() { return {}; }
  /// The same interval, and NaN allowed (unset).
  Limits orUnset() const {
    Limits l = *this;
    l.unset_ok = true;
    return l;
  }

  /// True if `v` lies in the interval (or is NaN and `unset_ok`).
  bool holds(double v) const;
  /// The interval as a reason's text: "> 0", ">= 0", "in [lo, hi]", "in (lo, hi]", "any number".
  std::string text() const;
  /// A value outside the interval (for tests that every key is checked), or NaN if none is.
  double outside() const;
};

/// The words a text key accepts (e.g. an insertion mode).
struct Choices {
  std::vector<std::string> words;
  Choices(std::initializer_list<std::string> w) : words(w) {}
  explicit Choices(std::vector<std::string> w) : words(std::move(w)) {}
  /// The words of a mode key's enum (core/common/word_enum.h).
  template <WordEnum E>
  static Choices of() {
    return Choices(wordsList<E>());
  }
  /// True if `word` is one of them.
  bool holds(const std::string& word) const;
  /// "a, b or c".
  std::string text() const;
  /// A word that is none of them.
  std::string outside() const { return "none_of_these"; }
};

/// A key whose value is a YAML map that msbench passes through as its one-line text, unread (a
/// Python factory's keyword arguments, which the factory validates). A map is required.
struct MapText {
  std::string text = "{}";  ///< the map in YAML flow style
};

/// The key-table visitor that validates: each number against its Limits (message "must be
/// LIMITS (got V)"), each word against its Choices, each group by its own validate().
class FieldCheck {
 public:
  explicit FieldCheck(ConfigChecker& c) : c_(c) {}

  void key(const char* name, double v, const Limits& l) { number(name, v, l); }
  void key(const char* name, int v, const Limits& l) { number(name, v, l); }
  void key(const char* name, uint64_t v, const Limits& l) { number(name, double(v), l); }
  void key(const char* name, const Vec2& v, const Limits& l) { components(name, v.data(), 2, l); }
  void key(const char* name, const Vec3& v, const Limits& l) { components(name, v.data(), 3, l); }
  template <size_t N>
  void key(const char* name, const std::array<double, N>& v, const Limits& l) {
    components(name, v.data(), N, l);
  }
  void key(const char*, bool) {}
  void key(const char*, const std::string&) {}
  void key(const char*, const MapText&) {}
  template <WordEnum E>
  void key(const char*, E) {}  // a mode key holds one of its words by its type
  void key(const char* name, const std::string& v, const Choices& c);
  template <class Sub>
  void group(const char* name, const Sub& sub) {
    c_.nested(name, sub);
  }
  void moved(const char*, const char*) {}

 private:
  void number(const char* name, double v, const Limits& l);
  void components(const char* name, const double* v, size_t n, const Limits& l);
  ConfigChecker& c_;
};

/// Validates every key of `config`'s table (the first part of a validate()).
template <class Config>
void checkFields(const Config& config, ConfigChecker& c) {
  FieldCheck check(c);
  Config::fields(config, check);
}

}  // namespace msb
