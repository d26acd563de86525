#include "tools/config/flight_keys.h"
#include "tools/config/flight_yaml.h"

#include <yaml-cpp/yaml.h>

#include "tools/config/yaml_reader.h"

#include <cmath>
#include <filesystem>

namespace msb {
namespace {

namespace fs = std::filesystem;

constexpr double kDeg = M_PI / 180.0;

void readVehicle(MapReader r, QuadrotorConfig& q) {
  r.read("mass_kg", q.mass_kg);
  r.read("inertia_kgm2", q.inertia_kgm2);
  r.read("arm_length_m", q.arm_length_m);
  r.read("rotor_radius_m", q.rotor_radius_m);
  r.read("max_thrust_n", q.max_thrust_n);
  r.read("yaw_torque_per_thrust_m", q.yaw_torque_per_thrust_m);
  r.read("motor_time_constant_s", q.motor_time_constant_s);
  r.finish();
}

void readPhysics(MapReader r, PhysicsConfig& p) {
  r.read("physics_hz", p.physics_hz);
  r.read("takeoff_clearance_m", p.takeoff_clearance_m);
  if (r.has("vehicle")) readVehicle(r.sub("vehicle"), p.vehicle);
  r.finish();
}

void readController(MapReader r, Se3ControllerConfig& c) {
  r.read("k_position", c.k_position);
  r.read("k_velocity", c.k_velocity);
  r.read("k_attitude", c.k_attitude);
  r.read("k_rate", c.k_rate);
  r.read("max_tilt_deg", c.max_tilt_deg);
  r.finish();
}

void readLimits(MapReader r, TrajectoryLimits& l) {
  r.read("max_speed_mps", l.max_speed_mps);
  r.read("max_accel_mps2", l.max_accel_mps2);
  r.read("max_jerk_mps3", l.max_jerk_mps3);
  r.read("max_yaw_rate_radps", l.max_yaw_rate_radps);
  r.finish();
}

// Waypoints: each either [x, y, z] or {position: [x, y, z], heading_deg: h}.
std::vector<Waypoint> readWaypoints(const YAML::Node& n, const std::string& key) {
  if (!n.IsSequence()) throw ConfigError(key, "expected a list of waypoints");
  std::vector<Waypoint> out;
  size_t i = 0;
  for (const YAML::Node& item : n) {  // iterators: indexing a yaml-cpp sequence is linear
    const std::string k = key + "[" + std::to_string(i++) + "]";
    Waypoint w;
    if (item.IsSequence()) {
      // [x, y, z] (no wrapping node: assigning nodes merges yaml-cpp's memory, quadratic in lists)
      MapReader(YAML::Node(YAML::NodeType::Map), "").value(item, k, w.position_m);
    } else {
      MapReader r(item, k + ".");
      if (!r.read("position", w.position_m)) throw ConfigError(k + ".position", "is required");
      double h;
      if (r.read("heading_deg", h)) w.heading_rad = h * kDeg;
      r.finish();
    }
    out.push_back(w);
  }
  return out;
}

void readTrajectory(MapReader r, FlightSpec& s) {
  auto& t = s.trajectory;
  if (r.has("limits")) {
    const YAML::Node n = r.raw("limits");
    if (n.IsScalar()) {
      try {
        t.limits = TrajectoryLimits::preset(n.Scalar());
      } catch (const ConfigError& e) {
        throw ConfigError(r.keyName("limits"), e.issues().front().reason);
      }
    } else {
      readLimits(MapReader(n, r.keyName("limits") + "."), t.limits);
    }
  }
  if (r.has("waypoints")) s.waypoints = readWaypoints(r.raw("waypoints"), r.keyName("waypoints"));
  r.read("corner_cut_m", t.corner_cut_m);
  r.read("lookahead_base_m", t.lookahead_base_m);
  r.read("lookahead_per_speed_s", t.lookahead_per_speed_s);
  r.read("velocity_gain_per_s", t.velocity_gain_per_s);
  r.read("yaw_gain_per_s", t.yaw_gain_per_s);
  r.finish();
}

void readImu(MapReader r, ImuConfig& c) {
  r.read("rate_hz", c.rate_hz);
  r.read("accel_noise_density", c.accel_noise_density);
  r.read("accel_random_walk", c.accel_random_walk);
  r.read("gyro_noise_density", c.gyro_noise_density);
  r.read("gyro_random_walk", c.gyro_random_walk);
  r.finish();
}

void readCamera(MapReader r, FisheyeCameraConfig& c) {
  r.read("width_px", c.width_px);
  r.read("height_px", c.height_px);
  r.read("fx_px", c.fx_px);
  r.read("fy_px", c.fy_px);
  r.read("cx_px", c.cx_px);
  r.read("cy_px", c.cy_px);
  r.read("k", c.k);
  r.read("fov_deg", c.fov_deg);
  r.read("scale", c.scale);
  r.read("mount_position_B_m", c.mount_position_B_m);
  r.read("mount_pitch_down_deg", c.mount_pitch_down_deg);
  r.finish();
}

void readRender(MapReader r, FisheyeRendererConfig& c) {
  r.read("face_focal_ratio", c.face_focal_ratio);
  r.read("ambient", c.ambient);
  r.read("tessellation_slices", c.tessellation_slices);
  r.read("tessellation_stacks", c.tessellation_stacks);
  r.read("plane_grid_m", c.plane_grid_m);
  r.read("near_clip_m", c.near_clip_m);
  r.read("far_clip_m", c.far_clip_m);
  r.read("read_red_channel_only", c.read_red_channel_only);
  r.read("sky", c.sky);
  r.read("sun", c.sun);
  r.read("sun_ambient", c.sun_ambient);
  r.read("cull_per_face", c.cull_per_face);
  r.read("trilinear_textures", c.trilinear_textures);
  r.read("framebuffer_per_face", c.framebuffer_per_face);
  r.read("single_channel_textures", c.single_channel_textures);
  r.read("single_channel_framebuffer", c.single_channel_framebuffer);
  r.finish();
}

// conditions: {preset: NAME, <field>: value, ...}: a named preset, then overrides.
void readConditions(MapReader r, RenderConditions& c) {
  std::string preset;
  if (r.read("preset", preset)) {
    const auto p = conditionsPreset(preset);
    if (!p) {
      std::string names;
      for (const auto& n : conditionsPresetNames()) names += (names.empty() ? "" : ", ") + n;
      throw ConfigError(r.keyName("preset"), "unknown preset '" + preset + "' (known: " + names + ")");
    }
    c = *p;
  }
  r.read("sun_elevation_deg", c.sun_elevation_deg);
  r.read("sun_azimuth_deg", c.sun_azimuth_deg);
  r.read("sun_intensity", c.sun_intensity);
  r.read("sun_colour", c.sun_colour);
  r.read("ambient", c.ambient);
  r.read("sky_brightness", c.sky_brightness);
  r.read("fog_start_m", c.fog_start_m);
  r.read("fog_end_m", c.fog_end_m);
  r.read("fog_colour", c.fog_colour);
  r.finish();
  ConfigChecker checker(r.keyName("") + ".");
  c.validate(checker);
  if (!checker.issues().empty()) throw ConfigError(checker.issues());
}

void readCameraStream(MapReader r, CameraStreamConfig& c) {
  r.read("enabled", c.enabled);
  r.read("rate_hz", c.rate_hz);
  r.read("save_every_n", c.save_every_n);
  r.read("renderer", c.renderer);
  r.finish();
}

void readVioDrift(MapReader r, VioDriftConfig& c) {
  r.read("enabled", c.enabled);
  r.read("position_drift_fraction", c.position_drift_fraction);
  r.read("drift_rate_wander_per_sqrt_m", c.drift_rate_wander_per_sqrt_m);
  r.read("position_random_walk_m_per_sqrt_m", c.position_random_walk_m_per_sqrt_m);
  r.read("yaw_random_walk_deg_per_sqrt_m", c.yaw_random_walk_deg_per_sqrt_m);
  r.read("frame_position_noise_m", c.frame_position_noise_m);
  r.read("frame_yaw_noise_deg", c.frame_yaw_noise_deg);
  r.read("nominal_tracks", c.nominal_tracks);
  r.read("few_tracks_gain", c.few_tracks_gain);
  r.read("yaw_error_per_turn_deg_per_rad", c.yaw_error_per_turn_deg_per_rad);
  r.finish();
}

void readOracle(MapReader r, OracleFeatureConfig& c) {
  r.read("max_tracks", c.max_tracks);
  r.read("min_distance_px", c.min_distance_px);
  r.read("pixel_noise_px", c.pixel_noise_px);
  r.read("landmark_spacing_m", c.landmark_spacing_m);
  r.read("max_range_m", c.max_range_m);
  r.read("ground_margin_m", c.ground_margin_m);
  r.read("border_px", c.border_px);
  r.read("textureless_landmarks", c.textureless_landmarks);
  r.read("thin_landmarks", c.thin_landmarks);
  r.finish();
}

void readPerception(MapReader r, PerceptionConfig& c) {
  r.read("enabled", c.enabled);
  r.read("source", c.source);
  if (r.has("oracle")) readOracle(r.sub("oracle"), c.oracle);
  r.read("lost_min_tracks", c.lost_min_tracks);
  r.read("lost_after_s", c.lost_after_s);
  r.finish();
}

void readTracker(MapReader r, FeatureTrackerConfig& c) {
  r.read("max_tracks", c.max_tracks);
  r.read("grid_cols", c.grid_cols);
  r.read("grid_rows", c.grid_rows);
  r.read("fast_threshold", c.fast_threshold);
  r.read("min_distance_px", c.min_distance_px);
  r.read("klt_window_px", c.klt_window_px);
  r.read("klt_pyramid_levels", c.klt_pyramid_levels);
  r.read("klt_max_iterations", c.klt_max_iterations);
  r.read("fb_max_error_px", c.fb_max_error_px);
  r.read("ransac", c.ransac);
  r.read("ransac_threshold_px", c.ransac_threshold_px);
  r.read("ransac_max_angle_deg", c.ransac_max_angle_deg);
  r.read("ransac_min_pairs", c.ransac_min_pairs);
  r.read("border_px", c.border_px);
  r.read("equalize_histogram", c.equalize_histogram);
  r.finish();
}

void readSlamPoints(MapReader r, SlamPointsConfig& c) {
  r.read("min_parallax_deg", c.min_parallax_deg);
  r.read("pixel_sigma_px", c.pixel_sigma_px);
  r.read("max_reprojection_rms_px", c.max_reprojection_rms_px);
  r.read("max_relative_depth_std", c.max_relative_depth_std);
  r.read("max_depth_m", c.max_depth_m);
  r.read("min_depth_m", c.min_depth_m);
  r.read("max_points", c.max_points);
  r.read("max_observations", c.max_observations);
  r.read("min_observations", c.min_observations);
  r.read("max_iterations", c.max_iterations);
  r.finish();
}

}  // namespace

void readFlightKeys(MapReader& r, const fs::path& dir, FlightSpec& s) {
  std::string world;
  // A value ending in .xml is an MJCF file relative to this file; anything else a world name.
  if (r.read("world", world)) {
    if (fs::path(world).extension() == ".xml") s.world_path = (dir / world).lexically_normal().string();
    else s.world_name = world;
  }
  r.read("seed", s.seed);
  r.read("duration_s", s.duration_s);
  r.read("hold_after_s", s.hold_after_s);
  r.read("controller_hz", s.controller_hz);
  if (r.has("start")) {
    MapReader st = r.sub("start");
    st.read("position", s.start_position_m);
    double yaw_deg;
    if (st.read("yaw_deg", yaw_deg)) s.start_yaw_rad = yaw_deg * kDeg;
    st.finish();
  }
  if (r.has("trajectory")) readTrajectory(r.sub("trajectory"), s);
  if (r.has("physics")) readPhysics(r.sub("physics"), s.physics);
  if (r.has("controller")) readController(r.sub("controller"), s.controller);
  if (r.has("imu")) readImu(r.sub("imu"), s.imu);
  if (r.has("camera")) readCamera(r.sub("camera"), s.camera);
  if (r.has("render")) readRender(r.sub("render"), s.render);
  if (r.has("conditions")) readConditions(r.sub("conditions"), s.render.conditions);
  if (r.has("camera_stream")) readCameraStream(r.sub("camera_stream"), s.camera_stream);
  if (r.has("vio_drift")) readVioDrift(r.sub("vio_drift"), s.vio_drift);
  if (r.has("perception")) readPerception(r.sub("perception"), s.perception);
  if (r.has("tracker")) readTracker(r.sub("tracker"), s.tracker);
  if (r.has("slam_points")) readSlamPoints(r.sub("slam_points"), s.slam_points);
}

FlightSpec loadFlightSpec(const std::string& path) {
  const fs::path dir = fs::absolute(path).parent_path();
  return parseConfigFile<FlightSpec>(path, [&](MapReader& r, FlightSpec& s) {
    readFlightKeys(r, dir, s);
    r.finish();
    if (s.waypoints.empty()) throw ConfigError("trajectory.waypoints", "needs at least one waypoint");
  });
}

}  // namespace msb
