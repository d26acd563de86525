// A small command-line parser: declared options with defaults and help text, positional
// arguments, unknown flags rejected with a usage error (exit code 2).
#pragma once

#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/common/config_check.h"  // UsageError

namespace msb {

/// Exit codes of every msbench command.
enum ExitCode { kExitOk = 0, kExitRuntime = 1, kExitUsage = 2 };

/// Declares options, parses argv, prints a help table.
class ArgParser {
 public:
  /// `command` and `summary` head the help text.
  ArgParser(std::string command, std::string summary);
  /// A value option "--name VALUE" with a default ("" = required when `required`).
  ArgParser& option(const std::string& name, const std::string& def, const std::string& help, bool required = false);
  /// A boolean flag "--name".
  ArgParser& flag(const std::string& name, const std::string& help);
  /// A positional argument (all declared positionals are required).
  ArgParser& positional(const std::string& name, const std::string& help);
  /// Parses; returns false if --help was given (help printed). Throws UsageError.
  bool parse(int argc, char** argv);

  /// Value of an option or positional.
  const std::string& get(const std::string& name) const;
  /// Numeric value; throws UsageError naming the option if not a number.
  double getDouble(const std::string& name) const;
  /// Numeric value that must lie in [lo, hi]; throws UsageError naming the option.
  double getDoubleIn(const std::string& name, double lo, double hi) const;
  /// Integer value; throws UsageError naming the option if not an integer.
  long getInt(const std::string& name) const;
  /// Integer value that must lie in [lo, hi]; throws UsageError naming the option.
  long getIntIn(const std::string& name, long lo, long hi) const;
  /// True if the option was given on the command line (not defaulted).
  bool given(const std::string& name) const;
  /// True if the flag was given.
  bool has(const std::string& name) const;
  /// The help text.
  std::string help() const;

 private:
  struct Opt {
    std::string name, def, help;
    bool is_flag = false, required = false;
  };
  std::string command_, summary_;
  std::vector<Opt> options_;
  std::vector<std::pair<std::string, std::string>> positionals_;
  std::map<std::string, std::string> values_;
  std::set<std::string> given_;
};

/// Removes every "--NAME VALUE" / "--NAME=VALUE" from argv (for options that may repeat, which
/// ArgParser keeps once) and returns the values in order.
std::vector<std::string> takeRepeatedOption(int& argc, char** argv, const std::string& name);

}  // namespace msb
