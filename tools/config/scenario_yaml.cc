#include "tools/config/scenario_yaml.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/common/config_check.h"
#include "core/common/rng.h"
#include "tools/config/field_keys.h"
#include "tools/config/flight_keys.h"
#include "tools/config/flight_yaml.h"
#include "tools/config/method_table.h"
#include "tools/config/yaml_reader.h"
#include "tools/config/yaml_writer.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

// b's keys over a's, recursively for maps; anything else in b replaces a's value.
YAML::Node merge(const YAML::Node& a, const YAML::Node& b) {
  if (!a.IsMap() || !b.IsMap()) return YAML::Clone(b);
  YAML::Node out = YAML::Clone(a);
  for (const auto& kv : b) {
    if (!kv.first.IsScalar()) throw FileConfigError("a scenario map has a non-text key");
    const std::string k = kv.first.Scalar();
    out[k] = out[k] ? merge(out[k], kv.second) : YAML::Clone(kv.second);
  }
  return out;
}

// How many files a scenario's `base:` chain may hold (the scenario itself included).
constexpr size_t kMaxBaseChain = 64;

// "a.yaml -> b.yaml -> c.yaml" (the chain so far, for messages).
std::string chainText(const std::vector<fs::path>& chain) {
  std::string s;
  for (const auto& f : chain) s += (s.empty() ? "" : " -> ") + f.filename().string();
  return s;
}

// One file of a chain, read: a map, its MJCF world path made relative to the file itself.
YAML::Node loadChainFile(const fs::path& file, const fs::path& dir) {
  YAML::Node node = loadYamlFile(file.string());
  if (!node.IsMap()) throw FileConfigError(file.string() + ": expected a map of keys at the top level");
  if (node["world"] && node["world"].IsScalar() && fs::path(node["world"].Scalar()).extension() == ".xml")
    node["world"] = (dir / node["world"].Scalar()).lexically_normal().string();
  return node;
}

}  // namespace

fs::path scenarioFileNamed(const fs::path& dir, const std::string& name) {
  const fs::path beside = dir / name;
  const bool bare = !name.empty() && name.find('/') == std::string::npos && fs::path(name).extension().empty();
  std::error_code ec;
  if (bare && !fs::is_regular_file(beside, ec)) return fs::path(MSB_MISSIONS_DIR) / (name + ".yaml");
  return beside;
}

