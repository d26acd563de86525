#include "tools/msbench/scenario_yaml.h"

#include <filesystem>
#include <sstream>

#include "tools/msbench/cli_args.h"
#include "tools/msbench/yaml_config.h"
#include "tools/msbench/yaml_reader.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

// b's keys over a's, recursively for maps; anything else in b replaces a's value.
YAML::Node merge(const YAML::Node& a, const YAML::Node& b) {
  if (!a.IsMap() || !b.IsMap()) return YAML::Clone(b);
  YAML::Node out = YAML::Clone(a);
  for (const auto& kv : b) {
    const std::string k = kv.first.as<std::string>();
    out[k] = out[k] ? merge(out[k], kv.second) : YAML::Clone(kv.second);
  }
  return out;
}

YAML::Node loadChain(const fs::path& file, std::vector<fs::path>& chain) {
  const fs::path abs = fs::weakly_canonical(fs::absolute(file));
  for (const auto& f : chain)
    if (f == abs) throw FileConfigError(file.string() + ": key 'base': circular base files");
  chain.push_back(abs);
  YAML::Node node = loadYamlFile(file.string());
  if (!node.IsMap()) throw FileConfigError(file.string() + ": expected a map of keys at the top level");
  const fs::path dir = abs.parent_path();
  // An MJCF world path is relative to the file that names it.
  if (node["world"] && node["world"].IsScalar() && fs::path(node["world"].Scalar()).extension() == ".xml")
    node["world"] = (dir / node["world"].Scalar()).lexically_normal().string();
  if (!node["base"]) return node;
  if (!node["base"].IsScalar()) throw FileConfigError(file.string() + ": key 'base': expected a file path");
  const fs::path base = dir / node["base"].Scalar();
  if (!fs::is_regular_file(base))
    throw FileConfigError(file.string() + ": key 'base': file not found: " + base.string());
  YAML::Node base_tree = loadChain(base, chain);
  node.remove("base");
  return merge(base_tree, node);
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
  std::vector<std::string> keys;
  std::stringstream ss(path);
  for (std::string k; std::getline(ss, k, '.');) {
    if (k.empty()) throw UsageError("--set: empty key component in '" + path + "'");
    keys.push_back(k);
  }
  // Walk with explicit copies: yaml-cpp nodes are handles, so assignment through them edits the tree.
  std::vector<YAML::Node> nodes = {root};
  for (size_t i = 0; i + 1 < keys.size(); ++i) {
    YAML::Node cur = nodes.back();
    if (!cur[keys[i]]) cur[keys[i]] = YAML::Node(YAML::NodeType::Map);
    YAML::Node next = cur[keys[i]];
    if (!next.IsMap()) throw UsageError("--set " + path + ": '" + keys[i] + "' is not a map");
    nodes.push_back(next);
  }
  nodes.back()[keys.back()] = value;
}

void readOvde(MapReader r, OpenAreaDepthConfig& c) {
  r.read("grid", c.grid);
  r.read("central_fraction", c.central_fraction);
  r.read("range_m", c.range_m);
  r.read("max_poses", c.max_poses);
  r.read("min_translation_m", c.min_translation_m);
  r.read("min_rotation_deg", c.min_rotation_deg);
  r.read("min_parallax_rad", c.min_parallax_rad);
  r.finish();
}

