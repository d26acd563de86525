#include "core/common/config_check.h"

#include <sstream>

namespace msb {

namespace {
std::string describe(const std::vector<ConfigIssue>& issues) {
  std::ostringstream os;
  for (size_t i = 0; i < issues.size(); ++i) {
    if (i) os << "; ";
    os << "key '" << issues[i].key << "': " << issues[i].reason;
  }
  return os.str();
}
std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}
}  // namespace

ConfigError::ConfigError(std::vector<ConfigIssue> issues)
    : std::runtime_error(describe(issues)), issues_(std::move(issues)) {}

void ConfigChecker::require(bool ok, const std::string& key, const std::string& reason) {
  if (!ok) issues_.push_back({prefix_ + key, reason});
}

void ConfigChecker::positive(const std::string& key, double value) {
  require(value > 0.0, key, "must be > 0 (got " + num(value) + ")");
}

void ConfigChecker::nonNegative(const std::string& key, double value) {
  require(value >= 0.0, key, "must be >= 0 (got " + num(value) + ")");
}

void ConfigChecker::inRange(const std::string& key, double value, double lo, double hi) {
  require(value >= lo && value <= hi, key, "must be in [" + num(lo) + ", " + num(hi) + "] (got " + num(value) + ")");
}

bool isValidUtf8(const std::string& text) {
  const auto* p = reinterpret_cast<const unsigned char*>(text.data());
  const auto* end = p + text.size();
  while (p < end) {
    const unsigned char c = *p;
    // The sequence length and the smallest code point it may encode (no overlong forms).
    const int n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    if (n == 0 || end - p < n) return false;
    uint32_t cp = n == 1 ? c : n == 2 ? (c & 0x1Fu) : n == 3 ? (c & 0x0Fu) : (c & 0x07u);
    for (int k = 1; k < n; ++k) {
      if ((p[k] >> 6) != 0x2) return false;
      cp = (cp << 6) | (p[k] & 0x3Fu);
    }
    const uint32_t min[5] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < min[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    p += n;
  }
  return true;
}

}  // namespace msb
