#include "tools/config/key_reference.h"

#include <memory>

#include <yaml-cpp/yaml.h>

#include "core/common/strict_number.h"
#include "tools/config/method_table.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/yaml_writer.h"

namespace msb {

namespace {

// Keys read outside the key tables (names, paths, lists, presets), as the reader takes them.
struct OutsideKey {
  const char* key;
  const char* accepts;
};
const OutsideKey kOutsideKeys[] = {
    {"name", "text (default: the file's name)"},
    {"suite", "a directory of published runs the run is for, e.g. results/table1 (docs/sweeps.md, \"Suites\")"},
    {"base", "a scenario file whose keys this file overrides (relative to this file)"},
    {"world", "a world name (msbench world list) or an MJCF file (.xml, relative to this file)"},
    {"held_out",
     "true: the world is drawn with the salt in $MSBENCH_WORLD_SALT or $MSBENCH_WORLD_SALT_FILE (docs/worlds.md, "
     "\"Held-out worlds\"; default false)"},
    {"start.position", "[x, y, z] in m (default: the world's start)"},
    {"start.yaw_deg", "a number (default: the world's start)"},
    {"exploration_box.min", "[x, y, z] in m (default: the world's box)"},
    {"exploration_box.max", "[x, y, z] in m, at least 2.5 x 2.5 x 1 m above min"},
    {"trajectory.limits",
     "a speed-set name (medium, fast) or a map of its keys; a name also sets trajectory.mrs.constraints "
     "to the MRS constraint set of that name (slow, medium, fast)"},
    {"trajectory.waypoints", "a list of [x, y, z] or {position, heading_deg} (msbench fly only)"},
    {"conditions.preset", "a conditions preset name (docs/conditions.md)"},
    {"frontend.preset", "a front-end preset name (docs/robustness.md)"},
    {"goals.entry", "\"package.module:chooser\" (a goal chooser in Python, docs/python.md)"},
    {"goals.path", "a directory put first on sys.path"},
    {"goals.params", "a map: the chooser factory's keyword arguments"},
    {"method.type", "a registered method (msbench methods)"},
    {"timing.map.per",
     "a map: a method counter, or counters joined by '*', to seconds per unit (>= 0; docs/compute.md)"},
    {"timing.plan.per", "the same for a planning step"},
    {"timing.replay", "a compute latency log of an earlier charged run (relative to this file; docs/compute.md)"},
    {"method.reference_code",
     "published or intended (MonoSpheres and the grid): `published` takes the authors' configuration before the "
     "keys named beside it (docs/deviations.md, \"The published configuration\"); MonoSpheres also takes a map "
     "of its switches"},
};

// True if `text` reads as a number (a number without a rule is an unchecked key).
bool isNumberText(const std::string& text) {
  double v;
  std::string why;
  return parseNumber(text, &v, &why);
}

// The text of a leaf: a scalar as written, a list in flow style.
std::string leafText(const YAML::Node& n) {
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e << YAML::Flow << n;
  return e.c_str();
}

// Appends a row per leaf of `node` (a map) under `prefix`.
void addLeaves(const YAML::Node& node, const std::string& prefix, const std::string& section,
               const MapWriter::KeyLog& log, std::vector<KeyRow>& rows) {
  for (const auto& kv : node) {
    const std::string key = prefix + kv.first.Scalar();
    const YAML::Node v = kv.second;
    if (v.IsMap() && v.size() > 0) {
      addLeaves(v, key + ".", section, log, rows);
      continue;
    }
    KeyRow row{section, key, leafText(v), "", "", true};
    if (auto it = log.find(key); it != log.end()) {
      row.accepts = it->second.accepts;
      row.refused_value = it->second.refused_value;
    } else if (v.IsMap()) {
      row.accepts = "a map (the factory's keyword arguments)";
      row.from_table = false;
    } else if (v.IsScalar() && (v.Scalar() == "true" || v.Scalar() == "false")) {
      row.accepts = "true or false";
    } else if (v.IsScalar() && !isNumberText(v.Scalar())) {
      row.accepts = "text";
    }
    rows.push_back(row);
  }
}

}  // namespace

std::vector<KeyRow> keyReference() {
  std::vector<KeyRow> rows;
  // The scenario without its method: flight sections, mission, video.
  auto log = std::make_shared<MapWriter::KeyLog>();
  ScenarioSpec spec;
  YAML::Node scenario = YAML::Load(effectiveScenarioYaml(spec, log));
  for (const char* k : {"name", "world", "method"}) scenario.remove(k);
  addLeaves(scenario, "", "scenario", *log, rows);
  for (const OutsideKey& o : kOutsideKeys) rows.push_back({"scenario", o.key, "", o.accepts, "", false});
  // Each method's section.
  for (const MethodRegistration& reg : methodRegistrations()) {
    auto mlog = std::make_shared<MapWriter::KeyLog>();
    YAML::Node method = YAML::Load(methodDefaultsYaml(reg.info.type, mlog))["method"];
    method.remove("type");
    addLeaves(method, "method.", "method.type: " + reg.info.type, *mlog, rows);
  }
  return rows;
}

std::string keyReferenceMarkdown() {
  std::string out =
      "# Configuration keys\n\n"
      "Every key a scenario may set, its default and the values it accepts, generated by `msbench keys`\n"
      "from the key tables (core/common/config_fields.h): each configuration struct names its keys once,\n"
      "and the same table validates, reads and writes them. A test keeps this file current\n"
      "(`KeyReference.TheDocsFileIsCurrent`; regenerate with `msbench keys > docs/keys.md`) and checks\n"
      "that every key refuses a value outside what it accepts. `--set KEY=VALUE` overrides one key;\n"
      "`msbench methods --type TYPE` prints a method's section as YAML. What the keys mean: the docs of\n"
      "their component (docs/architecture.md lists them).\n";
  std::string section;
  for (const KeyRow& r : keyReference()) {
    if (r.section != section) {
      section = r.section;
      out += "\n## " +
             (section == "scenario" ? std::string("Scenario (flight, sensors, front end, mission, video)")
                                    : "`" + section + "`") +
             "\n\n| key | default | accepts |\n| --- | --- | --- |\n";
    }
    out += "| `" + r.key + "` | " + (r.default_value.empty() ? "" : "`" + r.default_value + "`") + " | " +
           (r.accepts.empty() ? "(unchecked)" : r.accepts) + (r.from_table ? "" : " ¹") + " |\n";
  }
  out += "\n¹ read outside the key tables (a name, a path, a list or a preset): the reader checks it.\n";
  return out;
}

}  // namespace msb
