#include "tools/results/mission_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "core/common/png.h"
#include "tools/results/compute_log.h"
#include "tools/results/flight_records.h"
#include "tools/results/output_files.h"
#include "tools/results/provenance.h"
#include "tools/results/record_seal.h"
#include "tools/results/run_record.h"
#include "tools/results/topdown.h"

namespace msb {

namespace {
nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json stagesJson(const StageTimes& s, double per) {
  return {
      {"render", s.render_ms / per},  {"tracker", s.tracker_ms / per},   {"triangulation", s.triangulation_ms / per},
      {"map_update", s.map_ms / per}, {"planning", s.planning_ms / per}, {"metric", s.metric_ms / per}};
}
}  // namespace

namespace {

// metrics.json → coverage: the areas, the box's explorable columns, the longest stretch without gain.
nlohmann::json coverageJson(const MissionResult& r) {
  const double cell2 = r.columns.cellM() * r.columns.cellM();
  const size_t in_box = r.columns.countInside(r.exploration_box.min.head<2>(), r.exploration_box.max.head<2>());
  return {
      {"area_m2", r.columns.areaM2()},
      {"area_box_m2", double(in_box) * cell2},
      {"box_explorable_columns", r.box_explorable_columns},
      {"box_explored_explorable_columns", r.box_explored_explorable_columns},
      {"box_share", r.box_explorable_columns
                        ? nlohmann::json(double(r.box_explored_explorable_columns) / r.box_explorable_columns)
                        : nlohmann::json(nullptr)},
      {"box_share_true_frame",
       r.box_explorable_columns
           ? nlohmann::json(double(r.box_true_frame_explored_explorable_columns) / r.box_explorable_columns)
           : nlohmann::json(nullptr)},
      {"longest_no_gain_s", r.longest_no_gain.lengthS()},
      {"longest_no_gain_from_s", r.longest_no_gain.start_s},
      {"area_true_frame_m2", r.columns_gt.areaM2()},
      // The authors' evaluation rule for OctoMap maps (grid baseline; BUG-11, docs/metrics.md).
      {"area_published_rule_m2",
       r.columns_published_rule ? nlohmann::json(r.columns_published_rule->areaM2()) : nlohmann::json(nullptr)},
      // Verified coverage (docs/metrics.md): covered, truly free and seen; null without ground truth.
      {"verified_area_m2", r.columns_verified ? nlohmann::json(r.columns_verified->areaM2()) : nlohmann::json(nullptr)},
      {"verified_box_share", r.columns_verified && r.box_explorable_columns
                                 ? nlohmann::json(double(r.box_verified_explorable_columns) / r.box_explorable_columns)
                                 : nlohmann::json(nullptr)},
      {"seen_area_m2", r.columns_verified ? nlohmann::json(double(r.seen_columns) * cell2) : nlohmann::json(nullptr)},
      {"column_size_m", r.columns.cellM()},
      {"exploration_box", nlohmann::json{{"min", vec(r.exploration_box.min)}, {"max", vec(r.exploration_box.max)}}}};
}

// metrics.json → score: the earned score (docs/metrics.md, "The earned score"); a run that ended
// in a collision forfeits what it earned (a lost vehicle brings back no map) but keeps what it
// lost: the lower of its score and 0, so a crash never raises a score. Null without ground truth.
nlohmann::json scoreJson(const MissionResult& r) {
  if (!r.earned) return nullptr;
  const bool forfeit = r.flight.collision.has_value();
  const double earned = forfeit ? std::min(0.0, r.earned->earnedM3()) : r.earned->earnedM3();
  return {{"earned", earned},
          {"unit", "m3"},
          {"earned_share", r.box_free_m3 > 0 ? nlohmann::json(earned / r.box_free_m3) : nlohmann::json(nullptr)},
          {"before_forfeit", r.earned->earnedM3()},
          {"forfeited_by_collision", forfeit},
          {"credited_m3", r.earned->credited_m3},
          {"falsely_free_m3", r.earned->falsely_free_m3},
          {"unseen_m3", r.earned->unseen_m3},
          {"box_free_m3", r.box_free_m3},
          {"time_outside_box_s", r.time_outside_box_s}};
}

// metrics.json → collision: where, what it hit and how it looks to the front end, the audit.
nlohmann::json collisionJson(const FlightResult& f, const MissionResult& r, const WorldTruth* truth) {
  if (!f.collision) return nullptr;
  const auto& c = *f.collision;
  nlohmann::json j = {{"t_s", c.t_s},
                      {"vehicle_position_m", vec(c.vehicle_position_m)},
                      {"contact_position_m", vec(c.contact_position_m)},
                      {"vehicle_geom", c.vehicle_geom},
                      {"world_geom", c.world_geom}};
  // The object hit and what it looks like to the front end (report: collisions by kind).
  const Shape* hit = truth ? truth->shapeNamed(c.world_geom) : nullptr;
  j["object"] = hit ? nlohmann::json(hit->object.empty() ? hit->name : hit->object) : nlohmann::json(nullptr);
  j["kind"] = hit ? nlohmann::json(obstacleKindName(hit->kind)) : nlohmann::json(nullptr);
  if (r.collision_audit) {
    const CollisionAudit& a = *r.collision_audit;
    j["audit"] = {
        {"cause", a.cause},
        {"slam_points_on_object", a.slam_points_on_object},
        {"slam_points_on_part", a.slam_points_on_part},
        {"map_points_on_object", a.map_points_on_object},
        {"nearest_map_point_m",
         a.nearest_map_point_m < 0 ? nlohmann::json(nullptr) : nlohmann::json(a.nearest_map_point_m)},
        {"inside_free_space", a.inside_free_space},
        {"free_space_since_s", a.free_space_since_s ? nlohmann::json(*a.free_space_since_s) : nlohmann::json(nullptr)},
        {"carved_clearance_m", a.carved_clearance_m ? nlohmann::json(*a.carved_clearance_m) : nlohmann::json(nullptr)},
        {"drift_since_carved_m",
         a.drift_since_carved_m ? nlohmann::json(*a.drift_since_carved_m) : nlohmann::json(nullptr)},
        {"vio_drift_m", a.vio_drift_m},
        {"commanded_speed_mps", a.commanded_speed_mps},
        {"since_last_path_s", a.since_last_path_s < 0 ? nlohmann::json(nullptr) : nlohmann::json(a.since_last_path_s)}};
  }
  return j;
}

// metrics.json → map_accuracy (null: no accuracy measured).
nlohmann::json mapAccuracyJson(const MapAccuracy& a) {
  auto share = [](const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  return {{"obstacles", a.obstacles},
          {"obstacles_near_surface_share", share(a.nearSurfaceShare())},
          {"free_elements", a.free_elements},
          {"free_really_free_share", share(a.reallyFreeShare())},
          {"free_volume_m3", a.free_volume_m3},
          {"falsely_free_volume_share", share(a.falselyFreeVolumeShare())},
          {"falsely_free_element_share", share(a.falselyFreeElementShare())}};
}

// metrics.json → wall_ms_per_sim_second: wall time per simulated second, by stage; "other" as
// StageTimes::otherMs (on two threads the loop thread's, with its "waiting" for the second
// thread), as bench-loop splits it.
nlohmann::json wallPerSimSecondJson(const FlightResult& f, const StageTimes& s) {
  const double sim = std::max(f.sim_time_s, 1e-9);
  nlohmann::json st = stagesJson(s, sim);
  if (f.threads > 1) st["waiting"] = f.perception_wait_ms / sim;
  st["other"] = s.otherMs(f.wall_time_s * 1000.0, f.threads, f.perception_wait_ms) / sim;
  st["total"] = f.wall_time_s * 1000.0 / sim;
  return st;
}

}  // namespace

nlohmann::json recordedCounters(const std::map<std::string, double>& counters) {
  // Name order (the map's), the first kMaxRecordedCounters whose names fit; a long name is cut.
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, value] : counters) {
    if (out.size() == kMaxRecordedCounters) break;
    out[name.substr(0, kMaxCounterNameBytes)] = std::isfinite(value) ? nlohmann::json(value) : nlohmann::json();
  }
  return out;
}

