// The MRS trajectory generator (ctu-mrs/mrs_uav_trajectory_generation 1.0.4,
// src/mrs_trajectory_generation.cpp) as the authors' stack runs it under a path: the current
// tracker state prepended, waypoints closer than 5 cm dropped, a heading per waypoint, segment
// times from distance and heading (estimateSegmentTimes), Mellinger's redistribution of the times
// (NLopt LD_LBFGS, 10 evaluations), every segment stretched to meet the constraint set
// (scaleSegmentTimesToMeetConstraints), the trajectory sampled every 0.2 s, and segments whose
// samples leave the path by more than max_deviation split at their midpoint and solved again (up
// to 6 times). A trajectory 3× longer or 3× shorter than the "Baca" estimate falls back to
// constant-velocity sampling. docs/deviations.md, "Paths as the MRS generator flies them".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/common/config_fields.h"
#include "core/common/messages.h"

namespace msb {

/// A constraint set of the MRS constraint manager (mrs_uav_managers constraints.yaml): separate
/// horizontal, vertical and heading limits.
struct MrsConstraints {
  double horizontal_speed_mps = 4.0;  ///< `medium`
  double horizontal_accel_mps2 = 2.0;
  double horizontal_jerk_mps3 = 40.0;
  double vertical_speed_mps = 2.0;
  double vertical_accel_mps2 = 1.0;
  double vertical_jerk_mps3 = 40.0;
  double heading_speed_radps = 1.0;
  double heading_accel_radps2 = 1.0;
  double heading_jerk_radps3 = 20.0;

  /// The named set ("slow", "medium", "fast"), or nullopt.
  static std::optional<MrsConstraints> preset(const std::string& name);
  /// The keys, each once with the values it accepts.
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("horizontal_speed_mps", s.horizontal_speed_mps, Limits::range(0.1, 30.0));
    v.key("horizontal_accel_mps2", s.horizontal_accel_mps2, Limits::range(0.1, 20.0));
    v.key("horizontal_jerk_mps3", s.horizontal_jerk_mps3, Limits::range(0.5, 500.0));
    v.key("vertical_speed_mps", s.vertical_speed_mps, Limits::range(0.1, 30.0));
    v.key("vertical_accel_mps2", s.vertical_accel_mps2, Limits::range(0.1, 20.0));
    v.key("vertical_jerk_mps3", s.vertical_jerk_mps3, Limits::range(0.5, 500.0));
    v.key("heading_speed_radps", s.heading_speed_radps, Limits::range(0.05, 20.0));
    v.key("heading_accel_radps2", s.heading_accel_radps2, Limits::range(0.05, 50.0));
    v.key("heading_jerk_radps3", s.heading_jerk_radps3, Limits::range(0.05, 500.0));
  }
  /// Records invalid fields.
  void validate(ConfigChecker& c) const { checkFields(*this, c); }
};

/// The generator's settings (its public trajectory_generation.yaml; the constraint set).
struct MrsGeneratorConfig {
  MrsConstraints constraints;             ///< the constraint set the generator and tracker obey
  double max_deviation_m = 0.05;          ///< check_trajectory_deviation.max_deviation
  int max_deviation_iterations = 6;       ///< check_trajectory_deviation.max_iterations
  double min_waypoint_distance_m = 0.05;  ///< min_waypoint_distance
  double sampling_dt_s = 0.2;             ///< sampling_dt
  int max_evaluations = 10;               ///< the optimiser's max_iterations (NLopt maxeval)

  /// The keys, each once with the values it accepts (the rest are the generator's fixed values).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.group("constraints", s.constraints);
    v.key("max_deviation_m", s.max_deviation_m, Limits::range(0.001, 10.0));
  }
  /// Records invalid fields.
  void validate(ConfigChecker& c) const { checkFields(*this, c); }
};

/// A sample of the generated trajectory (every sampling_dt_s from the initial state).
struct MrsSample {
  Vec3 position_m = Vec3::Zero();
  Vec3 velocity_mps = Vec3::Zero();
  Vec3 accel_mps2 = Vec3::Zero();
  Vec3 jerk_mps3 = Vec3::Zero();
  double heading_rad = 0.0;  ///< unwrapped along the trajectory
  double heading_rate_radps = 0.0;
  double heading_accel_radps2 = 0.0;
};

/// The state the generator starts from (the tracker's current command).
struct MrsInitialState {
  TrajectoryReference reference;
  Vec3 jerk_mps3 = Vec3::Zero();
  double yaw_accel_radps2 = 0.0;
  bool moving = false;  ///< the tracker has a goal (then the first segment's deviation is not checked)
};

/// What one generation produced.
struct MrsTrajectory {
  std::vector<MrsSample> samples;  ///< at least one
  double dt_s = 0.2;               ///< the sampling interval
  bool fallback = false;           ///< constant-velocity fallback sampling was used
  int deviation_splits = 0;        ///< re-solves after splitting segments that left the path
  size_t waypoints = 0;            ///< waypoints after preprocessing and splitting
  double max_deviation_m = 0.0;    ///< largest deviation of a checked sample from its segment
  double baca_estimate_s = 0.0;    ///< the generator's "Baca" duration estimate
};

/// The MRS trajectory generator (docs/deviations.md).
class MrsTrajectoryGenerator {
 public:
  /// Throws ConfigError if invalid.
  explicit MrsTrajectoryGenerator(const MrsGeneratorConfig& config);

  /// The trajectory from `initial` through `waypoints` (headings filled as the authors' planner
  /// fills them where a waypoint has none: facing the next waypoint; the last faces as the one
  /// before it).
  MrsTrajectory generate(const MrsInitialState& initial, const std::vector<Waypoint>& waypoints) const;

  /// Segment time of the generator's estimateSegmentTimes (Euclidean, with the heading term
  /// 1.5·(Δψ/ω + 2ω/α) for Δψ > 45°), for a segment of `from` → `to` (x, y, z, heading).
  double euclideanSegmentTime(const Eigen::Vector4d& from, const Eigen::Vector4d& to) const;

 private:
  MrsGeneratorConfig config_;
};

}  // namespace msb
