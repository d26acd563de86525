#include "tools/msbench/mission_runner.h"

#include <chrono>
#include <cmath>

#include "core/common/clock.h"
#include "core/common/wall_time.h"
#include "core/common/rng.h"
#include "core/planning/monospheres_explorer.h"

namespace msb {

namespace {

// Box columns in the metric's node convention: the cells centred on the nodes (2.5 i, 2.5 j)
// that lie in the box, counted when not fully occupied by obstacles.
int explorableNodes(const WorldTruth& truth, const Aabb& box, double cell) {
  Aabb aligned = box;
  for (int k = 0; k < 2; ++k) {
    aligned.min[k] = (std::ceil(box.min[k] / cell) - 0.5) * cell;
    aligned.max[k] = (std::floor(box.max[k] / cell) + 0.5) * cell;
  }
  if ((aligned.max.head<2>().array() <= aligned.min.head<2>().array()).any()) return 0;
  return int(truth.explorableColumns(aligned, cell).size());
}

}  // namespace

std::unique_ptr<Explorer> makeExplorer(const ScenarioSpec& spec, const FisheyeCamera& camera,
                                       const ExplorerContext& context) {
  // The method table: one line per registered method type (ScenarioSpec::methodTypes()).
  if (spec.method_type == "monospheres") return std::make_unique<MonoSpheresExplorer>(spec.monospheres, camera, context);
  throw std::runtime_error("unknown method type '" + spec.method_type + "'");
}

uint64_t hashSnapshot(const ExplorerSnapshot& snap) {
  uint64_t h = fnv1a64(nullptr, 0);
  for (const auto& d : snap.free_space) {
    const double v[5] = {double(d.id), d.centre.x(), d.centre.y(), d.centre.z(), d.radius};
    h = fnv1a64(v, sizeof(v), h);
  }
  for (const auto& p : snap.obstacles) h = fnv1a64(p.data(), 3 * sizeof(double), h);
  for (const auto& p : snap.frontiers) h = fnv1a64(p.data(), 3 * sizeof(double), h);
  return h;
}

MissionResult runMission(const ScenarioSpec& spec, const Aabb& box, const WorldTruth* truth,
                         const MissionProgress& progress, const PerceptionCallback& on_perception) {
  checkValid(spec);
  MissionResult result;
  result.exploration_box = box;
  const double cell = result.columns.cellM();
  if (truth) result.box_explorable_columns = explorableNodes(*truth, box, cell);

  const FlightSpec& fs = spec.flight;
  const FisheyeCamera camera(fs.camera);
  ExplorerContext ctx;
  ctx.exploration_box = box;
  ctx.start = poseFromXyzYaw(fs.start_position_m, fs.start_yaw_rad);
  ctx.seed = fs.seed;
  std::unique_ptr<Explorer> explorer = makeExplorer(spec, camera, ctx);

  // Integer schedules of the closed loop.
  const int hz = fs.physics.physics_hz;
  const RateSchedule map_schedule(hz, spec.mission.map_rate_hz, "mission.map_rate_hz");
  const RateSchedule plan_schedule(hz, spec.mission.planning_rate_hz, "mission.planning_rate_hz");
  const RateSchedule metric_schedule(hz, spec.mission.metric_rate_hz, "mission.metric_rate_hz");

  std::optional<SlamPointsFrame> pending;  // latest SLAM points not yet given to the map
  std::map<uint64_t, Pose> first_seen;     // estimate → truth correction per free-space element
  Pose T_true_est = Pose::Identity();      // correction at the latest perception frame
  Vec3 last_gt = fs.start_position_m;
  double distance = 0;
  const auto wall_start = std::chrono::steady_clock::now();

  // One coverage sample: mark the current free space (VIO and true frame) and record A.
  auto sample = [&](double t_s) {
    const auto t0 = std::chrono::steady_clock::now();
    explorer->markCoverage(result.columns);
    const ExplorerSnapshot snap = explorer->snapshot();
    for (const auto& d : snap.free_space) {
      const Pose& T = first_seen.emplace(d.id, T_true_est).first->second;
      result.columns_gt.markDisk((T * d.centre).head<2>(), d.radius);
    }
    CoverageSample c;
    c.t_s = t_s;
    c.area_m2 = result.columns.areaM2();
    c.area_box_m2 = double(result.columns.countInside(box.min.head<2>(), box.max.head<2>())) * cell * cell;
    c.area_gt_m2 = result.columns_gt.areaM2();
    c.distance_m = distance;
    result.coverage.push_back(c);
    result.stages.metric_ms += msSince(t0);
  };

  FlightObservers obs;
  obs.trajectory_rate_hz = spec.mission.trajectory_rate_hz;
  obs.on_perception = [&](const PerceptionSample& s) {
    result.stages.render_ms += s.render_ms;
    result.stages.tracker_ms += s.tracker_ms;
    result.stages.triangulation_ms += s.triangulation_ms;
    T_true_est = s.frame.T_W_C * s.points.T_W_C.inverse();
    distance += (s.frame.T_W_C.translation() - last_gt).norm();
    last_gt = s.frame.T_W_C.translation();
    if (on_perception) on_perception(s);
  };
  obs.autopilot = [&](const AutopilotInput& in) -> std::optional<std::vector<Waypoint>> {
    const int64_t tick = in.tick;
    if (in.points) pending = *in.points;
    // Map update with the latest frame.
    if (map_schedule.due(tick) && pending) {
      const auto t0 = std::chrono::steady_clock::now();
      explorer->observe(*pending);
      result.stages.map_ms += msSince(t0);
      pending.reset();
    }
    // Coverage sample (after the map update of this tick).
    if (metric_schedule.due(tick)) {
      sample(double(tick) / hz);
      if (tick % (10 * int64_t(hz)) == 0) result.stage_timeline.emplace_back(double(tick) / hz, result.stages);
      if (progress)
        progress(double(tick) / hz,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count(),
                 result.columns.areaM2(), explorer->counters());
    }
    // Planning.
    if (!plan_schedule.due(tick)) return std::nullopt;
    const auto t0 = std::chrono::steady_clock::now();
    VehicleState vs;
    vs.tick = tick;
    vs.t_s = double(tick) / hz;
    vs.T_W_B = in.estimate.T_W_B;
    vs.velocity_mps = in.estimate.v_W_mps;
    vs.reference = in.trajectory.reference();
    vs.path_finished = in.trajectory.finished();
    std::optional<PathCommand> cmd = explorer->plan(vs);
    result.stages.planning_ms += msSince(t0);
    if (!cmd) return std::nullopt;
    return cmd->waypoints;
  };

  FlightSpec flight = fs;
  flight.waypoints.clear();
  result.flight = runFlight(flight, obs);

  // Final sample (the end of the run) and records.
  if (result.coverage.empty() || result.coverage.back().t_s < result.flight.sim_time_s) sample(result.flight.sim_time_s);
  result.stage_timeline.emplace_back(result.flight.sim_time_s, result.stages);
  result.final_map = explorer->snapshot();
  result.counters = explorer->counters();
  result.map_hash = hashSnapshot(result.final_map);
  uint64_t h = fnv1a64(&result.flight.trajectory_hash, sizeof(uint64_t));
  h = fnv1a64(&result.map_hash, sizeof(uint64_t), h);
  for (const auto& c : result.columns.columns()) h = fnv1a64(&c, sizeof(c), h);
  for (const auto& c : result.coverage) {
    const double v[4] = {c.t_s, c.area_m2, c.area_box_m2, c.area_gt_m2};
    h = fnv1a64(v, sizeof(v), h);
  }
  result.run_hash = h;
  return result;
}

}  // namespace msb
