// The closed loop (docs/architecture.md §2): one object that owns every stage of a run and advances it by one
// physics tick at a time, in a fixed order that reads top to bottom in step():
//
//   physics step 1 → contacts → VIO estimate → render → perceive (features, SLAM points,
//   tracking loss) → map update → planning → trajectory + controller → records →
//   physics step 2 (actuators, integration) → IMU
//
// Perception is one pipeline (tools/engine/perception_pipeline.h) for every
// perception.latency_frames = k: what a frame's tick computes from its image — tracks, SLAM
// points, the map update and the plan due on that tick, from the state snapshotted then — is
// used k frames later: render → use what is due → start frame n's perception → use what is due
// (k = 0: frame n's own results, on its tick). The map and planning rates divide the camera's.
// perception.threads = 2 runs that work on a second thread while the loop renders (k ≥ 1); the
// results are the same with one thread (the latency, not the thread, decides when they are used).
//
// A scripted flight and an exploration mission are two uses of the same loop: without an
// explorer the trajectory tracker follows the flight's waypoints and the run ends
// `hold_after_s` after the path; with one, the explorer observes SLAM points at the map rate,
// plans at the planning rate and its path commands replace the tracker's path, until the
// duration ends. The loop never calls back: after each step() the caller reads what the tick
// produced (a frame, tracks, SLAM points) from the returned record.
//
// Seams: the renderer (`camera_stream.renderer`: the OSMesa fisheye renderer, or the null
// renderer) and the feature source (`perception.source`: the KLT tracker, or the ground-truth
// oracle) are interfaces; the defaults are the benchmark's real parts.
#pragma once

#include <chrono>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/common/clock.h"
#include "core/eval/run_hash.h"
#include "core/explorer/explorer.h"
#include "core/perception/feature_tracker.h"
#include "core/perception/slam_points.h"
#include "sim/physics/quadrotor_sim.h"
#include "sim/physics/se3_controller.h"
#include "sim/physics/trajectory_tracker.h"
#include "sim/render/frame_renderer.h"
#include "sim/sensors/imu_model.h"
#include "sim/sensors/vio_drift.h"
#include "tools/engine/flight_spec.h"
#include "tools/engine/perception_pipeline.h"
#include "tools/engine/records.h"

namespace msb {

class WorldTruth;

/// Outcome and records of a run of the loop.
struct FlightResult {
  RunStatus status = RunStatus::kCompleted;
  std::optional<CollisionEvent> collision;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  int64_t ticks = 0;
  int64_t collision_detection_steps = 0;  ///< physics steps that ran MuJoCo's collision detection (contact gate)
  std::vector<TrajectoryRow> trajectory;  ///< at trajectory_rate_hz
  std::vector<ImuSample> imu;             ///< every IMU sample
  int frames_rendered = 0;
  RenderTiming render_time_sum;   ///< summed over frames
  double perception_wait_ms = 0;  ///< the loop's wall time waiting for its second thread (recorded only)
  int threads = 1;                ///< threads the loop ran on
  double tracking_rms_m = 0.0;    ///< RMS |estimate − reference| over controller ticks
  double tracking_max_m = 0.0;    ///< max |estimate − reference|
  double distance_flown_m = 0.0;  ///< ground truth, summed every tick
  double final_drift_m = 0.0;     ///< |estimated − true position| at the end
  double vio_lost_at_s = -1.0;    ///< when tracking was declared lost
  int perception_frames = 0;      ///< frames the feature source processed
  double tracked_sum = 0.0;       ///< features tracked from the previous frame, summed
  int tracked_min = -1;           ///< fewest tracked in a frame (after the first)
  int frames_few_tracks = 0;      ///< frames below perception.lost_min_tracks
  bool path_finished = false;
  std::string gl_description;                  ///< what rendered the frames
  std::map<std::string, int> mujoco_warnings;  ///< MuJoCo's warning counters (non-zero ones)
  uint64_t trajectory_hash = 0;                ///< FNV-1a over the trajectory rows
  std::vector<ComputeCall> compute_calls;      ///< the explorer's calls with their charged latencies