namespace {

// The file a node's `base:` names, checked (a regular file that exists).
fs::path baseOf(const YAML::Node& node, const fs::path& file, const fs::path& dir) {
  if (!node["base"].IsScalar()) throw FileConfigError(file.string() + ": key 'base': expected a file path");
  if (node["base"].Scalar().find('\0') != std::string::npos)
    throw FileConfigError(file.string() + ": key 'base': the file name contains a NUL character");
  const fs::path base = scenarioFileNamed(dir, node["base"].Scalar());
  std::error_code ec;
  const auto st = fs::status(base, ec);
  if (ec && ec != std::errc::no_such_file_or_directory)
    throw FileConfigError(file.string() + ": key 'base': " + base.string() + ": " + ec.message());
  if (!fs::exists(st)) throw FileConfigError(file.string() + ": key 'base': file not found: " + base.string());
  if (!fs::is_regular_file(st))
    throw FileConfigError(file.string() + ": key 'base': not a regular file: " + base.string());
  return base;
}

// The scenario file and its `base:` chain, read iteratively (at most kMaxBaseChain files, no
// file twice), merged from the last base outwards: each file's keys override its base's.
YAML::Node loadChain(const fs::path& file, std::vector<fs::path>& chain, std::vector<YAML::Node>& nodes) {
  fs::path next = file;
  while (true) {
    const fs::path abs = fs::weakly_canonical(fs::absolute(next));
    if (std::find(chain.begin(), chain.end(), abs) != chain.end())
      throw FileConfigError(next.string() + ": key 'base': circular base files (" + chainText(chain) + " -> " +
                            abs.filename().string() + ")");
    chain.push_back(abs);
    if (chain.size() > kMaxBaseChain)
      throw FileConfigError(file.string() + ": key 'base': a chain of more than " + std::to_string(kMaxBaseChain) +
                            " files (" + chainText({chain.begin(), chain.begin() + 3}) + " -> ... -> " +
                            abs.filename().string() + ")");
    nodes.push_back(loadChainFile(next, abs.parent_path()));
    if (!nodes.back()["base"]) break;
    next = baseOf(nodes.back(), next, abs.parent_path());
    nodes.back().remove("base");
  }
  // A copy: yaml-cpp nodes are handles, and the overrides merged (or --set) into the tree must
  // not edit the last base's own node, which issueLabel reads to find who gave a key.
  YAML::Node merged = YAML::Clone(nodes.back());
  for (size_t k = nodes.size() - 1; k-- > 0;) merged = merge(merged, nodes[k]);
  return merged;
}

// The node at the dotted key path `key` of `node` ("a.b[2].c": the list index and what follows it
// belong to the list's key), or an undefined node. Read through const nodes and initialised
// copies: assigning to a yaml-cpp handle would edit the tree.
YAML::Node nodeAt(const YAML::Node& node, const std::string& key) {
  const std::string path = key.substr(0, key.find('['));
  const size_t dot = path.find('.');
  if (!node.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  const YAML::Node child = node[path.substr(0, dot)];
  // A missing key gives yaml-cpp's invalid node, whose type throws: an undefined one instead.
  if (!child) return YAML::Node(YAML::NodeType::Undefined);
  if (dot == std::string::npos) return child;
  return nodeAt(child, path.substr(dot + 1));
}

/// True if `node` gives the dotted key path `key`.
bool givesKey(const YAML::Node& node, const std::string& key) { return nodeAt(node, key).IsDefined(); }

// The file of the chain a configuration issue belongs to: the nearest file to the scenario that
// gives its key (a base's key is reported against the base, naming the scenario it serves).
std::string issueLabel(const ConfigError& e, const std::vector<fs::path>& chain, const std::vector<YAML::Node>& nodes,
                       const std::vector<std::string>& sets, const std::string& path, const std::string& label) {
  if (e.issues().empty()) return label;
  // A value from the command line (--set, --seed) or a sweep's `set:` is named as such: no file
  // of the chain holds it. The last --set of a key is the one that counts.
  const std::string& key = e.issues().front().key;
  for (auto it = sets.rbegin(); it != sets.rend(); ++it) {
    const std::string set_key = it->substr(0, it->find('='));
    if (key == set_key || key.rfind(set_key + ".", 0) == 0 || key.rfind(set_key + "[", 0) == 0)
      return path + " (with --set " + set_key + ")";
  }
  for (size_t k = 0; k < nodes.size() && k < chain.size(); ++k)
    if (givesKey(nodes[k], e.issues().front().key))
      return k == 0 ? label : chain[k].string() + " (a base of " + label + ")";
  return label;
}

// Applies "a.b.c=value" to the tree.
void applySet(YAML::Node& root, const std::string& kv) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0) throw UsageError("--set: expected KEY=VALUE, got '" + kv + "'");
  const std::string path = kv.substr(0, eq), text = kv.substr(eq + 1);
  YAML::Node value;
  try {
    value = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw UsageError("--set " + path + ": value '" + text + "' is not valid YAML: " + e.msg);
  }
  rejectDuplicateKeys(value, "--set " + path);
  // KEY is dot-separated names of letters, digits and '_' ("a.b.c"): no empty component
  // (".a", "a..b", "a.") and nothing else, so that what is set is what was meant.
  std::vector<std::string> keys(1);
  for (const char ch : path) {
    if (ch == '.') {
      if (keys.back().empty()) break;
      keys.emplace_back();
    } else if (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_') {
      keys.back() += ch;
    } else {
      throw UsageError("--set: key '" + path + "' may hold only letters, digits, '_' and '.' between names");
    }
  }
  for (const auto& k : keys)
    if (k.empty()) throw UsageError("--set: empty key component in '" + path + "' (KEY is a.b.c)");
  // Walk with explicit copies: yaml-cpp nodes are handles, so assignment through them edits the tree.
  std::vector<YAML::Node> nodes = {root};
  for (size_t i = 0; i + 1 < keys.size(); ++i) {
    YAML::Node cur = nodes.back();
    if (!cur[keys[i]]) cur[keys[i]] = YAML::Node(YAML::NodeType::Map);
    YAML::Node next = cur[keys[i]];
    // A key under a preset name (trajectory.limits: medium): the preset expands to its map first.
    if (next.IsScalar() && i == 1 && keys[0] == "trajectory" && keys[1] == "limits") {
      TrajectoryLimits limits;
      try {
        limits = TrajectoryLimits::preset(next.Scalar());
      } catch (const ConfigError& e) {
        throw UsageError("--set " + path + ": trajectory.limits is '" + next.Scalar() + "', " +
                         e.issues().front().reason);
      }
      MapWriter w{YAML::Node(YAML::NodeType::Map)};
      fieldKeys(w, limits);
      cur[keys[i]] = w.node();
      next = cur[keys[i]];
    }
    if (!next.IsMap())
      throw UsageError("--set " + path + ": '" + keys[i] + "' is '" + (next.IsScalar() ? next.Scalar() : "a list") +
                       "', not a map: set '" + keys[i] + "' itself, or give it as a map first");
    nodes.push_back(next);
  }
  nodes.back()[keys.back()] = value;
}