// Mapper parameters (the caller finishes the reader).
void readSphereMapKeys(MapReader& r, SphereMapConfig& c) {
  if (r.has("ovde_params")) readOvde(r.sub("ovde_params"), c.ovde_params);
  r.read("dbof_alpha", c.dbof_alpha);
  r.read("r_max_m", c.r_max_m);
  r.read("r_min_m", c.r_min_m);
  r.read("new_sphere_samples", c.new_sphere_samples);
  r.read("max_sample_range_m", c.max_sample_range_m);
  r.read("max_point_range_m", c.max_point_range_m);
  r.read("obstacle_spacing_m", c.obstacle_spacing_m);
  r.read("sparsify_factor", c.sparsify_factor);
  r.read("min_points", c.min_points);
  r.read("max_view_angle_deg", c.max_view_angle_deg);
  r.read("frontier_surface_samples", c.frontier_surface_samples);
  r.read("frontier_shell_samples", c.frontier_shell_samples);
  r.read("frontier_jitter_m", c.frontier_jitter_m);
  r.read("shell_min_m", c.shell_min_m);
  r.read("shell_max_m", c.shell_max_m);
  r.read("frontier_spacing_m", c.frontier_spacing_m);
  r.read("frontier_obstacle_gap_m", c.frontier_obstacle_gap_m);
  r.read("frontier_range_m", c.frontier_range_m);
  r.read("frontier_min_normal_z", c.frontier_min_normal_z);
  r.read("frontier_min_balance", c.frontier_min_balance);
}

// Mapper parameters of a scenario; the switches ovde/dbof live under `switches`.
void readSphereMap(MapReader r, SphereMapConfig& c) {
  readSphereMapKeys(r, c);
  r.finish();
}

void readViewpoints(MapReader r, ViewpointConfig& c) {
  r.read("candidates", c.candidates);
  r.read("frontier_range_m", c.frontier_range_m);
  r.read("fov_half_angle_deg", c.fov_half_angle_deg);
  r.read("min_value", c.min_value);
  r.read("relaxed_min_value", c.relaxed_min_value);
  r.read("block_distance_m", c.block_distance_m);
  r.read("block_angle_deg", c.block_angle_deg);
  r.read("blacklist_radius_m", c.blacklist_radius_m);
  r.read("blacklist_duration_s", c.blacklist_duration_s);
  r.finish();
}

void readSafety(MapReader r, SafetyCostConfig& c) {
  r.read("weight", c.weight);
  r.read("r_min_m", c.r_min_m);
  r.read("r_safe_m", c.r_safe_m);
  r.finish();
}

// Planner parameters; the switches fff/vpb live under `switches`.
void readPlanner(MapReader r, MonoSpheresPlannerConfig& c) {
  if (r.has("viewpoints")) readViewpoints(r.sub("viewpoints"), c.viewpoints);
  if (r.has("safety")) readSafety(r.sub("safety"), c.safety);
  r.read("fff_turn_rate_rad_per_m", c.fff_turn_rate_rad_per_m);
  r.read("align_before_route_deg", c.align_before_route_deg);
  r.read("start_max_outside_m", c.start_max_outside_m);
  r.read("goal_max_outside_m", c.goal_max_outside_m);
  r.read("local_radius_m", c.local_radius_m);
  r.read("local_misses_before_global", c.local_misses_before_global);
  r.read("max_goal_candidates", c.max_goal_candidates);
  r.read("carrot_distance_m", c.carrot_distance_m);
  r.read("replan_period_s", c.replan_period_s);
  r.read("check_ahead_m", c.check_ahead_m);
  r.read("check_clearance_m", c.check_clearance_m);
  r.read("max_blocked_steps", c.max_blocked_steps);
  r.read("max_route_repairs", c.max_route_repairs);
  r.read("blocked_edge_timeout_s", c.blocked_edge_timeout_s);
  r.read("bridge_below_reachable", c.bridge_below_reachable);
  r.read("bridge_range_m", c.bridge_range_m);
  r.read("bridge_after_idle_s", c.bridge_after_idle_s);
  r.read("shortcut_depth_m", c.shortcut_depth_m);
  r.read("reach_distance_m", c.reach_distance_m);
  r.read("reach_angle_deg", c.reach_angle_deg);
  r.read("no_progress_timeout_s", c.no_progress_timeout_s);
  r.read("takeoff_altitude_m", c.takeoff_altitude_m);
  r.read("start_forward_m", c.start_forward_m);
  r.read("idle_turn_deg", c.idle_turn_deg);
  r.read("idle_turn_period_s", c.idle_turn_period_s);
  r.finish();
}