  /// Simulated seconds per wall-clock second.
  double realTimeFactor() const { return wall_time_s > 0 ? sim_time_s / wall_time_s : 0.0; }
};

/// What the loop needs besides the flight: the optional explorer and its rates.
struct LoopSetup {
  Explorer* explorer = nullptr;       ///< exploration method (not owned), or none: fly spec.waypoints
  const WorldTruth* truth = nullptr;  ///< ground truth (needed by the oracle feature source only)
  double trajectory_rate_hz = 50.0;   ///< trajectory rows
  double map_rate_hz = 5.0;           ///< explorer map updates (latest SLAM points)
  double planning_rate_hz = 5.0;      ///< explorer planning steps
  /// How the explorer's calls are charged (timing, replay, machine factor; the loop fills in
  /// its rates).
  ComputeSetup compute;
};

/// What one tick produced; pointers are valid until the next step().
struct TickRecord {
  int64_t tick = 0;                         ///< the tick that was stepped
  double t_s = 0.0;                         ///< its simulated time
  bool completed = false;                   ///< false: the run ended inside this tick
  const CameraFrame* frame = nullptr;       ///< rendered this tick
  const TrackFrame* tracks = nullptr;       ///< perception results used this tick ...
  const SlamPointsFrame* points = nullptr;  ///< ... and their SLAM points ...
  const CameraFrame* perceived = nullptr;   ///< ... computed from this frame (latency_frames earlier)
  const RenderTiming* render = nullptr;     ///< render split of this tick's frame
  bool map_updated = false;                 ///< the explorer integrated SLAM points (of `perceived`)
  TickTiming timing;
};

/// One run of the closed loop (see file comment).
class ClosedLoop {
 public:
  /// Builds every component from its validated config (loads the world). Throws ConfigError
  /// or std::runtime_error (world, GL context).
  ClosedLoop(const FlightSpec& spec, const LoopSetup& setup);
  ~ClosedLoop();
  ClosedLoop(const ClosedLoop&) = delete;
  ClosedLoop& operator=(const ClosedLoop&) = delete;

  /// True until the run has ended (duration, collision, divergence, tracking loss, path done).
  bool running() const;
  /// Steps one tick through every stage.
  const TickRecord& step();
  /// Runs to the end.
  void run();
  /// The latest rendered frame, shared: it stays valid (and unchanged) while held.
  std::shared_ptr<const CameraFrame> sharedFrame() const { return frame_; }
  /// Final records (timing, hash); call once the run has ended. Completes the perception still
  /// in flight (its map updates count; its paths are never flown) and rethrows its error.
  const FlightResult& finish();
  /// Waits until every frame's perception started so far has run (the explorer may then be read
  /// from this thread). Results do not depend on when it is called.
  void sync();
  /// Ends the run where it is (an interrupt, an error): the perception not yet started is
  /// dropped, a job running on the second thread completes, no result in flight is used.
  void abandon();
  /// abandon() that waits at most `limit` for the second thread (PerceptionPipeline::abandonWithin):
  /// false if its job is stuck, and then the loop must never be destroyed.
  bool abandonWithin(std::chrono::milliseconds limit);
  /// Called while the loop waits for its second thread (PerceptionPipeline::setWaitHook).
  void setWaitHook(std::function<void()> hook) {
    if (pipeline_) pipeline_->setWaitHook(std::move(hook));
  }

