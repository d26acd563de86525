#include "tools/config/method_table.h"

#include <stdexcept>

#include <yaml-cpp/yaml.h>

#include "core/baseline/grid_explorer.h"
#include "core/baseline/hover_turn/hover_turn_explorer.h"
#include "core/baseline/star_discovery_explorer.h"
#include "core/planning/monospheres_explorer.h"

namespace msb {

namespace {

template <class Keys>
void ovdeKeys(Keys r, OpenAreaDepthConfig& c) {
  r.field("grid", c.grid);
  r.field("central_fraction", c.central_fraction);
  r.field("range_m", c.range_m);
  r.field("max_poses", c.max_poses);
  r.field("min_translation_m", c.min_translation_m);
  r.field("min_rotation_deg", c.min_rotation_deg);
  r.field("min_parallax_rad", c.min_parallax_rad);
  r.field("visibility", c.visibility);
  r.finish();
}

template <class Keys>
void sphereMapKeys(Keys& r, SphereMapConfig& c) {
  if (r.has("ovde_params")) ovdeKeys(r.sub("ovde_params"), c.ovde_params);
  r.field("dbof_alpha", c.dbof_alpha);
  r.field("dbof_age_per_m", c.dbof_age_per_m);
  r.field("r_max_m", c.r_max_m);
  r.field("max_point_depth_std_m", c.max_point_depth_std_m);
  r.field("r_min_m", c.r_min_m);
  r.field("new_sphere_samples", c.new_sphere_samples);
  r.field("max_sample_range_m", c.max_sample_range_m);
  r.field("max_point_range_m", c.max_point_range_m);
  r.field("obstacle_spacing_m", c.obstacle_spacing_m);
  r.field("sparsify_factor", c.sparsify_factor);
  r.field("min_points", c.min_points);
  r.field("max_view_angle_deg", c.max_view_angle_deg);
  r.field("frontier_surface_samples", c.frontier_surface_samples);
  r.field("frontier_shell_samples", c.frontier_shell_samples);
  r.field("frontier_jitter_m", c.frontier_jitter_m);
  r.field("shell_min_m", c.shell_min_m);
  r.field("shell_max_m", c.shell_max_m);
  r.field("frontier_spacing_m", c.frontier_spacing_m);
  r.field("frontier_obstacle_gap_m", c.frontier_obstacle_gap_m);
  r.field("frontier_range_m", c.frontier_range_m);
  r.field("frontier_min_normal_z", c.frontier_min_normal_z);
  r.field("frontier_min_balance", c.frontier_min_balance);
}

template <class Keys>
void viewpointsKeys(Keys r, ViewpointConfig& c) {
  r.field("candidates", c.candidates);
  r.field("frontier_range_m", c.frontier_range_m);
  r.field("fov_half_angle_deg", c.fov_half_angle_deg);
  r.field("min_value", c.min_value);
  r.field("relaxed_min_value", c.relaxed_min_value);
  r.field("block_distance_m", c.block_distance_m);
  r.field("block_angle_deg", c.block_angle_deg);
  r.field("blacklist_radius_m", c.blacklist_radius_m);
  r.field("blacklist_duration_s", c.blacklist_duration_s);
  r.field("vpb_new_frontiers", c.vpb_new_frontiers);
  r.field("frontier_view_limit", c.frontier_view_limit);
  r.finish();
}

template <class Keys>
void safetyKeys(Keys r, SafetyCostConfig& c) {
  r.field("weight", c.weight);
  r.refuse("r_min_m", "not a key of its own: the minimum sphere radius is method.map.r_min_m");
  r.field("r_safe_m", c.r_safe_m);
  r.finish();
}

// Planner parameters; the switches fff/vpb live under `switches`.
template <class Keys>
void plannerKeys(Keys r, MonoSpheresPlannerConfig& c) {
  if (r.has("viewpoints")) viewpointsKeys(r.sub("viewpoints"), c.viewpoints);
  if (r.has("safety")) safetyKeys(r.sub("safety"), c.safety);
  r.field("fff_turn_rate_rad_per_m", c.fff_turn_rate_rad_per_m);
  r.field("align_before_route_deg", c.align_before_route_deg);
  r.field("start_max_outside_m", c.start_max_outside_m);
  r.field("local_radius_m", c.local_radius_m);
  r.field("local_misses_before_global", c.local_misses_before_global);
  r.field("max_goal_candidates", c.max_goal_candidates);
  r.field("carrot_distance_m", c.carrot_distance_m);
  r.field("replan_period_s", c.replan_period_s);
  pathCheckKeys(r, c);
  r.field("allow_moving_away", c.allow_moving_away);
  r.field("max_blocked_steps", c.max_blocked_steps);
  r.field("max_route_repairs", c.max_route_repairs);
  r.field("blocked_edge_timeout_s", c.blocked_edge_timeout_s);
  r.field("escape_margin_m", c.escape_margin_m);
  r.field("bridge_below_reachable", c.bridge_below_reachable);
  r.field("bridge_range_m", c.bridge_range_m);
  r.field("bridge_after_idle_s", c.bridge_after_idle_s);
  r.field("link_gap_m", c.link_gap_m);
  r.field("link_trail_radius_m", c.link_trail_radius_m);
  r.field("link_trail_max_m", c.link_trail_max_m);
  r.field("trail_spacing_m", c.trail_spacing_m);
  r.field("link_tests_per_pair", c.link_tests_per_pair);
  r.field("return_range_m", c.return_range_m);
  r.field("shortcut_depth_m", c.shortcut_depth_m);
  r.field("reach_distance_m", c.reach_distance_m);
  r.field("reach_angle_deg", c.reach_angle_deg);
  r.field("no_progress_timeout_s", c.no_progress_timeout_s);
  takeoffKeys(r, c);
  r.field("idle_turn_deg", c.idle_turn_deg);
  r.field("idle_turn_period_s", c.idle_turn_period_s);
  r.finish();
}

// Validates a method's config with its keys named under `method.` (before methodChoice()
// validates it again without the prefix).
template <class Config>
void validateMethod(const Config& c) {
  ConfigChecker checker("method.");
  c.validate(checker);
  if (!checker.issues().empty()) throw ConfigError(checker.issues());
}

// The published code's defects (docs/deviations.md, "The published code as switches"):
//   reference_code: published            every modelled defect on (`intended`: none)
//   reference_code: {path_resend_8s: true, ...}        the switches named
//   reference_code: {published: true, heading_check_signed: false}
// In a map `published: true` turns every switch on first; switches named beside it then set
// their own value. Written back as the full map of switches.
template <class Keys>
void referenceCodeKeys(Keys& m, ReferenceCodeConfig& c) {
  if constexpr (Keys::kReading) {
    if (!m.has("reference_code")) return;
    const YAML::Node n = m.raw("reference_code");
    const std::string key = m.keyName("reference_code");
    if (n.IsScalar()) {
      if (n.Scalar() != "published" && n.Scalar() != "intended")
        throw ConfigError(key, "expected published, intended or a map of switches, got '" + n.Scalar() + "'");
      c = n.Scalar() == "published" ? ReferenceCodeConfig::published() : ReferenceCodeConfig{};
      return;
    }
    MapReader r(n, key + ".");
    bool all = false;
    r.field("published", all);
    if (all) c = ReferenceCodeConfig::published();
    for (const auto& [name, member] : ReferenceCodeConfig::switches()) r.field(name, c.*member);
    r.finish();
  } else {
    auto w = m.sub("reference_code");
    for (const auto& [name, member] : ReferenceCodeConfig::switches()) w.field(name, c.*member);
  }
}

// MonoSpheres: switches, the published code's switches, mapper and planner keys.
template <class Keys>
void monoSpheresKeys(Keys& m, MonoSpheresConfig& c) {
  referenceCodeKeys(m, c.reference_code);
  if (m.has("switches")) {
    auto w = m.sub("switches");
    w.field("ovde", c.map.ovde);
    w.field("dbof", c.map.dbof);
    w.field("fff", c.planner.fff);
    w.field("vpb", c.planner.viewpoints.vpb);
    w.finish();
  }
  if (m.has("map")) {
    auto r = m.sub("map");
    sphereMapKeys(r, c.map);
    r.finish();
  }
  if (m.has("planner")) plannerKeys(m.sub("planner"), c.planner);
}

// The OctoMap map and grid planner keys shared by the grid-based methods.
template <class Keys>
void gridMapAndPlannerKeys(Keys& m, GridMapConfig& map, GridPlannerConfig& planner) {
  if (m.has("map")) {
    auto r = m.sub("map");
    r.field("resolution_m", map.resolution_m);
    r.field("max_range_m", map.max_range_m);
    r.field("free_ray_length_m", map.free_ray_length_m);
    r.field("prob_hit", map.prob_hit);
    r.field("prob_miss", map.prob_miss);
    r.field("clamp_min", map.clamp_min);
    r.field("clamp_max", map.clamp_max);
    r.field("insertion", map.insertion);
    r.field("confidence_depth_gain_per_m", map.confidence_depth_gain_per_m);
    r.finish();
  }
  if (m.has("planner")) {
    auto r = m.sub("planner");
    r.field("clearance_m", planner.clearance_m);
    r.field("unknown_is_occupied", planner.unknown_is_occupied);
    r.field("escape_radius_m", planner.escape_radius_m);
    r.field("escape_clearance_m", planner.escape_clearance_m);
    r.field("unknown_clearance_m", planner.unknown_clearance_m);
    r.field("max_expansions", planner.max_expansions);
    r.finish();
  }
}

// Star discovery: the grid map and planner, the star and global-step parameters.
template <class Keys>
void starDiscoveryKeys(Keys& m, StarDiscoveryConfig& c) {
  gridMapAndPlannerKeys(m, c.map, c.planner);
  m.field("rays", c.rays);
  m.field("heights", c.heights);
  m.field("height_step_m", c.height_step_m);
  m.field("max_ray_m", c.max_ray_m);
  m.field("min_ray_m", c.min_ray_m);
  m.field("candidates", c.candidates);
  m.field("los_range_m", c.los_range_m);
  m.field("look_around_step_deg", c.look_around_step_deg);
  m.field("replan_period_s", c.replan_period_s);
  m.field("transit_timeout_s", c.transit_timeout_s);
  m.field("retry_period_s", c.retry_period_s);
  pathCheckKeys(m, c);
  takeoffKeys(m, c);
}

// The grid baseline: OctoMap insertion, A*, goals.
template <class Keys>
void gridRandomKeys(Keys& m, GridExplorerConfig& c) {
  gridMapAndPlannerKeys(m, c.map, c.planner);
  m.field("goal_period_s", c.goal_period_s);
  m.field("goal_timeout_s", c.goal_timeout_s);
  m.field("goal_square_m", c.goal_square_m);
  m.field("goal_min_altitude_m", c.goal_min_altitude_m);
  m.field("goal_ceiling_margin_m", c.goal_ceiling_margin_m);
  m.field("replan_period_s", c.replan_period_s);
  m.field("reach_distance_m", c.reach_distance_m);
  pathCheckKeys(m, c);
  takeoffKeys(m, c);
}

// The example method (core/baseline/hover_turn).
template <class Keys>
void hoverTurnKeys(Keys& m, HoverTurnConfig& c) {
  m.field("takeoff_altitude_m", c.takeoff_altitude_m);
  m.field("turn_step_deg", c.turn_step_deg);
  m.field("land_altitude_m", c.land_altitude_m);
  m.field("max_radius_m", c.max_radius_m);
  m.field("margin_m", c.margin_m);
}

// A Python method's keys: entry and path, and `params`, a map passed through to its factory
// (which validates it) — read as YAML text, written back as the same map.
template <class Keys>
void pythonMethodKeys(Keys& m, PythonMethodConfig& c) {
  m.field("entry", c.entry);
  m.field("path", c.path);
  m.field("call_budget_s", c.call_budget_s);
  if constexpr (Keys::kReading) {
    if (m.has("params")) c.params_yaml = m.flowMap("params", "the method's own keys");
  } else {
    m.node()["params"] = YAML::Load(c.params_yaml);
  }
}

// The explorer slot of a Python method: the C++ binary cannot build one (the Python module does).
class PythonMethodStub final : public Explorer {
 public:
  PythonMethodStub(const PythonMethodConfig&, const ExplorerContext&) {
    throw ConfigError("method.type",
                      "'python' methods run through the Python module: msbench run hands them to "
                      "/usr/bin/python3 -m msbench (docs/python.md)");
  }
  void observe(const SlamPointsFrame&) override {}
  std::optional<PathCommand> plan(const VehicleState&) override { return std::nullopt; }
  ExplorerSnapshot snapshot() const override { return {}; }
  std::map<std::string, double> counters() const override { return {}; }
};

// One method-table entry from the method's explorer and config types and its keys function
// (`keys(k, config)` for any key visitor k: MapReader reads, MapWriter writes).
template <class ExplorerT, class Config, class KeysFn>
MethodEntry methodEntry(const char* type, const char* summary, KeysFn keys, std::vector<std::string> progress,
                        std::vector<PaperRow> paper_rows = {}) {
  MethodEntry e;
  e.type = type;
  e.summary = summary;
  e.paper_rows = std::move(paper_rows);
  e.progress_counters = std::move(progress);
  e.read = [type, keys](MapReader& m) {
    Config c;
    keys(m, c);
    m.finish();
    validateMethod(c);
    return methodChoice<ExplorerT>(type, c);
  };
  e.write = [keys](const std::any& config, MapWriter& w) {
    Config c = std::any_cast<const Config&>(config);
    keys(w, c);
  };
  // An outside goal chooser for the explorers that take one (a compile-time check on the
  // explorer type): the grid its goals, MonoSpheres its viewpoints. `x` is an explorer this
  // entry made, so the cast is exact.
  if constexpr (requires(ExplorerT & x, GoalChooser g) { x.setGoalChooser(g); })
    e.attach_goal_chooser = [](Explorer& x, const GoalChoosers& c) {
      static_cast<ExplorerT&>(x).setGoalChooser(c.goals);
    };
  if constexpr (requires(ExplorerT & x, ViewpointChooser v) { x.setViewpointChooser(v); })
    e.attach_goal_chooser = [](Explorer& x, const GoalChoosers& c) {
      static_cast<ExplorerT&>(x).setViewpointChooser(c.viewpoints);
    };
  return e;
}

}  // namespace

void readSphereMapKeys(MapReader& r, SphereMapConfig& c) { sphereMapKeys(r, c); }

const std::vector<MethodEntry>& methodTable() {
  // One entry per method: explorer and config types, `method.type`, summary, keys, Table I rows.
  static const std::vector<MethodEntry> table = {
      // MonoSpheres paper, Table I: the full method in the four worlds and its urban ablations.
      methodEntry<MonoSpheresExplorer, MonoSpheresConfig>(
          kMonoSpheresType, "MonoSpheres: sphere map, frontier viewpoints, sphere-graph A* (the paper's method)",
          [](auto& k, MonoSpheresConfig& c) { monoSpheresKeys(k, c); },
          {"spheres", "reachable_spheres", "viewpoints", "goals_reached", "goals_chosen"},
          // Collisions (§V-C): two of the six urban runs; none in the cave; not given for the rest.
          {{"urban", "", 4919, 6081, 6, 2},
           {"cave", "", 7627, 8006, 3, 0},
           {"rooftops", "", 3760, 4606, 3},
           {"sparse", "", 5127, 5150, 3},
           {"urban", "fff", 2470, 3181, 3},
           {"urban", "dbof", 2308, 3081, 3},
           {"urban", "ovde", 747, 862, 3},
           {"urban", "vpb", 3697, 4175, 3}}),
      methodEntry<GridExplorer, GridExplorerConfig>(
          "grid_random", "grid baseline: OctoMap, random goals, grid A* (the paper's Grid-Based rows)",
          [](auto& k, GridExplorerConfig& c) { gridRandomKeys(k, c); }, {"leaves", "goals_reached", "goals_chosen"},
          // Collisions (§V-C): one of the six urban runs (a metal rod); none in the cave.
          {{"urban", "", 1911, 2306, 6, 1},
           {"cave", "", 3171, 3375, 3, 0},
           {"rooftops", "", 1360, 1556, 3},
           {"sparse", "", 2108, 2168, 3}}),
      methodEntry<StarDiscoveryExplorer, StarDiscoveryConfig>(
          "star_discovery", "star discovery (von Stumberg et al.): look-around, star flights, interesting cells",
          [](auto& k, StarDiscoveryConfig& c) { starDiscoveryKeys(k, c); },
          {"leaves", "stars", "interesting_cells", "goals_reached"}),
      methodEntry<HoverTurnExplorer, HoverTurnConfig>(
          "hover_turn", "example method: take off, turn once, descend (a template for new methods)",
          [](auto& k, HoverTurnConfig& c) { hoverTurnKeys(k, c); }, {"turn_steps", "points_seen"}),
      methodEntry<PythonMethodStub, PythonMethodConfig>(
          kPythonMethodType, "a method written in Python (method.entry: \"package.module:factory\"; docs/python.md)",
          [](auto& k, PythonMethodConfig& c) { pythonMethodKeys(k, c); }, {}),
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

void writeMethod(MapWriter& w, const MethodChoice& method) {
  const MethodEntry* e = findMethod(method.type);
  if (!e) throw std::logic_error("writeMethod: method '" + method.type + "' is not in the method table");
  w.field("type", method.type);
  e->write(method.config, w);
}

std::string methodDefaultsYaml(const std::string& type) {
  // A `method:` section that names only the type: every other key takes its default.
  struct MethodSection {
    MethodChoice choice;
    void validate(ConfigChecker&) const {}
  };
  YAML::Node tree(YAML::NodeType::Map);
  tree["method"]["type"] = type;
  if (type == kPythonMethodType) tree["method"]["entry"] = "package.module:factory";  // required: a placeholder
  const MethodSection section = parseConfigNode<MethodSection>("--type", tree, [](MapReader& r, MethodSection& s) {
    s.choice = readMethod(r.sub("method"));
    r.finish();
  });
  MapWriter w{YAML::Node(YAML::NodeType::Map)};
  MapWriter m = w.sub("method");
  writeMethod(m, section.choice);
  return yamlText(w.node());
}

}  // namespace msb
