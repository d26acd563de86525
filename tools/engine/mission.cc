#include "tools/engine/mission.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/common/wall_time.h"
#include "core/eval/slam_point_truth.h"
#include "core/explorer/output_limits.h"

namespace msb {

ExplorerContext explorerContext(const ScenarioSpec& spec, const Aabb& box) {
  ExplorerContext ctx;
  ctx.exploration_box = box;
  ctx.start = poseFromXyzYaw(spec.flight.start_position_m, spec.flight.start_yaw_rad);
  ctx.seed = spec.flight.seed;
  return ctx;
}

namespace {

// The loop's flight: the explorer gives the path, so no scripted waypoints.
FlightSpec missionFlight(const ScenarioSpec& spec) {
  FlightSpec f = spec.flight;
  f.waypoints.clear();
  return f;
}

}  // namespace

Mission::Mission(const ScenarioSpec& spec, const Aabb& box, const WorldTruth* truth)
    : Mission(spec, box, truth,
              spec.method.make(FisheyeCamera(checkValid(spec).flight.camera), explorerContext(spec, box))) {}

Mission::Mission(const ScenarioSpec& spec, const Aabb& box, const WorldTruth* truth, std::unique_ptr<Explorer> explorer)
    : spec_(checkValid(spec)),
      explorer_(std::move(explorer)),
      coverage_(box, truth ? boxExplorableNodes(*truth, box, ColumnCoverage().cellM()) : std::set<ColumnIndex>{}),
      metric_schedule_(spec.flight.physics.physics_hz, spec.mission.metric_rate_hz, "mission.metric_rate_hz"),
      truth_(truth) {
  if (truth_) frontend_.emplace(*truth_);
  if (spec_.method.octree_resolution_m > 0) coverage_.enablePublishedOctomapRule(spec_.method.octree_resolution_m);
  LoopSetup setup;
  setup.explorer = explorer_.get();
  setup.truth = truth;
  setup.trajectory_rate_hz = spec.mission.trajectory_rate_hz;
  setup.map_rate_hz = spec.mission.map_rate_hz;
  setup.planning_rate_hz = spec.mission.planning_rate_hz;
  // Compute in the loop: a cost model's terms must be the method's counters; charged latencies
  // are measured (scaled by this machine's factor) or replayed from a log.
  setup.compute.timing = spec_.timing;
  setup.compute.replay = spec_.compute_replay.calls;
  checkModelTerms(spec_.timing, explorer_->workCounters(), spec_.method.type);
  if (spec_.timing.compute == ComputeMode::kCharged)
    setup.compute.machine_factor =
        spec_.timing.replay.empty() ? measureMachineFactor() : spec_.compute_replay.header.machine_factor;
  machine_factor_ = setup.compute.machine_factor;
  loop_ = std::make_unique<ClosedLoop>(missionFlight(spec), setup);
  // A box with nothing above the ground has nothing to explore.
  // A box with nothing above the ground, or beside the ground's extent, has nothing to explore.
  for (const GroundPlane& g : loop_->sim().groundPlanes()) {
    if (box.max.z() <= g.centre.z())
      throw ConfigError("exploration_box", "its top z = " + std::to_string(box.max.z()) +
                                               " m is not above the ground plane " + g.name +
                                               " (z = " + std::to_string(g.centre.z()) + " m)");
    const Vec2 lo = g.centre.head<2>() - g.half_size, hi = g.centre.head<2>() + g.half_size;
    if ((g.half_size.array() > 0).all() &&
        ((box.max.head<2>().array() <= lo.array()).any() || (box.min.head<2>().array() >= hi.array()).any())) {
      char why[320];
      std::snprintf(why, sizeof(why),
                    "x in [%g, %g], y in [%g, %g] lies outside the world (its ground %s spans x in [%g, %g], "
                    "y in [%g, %g])",
                    box.min.x(), box.max.x(), box.min.y(), box.max.y(), g.name.c_str(), lo.x(), hi.x(), lo.y(), hi.y());
      throw ConfigError("exploration_box", why);
    }
  }
  if (truth_) {
    audit_.emplace(*truth_, loop_->camera());
    VerifiedCoverageConfig v;
    v.z_lo_m = box.min.z(), v.z_hi_m = box.max.z();
    coverage_.enableVerification(*truth_, loop_->camera(), v);
  }
}

Mission::~Mission() = default;

const TickRecord& Mission::step() {
  const TickRecord& t = loop_->step();
  stages_.render_ms += t.timing.render_ms;
  stages_.tracker_ms += t.timing.tracker_ms;
  stages_.triangulation_ms += t.timing.triangulation_ms;
  stages_.map_ms += t.timing.map_ms;
  stages_.planning_ms += t.timing.planning_ms;
  if (t.map_updated) map_update_ms_.push_back(t.timing.map_ms);
  // The estimate → truth correction of the latest perception frame (true-frame coverage).
  if (t.frame) true_camera_ = t.frame->T_W_C;
  if (t.points) {
    true_from_est_ = t.perceived->T_W_C * t.points->T_W_C.inverse();
    coverage_.setTrueFromEstimate(true_from_est_);
    // The truth side of the points: each with the true camera pose of the frame they were
    // computed from (`perceived`, latency_frames before this tick; docs/architecture.md,
    // "Which tick a record carries"). The collision audit records the object each new SLAM
    // point lies on (its anchor ray from that pose, where new points are anchored).
    if (frontend_) frontend_->addFrame(*t.points, t.perceived->T_W_C, t.perceived->tick);
    if (audit_) audit_->addFrame(*t.points, t.perceived->T_W_C, t.perceived->tick);
  }
  if (!t.completed) return t;
  // Coverage sample after this tick's map update.
  if (metric_schedule_.due(t.tick)) {
    sample(t.t_s);
    if (t.tick % (10 * int64_t(loop_->physicsHz())) == 0) stage_timeline_.emplace_back(t.t_s, stages_);
  }
  return t;
}

void Mission::sample(double t_s) {
  loop_->sync();  // the pipelined loop's perception in flight has run
  const auto t0 = WallClock::now();
  // The metric scores the method's free space (the method only exposes it).
  const std::vector<FreeSpaceElement> free_space = explorer_->freeSpace();
  if (const auto problem = freeSpaceProblem(free_space, coverage_.box()))
    throw MethodOutputError("the method's free space at t = " + std::to_string(t_s) + " s (tick " +
                            std::to_string(std::llround(t_s * loop_->physicsHz())) + "): " + *problem);
  coverage_.columns().markFreeSpace(free_space);
  if (true_camera_) coverage_.look(*true_camera_);
  if (audit_) audit_->addSample(t_s, free_space, true_from_est_);
  coverage_.sample(t_s, loop_->result().distance_flown_m, free_space);
  stages_.metric_ms += msSince(t0);
}

MissionResult Mission::finish() {
  MissionResult r;
  r.method = spec_.method.type;
  r.flight = loop_->finish();
  // Final sample (the end of the run) and records.
  if (coverage_.samples().empty() || coverage_.samples().back().t_s < r.flight.sim_time_s) sample(r.flight.sim_time_s);
  stage_timeline_.emplace_back(r.flight.sim_time_s, stages_);
  r.coverage = coverage_.samples();
  r.columns = coverage_.columns();
  r.columns_gt = coverage_.trueFrameColumns();
  if (const ColumnCoverage* p = coverage_.publishedRuleColumns()) r.columns_published_rule = *p;
  if (const VerifiedCoverage* v = coverage_.verified()) {
    r.columns_verified = v->verified();
    r.seen_columns = v->seen().size();
    r.box_verified_explorable_columns = int(coverage_.verifiedExplorableColumns());
    r.earned = coverage_.earned()->tally();
    r.box_free_m3 = coverage_.earned()->boxFreeM3();
    r.time_outside_box_s = coverage_.timeOutsideBoxS();
  }
  r.final_map = explorer_->snapshot();
  if (const ExplorerHook* bt = findHook(spec_.method, kOctomapBinaryHook))
    (*bt)(*explorer_, std::any(&r.octomap_binary));
  r.counters = explorer_->counters();
  r.stages = stages_;
  r.stage_timeline = stage_timeline_;
  r.map_update_ms = map_update_ms_;
  r.compute_machine_factor = machine_factor_;
  r.exploration_box = coverage_.box();
  r.box_explorable_columns = coverage_.boxExplorableColumns();
  r.box_explored_explorable_columns = int(coverage_.exploredExplorableColumns());
  r.box_true_frame_explored_explorable_columns = int(coverage_.trueFrameExploredExplorableColumns());
  r.longest_no_gain = longestIntervalWithoutGain(r.coverage);
  r.map_hash = hashSnapshot(r.final_map);
  if (frontend_) r.frontend = frontend_->result();
  if (truth_) r.map_accuracy = mapAccuracy(r.final_map, *truth_);
  // The collision audit: what the map knew at contact (the map is the final one: the run ended there).
  if (r.flight.collision && audit_) {
    CollisionAuditInput in = audit_->input(r.flight.collision->world_geom);
    in.contact_W = r.flight.collision->contact_position_m;
    in.T_true_from_est = true_from_est_;
    in.vio_drift_m = (loop_->estimate().T_W_B.translation() - loop_->groundTruth().T_W_B.translation()).norm();
    in.map = &r.final_map;
    in.commanded_speed_mps = loop_->reference().velocity_mps.norm();
    in.since_last_path_s = loop_->lastPathTimeS() < 0 ? -1.0 : r.flight.collision->t_s - loop_->lastPathTimeS();
    r.collision_audit = auditCollision(in, *truth_);
  }
  r.run_hash = hashMission(r.flight.trajectory_hash, r.map_hash, r.columns, r.coverage);
  return r;
}

MissionResult runMission(const ScenarioSpec& spec, const Aabb& box, const WorldTruth* truth) {
  Mission mission(spec, box, truth);
  while (mission.running()) mission.step();
  return mission.finish();
}

}  // namespace msb
