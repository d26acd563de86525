#include "tools/engine/flight_spec.h"

#include <filesystem>

namespace msb {

void CameraStreamConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

void PerceptionConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(threads == 1 || latency_frames >= 1, "threads",
            "2 needs latency_frames >= 1 (with no latency there is nothing to overlap)");
}

void FlightSpec::validate(ConfigChecker& c) const {
  c.require(!world_path.empty() || !world_name.empty(), "world", "is required");
  c.require(isValidUtf8(world_path) && isValidUtf8(world_name), "world", "the path is not valid UTF-8");
  c.require(world_path.empty() || std::filesystem::is_regular_file(world_path), "world",
            "file not found: " + world_path);
  checkFields(*this, c);
  c.require(controller_hz <= physics.physics_hz, "controller_hz", "must not exceed physics.physics_hz");
  c.require(std::abs(physics.physics_hz / controller_hz - std::round(physics.physics_hz / controller_hz)) < 1e-9,
            "controller_hz", "must divide physics.physics_hz");
  c.require(camera_stream.rate_hz <= physics.physics_hz, "camera_stream.rate_hz", "must not exceed physics.physics_hz");
  if (frontend.drift_scale != 1.0)  // the scaled drift model must itself be valid
    c.nested("vio_drift (scaled by frontend.drift_scale)", scaledDrift(vio_drift, frontend.drift_scale));
  c.require(frontend.mistrack_share == 0.0 || perception.source == FeatureSourceKind::kKlt, "frontend.mistrack_share",
            "mis-tracks are the KLT tracker's: the oracle source has pixel_noise_px instead");
  c.require(!perception.enabled || camera_stream.enabled, "perception.enabled", "needs camera_stream.enabled");
  c.require(!perception.enabled || perception.source != FeatureSourceKind::kKlt ||
                camera_stream.renderer != RendererKind::kBlank,
            "camera_stream.renderer",
            "'blank' draws no images: the klt tracker needs the fisheye renderer "
            "(or perception.source: oracle)");
}

}  // namespace msb
