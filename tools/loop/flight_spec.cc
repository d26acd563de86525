#include "tools/loop/flight_spec.h"

#include <filesystem>

namespace msb {

void CameraStreamConfig::validate(ConfigChecker& c) const {
  c.inRange("rate_hz", rate_hz, 0.1, 500.0);
  c.require(save_every_n >= 0, "save_every_n", "must be >= 0");
  c.require(renderer == "fisheye" || renderer == "blank", "renderer",
            "must be fisheye or blank, got '" + renderer + "'");
}

void PerceptionConfig::validate(ConfigChecker& c) const {
  c.inRange("lost_min_tracks", lost_min_tracks, 0, 10000);
  c.positive("lost_after_s", lost_after_s);
  c.require(source == "klt" || source == "oracle", "source", "must be klt or oracle, got '" + source + "'");
  c.nested("oracle", oracle);
  c.inRange("latency_frames", latency_frames, 0, 30);
  c.inRange("threads", threads, 1, 2);
  c.require(threads == 1 || latency_frames >= 1, "threads",
            "2 needs latency_frames >= 1 (with no latency there is nothing to overlap)");
}

void FlightSpec::validate(ConfigChecker& c) const {
  c.require(!world_path.empty() || !world_name.empty(), "world", "is required");
  c.require(isValidUtf8(world_path) && isValidUtf8(world_name), "world", "the path is not valid UTF-8");
  c.require(world_path.empty() || std::filesystem::is_regular_file(world_path), "world",
            "file not found: " + world_path);
  c.inRange("duration_s", duration_s, 0.01, 36000.0);
  c.nonNegative("hold_after_s", hold_after_s);
  c.inRange("controller_hz", controller_hz, 50.0, physics.physics_hz);
  c.require(std::abs(physics.physics_hz / controller_hz - std::round(physics.physics_hz / controller_hz)) < 1e-9,
            "controller_hz", "must divide physics.physics_hz");
  c.require(camera_stream.rate_hz <= physics.physics_hz, "camera_stream.rate_hz", "must not exceed physics.physics_hz");
  c.nested("physics", physics);
  c.nested("controller", controller);
  c.nested("trajectory", trajectory);
  c.nested("imu", imu);
  c.nested("camera", camera);
  c.nested("render", render);
  c.nested("camera_stream", camera_stream);
  c.nested("vio_drift", vio_drift);
  c.nested("perception", perception);
  c.nested("tracker", tracker);
  c.nested("slam_points", slam_points);
  c.nested("frontend", frontend);
  if (frontend.drift_scale != 1.0)  // the scaled drift model must itself be valid
    c.nested("vio_drift (scaled by frontend.drift_scale)", scaledDrift(vio_drift, frontend.drift_scale));
  c.require(frontend.mistrack_share == 0.0 || perception.source == "klt", "frontend.mistrack_share",
            "mis-tracks are the KLT tracker's: the oracle source has pixel_noise_px instead");
  c.require(!perception.enabled || camera_stream.enabled, "perception.enabled", "needs camera_stream.enabled");
  c.require(!perception.enabled || perception.source != "klt" || camera_stream.renderer != "blank",
            "camera_stream.renderer",
            "'blank' draws no images: the klt tracker needs the fisheye renderer "
            "(or perception.source: oracle)");
}

}  // namespace msb