nlohmann::json missionMetrics(const ScenarioSpec& spec, const MissionResult& r, const WorldTruth* truth) {
  const FlightResult& f = r.flight;
  nlohmann::json j;
  j["name"] = spec.name;
  j["status"] = runStatusName(f.status);
  j["seed"] = spec.flight.seed;
  j["world"] = spec.flight.world_name.empty() ? spec.flight.world_path : spec.flight.world_name;
  if (!spec.paper_world.empty()) j["paper_world"] = spec.paper_world;  // only when set: older records as they were
  if (!spec.world_salt_commitment.empty()) j["world_salt_commitment"] = spec.world_salt_commitment;
  j["method"] = spec.method.type;
  j["switches"] = spec.method.switches;
  if (!spec.method.reference_code.empty()) j["reference_code"] = spec.method.reference_code;
  // What flew, as config.yaml records it: a Python method's entry, a goal chooser, replayability.
  if (spec.method.type == kPythonMethodType)
    j["method_entry"] = std::any_cast<const PythonMethodConfig&>(spec.method.config).entry;
  if (!spec.method.goal_chooser.empty()) j["goal_chooser"] = spec.method.goal_chooser;
  j["replayable"] = spec.method.not_replayable.empty();
  j["method_confinement"] = spec.method.confinement.empty() ? "compiled into msbench" : spec.method.confinement;
  if (!spec.fixed_settings_hash.empty()) j["fixed_settings_hash"] = spec.fixed_settings_hash;
  if (!spec.suite.empty()) j["suite"] = spec.suite;
  j["duration_s"] = spec.flight.duration_s;
  j["timing"] = computeTimingJson(spec, r);  // how the method's computation was charged
  j["sim_time_s"] = f.sim_time_s;
  j["coverage"] = coverageJson(r);
  j["score"] = scoreJson(r);
  j["collision"] = collisionJson(f, r, truth);
  // The front-end error profile and the final map's accuracy (truth side; core/eval).
  if (r.frontend) j["frontend_profile"] = frontEndProfileJson(*r.frontend);
  if (r.map_accuracy) j["map_accuracy"] = mapAccuracyJson(*r.map_accuracy);
  j["vio_lost_at_s"] = f.vio_lost_at_s >= 0 ? nlohmann::json(f.vio_lost_at_s) : nlohmann::json(nullptr);
  j["distance_flown_m"] = f.distance_flown_m;
  j["perception"] = {{"frames", f.perception_frames},
                     {"tracked_mean", f.perception_frames > 1 ? f.tracked_sum / (f.perception_frames - 1) : 0.0},
                     {"tracked_min", f.tracked_min},
                     {"frames_few_tracks", f.frames_few_tracks}};
  j["final_drift_m"] = f.final_drift_m;
  j["frames_rendered"] = f.frames_rendered;
  j["mujoco_warnings"] = f.mujoco_warnings;
  j["wall_time_s"] = f.wall_time_s;
  j["real_time_factor"] = f.realTimeFactor();
  j["wall_ms_per_sim_second"] = wallPerSimSecondJson(f, r.stages);
  j["map_update_ms"] = {{"updates", r.map_update_ms.size()},
                        {"median", percentile(r.map_update_ms, 0.5)},
                        {"p99", percentile(r.map_update_ms, 0.99)},
                        {"max", percentile(r.map_update_ms, 1.0)}};
  j["peak_rss_mb"] = peakRssMb();
  j["counters"] = recordedCounters(r.counters);
  if (r.counters.size() > kMaxRecordedCounters) j["counters_dropped"] = r.counters.size() - kMaxRecordedCounters;
  j["versions"] = versionInfo();
  j["machine"] = machineFingerprint(f.gl_description);
  j["trajectory_hash"] = hexHash(f.trajectory_hash);
  j["map_hash"] = hexHash(r.map_hash);
  j["determinism_hash"] = hexHash(r.run_hash);
  return j;
}

