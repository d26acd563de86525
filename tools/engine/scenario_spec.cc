#include "tools/engine/scenario_spec.h"

#include <algorithm>

namespace msb {

FlightSpec missionFlightDefaults() {
  FlightSpec f;
  f.duration_s = 1200.0;
  f.perception.enabled = true;
  // What a frame gives is used 3 frames (200 ms) later, as the reference's mapper lagged
  // (docs/architecture.md §2); its perception runs on a second thread.
  f.perception.latency_frames = 3;
  f.perception.threads = 2;
  f.camera_stream.save_every_n = 0;
  return f;
}

void MissionSettings::validate(ConfigChecker& c) const { checkFields(*this, c); }

void VideoSettings::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(height % 2 == 0, "height", "must be even (the encoder's 4:2:0 chroma), got " + std::to_string(height));
}

void ScenarioSpec::validate(ConfigChecker& c) const {
  c.require(bool(method.make), "method", "no exploration method chosen");
  flight.validate(c);
  c.require(flight.perception.enabled, "perception.enabled", "must be true for a mission");
  c.require(flight.camera_stream.enabled, "camera_stream.enabled", "must be true for a mission");
  c.require(flight.waypoints.empty(), "trajectory.waypoints",
            "a mission's path comes from its method; waypoints are for scripted flights (msbench fly)");
  if (exploration_box) {
    // At least one metric column across (2.5 m) and 1 m high; at most 10 km.
    const Vec3 size = exploration_box->max - exploration_box->min;
    c.require(size.x() >= 2.5 && size.y() >= 2.5 && size.z() >= 1.0, "exploration_box",
              "must be at least 2.5 m x 2.5 m (one coverage column) and 1 m high, got " + std::to_string(size.x()) +
                  " x " + std::to_string(size.y()) + " x " + std::to_string(size.z()) + " m");
    c.require(size.maxCoeff() <= 10000.0, "exploration_box", "must be at most 10 km on every axis");
  }
  c.nested("mission", mission);
  c.nested("video", video);
  c.nested("timing", timing);
  if (goals) {
    c.nested("goals", *goals);
    c.require(
        takesGoalChooser(method), "goals",
        "method.type '" + method.type + "' takes no goal chooser (its explorer has no goal or viewpoint chooser hook)");
  }
}

}  // namespace msb
