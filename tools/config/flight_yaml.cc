#include "tools/config/flight_yaml.h"
#include "tools/config/flight_keys.h"

#include <yaml-cpp/yaml.h>

#include "core/common/types.h"
#include "tools/config/yaml_reader.h"
#include "tools/config/yaml_writer.h"

#include <cmath>
#include <filesystem>

namespace msb {
namespace {

namespace fs = std::filesystem;

template <class Keys>
void vehicleKeys(Keys r, QuadrotorConfig& q) {
  r.field("mass_kg", q.mass_kg);
  r.field("inertia_kgm2", q.inertia_kgm2);
  r.field("arm_length_m", q.arm_length_m);
  r.field("rotor_radius_m", q.rotor_radius_m);
  r.field("max_thrust_n", q.max_thrust_n);
  r.field("yaw_torque_per_thrust_m", q.yaw_torque_per_thrust_m);
  r.field("motor_time_constant_s", q.motor_time_constant_s);
  r.finish();
}

template <class Keys>
void physicsKeys(Keys r, PhysicsConfig& p) {
  r.field("physics_hz", p.physics_hz);
  r.field("takeoff_clearance_m", p.takeoff_clearance_m);
  r.field("contact_gate", p.contact_gate);
  if (r.has("vehicle")) vehicleKeys(r.sub("vehicle"), p.vehicle);
  r.finish();
}

template <class Keys>
void controllerKeys(Keys r, Se3ControllerConfig& c) {
  r.field("k_position", c.k_position);
  r.field("k_velocity", c.k_velocity);
  r.field("k_attitude", c.k_attitude);
  r.field("k_rate", c.k_rate);
  r.field("max_tilt_deg", c.max_tilt_deg);
  r.finish();
}

template <class Keys>
void limitsKeys(Keys r, TrajectoryLimits& l) {
  r.field("max_speed_mps", l.max_speed_mps);
  r.field("max_accel_mps2", l.max_accel_mps2);
  r.field("max_jerk_mps3", l.max_jerk_mps3);
  r.field("max_yaw_rate_radps", l.max_yaw_rate_radps);
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
      if (!r.field("position", w.position_m)) throw ConfigError(k + ".position", "is required");
      double h;
      if (r.field("heading_deg", h)) w.heading_rad = h * kDeg;
      r.finish();
    }
    out.push_back(w);
  }
  return out;
}

// The writer's waypoints: [x, y, z] or {position, heading_deg}.
YAML::Node waypointsNode(const std::vector<Waypoint>& waypoints) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (const Waypoint& w : waypoints) {
    if (!w.heading_rad) {
      list.push_back(MapWriter::encode(w.position_m));
      continue;
    }
    MapWriter m{YAML::Node(YAML::NodeType::Map)};
    m.field("position", w.position_m);
    m.field("heading_deg", exactDegrees(*w.heading_rad));
    list.push_back(m.node());
  }
  return list;
}

// limits: a preset name or a map; waypoints; tracker gains. The writer writes the limits as a map.
template <class Keys>
void trajectoryKeys(Keys r, FlightSpec& s) {
  auto& t = s.trajectory;
  if constexpr (Keys::kReading) {
    if (r.has("limits")) {
      const YAML::Node n = r.raw("limits");
      if (n.IsScalar()) {
        try {
          t.limits = TrajectoryLimits::preset(n.Scalar());
        } catch (const ConfigError& e) {
          throw ConfigError(r.keyName("limits"), e.issues().front().reason);
        }
      } else {
        limitsKeys(MapReader(n, r.keyName("limits") + "."), t.limits);
      }
    }
    if (r.has("waypoints")) s.waypoints = readWaypoints(r.raw("waypoints"), r.keyName("waypoints"));
  } else {
    limitsKeys(r.sub("limits"), t.limits);
    if (!s.waypoints.empty()) r.node()["waypoints"] = waypointsNode(s.waypoints);
  }
  r.field("corner_cut_m", t.corner_cut_m);
  r.field("lookahead_base_m", t.lookahead_base_m);
  r.field("lookahead_per_speed_s", t.lookahead_per_speed_s);
  r.field("velocity_gain_per_s", t.velocity_gain_per_s);
  r.field("yaw_gain_per_s", t.yaw_gain_per_s);
  r.finish();
}