std::string coverageCsv(const std::vector<CoverageSample>& samples) {
  std::ostringstream o;
  o << "t_s,area_m2,area_box_m2,area_true_frame_m2,distance_m,box_share,area_verified_m2,score_earned_m3\n";
  char line[240];
  for (const auto& c : samples) {
    std::snprintf(line, sizeof(line), "%.3f,%.2f,%.2f,%.2f,%.3f,%.4f,%.2f,%.3f\n", c.t_s, c.area_m2, c.area_box_m2,
                  c.area_gt_m2, c.distance_m, c.box_share, c.area_verified_m2, c.score_earned_m3);
    o << line;
  }
  return o.str();
}

std::string timingCsv(const MissionResult& r) {
  std::ostringstream o;
  o << "t_s,render_ms,tracker_ms,triangulation_ms,map_update_ms,planning_ms,metric_ms\n";
  char line[200];
  for (const auto& [t, s] : r.stage_timeline) {
    std::snprintf(line, sizeof(line), "%.1f,%.1f,%.1f,%.1f,%.1f,%.1f,%.1f\n", t, s.render_ms, s.tracker_ms,
                  s.triangulation_ms, s.map_ms, s.planning_ms, s.metric_ms);
    o << line;
  }
  return o.str();
}

std::string mapPly(const ExplorerSnapshot& snap) {
  std::ostringstream ply;
  ply << "ply\nformat ascii 1.0\ncomment msbench map (VIO frame, ROS frame_id odom); kind 0 free-space sphere "
         "(radius), "
         "1 obstacle point, 2 frontier\nelement vertex "
      << snap.free_space.size() + snap.obstacles.size() + snap.frontiers.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty float radius\n"
         "property uchar kind\nend_header\n";
  char line[160];
  for (const auto& s : snap.free_space) {
    std::snprintf(line, sizeof(line), "%.4f %.4f %.4f %.4f 0\n", s.centre.x(), s.centre.y(), s.centre.z(), s.radius);
    ply << line;
  }
  for (const auto& p : snap.obstacles) {
    std::snprintf(line, sizeof(line), "%.4f %.4f %.4f 0 1\n", p.x(), p.y(), p.z());
    ply << line;
  }
  for (const auto& p : snap.frontiers) {
    std::snprintf(line, sizeof(line), "%.4f %.4f %.4f 0 2\n", p.x(), p.y(), p.z());
    ply << line;
  }
  return ply.str();
}

