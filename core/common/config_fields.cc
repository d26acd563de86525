#include "core/common/config_fields.h"

#include <sstream>

namespace msb {

namespace {
// A number as config messages print it (6 significant digits, as ConfigChecker does).
std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}
}  // namespace

bool Limits::holds(double v) const {
  if (std::isnan(v)) return unset_ok;
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Limits::text() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  std::string t;
  if (has_lo && has_hi)
    t = std::string("in ") + (lo_open ? "(" : "[") + num(lo) + ", " + num(hi) + (hi_open ? ")" : "]");
  else if (has_lo)
    t = (lo_open ? "> " : ">= ") + num(lo);
  else if (has_hi)
    t = (hi_open ? "< " : "<= ") + num(hi);
  else
    t = "any number";
  return unset_ok ? t + " (or unset)" : t;
}

double Limits::outside() const {
  if (std::isfinite(lo)) return lo_open ? lo : lo - 1.0;
  if (std::isfinite(hi)) return hi_open ? hi : hi + 1.0;
  return std::nan("");
}

bool Choices::holds(const std::string& word) const {
  for (const auto& w : words)
    if (w == word) return true;
  return false;
}

std::string Choices::text() const {
  std::string t;
  for (size_t i = 0; i < words.size(); ++i) t += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
  return t;
}

void FieldCheck::number(const char* name, double v, const Limits& l) {
  if (!l.holds(v)) c_.require(false, name, "must be " + l.text() + " (got " + num(v) + ")");
}

void FieldCheck::components(const char* name, const double* v, size_t n, const Limits& l) {
  for (size_t i = 0; i < n; ++i)
    if (!l.holds(v[i])) {
      c_.require(false, name, "each component must be " + l.text() + " (got " + num(v[i]) + ")");
      return;
    }
}

void FieldCheck::key(const char* name, const std::string& v, const Choices& c) {
  if (!c.holds(v)) c_.require(false, name, "must be " + c.text() + " (got '" + v + "')");
}

}  // namespace msb