// `--set S.preset=NAME` over a file whose section S sets its own values: those would silently
// override the preset the user asked for; refused unless each is also given by --set.
void checkPresetSet(const YAML::Node& files, const std::string& kv, const std::vector<std::string>& sets,
                    const std::string& path) {
  const std::string key = kv.substr(0, kv.find('='));
  const std::string suffix = ".preset";
  if (key.size() <= suffix.size() || key.compare(key.size() - suffix.size(), suffix.size(), suffix) != 0) return;
  const std::string section = key.substr(0, key.size() - suffix.size());
  const YAML::Node node = nodeAt(files, section);
  if (!node.IsMap()) return;
  std::string kept;
  for (const auto& field : node) {
    const std::string name = field.first.Scalar();
    const bool by_set = std::any_of(sets.begin(), sets.end(),
                                    [&](const std::string& s) { return s.rfind(section + "." + name + "=", 0) == 0; });
    if (name != "preset" && !by_set) kept += (kept.empty() ? "" : ", ") + section + "." + name;
  }
  if (!kept.empty())
    throw UsageError("--set " + key + ": " + path + " also sets " + kept +
                     ", which would override the preset's values; give them with --set too, or remove them");
}

// The mission and video sections: their tables.
template <class Keys, class Section>
void sectionKeys(Keys r, Section& section) {
  fieldKeys(r, section);
  r.finish();
}

// The `goals` section: entry, path, and params (a map, kept as YAML text for the factory).
PythonMethodConfig readGoals(MapReader g) {
  PythonMethodConfig c;
  if (!g.read("entry", c.entry)) throw ConfigError(g.keyName("entry"), "is required (\"module:chooser\")");
  g.read("path", c.path);
  g.read("params", c.params);
  g.finish();
  return c;
}

// A stage's cost model: base_s from its table, `per` as a map of term → seconds per unit.
template <class Keys>
void stageModelKeys(Keys r, StageCostModel& m) {
  fieldKeys(r, m);
  if constexpr (Keys::kReading) {
    if (r.has("per")) {
      const YAML::Node n = r.raw("per");
      if (!n.IsMap()) throw ConfigError(r.keyName("per"), "expected a map of term: seconds per unit");
      MapReader p(n, r.keyName("per") + ".");
      for (const auto& kv : n) {
        const std::string term = kv.first.Scalar();
        p.read(term, m.per[term]);
      }
    }
  } else {
    MapWriter p = r.sub("per");
    for (const auto& [term, coef] : m.per) p.field(term, coef);
  }
  r.finish();
}

// The `timing` section (docs/compute.md): the profile named by compute_model first, then the
// keys named beside it; `replay` is read as a path relative to the file.
void readTiming(MapReader t, const fs::path& dir, ComputeTiming& timing) {
  t.read("compute", timing.compute);
  t.read("compute_model", timing.compute_model);
  timing.applyProfile();
  if (t.has("map")) stageModelKeys(t.sub("map"), timing.map);
  if (t.has("plan")) stageModelKeys(t.sub("plan"), timing.plan);
  if (t.read("replay", timing.replay) && !timing.replay.empty() && fs::path(timing.replay).is_relative())
    timing.replay = (dir / timing.replay).lexically_normal().string();
  t.finish();
}