cv::Mat topdownImage(const MissionResult& r, const WorldTruth* truth) {
  const TopdownView view{r.exploration_box,  r.flight.trajectory, r.final_map,    r.columns,
                         r.flight.collision, r.flight.sim_time_s, r.flight.status};
  return topdownImage(view, truth);
}

void writeTopdown(const std::filesystem::path& file, const MissionResult& r, const WorldTruth* truth) {
  writeFileAtomic(file, encodePng(viewOf(topdownImage(r, truth))));
}

std::string configYamlText(const std::string& scenario_file, bool with_overrides, const std::string& effective_yaml,
                           const std::string& not_replayable) {
  if (!not_replayable.empty())
    return "# NOT REPLAYABLE: " + not_replayable + ".\n# The configuration of " + scenario_file +
           (with_overrides ? " with overrides" : "") +
           " as the run used it; `msbench run` cannot reproduce the run from it.\n" + effective_yaml;
  return "# effective configuration (every key, defaults included) of " + scenario_file +
         (with_overrides ? " with overrides" : "") + "; `msbench run` reproduces the run from it\n" + effective_yaml;
}

nlohmann::json writeMissionOutputs(const std::filesystem::path& dir, const ScenarioSpec& spec, const MissionResult& r,
                                   const WorldTruth* truth, const std::function<nlohmann::json()>& extra) {
  nlohmann::json metrics = missionMetrics(spec, r, truth);
  const std::string coverage_csv = coverageCsv(r.coverage);
  writeFileAtomic(dir / "coverage.csv", coverage_csv);
  writeFileAtomic(dir / "trajectory.csv", trajectoryCsv(r.flight.trajectory));
  writeFileAtomic(dir / "timing.csv", timingCsv(r));
  if (spec.mission.write_map_ply) writeFileAtomic(dir / "map.ply", mapPly(r.final_map));
  // A method whose map is an OctoMap (its "octomap_binary" hook) leaves it as liboctomap's .bt.
  if (!r.octomap_binary.empty()) writeFileAtomic(dir / "map.bt", r.octomap_binary);
  writeTopdown(dir / "topdown.png", r, truth);
  if (!spec.timing.free())
    writeFileAtomic(
        dir / kComputeLogFile,
        computeLogText(r.flight.compute_calls, {msbGitRevision(), wordOf(spec.timing.compute), r.compute_machine_factor,
                                                spec.flight.seed, spec.replay_settings_hash}));
  // What finishes after the run's files (its video: on a full disk, they go first) adds its keys
  // before the record is sealed.
  if (extra) metrics.update(extra());
  // The seals: keyed by the evaluator's key when the process has one (docs/integrity.md), and the
  // unkeyed digest every reader checks for edits.
  metrics["record_format"] = kRecordFormat;
  const SealingKey& key = processSealingKey();
  metrics["record_seal"] = key.key ? recordSeal(*key.key, metrics, coverage_csv) : std::string(kSelfSealedValue);
  metrics["record_digest"] = recordDigest(metrics, coverage_csv);
  writeFileAtomic(dir / "metrics.json", metrics.dump(2) + "\n");
  return metrics;
}

