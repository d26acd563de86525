// The start of every exploration method: climb vertically above the start, then fly a short
// straight stretch ahead, so that the first SLAM points get parallax before the method plans.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "core/common/messages.h"

namespace msb {

/// Take-off phases, stepped once per planning step.
class TakeoffSequence {
 public:
  /// `start`: body pose on the ground; climb by `altitude_m`, then fly `forward_m` ahead.
  TakeoffSequence(const Pose& start, double altitude_m, double forward_m)
      : start_(start.translation()), yaw_(yawOf(start.linear())), altitude_m_(altitude_m), forward_m_(forward_m) {}

  /// True once both phases are done.
  bool done() const { return phase_ == Phase::kDone; }

  /// One planning step: the path to send now, if any (`path_finished`: the last one is done).
  std::optional<std::vector<Waypoint>> step(bool path_finished) {
    const Vec3 up = start_ + Vec3(0, 0, altitude_m_);
    switch (phase_) {
      case Phase::kClimb:
        if (!sent_) return sent_ = true, std::vector<Waypoint>{{up, yaw_}};
        if (path_finished) phase_ = Phase::kForward, sent_ = false;
        return std::nullopt;
      case Phase::kForward:
        if (!sent_) return sent_ = true, std::vector<Waypoint>{{up + forward_m_ * Vec3(std::cos(yaw_), std::sin(yaw_), 0), yaw_}};
        if (path_finished) phase_ = Phase::kDone;
        return std::nullopt;
      case Phase::kDone:
        break;
    }
    return std::nullopt;
  }

 private:
  enum class Phase { kClimb, kForward, kDone };
  Vec3 start_;
  double yaw_, altitude_m_, forward_m_;
  Phase phase_ = Phase::kClimb;
  bool sent_ = false;
};

}  // namespace msb