void readMission(MapReader r, MissionSettings& m) {
  r.read("map_rate_hz", m.map_rate_hz);
  r.read("planning_rate_hz", m.planning_rate_hz);
  r.read("metric_rate_hz", m.metric_rate_hz);
  r.read("trajectory_rate_hz", m.trajectory_rate_hz);
  r.read("write_map_ply", m.write_map_ply);
  r.read("progress", m.progress);
  r.finish();
}

void readScenario(MapReader& r, const fs::path& dir, ScenarioSpec& s) {
  r.read("name", s.name);
  s.start_from_world = !r.has("start");
  readFlightKeys(r, dir, s.flight);
  if (r.has("method")) {
    MapReader m = r.sub("method");
    m.read("type", s.method_type);
    if (m.has("map")) readSphereMap(m.sub("map"), s.monospheres.map);
    if (m.has("planner")) readPlanner(m.sub("planner"), s.monospheres.planner);
    m.finish();
  }
  if (r.has("switches")) {
    MapReader w = r.sub("switches");
    w.read("ovde", s.switches.ovde);
    w.read("dbof", s.switches.dbof);
    w.read("fff", s.switches.fff);
    w.read("vpb", s.switches.vpb);
    w.finish();
  }
  if (r.has("exploration_box")) {
    MapReader b = r.sub("exploration_box");
    Aabb box;
    if (!b.read("min", box.min)) throw ConfigError(b.keyName("min"), "is required");
    if (!b.read("max", box.max)) throw ConfigError(b.keyName("max"), "is required");
    b.finish();
    s.exploration_box = box;
  }
  if (r.has("mission")) readMission(r.sub("mission"), s.mission);
  r.finish();
  // The switches land in the method's configs.
  s.monospheres.map.ovde = s.switches.ovde;
  s.monospheres.map.dbof = s.switches.dbof;
  s.monospheres.planner.fff = s.switches.fff;
  s.monospheres.planner.viewpoints.vpb = s.switches.vpb;
}

}  // namespace

YAML::Node loadScenarioTree(const std::string& path, const std::vector<std::string>& sets) {
  std::vector<fs::path> chain;
  YAML::Node tree = loadChain(path, chain);
  for (const auto& kv : sets) applySet(tree, kv);
  return tree;
}

ScenarioSpec loadScenario(const std::string& path, const std::vector<std::string>& sets) {
  const YAML::Node tree = loadScenarioTree(path, sets);
  const fs::path dir = fs::absolute(path).parent_path();
  const std::string label = sets.empty() ? path : path + " (with --set overrides)";
  ScenarioSpec spec = parseConfigNode<ScenarioSpec>(label, tree, [&](MapReader& r, ScenarioSpec& s) {
    // Mission defaults that differ from a scripted flight.
    s.flight.duration_s = 1200.0;
    s.flight.perception.enabled = true;
    s.flight.camera_stream.save_every_n = 0;
    readScenario(r, dir, s);
  });
  if (spec.name.empty()) spec.name = fs::path(path).stem().string();
  return spec;
}

SphereMapConfig loadMapOverrides(const std::vector<std::string>& sets) {
  YAML::Node tree(YAML::NodeType::Map);
  for (const auto& kv : sets) {
    if (kv.rfind("map.", 0) != 0) throw UsageError("--set: expected map.KEY=VALUE, got '" + kv + "'");
    applySet(tree, kv);
  }
  return parseConfigNode<SphereMapConfig>("--set", tree, [](MapReader& r, SphereMapConfig& c) {
    if (r.has("map")) {
      MapReader m = r.sub("map");
      m.read("ovde", c.ovde);
      m.read("dbof", c.dbof);
      readSphereMapKeys(m, c);
      m.finish();
    }
    r.finish();
  });
}

std::string scenarioTreeToString(const YAML::Node& tree) {
  YAML::Emitter e;
  e << tree;
  return std::string(e.c_str()) + "\n";
}

}  // namespace msb
