// Trajectory tracker: turns a path of waypoints (with optional headings) into a smooth
// position/velocity/acceleration/yaw reference under speed, acceleration, jerk and yaw-rate
// limits. The reference is a jerk-limited double integrator that pursues a look-ahead point on
// the path; its speed is capped so it can brake for every upcoming corner and for the end.
// Corner speed: a turn of angle θ is rounded with radius R = L_c / (2 tan(θ/2)), where L_c is the
// corner-cut length (or half the shorter adjacent segment), and taken at v = sqrt(a_max R).
#pragma once

#include <string>
#include <vector>

#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "sim/physics/mrs_trajectory_generator.h"

namespace msb {

/// Motion limits of the reference (presets "medium" and "fast" of the reference code).
struct TrajectoryLimits {
  double max_speed_mps = 4.0;       ///< speed along the path
  double max_accel_mps2 = 2.0;      ///< norm of the reference acceleration
  double max_jerk_mps3 = 10.0;      ///< norm of the acceleration change rate
  double max_yaw_rate_radps = 1.0;  ///< heading rate

  /// The named preset ("medium": 4 m/s, 2 m/s², 1 rad/s; "fast": 8 m/s, 4 m/s², 2 rad/s).
  /// Throws ConfigError for an unknown name.
  static TrajectoryLimits preset(const std::string& name);
  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("max_speed_mps", s.max_speed_mps, Limits::range(0.1, 30.0));
    v.key("max_accel_mps2", s.max_accel_mps2, Limits::range(0.1, 20.0));
    v.key("max_jerk_mps3", s.max_jerk_mps3, Limits::range(0.5, 200.0));
    v.key("max_yaw_rate_radps", s.max_yaw_rate_radps, Limits::range(0.05, 10.0));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Tracker configuration.
struct TrajectoryTrackerConfig {
  TrajectoryLimits limits;              ///< motion limits
  double corner_cut_m = 2.0;            ///< length over which a sharp corner is rounded
  double lookahead_base_m = 0.8;        ///< pursuit look-ahead at rest
  double lookahead_per_speed_s = 0.25;  ///< extra look-ahead per m/s of speed
  double velocity_gain_per_s = 4.0;     ///< how fast the reference velocity converges
  double yaw_gain_per_s = 2.0;          ///< heading error to yaw rate
  double heading_min_speed_mps = 0.5;   ///< below this speed the heading is held
  double arrive_tolerance_m = 0.05;     ///< path is finished within this distance at rest
  /// Who turns a path into the reference: "msbench" (the pursuit above) or "mrs" (the authors'
  /// MRS trajectory generator, sampled, the reference following its samples).
  std::string generator = "msbench";
  MrsGeneratorConfig mrs;  ///< the MRS generator's constraint set and deviation limit (generator "mrs")

  /// The keys, each once with the values it accepts (heading_min_speed_mps and arrive_tolerance_m are fixed: no keys).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.group("limits", s.limits);
    v.key("corner_cut_m", s.corner_cut_m, Limits::positive());
    v.key("lookahead_base_m", s.lookahead_base_m, Limits::positive());
    v.key("lookahead_per_speed_s", s.lookahead_per_speed_s, Limits::nonNegative());
    v.key("velocity_gain_per_s", s.velocity_gain_per_s, Limits::positive());
    v.key("yaw_gain_per_s", s.yaw_gain_per_s, Limits::positive());
    v.key("generator", s.generator, Choices{"msbench", "mrs"});
    v.group("mrs", s.mrs);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Smooth reference generator following the last PathCommand.
class TrajectoryTracker {
 public:
  /// Starts at rest at `start` position and yaw. Throws ConfigError if invalid.
  TrajectoryTracker(const TrajectoryTrackerConfig& config, const Vec3& start_m, double yaw_rad);

  /// Replaces the path; the reference continues smoothly from its current state.
  void setPath(const std::vector<Waypoint>& waypoints);
  /// Advances the reference by dt seconds and returns it.
  const TrajectoryReference& update(double dt_s);
  /// The current reference.
  const TrajectoryReference& reference() const { return ref_; }
  /// True when the last waypoint is reached at rest with its heading (or no path given).
  bool finished() const { return finished_; }
  /// Number of waypoints of the current path already passed (generator "msbench").
  size_t waypointsPassed() const { return segment_; }
  /// The last trajectory the MRS generator made (generator "mrs"; empty samples before the first).
  const MrsTrajectory& generated() const { return generated_; }

 private:
  // Speed that can still brake for every upcoming corner and for the end (`end_dist` is the
  // straight-line distance to the last point, used once the reference has overshot it).
  double speedLimit(double s_along, double end_dist) const;
  Vec3 pointAt(double s) const;
  // The steps of update(): the projection advanced along the path; the look-ahead point and the
  // velocity towards it; the jerk-limited integration; the heading (returns its error).
  struct Carrot {
    double s = 0.0, dist = 0.0;  // look-ahead arc length, distance to it
    Vec3 v_des = Vec3::Zero();
  };
  bool sharpAfter(size_t seg) const;  // the turn after segment `seg` is sharper than 120°
  void advanceProjection();
  Carrot desiredVelocity() const;
  void integrateTowards(const Vec3& v_des, double dt);
  double steerHeading(double dt);
  // Generator "mrs": the samples from the current state; following them.
  void generate(const std::vector<Waypoint>& waypoints);
  void followSamples(double dt);

  TrajectoryTrackerConfig config_;
  TrajectoryReference ref_;
  std::vector<Vec3> points_;  // path polyline: start point then waypoints
  std::vector<std::optional<double>> headings_;
  std::vector<double> cumulative_;  // arc length at each polyline vertex
  std::vector<double> corner_speed_;
  size_t segment_ = 0;   // index of the segment holding the projection
  double s_proj_ = 0.0;  // arc length of the reference's projection on the path
  bool finished_ = true;
  std::optional<MrsTrajectoryGenerator> mrs_;  // generator "mrs"
  MrsTrajectory generated_;
  double sample_t_s_ = 0.0;   // time along generated_
  Vec3 jerk_ = Vec3::Zero();  // the reference's jerk and heading acceleration (the generator's start)
  double yaw_accel_ = 0.0;
  double heading_unwrapped_ = 0.0;
};

}  // namespace msb
