#include "tools/config/method_table.h"

namespace msb {

namespace {

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

}  // namespace

void readSphereMapKeys(MapReader& r, SphereMapConfig& c) {
  if (r.has("ovde_params")) readOvde(r.sub("ovde_params"), c.ovde_params);
  r.read("dbof_alpha", c.dbof_alpha);
  r.read("dbof_age_per_m", c.dbof_age_per_m);
  r.read("r_max_m", c.r_max_m);
  r.read("max_point_depth_std_m", c.max_point_depth_std_m);
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

namespace {

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
  r.read("vpb_new_frontiers", c.vpb_new_frontiers);
  r.read("frontier_view_limit", c.frontier_view_limit);
  r.finish();
}

void readSafety(MapReader r, SafetyCostConfig& c) {
  r.read("weight", c.weight);
  if (r.has("r_min_m"))
    throw ConfigError(r.keyName("r_min_m"), "not a key of its own: the minimum sphere radius is method.map.r_min_m");
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
  r.read("allow_moving_away", c.allow_moving_away);
  r.read("max_blocked_steps", c.max_blocked_steps);
  r.read("max_route_repairs", c.max_route_repairs);
  r.read("blocked_edge_timeout_s", c.blocked_edge_timeout_s);
  r.read("escape_margin_m", c.escape_margin_m);
  r.read("bridge_below_reachable", c.bridge_below_reachable);
  r.read("bridge_range_m", c.bridge_range_m);
  r.read("bridge_after_idle_s", c.bridge_after_idle_s);
  r.read("link_gap_m", c.link_gap_m);
  r.read("link_trail_radius_m", c.link_trail_radius_m);
  r.read("link_trail_max_m", c.link_trail_max_m);
  r.read("trail_spacing_m", c.trail_spacing_m);
  r.read("link_tests_per_pair", c.link_tests_per_pair);
  r.read("return_range_m", c.return_range_m);
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

// Validates a method's config with its keys named under `method.` (before the factory
// validates it again without the prefix).
template <class Config>
void validateMethod(const Config& c) {
  ConfigChecker checker("method.");
  c.validate(checker);
  if (!checker.issues().empty()) throw ConfigError(checker.issues());
}

// MonoSpheres: switches, mapper and planner keys.
MethodChoice readMonoSpheres(MapReader& m) {
  MonoSpheresConfig c;
  if (m.has("switches")) {
    MapReader w = m.sub("switches");
    w.read("ovde", c.map.ovde);
    w.read("dbof", c.map.dbof);
    w.read("fff", c.planner.fff);
    w.read("vpb", c.planner.viewpoints.vpb);
    w.finish();
  }
  if (m.has("map")) {
    MapReader r = m.sub("map");
    readSphereMapKeys(r, c.map);
    r.finish();
  }
  if (m.has("planner")) readPlanner(m.sub("planner"), c.planner);
  m.finish();
  validateMethod(c);
  return monospheresMethod(c);
}

// The OctoMap map and grid planner keys shared by the grid-based methods.
void readGridMapAndPlanner(MapReader& m, GridMapConfig& map, GridPlannerConfig& planner) {
  if (m.has("map")) {
    MapReader r = m.sub("map");
    r.read("resolution_m", map.resolution_m);
    r.read("max_range_m", map.max_range_m);
    r.read("free_ray_length_m", map.free_ray_length_m);
    r.read("prob_hit", map.prob_hit);
    r.read("prob_miss", map.prob_miss);
    r.read("clamp_min", map.clamp_min);
    r.read("clamp_max", map.clamp_max);
    r.read("insertion", map.insertion);
    r.read("confidence_depth_gain_per_m", map.confidence_depth_gain_per_m);
    r.finish();
  }
  if (m.has("planner")) {
    MapReader r = m.sub("planner");
    r.read("clearance_m", planner.clearance_m);
    r.read("unknown_is_occupied", planner.unknown_is_occupied);
    r.read("escape_radius_m", planner.escape_radius_m);
    r.read("escape_clearance_m", planner.escape_clearance_m);
    r.read("unknown_clearance_m", planner.unknown_clearance_m);
    r.read("max_expansions", planner.max_expansions);
    r.finish();
  }
}

// Star discovery: the grid map and planner, the star and global-step parameters.
MethodChoice readStarDiscovery(MapReader& m) {
  StarDiscoveryConfig c;
  readGridMapAndPlanner(m, c.map, c.planner);
  m.read("rays", c.rays);
  m.read("heights", c.heights);
  m.read("height_step_m", c.height_step_m);
  m.read("max_ray_m", c.max_ray_m);
  m.read("min_ray_m", c.min_ray_m);
  m.read("candidates", c.candidates);
  m.read("los_range_m", c.los_range_m);
  m.read("look_around_step_deg", c.look_around_step_deg);
  m.read("replan_period_s", c.replan_period_s);
  m.read("transit_timeout_s", c.transit_timeout_s);
  m.read("retry_period_s", c.retry_period_s);
  m.read("check_ahead_m", c.check_ahead_m);
  m.read("check_clearance_m", c.check_clearance_m);
  m.read("takeoff_altitude_m", c.takeoff_altitude_m);
  m.read("start_forward_m", c.start_forward_m);
  m.finish();
  validateMethod(c);
  return starDiscoveryMethod(c);
}

// The grid baseline: OctoMap insertion, A*, goals.
MethodChoice readGridRandom(MapReader& m) {
  GridExplorerConfig c;
  readGridMapAndPlanner(m, c.map, c.planner);
  m.read("goal_period_s", c.goal_period_s);
  m.read("goal_timeout_s", c.goal_timeout_s);
  m.read("goal_square_m", c.goal_square_m);
  m.read("goal_min_altitude_m", c.goal_min_altitude_m);
  m.read("goal_ceiling_margin_m", c.goal_ceiling_margin_m);
  m.read("replan_period_s", c.replan_period_s);
  m.read("reach_distance_m", c.reach_distance_m);
  m.read("check_ahead_m", c.check_ahead_m);
  m.read("check_clearance_m", c.check_clearance_m);
  m.read("takeoff_altitude_m", c.takeoff_altitude_m);
  m.read("start_forward_m", c.start_forward_m);
  m.finish();
  validateMethod(c);
  return gridRandomMethod(c);
}

}  // namespace

const std::vector<MethodEntry>& methodTable() {
  static const std::vector<MethodEntry> table = {
      // MonoSpheres paper, Table I: the full method in the four worlds and its urban ablations.
      {kMonoSpheresType, "MonoSpheres: sphere map, frontier viewpoints, sphere-graph A* (the paper's method)",
       readMonoSpheres,
       {{"urban", "", 4919, 6081}, {"cave", "", 7627, 8006}, {"rooftops", "", 3760, 4606}, {"sparse", "", 5127, 5150},
        {"urban", "fff", 2470, 3181}, {"urban", "dbof", 2308, 3081}, {"urban", "ovde", 747, 862},
        {"urban", "vpb", 3697, 4175}}},
      {kGridRandomType, "grid baseline: OctoMap, random goals, grid A* (the paper's Grid-Based rows)", readGridRandom,
       {{"urban", "", 1911, 2306}, {"cave", "", 3171, 3375}, {"rooftops", "", 1360, 1556}, {"sparse", "", 2108, 2168}}},
      {kStarDiscoveryType, "star discovery (von Stumberg et al.): look-around, star flights, interesting cells",
       readStarDiscovery, {}},
  };
  return table;
}

const MethodEntry* findMethod(const std::string& type) {
  for (const auto& e : methodTable())
    if (type == e.type) return &e;
  return nullptr;
}

MethodChoice readMethod(MapReader m) {
  std::string type = kMonoSpheresType;
  m.read("type", type);
  std::string names;
  for (const auto& e : methodTable()) {
    if (type == e.type) return e.read(m);
    names += (names.empty() ? "" : ", ") + std::string(e.type);
  }
  throw ConfigError(m.keyName("type"), "unknown method '" + type + "' (known: " + names + ")");
}

}  // namespace msb
