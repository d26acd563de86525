// A method's counters (metrics.json → counters, the progress line), indexed by the method's own
// enum: each counter is named once, beside its enumerator, so a misspelt counter is a compile
// error instead of a new counter. The written names are the JSON keys.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <string>

namespace msb {

/// Counters indexed by `E`, an enum class whose last enumerator is `kCount`.
template <class E>
class Counters {
 public:
  static constexpr size_t kSize = size_t(E::kCount);

  /// `names[i]`: the JSON name of the enumerator with value i.
  explicit Counters(const std::array<const char*, kSize>& names) : names_(names) {}

  /// The counter of `e`.
  double& operator[](E e) { return values_[size_t(e)]; }
  double operator[](E e) const { return values_[size_t(e)]; }

  /// Every counter by its name (all of them, zeros included).
  std::map<std::string, double> toMap() const {
    std::map<std::string, double> m;
    for (size_t i = 0; i < kSize; ++i) m[names_[i]] = values_[i];
    return m;
  }

 private:
  std::array<const char*, kSize> names_;
  std::array<double, kSize> values_{};
};

}  // namespace msb
