// Everything one run of the closed loop needs: world, start pose, waypoints (scripted flights),
// vehicle, sensors, renderer and perception settings. Plain struct with defaults and
// validation; YAML is converted in tools/msbench/yaml_config.cc only.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/camera/fisheye_camera.h"
#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "core/perception/feature_tracker.h"
#include "core/perception/frontend_degradation.h"
#include "core/perception/oracle_features.h"
#include "core/perception/slam_points.h"
#include "sim/physics/quadrotor_sim.h"
#include "sim/physics/se3_controller.h"
#include "sim/physics/trajectory_tracker.h"
#include "sim/render/fisheye_renderer.h"
#include "sim/sensors/imu_model.h"
#include "sim/sensors/vio_drift.h"

namespace msb {

/// What renders the camera's frames (`camera_stream.renderer`).
enum class RendererKind {
  kFisheye,  ///< the OSMesa cube-map fisheye renderer
  kBlank,    ///< uniform grey frames, no GL (tests; a named shortcut, never the default)
};
/// The words of RendererKind (core/common/word_enum.h).
constexpr auto wordsOf(RendererKind) {
  return std::array{std::pair{RendererKind::kFisheye, "fisheye"}, std::pair{RendererKind::kBlank, "blank"}};
}

/// Where the features of a frame come from (`perception.source`).
enum class FeatureSourceKind {
  kKlt,     ///< the KLT tracker on the rendered image
  kOracle,  ///< ground-truth features (a named shortcut, never the default)
};
/// The words of FeatureSourceKind.
constexpr auto wordsOf(FeatureSourceKind) {
  return std::array{std::pair{FeatureSourceKind::kKlt, "klt"}, std::pair{FeatureSourceKind::kOracle, "oracle"}};
}

/// Camera stream settings of a flight.
struct CameraStreamConfig {
  bool enabled = true;                             ///< render fisheye frames at all
  RendererKind renderer = RendererKind::kFisheye;  ///< the OSMesa fisheye renderer, or blank frames
  double rate_hz = 15.0;                           ///< render rate (first tick at or after each period)
  int save_every_n = 15;                           ///< write every N-th rendered frame as PNG (0 = none)

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("enabled", s.enabled);
    v.key("rate_hz", s.rate_hz, Limits::range(0.1, 500.0));
    v.key("save_every_n", s.save_every_n, Limits::nonNegative());
    v.key("renderer", s.renderer);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Perception in the loop: tracker + SLAM points on every rendered frame, tracking loss.
struct PerceptionConfig {
  bool enabled = false;                                ///< run the tracker and triangulation (vio-eval, missions)
  FeatureSourceKind source = FeatureSourceKind::kKlt;  ///< the tracker, or ground truth
  OracleFeatureConfig oracle;                          ///< settings of the oracle source
  int lost_min_tracks = 15;                            ///< fewer features tracked from the previous frame than this ...
  double lost_after_s = 2.0;                           ///< ... for this long ends the run as vio_lost
  /// Camera frames between an image and the use of what was computed from it (tracks, SLAM
  /// points, the map update and the plan of that frame's tick): 0 = the same tick (sequential
  /// loop); k ≥ 1 = k frames later (pipelined loop; docs/performance.md, "Two cores").
  int latency_frames = 0;
  /// Threads of the pipelined loop: 1 runs each frame's perception on the loop's thread, 2 on a
  /// second thread while the loop renders the next frame. Same results either way (the latency
  /// fixes when results are used); needs latency_frames ≥ 1.
  int threads = 1;

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("enabled", s.enabled);
    v.key("source", s.source);
    v.group("oracle", s.oracle);
    v.key("lost_min_tracks", s.lost_min_tracks, Limits::range(0, 10000));
    v.key("lost_after_s", s.lost_after_s, Limits::positive());
    v.key("latency_frames", s.latency_frames, Limits::range(0, 30));
    v.key("threads", s.threads, Limits::range(1, 2));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// Everything `msbench fly` needs.
struct FlightSpec {
  std::string world_path;     ///< MJCF world file (absolute after loading), or
  std::string world_name;     ///< a world name (worlds/<name>/), resolved when flying
  bool held_out = false;      ///< the world is drawn with the evaluator's salt (docs/worlds.md, "Held-out worlds")
  uint64_t seed = 1;          ///< scenario seed for all RNG streams
  double duration_s = 60.0;   ///< hard limit on simulated time
  double hold_after_s = 2.0;  ///< keep flying this long after the path is finished
  Vec3 start_position_m = Vec3(0, 0, 0.05);  ///< body origin at start (0.05 m = on the ground)
  double start_yaw_rad = 0.0;                ///< heading at start
  std::vector<Waypoint> waypoints;           ///< the scripted path
  double controller_hz = 500.0;              ///< controller rate (divides physics_hz)
  PhysicsConfig physics;                     ///< physics and vehicle
  Se3ControllerConfig controller;            ///< controller gains
  TrajectoryTrackerConfig trajectory;        ///< tracker and limits
  ImuConfig imu;                             ///< IMU noise and rate
  FisheyeCameraConfig camera;                ///< camera model
  FisheyeRendererConfig render;              ///< render settings
  CameraStreamConfig camera_stream;          ///< render rate and frame saving
  VioDriftConfig vio_drift;                  ///< the drifting pose estimate the controller flies on
  PerceptionConfig perception;               ///< tracker, SLAM points, tracking loss
  FeatureTrackerConfig tracker;              ///< feature tracker
  SlamPointsConfig slam_points;              ///< triangulation
  FrontendDegradationConfig frontend;        ///< degradation axes of the front end (off by default)

  /// The keys of a flight's sections, each once with the values it accepts (`world`, `start` and `trajectory.waypoints`
  /// are read in tools/config).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("seed", s.seed, Limits::nonNegative());
    v.key("duration_s", s.duration_s, Limits::range(0.01, 36000.0));
    v.key("hold_after_s", s.hold_after_s, Limits::nonNegative());
    v.key("controller_hz", s.controller_hz, Limits::range(50.0, 5000.0));
    v.group("trajectory", s.trajectory);
    v.group("physics", s.physics);
    v.group("controller", s.controller);
    v.group("imu", s.imu);
    v.group("camera", s.camera);
    v.group("render", s.render);
    v.group("conditions", s.render.conditions);
    v.group("camera_stream", s.camera_stream);
    v.group("vio_drift", s.vio_drift);
    v.group("perception", s.perception);
    v.group("tracker", s.tracker);
    v.group("slam_points", s.slam_points);
    v.group("frontend", s.frontend);
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

}  // namespace msb
