#include "tools/config/sweep_plan.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/common/rng.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/yaml_reader.h"

namespace msb {

namespace fs = std::filesystem;

namespace {

// One value of an axis: its label and the overrides it applies.
struct AxisValue {
  std::string label;
  std::string scenario;  // replaces the base scenario if not empty
  std::vector<std::pair<std::string, std::string>> sets;
};

struct Axis {
  std::string name;
  std::vector<AxisValue> values;
};

// A YAML value as the text `--set key=VALUE` parses back to the same value: a scalar that would
// read back as something else (a list, a map, a quote, a comment) is written quoted.
std::string yamlText(const YAML::Node& n) {
  if (n.IsScalar()) {
    const std::string& text = n.Scalar();
    try {
      const YAML::Node back = YAML::Load(text);
      if (back.IsScalar() && back.Scalar() == text) return text;
    } catch (const YAML::Exception&) {
    }
    YAML::Emitter e;
    e << YAML::DoubleQuoted << text;
    return e.c_str();
  }
  YAML::Emitter e;
  e << YAML::Flow << n;
  return e.c_str();
}

// Labels become parts of directory names: letters, digits, '.', '_' and '+' only.
void checkLabel(const std::string& label, const std::string& key) {
  const bool ok = !label.empty() && std::all_of(label.begin(), label.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '+';
  });
  if (!ok) throw ConfigError(key, "label '" + label + "' may hold only letters, digits, '.', '_' and '+'");
}

// key path: value pairs of a map (in file order).
std::vector<std::pair<std::string, std::string>> overrides(const YAML::Node& m, const std::string& key) {
  if (!m.IsMap()) throw ConfigError(key, "expected a map of key paths to values");
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& kv : m) {
    if (!kv.first.IsScalar()) throw ConfigError(key, "keys must be key paths");
    out.emplace_back(kv.first.Scalar(), yamlText(kv.second));
  }
  return out;
}

Axis readAxis(MapReader& r, const fs::path& dir) {
  Axis a;
  if (!r.read("name", a.name) || a.name.empty()) throw ConfigError(r.keyName("name"), "required");
  checkLabel(a.name, r.keyName("name"));
  std::string key;
  const bool has_key = r.read("key", key);
  if (r.has("values") == r.has("variants"))
    throw ConfigError(r.keyName("values"), "give either values (with key) or variants");
  if (r.has("values")) {
    if (!has_key) throw ConfigError(r.keyName("key"), "required with values");
    const YAML::Node vals = r.raw("values");
    if (!vals.IsSequence() || vals.size() == 0) throw ConfigError(r.keyName("values"), "expected a non-empty list");
    for (const auto& v : vals) {
      AxisValue av;
      av.label = yamlText(v);
      checkLabel(av.label, r.keyName("values"));
      av.sets.emplace_back(key, av.label);
      a.values.push_back(av);
    }
  } else {
    if (has_key) throw ConfigError(r.keyName("key"), "not used with variants (each variant names its keys)");
    const YAML::Node vars = r.raw("variants");
    if (!vars.IsMap() || vars.size() == 0) throw ConfigError(r.keyName("variants"), "expected a non-empty map");
    for (const auto& kv : vars) {
      AxisValue av;
      av.label = kv.first.Scalar();
      const std::string vkey = r.keyName("variants") + "." + av.label;
      checkLabel(av.label, vkey);
      if (!kv.second.IsMap()) throw ConfigError(vkey, "expected a map of key paths to values ({} for none)");
      for (auto& [k, v] : overrides(kv.second, vkey)) {
        if (k == "scenario")
          av.scenario = scenarioFileNamed(dir, v).lexically_normal().string();
        else
          av.sets.emplace_back(k, v);
      }
      a.values.push_back(av);
    }
  }
  r.finish();
  return a;
}

// A combination filter: axis name → label.
using Combination = std::map<std::string, std::string>;

std::vector<Combination> readCombinations(MapReader& r, const std::string& key, const std::vector<Axis>& axes) {
  std::vector<Combination> out;
  r.forEachInList(key, [&](MapReader& m) {
    Combination c;
    for (const Axis& a : axes) {
      std::string label;
      if (m.read(a.name, label)) c[a.name] = label;
    }
    // `seed`: one seed, or a list of seeds (one combination each).
    std::vector<uint64_t> seeds;
    if (m.has("seed") && m.raw("seed").IsSequence()) {
      size_t i = 0;
      for (const YAML::Node& v : m.raw("seed")) {
        uint64_t x = 0;
        m.value(v, "seed[" + std::to_string(i++) + "]", x);
        seeds.push_back(x);
      }
      if (seeds.empty()) throw ConfigError(m.keyName("seed"), "an empty list matches nothing");
    } else if (uint64_t seed = 0; m.read("seed", seed)) {
      seeds.push_back(seed);
    }
    m.finish();
    for (const uint64_t x : seeds) {
      std::string& list = c["seed"];
      if (!list.empty()) list.push_back(',');
      list.append(std::to_string(x));
    }
    out.push_back(c);
  });
  return out;
}

bool matches(const Combination& c, const std::map<std::string, std::string>& labels) {
  for (const auto& [axis, label] : c) {
    if (!labels.count(axis)) return false;
    if (axis == "seed") {  // one seed or a comma-separated list of them
      std::istringstream list(label);
      std::string one;
      bool any = false;
      while (std::getline(list, one, ',')) any = any || one == labels.at(axis);
      if (!any) return false;
    } else if (labels.at(axis) != label) {
      return false;
    }
  }
  return true;
}