template <class Keys>
void imuKeys(Keys r, ImuConfig& c) {
  r.field("rate_hz", c.rate_hz);
  r.field("accel_noise_density", c.accel_noise_density);
  r.field("accel_random_walk", c.accel_random_walk);
  r.field("gyro_noise_density", c.gyro_noise_density);
  r.field("gyro_random_walk", c.gyro_random_walk);
  r.finish();
}

template <class Keys>
void cameraKeys(Keys r, FisheyeCameraConfig& c) {
  r.field("width_px", c.width_px);
  r.field("height_px", c.height_px);
  r.field("fx_px", c.fx_px);
  r.field("fy_px", c.fy_px);
  r.field("cx_px", c.cx_px);
  r.field("cy_px", c.cy_px);
  r.field("k", c.k);
  r.field("fov_deg", c.fov_deg);
  r.field("scale", c.scale);
  r.field("mount_position_B_m", c.mount_position_B_m);
  r.field("mount_pitch_down_deg", c.mount_pitch_down_deg);
  r.field("clip_far_m", c.clip_far_m);
  r.finish();
}

template <class Keys>
void renderKeys(Keys r, FisheyeRendererConfig& c) {
  r.field("face_focal_ratio", c.face_focal_ratio);
  r.field("ambient", c.ambient);
  r.field("tessellation_slices", c.tessellation_slices);
  r.field("tessellation_stacks", c.tessellation_stacks);
  r.field("plane_grid_m", c.plane_grid_m);
  r.field("near_clip_m", c.near_clip_m);
  r.field("read_red_channel_only", c.read_red_channel_only);
  r.field("max_visible_geom_group", c.max_visible_geom_group);
  r.field("sky", c.sky);
  r.field("sun", c.sun);
  r.field("sun_ambient", c.sun_ambient);
  r.field("cull_per_face", c.cull_per_face);
  r.field("trilinear_textures", c.trilinear_textures);
  r.field("framebuffer_per_face", c.framebuffer_per_face);
  r.field("single_channel_textures", c.single_channel_textures);
  r.field("single_channel_framebuffer", c.single_channel_framebuffer);
  r.finish();
}

// `preset: NAME` of a section (read only: the writer writes every field instead): the named
// preset's values, which the section's other keys then override; an unknown name lists the known.
template <class Keys, class Config, class Lookup>
void presetKey(Keys& r, Config& c, Lookup lookup, const std::vector<std::string>& known) {
  std::string preset;
  if (!Keys::kReading || !r.field("preset", preset)) return;
  const std::optional<Config> p = lookup(preset);
  if (!p) {
    std::string names;
    for (const auto& n : known) names += (names.empty() ? "" : ", ") + n;
    throw ConfigError(r.keyName("preset"), "unknown preset '" + preset + "' (known: " + names + ")");
  }
  c = *p;
}

// conditions: {preset: NAME, <field>: value, ...}: a named preset, then overrides.
template <class Keys>
void conditionsKeys(Keys r, RenderConditions& c) {
  presetKey(r, c, conditionsPreset, conditionsPresetNames());
  r.field("sun_elevation_deg", c.sun_elevation_deg);
  r.field("sun_azimuth_deg", c.sun_azimuth_deg);
  r.field("sun_intensity", c.sun_intensity);
  r.field("sun_colour", c.sun_colour);
  r.field("ambient", c.ambient);
  r.field("sky_brightness", c.sky_brightness);
  r.field("fog_start_m", c.fog_start_m);
  r.field("fog_end_m", c.fog_end_m);
  r.field("fog_colour", c.fog_colour);
  r.finish();
  ConfigChecker checker(r.keyName("") + ".");
  c.validate(checker);
  if (!checker.issues().empty()) throw ConfigError(checker.issues());
}