nlohmann::json writeErroredMissionOutputs(const std::filesystem::path& dir, const ScenarioSpec& spec, Mission& mission,
                                          const std::string& what, int64_t error_tick, const WorldTruth* truth,
                                          RunStatus status) {
  nlohmann::json m;
  try {
    MissionResult r = mission.finish();
    r.flight.status = status;
    m = writeMissionOutputs(dir, spec, r, truth);
    m.erase("record_digest");  // an error record is no result: nothing to seal
    m.erase("record_seal");
    m["error"] = what;
    if (error_tick < 0) error_tick = r.flight.ticks;
  } catch (const std::exception& again) {
    // The method fails again when asked for its map: the record alone, as before.
    m = errorMetrics(spec, what, status);
    m["finish_error"] = again.what();
  }
  m["error_tick"] = error_tick;
  writeFileAtomic(dir / "metrics.json", m.dump(2) + "\n");
  return m;
}

std::vector<NamedPath> missionInputs(const std::string& scenario_file, const ScenarioSpec& spec,
                                     const std::vector<NamedPath>& extra) {
  std::vector<NamedPath> in = {{"SCENARIO", scenario_file}};
  for (size_t i = 1; i < spec.input_files.size(); ++i) in.push_back({"its base: file", spec.input_files[i]});
  addWorldInputs(in, spec.flight);
  in.insert(in.end(), extra.begin(), extra.end());
  return in;
}

nlohmann::json errorMetrics(const ScenarioSpec& spec, const std::string& what, RunStatus status) {
  return {{"name", spec.name},
          {"status", runStatusName(status)},
          {"error", what},
          {"seed", spec.flight.seed},
          {"versions", versionInfo()}};
}

nlohmann::json frontEndProfileJson(const FrontEndProfile& p) {
  nlohmann::json bands = nlohmann::json::array();
  for (const DepthBandErrors& b : p.bands)
    bands.push_back({{"depth_from_m", b.lo_m},
                     {"depth_to_m", b.hi_m > 1e8 ? nlohmann::json() : nlohmann::json(b.hi_m)},
                     {"points", b.points},
                     {"median_error_m", b.median_m},
                     {"p90_error_m", b.p90_m},
                     {"share_over_0_5_m", b.share_over_half_m},
                     {"share_over_2_m", b.share_over_2_m}});
  return {{"points", p.points},
          {"depth_bands", bands},
          {"tracks", p.tracks},
          {"moved_over_0_3_m_share", p.moved_share},
          {"median_track_motion_m", p.median_motion_m}};
}

}  // namespace msb