void writeTiming(MapWriter t, const ComputeTiming& timing) {
  ComputeTiming keys = timing;
  if (timing.compute == ComputeMode::kModelled || t.keepsLog()) {
    fieldKeys(t, keys);  // compute, compute_model and each stage's base_s, with their rules
    if (!timing.map.per.empty()) stageModelKeys(t.sub("map"), keys.map);
    if (!timing.plan.per.empty()) stageModelKeys(t.sub("plan"), keys.plan);
  } else {
    t.field("compute", timing.compute);
  }
  if (!timing.replay.empty()) t.field("replay", timing.replay);
}

// True if the method runs as the authors' code (`method.reference_code: published`, by name or
// as a map with `published: true`).
bool runsPublished(const YAML::Node& method) {
  const YAML::Node rc = method["reference_code"];
  if (!rc) return false;
  if (rc.IsScalar()) return rc.Scalar() == "published";
  return rc.IsMap() && rc["published"] && rc["published"].as<bool>(false);
}

void readScenario(MapReader& r, const fs::path& dir, ScenarioSpec& s) {
  r.read("name", s.name);
  r.read("suite", s.suite);
  s.start_from_world = !r.has("start");
  readFlightKeys(r, dir, s.flight);
  if (r.has("method")) {
    // A published method flies its paths through the authors' MRS trajectory generator unless
    // the scenario names the generator (docs/deviations.md, "Paths as the MRS generator flies them").
    const bool names_generator = r.has("trajectory") && r.raw("trajectory")["generator"];
    if (runsPublished(r.raw("method")) && !names_generator) s.flight.trajectory.generator = "mrs";
    s.method = readMethod(r.sub("method"));
  }
  if (r.has("exploration_box")) {
    MapReader b = r.sub("exploration_box");
    Aabb box;
    if (!b.read("min", box.min)) throw ConfigError(b.keyName("min"), "is required");
    if (!b.read("max", box.max)) throw ConfigError(b.keyName("max"), "is required");
    b.finish();
    s.exploration_box = box;
  }
  if (r.has("mission")) sectionKeys(r.sub("mission"), s.mission);
  if (r.has("video")) sectionKeys(r.sub("video"), s.video);
  if (r.has("goals")) s.goals = readGoals(r.sub("goals"));
  if (r.has("timing")) readTiming(r.sub("timing"), dir, s.timing);
  r.finish();
}

YAML::Node loadScenarioTree(const std::string& path, const std::vector<std::string>& sets, std::vector<fs::path>& chain,
                            std::vector<YAML::Node>& nodes) {
  YAML::Node tree = loadChain(path, chain, nodes);
  for (const auto& kv : sets) checkPresetSet(tree, kv, sets, path);
  for (const auto& kv : sets) applySet(tree, kv);
  return tree;
}

}  // namespace

ScenarioSpec loadScenario(const std::string& path, const std::vector<std::string>& sets) {
  std::vector<fs::path> chain;
  std::vector<YAML::Node> nodes;
  const YAML::Node tree = loadScenarioTree(path, sets, chain, nodes);
  const fs::path dir = fs::absolute(path).parent_path();
  const std::string label = sets.empty() ? path : path + " (with --set overrides)";
  // The defaults are ScenarioSpec's own (missionFlightDefaults()); the file overrides them. A
  // key's error names the file of the chain that gave the key.
  ScenarioSpec spec = parseConfigNode<ScenarioSpec>(label, tree, [&](MapReader& r, ScenarioSpec& s) {
    try {
      readScenario(r, dir, s);
      checkValid(s);
    } catch (const ConfigError& e) {
      throw FileConfigError(issueLabel(e, chain, nodes, sets, path, label) + ": " + e.what());
    }
  });
  if (spec.name.empty()) spec.name = fs::path(path).stem().string();
  for (const auto& f : chain) spec.input_files.push_back(f.string());
  // A Python method's directory as an absolute path: config.yaml, written elsewhere, replays it.
  if (spec.method.type == kPythonMethodType) {
    auto& c = std::any_cast<PythonMethodConfig&>(spec.method.config);
    if (!c.path.empty() && fs::path(c.path).is_relative()) c.path = (dir / c.path).lexically_normal().string();
  }
  if (spec.goals && !spec.goals->path.empty() && fs::path(spec.goals->path).is_relative())
    spec.goals->path = (dir / spec.goals->path).lexically_normal().string();
  spec.fixed_settings_hash = fixedSettingsHash(spec);
  spec.replay_settings_hash = replaySettingsHash(spec);
  // Names and paths end up in metrics.json (JSON is UTF-8): checked now, not after the mission.
  if (!isValidUtf8(path)) throw FileConfigError(path + ": the file name is not valid UTF-8");
  if (!isValidUtf8(spec.name)) throw FileConfigError(label + ": key 'name': not valid UTF-8");
  if (!isValidUtf8(spec.suite)) throw FileConfigError(label + ": key 'suite': not valid UTF-8");
  return spec;
}