template <class Keys>
void cameraStreamKeys(Keys r, CameraStreamConfig& c) {
  r.field("enabled", c.enabled);
  r.field("rate_hz", c.rate_hz);
  r.field("save_every_n", c.save_every_n);
  r.field("renderer", c.renderer);
  r.finish();
}

template <class Keys>
void vioDriftKeys(Keys r, VioDriftConfig& c) {
  r.field("enabled", c.enabled);
  r.field("position_drift_fraction", c.position_drift_fraction);
  r.field("drift_rate_wander_per_sqrt_m", c.drift_rate_wander_per_sqrt_m);
  r.field("position_random_walk_m_per_sqrt_m", c.position_random_walk_m_per_sqrt_m);
  r.field("yaw_random_walk_deg_per_sqrt_m", c.yaw_random_walk_deg_per_sqrt_m);
  r.field("frame_position_noise_m", c.frame_position_noise_m);
  r.field("frame_yaw_noise_deg", c.frame_yaw_noise_deg);
  r.field("nominal_tracks", c.nominal_tracks);
  r.field("few_tracks_gain", c.few_tracks_gain);
  r.field("yaw_error_per_turn_deg_per_rad", c.yaw_error_per_turn_deg_per_rad);
  r.finish();
}

template <class Keys>
void oracleKeys(Keys r, OracleFeatureConfig& c) {
  r.field("max_tracks", c.max_tracks);
  r.field("min_distance_px", c.min_distance_px);
  r.field("pixel_noise_px", c.pixel_noise_px);
  r.field("landmark_spacing_m", c.landmark_spacing_m);
  r.field("max_range_m", c.max_range_m);
  r.field("ground_margin_m", c.ground_margin_m);
  r.field("border_px", c.border_px);
  r.field("textureless_landmarks", c.textureless_landmarks);
  r.field("thin_landmarks", c.thin_landmarks);
  r.finish();
}

template <class Keys>
void perceptionKeys(Keys r, PerceptionConfig& c) {
  r.field("enabled", c.enabled);
  r.field("source", c.source);
  if (r.has("oracle")) oracleKeys(r.sub("oracle"), c.oracle);
  r.field("lost_min_tracks", c.lost_min_tracks);
  r.field("lost_after_s", c.lost_after_s);
  r.field("latency_frames", c.latency_frames);
  r.field("threads", c.threads);
  r.finish();
}

template <class Keys>
void trackerKeys(Keys r, FeatureTrackerConfig& c) {
  r.field("max_tracks", c.max_tracks);
  r.field("grid_cols", c.grid_cols);
  r.field("grid_rows", c.grid_rows);
  r.field("fast_threshold", c.fast_threshold);
  r.field("min_distance_px", c.min_distance_px);
  r.field("klt_window_px", c.klt_window_px);
  r.field("klt_pyramid_levels", c.klt_pyramid_levels);
  r.field("klt_max_iterations", c.klt_max_iterations);
  r.field("forward_backward_check", c.forward_backward_check);
  r.field("fb_max_error_px", c.fb_max_error_px);
  r.field("ransac", c.ransac);
  r.field("ransac_threshold_px", c.ransac_threshold_px);
  r.field("ransac_max_angle_deg", c.ransac_max_angle_deg);
  r.field("ransac_min_pairs", c.ransac_min_pairs);
  r.field("border_px", c.border_px);
  r.field("equalize_histogram", c.equalize_histogram);
  r.finish();
}

