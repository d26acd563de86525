// The config-validation pattern: every component has a plain Config struct with in-class
// defaults and a `validate(ConfigChecker&)` method; its constructor calls `checkValid(config)`,
// which throws ConfigError listing every bad field by its key path. The YAML layer (tools/)
// prefixes the file name, so a user sees "file.yaml: key 'a.b': reason".
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace msb {

/// One problem with one configuration key.
struct ConfigIssue {
  std::string key;     ///< dotted key path, e.g. "trajectory.max_speed_mps"
  std::string reason;  ///< what is wrong, e.g. "must be > 0 (got -1)"
};

/// Thrown when a configuration is invalid; `issues()` names every bad key.
class ConfigError : public std::runtime_error {
 public:
  explicit ConfigError(std::vector<ConfigIssue> issues);
  ConfigError(const std::string& key, const std::string& reason)
      : ConfigError(std::vector<ConfigIssue>{{key, reason}}) {}
  const std::vector<ConfigIssue>& issues() const { return issues_; }

 private:
  std::vector<ConfigIssue> issues_;
};

/// Collects issues while a Config validates its fields; keys get the current prefix.
class ConfigChecker {
 public:
  explicit ConfigChecker(std::string prefix = "") : prefix_(std::move(prefix)) {}

  /// Records an issue unless `ok`.
  void require(bool ok, const std::string& key, const std::string& reason);
  /// value > 0.
  void positive(const std::string& key, double value);
  /// value >= 0.
  void nonNegative(const std::string& key, double value);
  /// lo <= value <= hi.
  void inRange(const std::string& key, double value, double lo, double hi);
  /// Validates a nested config under "<prefix><key>.".
  template <class Sub>
  void nested(const std::string& key, const Sub& sub) {
    ConfigChecker child(prefix_ + key + ".");
    sub.validate(child);
    issues_.insert(issues_.end(), child.issues_.begin(), child.issues_.end());
  }
  /// All issues so far.
  const std::vector<ConfigIssue>& issues() const { return issues_; }

 private:
  std::string prefix_;
  std::vector<ConfigIssue> issues_;
};

/// Validates `config` and returns it, or throws ConfigError naming every bad key.
template <class Config>
const Config& checkValid(const Config& config) {
  ConfigChecker checker;
  config.validate(checker);
  if (!checker.issues().empty()) throw ConfigError(checker.issues());
  return config;
}

/// A configuration problem in a named file (message: "FILE: key 'k': reason"). Bad input:
/// every command exits 2.
class FileConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Wrong command-line usage, or a request that cannot be honoured as given (exit code 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Builds what `build` returns (a loop, a mission); a ConfigError it throws (a world that does
/// not load, a start pose inside an obstacle) is re-thrown as FileConfigError naming `file`.
template <class Build>
auto buildNamingFile(const std::string& file, Build&& build) -> decltype(build()) {
  try {
    return build();
  } catch (const ConfigError& e) {
    throw FileConfigError(file + ": " + e.what());
  }
}

/// True if `text` is valid UTF-8 (no overlong forms, no surrogates, at most U+10FFFF): names and
/// paths go into JSON results, which must be valid UTF-8, so they are checked before a run.
bool isValidUtf8(const std::string& text);

}  // namespace msb
