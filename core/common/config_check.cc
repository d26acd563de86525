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
  require(value >= lo && value <= hi, key,
          "must be in [" + num(lo) + ", " + num(hi) + "] (got " + num(value) + ")");
}

}  // namespace msb
