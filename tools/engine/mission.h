// One exploration mission (`msbench run`, docs/architecture.md §2, §10): the closed loop with an exploration
// method in it, plus the coverage metric sampled at its rate. A Mission is stepped like the
// loop (step() returns what the tick produced) so that the caller can record perception or
// print progress between ticks without callbacks; runMission() steps it to the end.
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/common/aabb.h"
#include "core/eval/collision_audit.h"
#include "core/eval/frontend_profile.h"
#include "core/eval/map_accuracy.h"
#include "core/eval/mission_coverage.h"
#include "core/explorer/explorer.h"
#include "tools/engine/closed_loop.h"
#include "tools/engine/scenario_spec.h"

namespace msb {

/// Wall time per stage, summed over the mission (ms; recorded, never used).
struct StageTimes {
  double render_ms = 0, tracker_ms = 0, triangulation_ms = 0, map_ms = 0, planning_ms = 0, metric_ms = 0;

  /// Wall time of the loop thread outside the timed stages ("other": physics, controller, IMU,
  /// VIO, records): on two threads tracker, triangulation, map and planning run beside the loop
  /// thread, which counts its render, metric and wait (`wait_ms`) instead.
  double otherMs(double wall_ms, int threads, double wait_ms) const {
    if (threads > 1) return wall_ms - render_ms - metric_ms - wait_ms;
    return wall_ms - render_ms - tracker_ms - triangulation_ms - map_ms - planning_ms - metric_ms;
  }
};

/// Everything a mission produced.
struct MissionResult {
  std::string method;                              ///< method.type
  FlightResult flight;                             ///< status, collision, trajectory, timing
  std::vector<CoverageSample> coverage;            ///< at the metric rate
  ColumnCoverage columns;                          ///< explored columns (VIO frame)
  ColumnCoverage columns_gt;                       ///< explored columns (true frame)
  std::optional<ColumnCoverage> columns_verified;  ///< verified columns (worlds with ground truth)
  /// Columns by the authors' evaluation rule for OctoMap maps (grid baseline only; BUG-11).
  std::optional<ColumnCoverage> columns_published_rule;
  size_t seen_columns = 0;                  ///< columns the camera saw (verified coverage's (c))
  int box_verified_explorable_columns = 0;  ///< verified columns among the box's explorable ones
  std::optional<EarnedTally> earned;        ///< the earned score's parts at the end (ground truth)
  double box_free_m3 = 0;                   ///< the box's truly free volume (the earned score's ceiling)
  double time_outside_box_s = 0;            ///< seconds the camera spent outside the box (+ margin)
  ExplorerSnapshot final_map;               ///< the map at the end
  /// The map at the end as an OctoMap binary (.bt), from a method that offers kOctomapBinaryHook
  /// ("" otherwise).
  std::string octomap_binary;
  std::map<std::string, double> counters;  ///< the method's counters at the end
  StageTimes stages;
  std::vector<std::pair<double, StageTimes>> stage_timeline;  ///< cumulative, every 10 simulated s
  std::vector<double> map_update_ms;                          ///< wall time of every map update (recorded only)
  double compute_machine_factor = 0;  ///< charged: the machine factor the latencies were scaled by
  Aabb exploration_box;
  int box_explorable_columns = 0;                      ///< 0 if the world has no ground truth
  int box_explored_explorable_columns = 0;             ///< explored columns among those (box_share numerator)
  int box_true_frame_explored_explorable_columns = 0;  ///< the same with true-frame columns
  NoGainInterval longest_no_gain;                      ///< longest stretch without coverage gain
  uint64_t map_hash = 0;                               ///< FNV-1a over the final map snapshot
  uint64_t run_hash = 0;                               ///< trajectory + map + coverage
  std::optional<CollisionAudit> collision_audit;       ///< a collision in a world with ground truth
  std::optional<FrontEndProfile> frontend;             ///< the SLAM points' errors (worlds with ground truth)
  std::optional<MapAccuracy> map_accuracy;  ///< the final map against the truth (non-empty map, ground truth)
};

/// The context a mission hands its method: the box, the start pose, the seed.
ExplorerContext explorerContext(const ScenarioSpec& spec, const Aabb& box);

/// A mission in progress.
class Mission {
 public:
  /// `truth` (generated worlds) gives the box share and enables the oracle feature source;
  /// `spec.flight.world_path` must be resolved and the start pose set. Throws ConfigError or
  /// std::runtime_error on setup failures.
  Mission(const ScenarioSpec& spec, const Aabb& box, const WorldTruth* truth);
  /// The same with an explorer built by the caller (a Python method) instead of the one
  /// `spec.method` names.
  Mission(const ScenarioSpec& spec, const Aabb& box, const WorldTruth* truth, std::unique_ptr<Explorer> explorer);
  ~Mission();

  /// True until the run has ended.
  bool running() const { return loop_->running(); }
  /// One tick of the loop, then the coverage sample when due.
  const TickRecord& step();
  /// Final sample and records; call once, after the run has ended.
  MissionResult finish();

  /// The exploration method (counters for progress lines), once its work in flight has run.
  const Explorer& explorer() const {
    loop_->sync();
    return *explorer_;
  }
  /// Waits for the pipelined loop's perception in flight (results do not depend on it).
  void sync() { loop_->sync(); }
  /// Ends the run where it is, dropping the perception in flight (ClosedLoop::abandon).
  void abandon() { loop_->abandon(); }
  /// abandon() that waits at most `limit` for a method stuck on the loop's second thread: false
  /// if it is still running, and then the mission must never be destroyed (ClosedLoop::abandonWithin).
  bool abandonWithin(std::chrono::milliseconds limit) { return loop_->abandonWithin(limit); }
  /// Called while the loop waits for its second thread: an in-process Python method's interrupts.
  void setWaitHook(std::function<void()> hook) { loop_->setWaitHook(std::move(hook)); }
  /// Explored area so far (VIO frame, m²).
  double areaM2() const { return coverage_.columns().areaM2(); }
  /// Explored columns so far (VIO frame).
  const ColumnCoverage& columns() const { return coverage_.columns(); }
  /// The closed loop (frames, vehicle states) for callers that read more than a TickRecord.
  const ClosedLoop& loop() const { return *loop_; }
  /// The loop's tick rate.
  int physicsHz() const { return loop_->physicsHz(); }

 private:
  void sample(double t_s);

  ScenarioSpec spec_;
  std::unique_ptr<Explorer> explorer_;
  std::unique_ptr<ClosedLoop> loop_;
  MissionCoverage coverage_;
  RateSchedule metric_schedule_;
  StageTimes stages_;
  std::vector<std::pair<double, StageTimes>> stage_timeline_;
  std::vector<double> map_update_ms_;
  double machine_factor_ = 1.0;  // charged: reference seconds per CPU second here
  // Truth-side records (worlds with ground truth only).
  const WorldTruth* truth_ = nullptr;
  std::optional<FrontEndProfiler> frontend_;     // the front-end error profile
  std::optional<CollisionAuditRecorder> audit_;  // what a collision audit needs
  Pose true_from_est_ = Pose::Identity();        // the latest frame's VIO → true correction
  std::optional<Pose> true_camera_;              // the latest frame's true camera pose
};

/// Runs a mission to its end.
MissionResult runMission(const ScenarioSpec& spec, const Aabb& box, const WorldTruth* truth);

}  // namespace msb
