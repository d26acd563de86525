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
  const auto types = methodTypes();
  std::string names;
  for (const auto& t : types) names += (names.empty() ? "" : ", ") + t;
  c.require(std::find(types.begin(), types.end(), method_type) != types.end(), "method.type",
            "unknown method '" + method_type + "' (known: " + names + ")");
  flight.validate(c);
  c.require(flight.perception.enabled, "perception.enabled", "must be true for a mission");
  c.require(flight.camera_stream.enabled, "camera_stream.enabled", "must be true for a mission");
  if (exploration_box)
    c.require((exploration_box->max.array() > exploration_box->min.array()).all(), "exploration_box",
              "max must exceed min on every axis");
  c.nested("method", monospheres);
  c.nested("mission", mission);
}

}  // namespace msb