  /// The result so far (status, trajectory rows, distance).
  const FlightResult& result() const { return result_; }
  /// The physics (model/data for tools; the ground truth of the current state).
  const QuadrotorSim& sim() const { return sim_; }
  /// The camera model.
  const FisheyeCamera& camera() const { return camera_; }
  /// The loop's tick rate.
  int physicsHz() const { return spec_.physics.physics_hz; }
  /// The trajectory tracker's current reference (estimate frame).
  const TrajectoryReference& reference() const { return trajectory_.reference(); }
  /// The VIO estimate and the ground truth of the vehicle at the last tick.
  const Odometry& estimate() const { return est_; }
  const Odometry& groundTruth() const { return gt_; }
  /// Simulated time of the explorer's last path command (-1: none yet).
  double lastPathTimeS() const { return last_path_t_s_; }
  /// State hash of everything the loop has decided so far (trajectory rows and the
  /// current true state), for in-process determinism checks.
  uint64_t stateHash() const;

 private:
  // The stages of a tick, in order.
  bool stepPhysicsAndContacts();
  void estimateState();
  void renderFrame();
  // Applies the perception due now (tracks, drift, path, tracking loss); false when tracking
  // has been lost.
  bool usePerception();
  // Starts the perception of the frame just rendered, with the map update and plan due on its tick.
  void launchPerception();
  // Throws MethodOutputError for a waypoint that is not finite or lies beyond
  // kMaxWaypointDistanceM of the start (core/explorer/output_limits.h).
  void checkWaypoints(const PathCommand& cmd, const VehicleState& vs) const;
  // Starts following the paths whose planning step has ended by this tick.
  void takeEndedPaths();
  void trackAndControl();
  void recordTick();
  void actuateAndSampleImu();
  // Tracking statistics and loss of a frame's tracks (`frame_tick`: the frame's tick); false
  // when tracking has been lost.
  bool trackingHolds(const TrackFrame& tracks, int64_t frame_tick);
  // The vehicle state the explorer plans on (this tick).
  VehicleState vehicleState() const;
  void startPipeline(const FlightSpec& spec, const LoopSetup& setup);

  // Configuration (fixed for the loop's life) ...
  const FlightSpec spec_;
  const LoopSetup setup_;
  // Components.
  QuadrotorSim sim_;
  FisheyeCamera camera_;
  std::unique_ptr<FrameRenderer> renderer_;
  Se3Controller controller_;
  TrajectoryTracker trajectory_;
  ImuModel imu_;
  VioDriftModel vio_;
  std::unique_ptr<FeatureSource> features_;
  std::unique_ptr<SlamPointEstimator> slam_;
  std::optional<ImageNoise> image_noise_;  // front-end degradation (none by default)
  std::optional<LandmarkJitter> jitter_;
  // Schedules (integer ticks).
  int64_t ctrl_div_ = 1, lost_ticks_ = 0, max_ticks_ = 0, hold_ticks_ = 0;
  double ctrl_dt_ = 0.0;
  std::optional<RateSchedule> cam_schedule_, imu_schedule_, traj_schedule_, map_schedule_, plan_schedule_;
  // State between ticks.
  Vec4 cmd_ = Vec4::Zero();
  Odometry gt_, est_;
  std::shared_ptr<CameraFrame> frame_ = std::make_shared<CameraFrame>();  // shared with Python views
  FramePool frame_pool_;                                                  // frames to render into again
  int64_t frame_index_ = -1;                                              // index of the latest rendered frame
  RenderTiming frame_timing_;
  int64_t few_tracks_since_ = -1, finished_tick_ = -1, last_imu_tick_ = 0, err_count_ = 0;
  double err_sq_sum_ = 0.0, last_path_t_s_ = -1.0;
  std::deque<std::pair<int64_t, PathCommand>> ending_paths_;  // planned paths by the tick they take effect
  Vec3 last_position_;
  bool ended_ = false, finished_ = false;
  TickRecord record_;
  FlightResult result_;
  std::chrono::steady_clock::time_point wall_start_;
  // Perception (when on): last, so that its worker stops before the stages it borrows go.
  std::unique_ptr<PerceptionPipeline> pipeline_;
};

}  // namespace msb
