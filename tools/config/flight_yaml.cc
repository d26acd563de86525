#include "tools/config/flight_yaml.h"
#include "tools/config/field_keys.h"
#include "tools/config/flight_keys.h"

#include <yaml-cpp/yaml.h>

#include "core/common/types.h"
#include "tools/config/yaml_reader.h"
#include "tools/config/yaml_writer.h"

#include <cmath>
#include <filesystem>

namespace msb {
namespace {

namespace fs = std::filesystem;

// Waypoints: each either [x, y, z] or {position: [x, y, z], heading_deg: h}.
std::vector<Waypoint> readWaypoints(const YAML::Node& n, const std::string& key) {
  if (!n.IsSequence()) throw ConfigError(key, "expected a list of waypoints");
  std::vector<Waypoint> out;
  size_t i = 0;
  for (const YAML::Node& item : n) {  // iterators: indexing a yaml-cpp sequence is linear
    const std::string k = key + "[" + std::to_string(i++) + "]";
    Waypoint w;
    if (item.IsSequence()) {
      // [x, y, z] (no wrapping node: assigning nodes merges yaml-cpp's memory, quadratic in lists)
      MapReader(YAML::Node(YAML::NodeType::Map), "").value(item, k, w.position_m);
    } else {
      MapReader r(item, k + ".");
      if (!r.field("position", w.position_m)) throw ConfigError(k + ".position", "is required");
      double h;
      if (r.field("heading_deg", h)) w.heading_rad = h * kDeg;
      r.finish();
    }
    out.push_back(w);
  }
  return out;
}

// The writer's waypoints: [x, y, z] or {position, heading_deg}.
YAML::Node waypointsNode(const std::vector<Waypoint>& waypoints) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (const Waypoint& w : waypoints) {
    if (!w.heading_rad) {
      list.push_back(MapWriter::encode(w.position_m));
      continue;
    }
    MapWriter m{YAML::Node(YAML::NodeType::Map)};
    m.field("position", w.position_m);
    m.field("heading_deg", exactDegrees(*w.heading_rad));
    list.push_back(m.node());
  }
  return list;
}

// limits: a preset name or a map; waypoints; tracker gains. The writer writes the limits as a map.
template <class Keys>
void trajectoryKeys(Keys r, FlightSpec& s) {
  auto& t = s.trajectory;
  FieldKeys<Keys> v(r);
  v.custom("limits", [&](Keys& k) {
    if constexpr (Keys::kReading) {
      if (!k.has("limits")) return;
      const YAML::Node n = k.raw("limits");
      if (!n.IsScalar()) {
        MapReader m(n, k.keyName("limits") + ".");
        fieldKeys(m, t.limits);
        m.finish();
        return;
      }
      try {
        t.limits = TrajectoryLimits::preset(n.Scalar());
      } catch (const ConfigError& e) {
        throw ConfigError(k.keyName("limits"), e.issues().front().reason);
      }
      // The MRS generator's constraint set of the same name (its keys under `mrs` override it).
      if (const auto c = MrsConstraints::preset(n.Scalar())) t.mrs.constraints = *c;
    } else {
      auto w = k.sub("limits");
      fieldKeys(w, t.limits);
    }
  });
  if constexpr (Keys::kReading) {
    if (r.has("waypoints")) s.waypoints = readWaypoints(r.raw("waypoints"), r.keyName("waypoints"));
  } else {
    if (!s.waypoints.empty()) r.node()["waypoints"] = waypointsNode(s.waypoints);
  }
  TrajectoryTrackerConfig::fields(t, v);
  r.finish();
}

// `preset: NAME` of a section (read only: the writer writes every field instead): the named
// preset's values, which the section's other keys then override; an unknown name lists the known.
template <class Keys, class Config, class Lookup>
void presetKey(Keys& r, Config& c, Lookup lookup, const std::vector<std::string>& known) {
  std::string preset;
  if (!Keys::kReading || !r.field("preset", preset)) return;
  const std::optional<Config> p = lookup(preset);
  if (!p) {
    std::string names;
    for (const auto& n : known) names += (names.empty() ? "" : ", ") + n;
    throw ConfigError(r.keyName("preset"), "unknown preset '" + preset + "' (known: " + names + ")");
  }
  c = *p;
}

// conditions: {preset: NAME, <field>: value, ...}: a named preset, then overrides.
template <class Keys>
void conditionsKeys(Keys r, RenderConditions& c) {
  presetKey(r, c, conditionsPreset, conditionsPresetNames());
  fieldKeys(r, c);
  r.finish();
  ConfigChecker checker(r.keyName("") + ".");
  c.validate(checker);
  if (!checker.issues().empty()) throw ConfigError(checker.issues());
}

// frontend: {preset: NAME, <axis>: value, ...}: a named preset, then overrides.
template <class Keys>
void frontendKeys(Keys r, FrontendDegradationConfig& c) {
  presetKey(r, c, frontendPreset, frontendPresetNames());
  fieldKeys(r, c);
  r.finish();
}

// The keys of a flight shared by reading and writing; `world` and `start` are the callers'.
template <class Keys>
void flightSectionKeys(Keys& r, FlightSpec& s) {
  FieldKeys<Keys> v(r);
  // Sections that also take a preset name (or hold the waypoints): read here, their keys by table.
  v.custom("trajectory", [&](Keys& k) {
    if (k.has("trajectory")) trajectoryKeys(k.sub("trajectory"), s);
  });
  v.custom("conditions", [&](Keys& k) {
    if (k.has("conditions")) conditionsKeys(k.sub("conditions"), s.render.conditions);
  });
  v.custom("frontend", [&](Keys& k) {
    if (k.has("frontend")) frontendKeys(k.sub("frontend"), s.frontend);
  });
  FlightSpec::fields(s, v);
}

}  // namespace

void readFlightKeys(MapReader& r, const fs::path& dir, FlightSpec& s) {
  std::string world;
  // A value ending in .xml is an MJCF file relative to this file; anything else a world name.
  if (r.read("world", world)) {
    if (fs::path(world).extension() == ".xml")
      s.world_path = (dir / world).lexically_normal().string();
    else
      s.world_name = world;
  }
  r.read("held_out", s.held_out);
  if (r.has("start")) {
    MapReader st = r.sub("start");
    st.read("position", s.start_position_m);
    double yaw_deg;
    if (st.read("yaw_deg", yaw_deg)) s.start_yaw_rad = yaw_deg * kDeg;
    st.finish();
  }
  flightSectionKeys(r, s);
}

void writeFlightKeys(MapWriter& w, const FlightSpec& spec, bool with_start) {
  FlightSpec s = spec;
  // The world as it was named: a world name, else the MJCF file (absolute).
  w.field("world", s.world_name.empty() ? s.world_path : s.world_name);
  if (s.held_out) w.field("held_out", true);  // only when set: every other run's text as it was
  if (with_start) {
    MapWriter st = w.sub("start");
    st.field("position", s.start_position_m);
    st.field("yaw_deg", exactDegrees(s.start_yaw_rad));
  }
  flightSectionKeys(w, s);
}

FlightSpec loadFlightSpec(const std::string& path) {
  const fs::path dir = fs::absolute(path).parent_path();
  return parseConfigFile<FlightSpec>(path, [&](MapReader& r, FlightSpec& s) {
    readFlightKeys(r, dir, s);
    r.finish();
    if (s.waypoints.empty()) throw ConfigError("trajectory.waypoints", "needs at least one waypoint");
  });
}

}  // namespace msb
