#include "core/common/strict_number.h"

#include <charconv>
#include <cmath>
#include <cstdlib>

namespace msb {

namespace {
// Trims surrounding blanks (YAML scalars and flags may carry none; logs may).
std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}
// "'TEXT' REASON" (built by appending: GCC 12 warns falsely on chained operator+ here).
std::string quoted(std::string_view text, const char* reason) {
  std::string m = "'";
  m.append(text);
  m.append("' ");
  m.append(reason);
  return m;
}
}  // namespace

bool parseNumber(std::string_view text, double* out, std::string* why) {
  const std::string s(trim(text));
  if (s.empty()) return *why = "empty, expected a number", false;
  // Decimal only: strtod would also take hexadecimal ("0x1p3").
  if (s.find_first_of("xX") != std::string::npos) return *why = quoted(s, "is not a decimal number"), false;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0') return *why = quoted(s, "is not a number"), false;
  if (!std::isfinite(v)) return *why = quoted(s, "is not a finite number"), false;
  if (std::abs(v) > kMaxTextNumber) return *why = quoted(s, "is out of range (|x| ≤ 1e12)"), false;
  *out = v;
  return true;
}

bool parseInteger(std::string_view text, int64_t* out, std::string* why) {
  const std::string_view s = trim(text);
  if (s.empty()) return *why = "empty, expected an integer", false;
  std::string_view digits = s;
  if (digits.front() == '+') digits.remove_prefix(1);
  int64_t v = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (ec == std::errc::result_out_of_range) return *why = quoted(s, "is out of range"), false;
  if (ec != std::errc() || ptr != digits.data() + digits.size()) return *why = quoted(s, "is not an integer"), false;
  *out = v;
  return true;
}

bool parseUnsigned(std::string_view text, uint64_t* out, std::string* why) {
  const std::string_view s = trim(text);
  if (s.empty()) return *why = "empty, expected a non-negative integer", false;
  // "-0" is no negative number, but a sign where none belongs: said as such.
  if (s.front() == '-')
    return *why = quoted(s, s.find_first_not_of('0', 1) == std::string_view::npos && s.size() > 1
                                ? "carries a minus sign (a non-negative integer is written without one: 0)"
                                : "is negative"),
           false;
  std::string_view digits = s;
  if (digits.front() == '+') digits.remove_prefix(1);
  uint64_t v = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (ec == std::errc::result_out_of_range) return *why = quoted(s, "is out of range"), false;
  if (ec != std::errc() || ptr != digits.data() + digits.size())
    return *why = quoted(s, "is not a non-negative integer"), false;
  *out = v;
  return true;
}

}  // namespace msb