// The sweep file's FNV-1a hash as 16 hex digits (a changed file is detected on resume).
std::string fileHash(const std::string& path) {
  std::ostringstream bytes;
  bytes << std::ifstream(path, std::ios::binary).rdbuf();
  const std::string text = bytes.str();
  char hash[17];
  std::snprintf(hash, sizeof(hash), "%016llx", static_cast<unsigned long long>(fnv1a64(text.data(), text.size())));
  return hash;
}

// `seeds`: a list, or a count n meaning 1..n (default: seed 1).
std::vector<uint64_t> readSeeds(MapReader& r) {
  std::vector<uint64_t> seeds = {1};
  if (r.has("seeds")) {
    const YAML::Node s = r.raw("seeds");
    seeds.clear();
    if (s.IsSequence()) {
      for (const auto& v : s) {
        uint64_t x = 0;
        r.value(v, "seeds", x);
        seeds.push_back(x);
      }
    } else {
      uint64_t n = 0;
      r.value(s, "seeds", n);
      if (n < 1 || n > 10000) throw ConfigError("seeds", "a count must be in [1, 10000]");
      for (uint64_t k = 1; k <= n; ++k) seeds.push_back(k);
    }
    if (seeds.empty()) throw ConfigError("seeds", "expected at least one seed");
  }
  return seeds;
}

// The runs of the axes' combinations and the seeds (the first axis slowest, seeds fastest), with
// include / exclude applied; an include or exclude entry that matches nothing is refused.
void expandRuns(SweepPlan& plan, const std::string& base,
                const std::vector<std::pair<std::string, std::string>>& common, const std::vector<Axis>& axes,
                const std::vector<uint64_t>& seeds, const std::vector<Combination>& include,
                const std::vector<Combination>& exclude) {
  std::vector<bool> include_used(include.size(), false), exclude_used(exclude.size(), false);
  std::vector<size_t> index(axes.size(), 0);
  while (true) {
    std::map<std::string, std::string> labels;
    std::string id, file = base;
    std::vector<std::pair<std::string, std::string>> sets = common;
    for (size_t k = 0; k < axes.size(); ++k) {
      const AxisValue& v = axes[k].values[index[k]];
      labels[axes[k].name] = v.label;
      id += v.label + "-";
      if (!v.scenario.empty()) file = v.scenario;
      sets.insert(sets.end(), v.sets.begin(), v.sets.end());
    }
    for (uint64_t s : seeds) {
      std::map<std::string, std::string> with_seed = labels;
      with_seed["seed"] = std::to_string(s);
      auto hit = [&](const Combination& c) { return matches(c, with_seed); };
      for (size_t i = 0; i < include.size(); ++i) include_used[i] = include_used[i] || hit(include[i]);
      for (size_t i = 0; i < exclude.size(); ++i) exclude_used[i] = exclude_used[i] || hit(exclude[i]);
      const bool kept = (include.empty() || std::any_of(include.begin(), include.end(), hit)) &&
                        std::none_of(exclude.begin(), exclude.end(), hit);
      if (kept) plan.runs.push_back({id + "s" + std::to_string(s), file, s, sets, labels});
    }
    size_t k = axes.size();
    while (k > 0 && ++index[k - 1] == axes[k - 1].values.size()) index[--k] = 0;
    if (k == 0) break;
  }
  for (size_t i = 0; i < include.size(); ++i)
    if (!include_used[i])
      throw ConfigError("include[" + std::to_string(i) + "]", "matches no combination of the axes and seeds");
  for (size_t i = 0; i < exclude.size(); ++i)
    if (!exclude_used[i])
      throw ConfigError("exclude[" + std::to_string(i) + "]", "matches no combination of the axes and seeds");
  for (size_t i = 0; i < plan.runs.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (plan.runs[i].id == plan.runs[j].id) throw ConfigError("axes", "two runs share the id " + plan.runs[i].id);
  if (plan.runs.empty()) throw ConfigError("include", "no run left after include/exclude");
}

}  // namespace

SweepPlan loadSweepPlan(const std::string& path) {
  const YAML::Node root = loadYamlFile(path);
  SweepPlan plan;
  plan.file = fs::absolute(path).lexically_normal().string();
  plan.file_hash = fileHash(path);
  const fs::path dir = fs::path(plan.file).parent_path();
  try {
    MapReader r(root, "");
    std::string scenario;
    if (!r.read("scenario", scenario)) throw ConfigError("scenario", "required (the base scenario file)");
    const std::string base = scenarioFileNamed(dir, scenario).lexically_normal().string();
    std::vector<std::pair<std::string, std::string>> common;
    if (r.has("set")) common = overrides(r.raw("set"), "set");
    std::vector<Axis> axes;
    if (r.has("axes")) r.forEachInList("axes", [&](MapReader& m) { axes.push_back(readAxis(m, dir)); });
    for (size_t i = 0; i < axes.size(); ++i)
      for (size_t j = 0; j < i; ++j)
        if (axes[i].name == axes[j].name) throw ConfigError("axes", "axis name '" + axes[i].name + "' given twice");
    const std::vector<uint64_t> seeds = readSeeds(r);
    std::vector<Combination> include, exclude;
    if (r.has("include")) include = readCombinations(r, "include", axes);
    if (r.has("exclude")) exclude = readCombinations(r, "exclude", axes);
    r.finish();
    for (const Axis& a : axes) plan.axes.push_back(a.name);
    expandRuns(plan, base, common, axes, seeds, include, exclude);
  } catch (const ConfigError& e) {
    throw FileConfigError(path + ": " + e.what());
  } catch (const YAML::Exception& e) {
    throw FileConfigError(path + ": unreadable YAML value: " + e.msg);
  }
  return plan;
}

}  // namespace msb
