// msbench grid-audit: how the grid baseline's map came to hold free space where its vehicle hit
// an object (docs/baseline.md, "Why the grid collides in urban"). The run's recorded perception
// log is replayed open loop through the run's own grid map, on the loop's schedule (the latest
// frame at each map update), so the map is the one the run had; the cells around the contact
// point — placed in the map frame with the VIO error at contact — are watched, and every ray
// that hit or cleared them is described: when, from what pose error, to which point (its true
// object and distance beyond the cell), at what angle to the surface. The predicted-path check
// (check_ahead_m ahead, check_clearance_m) is re-run on the flown estimate over the last seconds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/common/clock.h"
#include "core/geometry/world_truth.h"
#include "core/methods/grid_random/grid_explorer.h"
#include "tools/config/scenario_yaml.h"
#include "tools/config/world_registry.h"
#include "tools/msbench/cli_args.h"
#include "tools/msbench/commands.h"
#include "tools/msbench/interrupt.h"
#include "tools/msbench/map_replay.h"
#include "tools/results/input_files.h"
#include "tools/results/output_files.h"
#include "tools/results/perception_log.h"

namespace msb {

namespace {

namespace fs = std::filesystem;

// The contact of a collided run (true world frame).
struct Contact {
  double t_s = 0;
  Vec3 point = Vec3::Zero(), vehicle = Vec3::Zero();
  std::string object, geom, kind, cause;
};

Vec3 vec3(const nlohmann::json& a) { return Vec3(a.at(0).get<double>(), a.at(1).get<double>(), a.at(2).get<double>()); }

Contact readContact(const fs::path& run) {
  const auto m = readJsonFile(run / "metrics.json");
  if (!m.contains("collision") || !m["collision"].is_object())
    throw UsageError((run / "metrics.json").string() + ": the run did not collide (no collision to audit)");
  const auto& c = m["collision"];
  Contact k{c.at("t_s").get<double>(),
            vec3(c.at("contact_position_m")),
            vec3(c.at("vehicle_position_m")),
            c.value("object", ""),
            c.value("world_geom", ""),
            c.value("kind", ""),
            ""};
  if (c.contains("audit")) k.cause = c["audit"].value("cause", "");
  return k;
}

// (t, estimated position) rows of trajectory.csv.
std::vector<std::pair<double, Vec3>> readEstimate(const fs::path& file) {
  std::istringstream in(readInputFile(file));
  std::string line;
  std::getline(in, line);  // header: t,x,y,z,qw,qx,qy,qz,vx,vy,vz,est_x,est_y,est_z,...
  std::vector<std::pair<double, Vec3>> rows;
  while (std::getline(in, line)) {
    std::vector<double> v;
    std::istringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');) v.push_back(std::strtod(c.c_str(), nullptr));
    if (v.size() >= 14) rows.push_back({v[0], Vec3(v[11], v[12], v[13])});
  }
  return rows;
}

// The outward surface normal of the truth at p (gradient of the signed distance).
Vec3 surfaceNormal(const WorldTruth& truth, const Vec3& p) {
  const double h = 0.05;
  Vec3 g;
  for (int k = 0; k < 3; ++k) {
    Vec3 d = Vec3::Zero();
    d[k] = h;
    g[k] = truth.nearest(p + d, 5.0).distance_m - truth.nearest(p - d, 5.0).distance_m;
  }
  return g.norm() > 1e-9 ? Vec3(g.normalized()) : Vec3::UnitZ();
}

// One ray that updated a watched cell.
struct RayNote {
  double t_s;
  bool hit;
  double beyond_m;       // misses: how far past the cell's centre the ray's point lies
  double angle_deg;      // between the ray and the surface plane at contact (90: head-on)
  double pose_error_m;   // |estimated - true camera position| of the frame
  double shift_m;        // where the contact point lay in the map frame then, from where it lies at contact
  std::string object;    // the true object of the ray's point ("" none within 0.5 m)
  double point_error_m;  // the point's distance from the nearest true surface
};

// The frames the loop gave the map: at each map tick the latest frame not yet used.
std::vector<size_t> scheduledFrames(const PerceptionLog& log, int physics_hz, double map_rate_hz) {
  const RateSchedule schedule(physics_hz, map_rate_hz, "mission.map_rate_hz");
  std::vector<size_t> used;
  for (size_t i = 0; i < log.frames.size(); ++i) {
    int64_t t = log.frames[i].points.tick;
    while (!schedule.due(t)) ++t;  // the map tick that takes it, unless a newer frame comes first
    if (i + 1 < log.frames.size() && log.frames[i + 1].points.tick <= t) continue;
    used.push_back(i);
  }
  return used;
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The watched cells: centres within `radius` of the contact point in the map frame.
std::vector<uint64_t> watchedKeys(const GridMap& map, const Vec3& c_map, double radius, double res) {
  std::vector<uint64_t> keys;
  const int n = int(std::ceil(radius / res)) + 1;
  for (int x = -n; x <= n; ++x)
    for (int y = -n; y <= n; ++y)
      for (int z = -n; z <= n; ++z)
        if (const auto k = map.keyOf(c_map + res * Vec3(x, y, z)); k && (map.centreOf(*k) - c_map).norm() <= radius)
          keys.push_back(*k);
  return keys;
}

// What the replay up to contact saw: every watched update described, the contact cell's
// probability over time, and the predicted-path checks of the last `window` seconds.
struct AuditReplay {
  std::vector<RayNote> notes;
  std::optional<double> first_check_fired, contact_p, max_p;
  double last_hit_t = -1, last_occupied_t = -1;
  int checks = 0, fired = 0;
};

// The frame-to-map correction (estimated camera pose over true) of log frame i.
Pose logCorrection(const PerceptionLog& log, size_t i) {
  return Pose(log.frames[i].points.T_W_C * log.frames[i].T_W_C_truth.inverse());
}

// Replays the log through `map` on the loop's schedule up to the contact.
AuditReplay replayToContact(const PerceptionLog& log, const ScenarioSpec& spec, const GridExplorerConfig& grid,
                            const WorldTruth& truth, const Contact& contact, const Vec3& c_map, const Vec3& normal_map,
                            const std::optional<uint64_t>& contact_key, double window, const fs::path& run,
                            GridMap& map) {
  const auto estimate = readEstimate(run / "trajectory.csv");
  AuditReplay a;
  for (size_t i : scheduledFrames(log, spec.flight.physics.physics_hz, spec.mission.map_rate_hz)) {
    throwIfInterrupted();
    const LoggedFrame& f = log.frames[i];
    if (f.points.t_s > contact.t_s) break;
    map.insert(f.points);
    const Pose corr = logCorrection(log, i);
    const Vec3 o = f.points.T_W_C.translation();
    for (const WatchedUpdate& u : map.lastWatched()) {
      const Vec3 p = f.points.points[size_t(u.point)].p_W, dir = (p - o).normalized();
      const Vec3 p_true = corr.inverse() * p;
      const NearestObstacle near = truth.nearest(p_true, 5.0);
      const std::string object =
          near.shape >= 0 && near.distance_m < 0.5 ? truth.shapes()[size_t(near.shape)].object : "";
      a.notes.push_back({f.points.t_s, u.hit, (p - o).norm() - (map.centreOf(u.key) - o).norm(),
                         std::asin(std::min(1.0, std::abs(dir.dot(normal_map)))) * 180.0 / M_PI,
                         (f.points.T_W_C.translation() - f.T_W_C_truth.translation()).norm(),
                         (corr * contact.point - c_map).norm(), object, std::abs(near.distance_m)});
      if (u.hit) a.last_hit_t = f.points.t_s;
    }
    if (contact_key) {
      a.contact_p = map.probabilityOf(*contact_key);
      if (a.contact_p && *a.contact_p > 0.5) a.last_occupied_t = f.points.t_s;
      if (a.contact_p) a.max_p = std::max(a.max_p.value_or(0.0), *a.contact_p);
    }
    // The predicted-path check on the estimate flown from now (as the last path's stand-in).
    if (f.points.t_s >= contact.t_s - window) {
      std::vector<Vec3> path;
      for (const auto& [t, p] : estimate)
        if (t >= f.points.t_s && t <= contact.t_s) path.push_back(p);
      if (path.size() >= 2) {
        ++a.checks;
        if (pathNearOccupied(map, path, path.front(), grid.check_ahead_m, grid.check_clearance_m)) {
          ++a.fired;
          if (!a.first_check_fired) a.first_check_fired = contact.t_s - f.points.t_s;
        }
      }
    }
  }
  return a;
}

// The audit as JSON.
nlohmann::json auditSummary(const fs::path& run, const Contact& contact, const Vec3& c_map,
                            const std::vector<uint64_t>& keys, const GridMap& map, const AuditReplay& a) {
  const std::vector<RayNote>& notes = a.notes;
  const double last_hit_t = a.last_hit_t, last_occupied_t = a.last_occupied_t;
  const std::optional<double>&contact_p = a.contact_p, &max_p = a.max_p, &first_check_fired = a.first_check_fired;
  const int checks = a.checks, fired = a.fired;
  int hits = 0, misses = 0, misses_after_hit = 0, on_object = 0;
  std::vector<double> beyond, angle, pose_error, shift;
  for (const RayNote& r : notes) {
    (r.hit ? hits : misses)++;
    on_object += r.hit && r.object == contact.object;
    if (!r.hit) {
      beyond.push_back(r.beyond_m), angle.push_back(r.angle_deg), pose_error.push_back(r.pose_error_m);
      if (last_hit_t >= 0 && r.t_s > last_hit_t - 1e-9) ++misses_after_hit;
    }
    shift.push_back(r.shift_m);
  }
  int misses_via_object = 0;
  std::map<std::string, int> misses_by_object;  // the true object of each clearing ray's point
  for (const RayNote& r : notes)
    if (!r.hit)
      ++misses_by_object[r.object.empty() ? "(none within 0.5 m)" : r.object],
          misses_via_object += r.object == contact.object;
  int occupied_at_contact = 0;
  for (uint64_t k : keys)
    if (const auto p = map.probabilityOf(k); p && *p > 0.5) ++occupied_at_contact;
  const std::string state = !contact_p ? "unknown" : *contact_p > 0.5 ? "occupied" : "free";
  nlohmann::json j = {
      {"run", run.string()},
      {"t_contact_s", contact.t_s},
      {"object", contact.object},
      {"geom", contact.geom},
      {"kind", contact.kind},
      {"audit_cause", contact.cause},
      {"vio_error_at_contact_m", (c_map - contact.point).norm()},
      {"watched_cells", keys.size()},
      {"hits", hits},
      {"hits_of_the_object", on_object},
      {"misses", misses},
      {"misses_after_last_hit", misses_after_hit},
      {"misses_to_points_on_the_object", misses_via_object},
      {"misses_by_point_object", misses_by_object},
      {"watched_cells_occupied_at_contact", occupied_at_contact},
      {"last_hit_s", last_hit_t},
      {"contact_cell_at_contact", state},
      {"contact_cell_max_probability", max_p.value_or(0.0)},
      {"contact_cell_last_occupied_s", last_occupied_t},
      {"miss_median_beyond_m", median(beyond)},
      {"miss_median_angle_deg", median(angle)},
      {"miss_median_pose_error_m", median(pose_error)},
      {"median_contact_shift_m", median(shift)},
      {"path_checks", checks},
      {"path_checks_fired", fired},
      {"first_fired_before_contact_s", first_check_fired ? nlohmann::json(*first_check_fired) : nlohmann::json()}};
  return j;
}

}  // namespace

int runGridAuditCommand(int argc, char** argv) {
  const std::vector<std::string> sets = takeRepeatedOption(argc, argv, "set");
  ArgParser args("msbench grid-audit",
                 "Audit a grid-baseline collision: replay the run's perception log (msbench run ...\n"
                 "--record LOG) through its grid map on the loop's schedule, watch the cells around\n"
                 "the contact point (in the map frame) and describe every ray that hit or cleared\n"
                 "them; re-run the predicted-path check on the flown estimate before contact.\n"
                 "Prints a summary and writes it as JSON with --out. --set KEY=VALUE (repeatable)\n"
                 "changes the run's configuration for the replay, e.g. --set method.map.prob_miss=0.45.");
  args.positional("LOG", "perception log of the run")
      .positional("RUN", "the run's result directory (metrics.json, config.yaml, trajectory.csv)")
      .option("radius", "0.75", "watch cells whose centre lies within this of the contact point (m)")
      .option("window", "5", "seconds before contact for the predicted-path check")
      .option("out", "", "write the audit as JSON to this file");
  if (!args.parse(argc, argv)) return kExitOk;
  const fs::path run = args.get("RUN");
  // --out is a new file, never one of the inputs or inside the run's directory.
  if (!args.get("out").empty()) {
    checkNoOverlap({{"LOG", args.get("LOG")}, {"RUN", run}}, {{"--out", args.get("out")}});
    checkOutputFile(args.get("out"), /*overwrite=*/false, "out");
  }
  const double radius = args.getDoubleIn("radius", 0.1, 5.0), window = args.getDoubleIn("window", 0.5, 60.0);
  const Contact contact = readContact(run);
  const ScenarioSpec spec = loadScenario((run / "config.yaml").string(), sets);
  const auto* grid = std::any_cast<GridExplorerConfig>(&spec.method.config);
  if (!grid)
    throw UsageError((run / "config.yaml").string() + ": method.type is " + spec.method.type + ", not grid_random");
  const PerceptionLog log = readReplayableLog(args.get("LOG"));
  const ResolvedWorld world = resolveWorld(log.header.at("world").get<std::string>());
  if (!world.built) throw UsageError(args.get("LOG") + ": its world is not a generated world (no ground truth)");
  const WorldTruth truth(world.built->generated.shapes);

  // The map frame at contact: the VIO error of the last frame at or before it.
  size_t last = 0;
  for (size_t i = 0; i < log.frames.size(); ++i)
    if (log.frames[i].points.t_s <= contact.t_s) last = i;
  const Pose at_contact = logCorrection(log, last);
  const Vec3 c_map = at_contact * contact.point;
  const Vec3 normal_map = at_contact.linear() * surfaceNormal(truth, contact.point);

  // The watched cells: centres within the radius of the contact point in the map frame.
  GridMap map(grid->map);
  const double res = grid->map.resolution_m;
  const std::vector<uint64_t> keys = watchedKeys(map, c_map, radius, res);
  map.watch(keys);
  const auto contact_key = map.keyOf(c_map);

  // Replay up to contact, describing every watched update and re-running the path check.
  AuditReplay replayed =
      replayToContact(log, spec, *grid, truth, contact, c_map, normal_map, contact_key, window, run, map);
  const nlohmann::json j = auditSummary(run, contact, c_map, keys, map, replayed);
  std::printf("%s\n", j.dump(2).c_str());
  if (!args.get("out").empty()) writeFileAtomic(args.get("out"), j.dump(2) + "\n");
  return kExitOk;
}

}  // namespace msb
