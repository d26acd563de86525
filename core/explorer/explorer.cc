#include "core/explorer/explorer.h"

#include <cmath>

#include "core/explorer/takeoff.h"

namespace msb {

PathCommand sendPath(const VehicleState& vehicle, std::vector<Waypoint> waypoints, std::vector<Vec3>& last_path,
                     double& paths_sent) {
  PathCommand cmd{vehicle.tick, std::move(waypoints)};
  last_path = {vehicle.reference.position_m};
  for (const auto& wp : cmd.waypoints) last_path.push_back(wp.position_m);
  ++paths_sent;
  return cmd;
}

TakeoffSequence::TakeoffSequence(const Pose& start, double altitude_m, double forward_m)
    : start_(start.translation()), yaw_(yawOf(start.linear())), altitude_m_(altitude_m), forward_m_(forward_m) {}

std::optional<std::vector<Waypoint>> TakeoffSequence::step(bool path_finished) {
  const Vec3 up = start_ + Vec3(0, 0, altitude_m_);
  switch (phase_) {
    case Phase::kClimb:
      if (!sent_) return sent_ = true, std::vector<Waypoint>{{up, yaw_}};
      if (path_finished) phase_ = Phase::kForward, sent_ = false;
      return std::nullopt;
    case Phase::kForward:
      if (!sent_)
        return sent_ = true, std::vector<Waypoint>{{up + forward_m_ * Vec3(std::cos(yaw_), std::sin(yaw_), 0), yaw_}};
      if (path_finished) phase_ = Phase::kDone;
      return std::nullopt;
    case Phase::kDone:
      break;
  }
  return std::nullopt;
}

}  // namespace msb