SphereMapConfig loadMapOverrides(const std::vector<std::string>& sets) {
  // The scenario's spelling without `method.`: switches.ovde / switches.dbof, map.KEY.
  YAML::Node tree(YAML::NodeType::Map);
  for (const auto& kv : sets) {
    if (kv.rfind("map.ovde=", 0) == 0 || kv.rfind("map.dbof=", 0) == 0)
      throw UsageError("--set " + kv.substr(0, kv.find('=')) + ": the switch is spelt switches." + kv.substr(4, 4) +
                       " (method.switches." + kv.substr(4, 4) + " in a scenario)");
    if (kv.rfind("map.", 0) != 0 && kv.rfind("switches.", 0) != 0)
      throw UsageError("--set: expected map.KEY=VALUE or switches.ovde|dbof=VALUE, got '" + kv + "'");
    applySet(tree, kv);
  }
  return parseConfigNode<SphereMapConfig>("--set", tree, [](MapReader& r, SphereMapConfig& c) {
    if (r.has("switches")) {
      MapReader w = r.sub("switches");
      w.read("ovde", c.ovde);
      w.read("dbof", c.dbof);
      w.finish();
    }
    if (r.has("map")) {
      MapReader m = r.sub("map");
      readSphereMapKeys(m, c);
      m.finish();
    }
    r.finish();
  });
}

std::string effectiveScenarioYaml(const ScenarioSpec& spec, std::shared_ptr<MapWriter::KeyLog> log) {
  MapWriter w{YAML::Node(YAML::NodeType::Map), std::move(log)};
  w.field("name", spec.name);
  if (!spec.suite.empty()) w.field("suite", spec.suite);  // only when set: older runs' text stays as it was
  writeFlightKeys(w, spec.flight, !spec.start_from_world);
  MapWriter m = w.sub("method");
  writeMethod(m, spec.method);
  if (spec.exploration_box) {
    MapWriter b = w.sub("exploration_box");
    b.field("min", spec.exploration_box->min);
    b.field("max", spec.exploration_box->max);
  }
  MissionSettings mission = spec.mission;
  sectionKeys(w.sub("mission"), mission);
  VideoSettings video = spec.video;
  sectionKeys(w.sub("video"), video);
  // Only when not free (a free run's text stays as it was), and always in the key reference.
  if (!spec.timing.free() || w.keepsLog()) writeTiming(w.sub("timing"), spec.timing);
  if (spec.goals) {
    MapWriter g = w.sub("goals");
    g.field("entry", spec.goals->entry);
    g.field("path", spec.goals->path);
    g.field("params", spec.goals->params);
  }
  return yamlText(w.node());
}

namespace {

// The effective YAML without the top-level keys `drop` and what never changes a flight: the
// replay log named, the progress line, the map file.
std::string effectiveYamlWithout(const ScenarioSpec& spec, std::initializer_list<const char*> drop) {
  YAML::Node tree = YAML::Load(effectiveScenarioYaml(spec));
  for (const char* key : drop) tree.remove(key);
  if (tree["timing"]) tree["timing"].remove("replay");
  if (tree["mission"]) {
    tree["mission"].remove("progress");
    tree["mission"].remove("write_map_ply");
  }
  return yamlText(tree);
}

// FNV-1a 64 of `text`, 16 hex digits.
std::string hexFnv(const std::string& text) {
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(fnv1a64(text.data(), text.size())));
  return hex;
}

}  // namespace

std::string fixedSettingsYaml(const ScenarioSpec& spec) {
  return effectiveYamlWithout(spec, {"name", "suite", "seed", "method", "goals", "video"});
}

std::string fixedSettingsHash(const ScenarioSpec& spec) { return hexFnv(fixedSettingsYaml(spec)); }

std::string replaySettingsHash(const ScenarioSpec& spec) {
  return hexFnv(effectiveYamlWithout(spec, {"name", "suite", "seed", "video"}));
}

}  // namespace msb
