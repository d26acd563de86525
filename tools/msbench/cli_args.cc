#include "tools/msbench/cli_args.h"

#include "core/common/strict_number.h"

#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace msb {

ArgParser::ArgParser(std::string command, std::string summary)
    : command_(std::move(command)), summary_(std::move(summary)) {}

ArgParser& ArgParser::option(const std::string& name, const std::string& def, const std::string& help, bool required) {
  options_.push_back({name, def, help, false, required});
  return *this;
}

ArgParser& ArgParser::flag(const std::string& name, const std::string& help) {
  options_.push_back({name, "", help, true, false});
  return *this;
}

ArgParser& ArgParser::positional(const std::string& name, const std::string& help) {
  positionals_.push_back({name, help});
  return *this;
}

bool ArgParser::parse(int argc, char** argv) {
  size_t next_positional = 0;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::cout << help();
      return false;
    }
    if (a.rfind("--", 0) == 0) {
      std::string name = a.substr(2), value;
      const auto eq = name.find('=');
      if (eq != std::string::npos) value = name.substr(eq + 1), name = name.substr(0, eq);
      const Opt* opt = nullptr;
      for (const auto& o : options_)
        if (o.name == name) opt = &o;
      if (!opt) throw UsageError("unknown option --" + name + " (see " + command_ + " --help)");
      if (opt->is_flag) {
        if (eq != std::string::npos) throw UsageError("--" + name + " takes no value");
        values_.insert_or_assign(name, std::string(1, '1'));  // (GCC 12 -Wrestrict false positive on = "1")
      } else {
        if (eq == std::string::npos) {
          if (i + 1 >= argc) throw UsageError("--" + name + " needs a value");
          value = argv[++i];
        }
        if (value.empty()) throw UsageError("--" + name + ": empty value");
        if (given_.count(name)) throw UsageError("--" + name + " given twice");
        values_[name] = value;
        given_.insert(name);
      }
      continue;
    }
    if (next_positional >= positionals_.size())
      throw UsageError("unexpected argument '" + a + "' (see " + command_ + " --help)");
    values_[positionals_[next_positional++].first] = a;
  }
  if (next_positional < positionals_.size())
    throw UsageError("missing argument " + positionals_[next_positional].first + " (see " + command_ + " --help)");
  for (const auto& o : options_) {
    if (values_.count(o.name)) continue;
    if (o.required) throw UsageError("option --" + o.name + " is required");
    if (!o.is_flag) values_[o.name] = o.def;
  }
  return true;
}

const std::string& ArgParser::get(const std::string& name) const {
  static const std::string empty;
  const auto it = values_.find(name);
  return it == values_.end() ? empty : it->second;
}

double ArgParser::getDouble(const std::string& name) const {
  double d;
  std::string why;
  if (!parseNumber(get(name), &d, &why)) throw UsageError("--" + name + ": " + why);
  return d;
}

double ArgParser::getDoubleIn(const std::string& name, double lo, double hi) const {
  const double d = getDouble(name);
  if (d < lo || d > hi) {
    std::ostringstream os;
    os << "--" << name << ": must be in [" << lo << ", " << hi << "] (got " << d << ")";
    throw UsageError(os.str());
  }
  return d;
}

long ArgParser::getInt(const std::string& name) const {
  int64_t v;
  std::string why;
  if (!parseInteger(get(name), &v, &why)) throw UsageError("--" + name + ": " + why);
  return long(v);
}

long ArgParser::getIntIn(const std::string& name, long lo, long hi) const {
  const long v = getInt(name);
  if (v < lo || v > hi)
    throw UsageError("--" + name + ": must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "] (got " +
                     std::to_string(v) + ")");
  return v;
}

bool ArgParser::given(const std::string& name) const { return given_.count(name) > 0; }

bool ArgParser::has(const std::string& name) const { return values_.count(name) > 0; }

std::string ArgParser::help() const {
  std::ostringstream os;
  os << "usage: " << command_;
  for (const auto& p : positionals_) os << ' ' << p.first;
  os << " [options]\n\n" << summary_ << "\n";
  if (!positionals_.empty()) {
    os << "\narguments:\n";
    for (const auto& p : positionals_) os << "  " << std::left << std::setw(22) << p.first << p.second << "\n";
  }
  os << "\noptions:                default       meaning\n";
  for (const auto& o : options_) {
    const std::string flag = "--" + o.name + (o.is_flag ? "" : " V");
    const std::string def = o.is_flag ? "off" : (o.required ? "(required)" : o.def);
    // A name too long for its column keeps a space before the default.
    os << "  " << std::left << std::setw(22) << (flag.size() < 22 ? flag : flag + " ") << std::setw(14) << def << o.help
       << "\n";
  }
  os << "  " << std::left << std::setw(36) << "--help"
     << "show this help\n";
  return os.str();
}

std::vector<std::string> takeRepeatedOption(int& argc, char** argv, const std::string& name) {
  const std::string flag = "--" + name, prefix = flag + "=";
  std::vector<std::string> values;
  int w = 0;
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == flag && i + 1 >= argc) throw UsageError(flag + " needs a value (" + flag + " KEY=VALUE)");
    if (a == flag)
      values.push_back(argv[++i]);
    else if (a.rfind(prefix, 0) == 0)
      values.push_back(a.substr(prefix.size()));
    else
      argv[w++] = argv[i];
  }
  argc = w;
  return values;
}

}  // namespace msb
