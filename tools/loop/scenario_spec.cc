#include "tools/loop/scenario_spec.h"

#include <algorithm>

namespace msb {

void MissionSettings::validate(ConfigChecker& c) const {
  c.inRange("map_rate_hz", map_rate_hz, 0.1, 100.0);
  c.inRange("planning_rate_hz", planning_rate_hz, 0.1, 100.0);
  c.inRange("metric_rate_hz", metric_rate_hz, 0.01, 100.0);
  c.inRange("trajectory_rate_hz", trajectory_rate_hz, 0.1, 500.0);
}

void ScenarioSpec::validate(ConfigChecker& c) const {
  c.require(bool(method.make), "method", "no exploration method chosen");
  flight.validate(c);
  c.require(flight.perception.enabled, "perception.enabled", "must be true for a mission");
  c.require(flight.camera_stream.enabled, "camera_stream.enabled", "must be true for a mission");
  if (exploration_box)
    c.require((exploration_box->max.array() > exploration_box->min.array()).all(), "exploration_box",
              "max must exceed min on every axis");
  c.nested("mission", mission);
}

}  // namespace msb
