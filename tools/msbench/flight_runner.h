// Runs one scripted flight: MuJoCo quadrotor, controller, trajectory tracker, IMU and fisheye
// camera stepped by the integer tick clock in the fixed order of DESIGN §2. Until the VIO
// model exists the controller flies on ground truth.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tools/msbench/flight_spec.h"

namespace msb {

/// One row of trajectory.csv.
struct TrajectoryRow {
  double t_s;
  Vec3 position_m;       ///< ground truth
  Quat orientation;      ///< ground truth
  Vec3 velocity_mps;     ///< ground truth
  Vec3 est_position_m;   ///< VIO estimate
  double est_yaw_rad;    ///< VIO estimate
  Vec3 ref_position_m;   ///< trajectory reference (estimate frame)
  double ref_yaw_rad;
};

/// What perception produced for one camera frame (with the truth needed to evaluate it).
struct PerceptionSample {
  const CameraFrame& frame;       ///< the rendered image (pose = ground truth)
  const TrackFrame& tracks;       ///< tracker output
  const SlamPointsFrame& points;  ///< SLAM points (estimate frame)
  double tracker_ms;              ///< wall time of the tracker (recorded only)
  double triangulation_ms;        ///< wall time of the SLAM-point update (recorded only)
  double render_ms;               ///< wall time of rendering the frame
};

/// Outcome and records of a flight.
struct FlightResult {
  std::string status = "completed";     ///< completed | collided | vio_lost | diverged
  std::optional<CollisionEvent> collision;
  double sim_time_s = 0.0;
  double wall_time_s = 0.0;
  int64_t ticks = 0;
  std::vector<TrajectoryRow> trajectory;  ///< at trajectory_rate_hz
  std::vector<ImuSample> imu;             ///< every IMU sample
  int frames_rendered = 0;
  RenderTiming render_time_sum;           ///< summed over frames
  double tracking_rms_m = 0.0;            ///< RMS |GT − reference| over controller ticks
  double tracking_max_m = 0.0;            ///< max |GT − reference|
  double distance_flown_m = 0.0;
  double final_drift_m = 0.0;             ///< |estimated − true position| at the end
  double vio_lost_at_s = -1.0;            ///< when tracking was declared lost
  bool path_finished = false;
  std::string gl_description;
  uint64_t trajectory_hash = 0;           ///< FNV-1a over the trajectory rows' bytes

  /// Simulated seconds per wall-clock second.
  double realTimeFactor() const { return wall_time_s > 0 ? sim_time_s / wall_time_s : 0.0; }
};

/// Called for every rendered frame (index counts rendered frames from 0).
using FrameCallback = std::function<void(const CameraFrame&, int index)>;

/// Called once per simulated second with the simulated time and the wall time so far.
using ProgressCallback = std::function<void(double sim_s, double wall_s)>;

/// Called for every frame processed by perception (when spec.perception.enabled).
using PerceptionCallback = std::function<void(const PerceptionSample&)>;

/// What a closed-loop autopilot sees each tick (after perception, before the trajectory step).
struct AutopilotInput {
  int64_t tick;
  const Odometry& estimate;             ///< VIO estimate of the body
  const SlamPointsFrame* points;        ///< this tick's SLAM points, or null if no frame was processed
  const TrajectoryTracker& trajectory;  ///< the tracker (reference, finished)
};

/// Closed loop: returns a new path to follow (replacing the current one), or none.
using AutopilotCallback = std::function<std::optional<std::vector<Waypoint>>(const AutopilotInput&)>;

/// Optional observers of a flight.
struct FlightObservers {
  FrameCallback on_frame;
  ProgressCallback on_progress;
  PerceptionCallback on_perception;
  AutopilotCallback autopilot;  ///< if set, the flight ignores hold_after_s and runs to its limit
  double trajectory_rate_hz = 50.0;
};

/// Runs the flight to its end. Throws std::runtime_error if the world cannot be loaded.
FlightResult runFlight(const FlightSpec& spec, const FlightObservers& observers = {});

/// Hash of trajectory rows (positions, orientations, velocities, time).
uint64_t hashTrajectory(const std::vector<TrajectoryRow>& rows);

}  // namespace msb