template <class Keys>
void slamPointsKeys(Keys r, SlamPointsConfig& c) {
  r.field("max_clones", c.max_clones);
  r.field("reference_rate_hz", c.reference_rate_hz);
  r.field("dt_slam_delay_s", c.dt_slam_delay_s);
  r.field("max_slam_in_update", c.max_slam_in_update);
  r.field("max_slam", c.max_slam);
  r.field("min_dist_m", c.min_dist_m);
  r.field("max_dist_m", c.max_dist_m);
  r.field("max_baseline", c.max_baseline);
  r.field("max_cond_number", c.max_cond_number);
  r.field("pixel_sigma_px", c.pixel_sigma_px);
  r.field("max_reprojection_rms_px", c.max_reprojection_rms_px);
  r.field("max_observations", c.max_observations);
  r.field("max_iterations", c.max_iterations);
  r.finish();
}

// frontend: {preset: NAME, <axis>: value, ...}: a named preset, then overrides.
template <class Keys>
void frontendKeys(Keys r, FrontendDegradationConfig& c) {
  presetKey(r, c, frontendPreset, frontendPresetNames());
  r.field("image_noise_sigma", c.image_noise_sigma);
  r.field("mistrack_share", c.mistrack_share);
  r.field("mistrack_px", c.mistrack_px);
  r.field("landmark_jitter_inv_depth", c.landmark_jitter_inv_depth);
  r.field("drift_scale", c.drift_scale);
  r.finish();
}

// The keys of a flight shared by reading and writing; `world` and `start` are the callers'.
template <class Keys>
void flightSectionKeys(Keys& r, FlightSpec& s) {
  r.field("seed", s.seed);
  r.field("duration_s", s.duration_s);
  r.field("hold_after_s", s.hold_after_s);
  r.field("controller_hz", s.controller_hz);
  if (r.has("trajectory")) trajectoryKeys(r.sub("trajectory"), s);
  if (r.has("physics")) physicsKeys(r.sub("physics"), s.physics);
  if (r.has("controller")) controllerKeys(r.sub("controller"), s.controller);
  if (r.has("imu")) imuKeys(r.sub("imu"), s.imu);
  if (r.has("camera")) cameraKeys(r.sub("camera"), s.camera);
  if (r.has("render")) renderKeys(r.sub("render"), s.render);
  if (r.has("conditions")) conditionsKeys(r.sub("conditions"), s.render.conditions);
  if (r.has("camera_stream")) cameraStreamKeys(r.sub("camera_stream"), s.camera_stream);
  if (r.has("vio_drift")) vioDriftKeys(r.sub("vio_drift"), s.vio_drift);
  if (r.has("perception")) perceptionKeys(r.sub("perception"), s.perception);
  if (r.has("tracker")) trackerKeys(r.sub("tracker"), s.tracker);
  if (r.has("slam_points")) slamPointsKeys(r.sub("slam_points"), s.slam_points);
  if (r.has("frontend")) frontendKeys(r.sub("frontend"), s.frontend);
}

}  // namespace

void readFlightKeys(MapReader& r, const fs::path& dir, FlightSpec& s) {
  std::string world;
  // A value ending in .xml is an MJCF file relative to this file; anything else a world name.
  if (r.read("world", world)) {
    if (fs::path(world).extension() == ".xml")
      s.world_path = (dir / world).lexically_normal().string();
    else
      s.world_name = world;
  }
  if (r.has("start")) {
    MapReader st = r.sub("start");
    st.read("position", s.start_position_m);
    double yaw_deg;
    if (st.read("yaw_deg", yaw_deg)) s.start_yaw_rad = yaw_deg * kDeg;
    st.finish();
  }
  flightSectionKeys(r, s);
}

void writeFlightKeys(MapWriter& w, const FlightSpec& spec, bool with_start) {
  FlightSpec s = spec;
  // The world as it was named: a world name, else the MJCF file (absolute).
  w.field("world", s.world_name.empty() ? s.world_path : s.world_name);
  if (with_start) {
    MapWriter st = w.sub("start");
    st.field("position", s.start_position_m);
    st.field("yaw_deg", exactDegrees(s.start_yaw_rad));
  }
  flightSectionKeys(w, s);
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
