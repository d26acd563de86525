// The start of every exploration method: climb vertically above the start, then fly a short
// straight stretch ahead, so that the first SLAM points get parallax before the method plans. The
// configuration is shared by the methods that fly it (their configs derive from TakeoffConfig, so
// the keys stay where they are in a scenario).
#pragma once

#include <optional>
#include <vector>

#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "core/explorer/explorer.h"

namespace msb {

/// The take-off's two legs (the reference's sessions: 3 m up, then goforward5m.sh's 4 m ahead).
struct TakeoffConfig {
  double takeoff_altitude_m = 3.0;  ///< climb to this height above the start (the reference's 3 m)
  double start_forward_m = 4.0;     ///< then fly this far straight ahead (the reference's goforward5m.sh: 4 m)

  /// The take-off keys (a derived config's table includes them: `TakeoffConfig::fields(s, v)`).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("takeoff_altitude_m", s.takeoff_altitude_m, Limits::range(0.3, 50.0));
    v.key("start_forward_m", s.start_forward_m, Limits::nonNegative());
  }
};

/// The predicted-path check every method flies with: stop and re-plan when the first
/// `check_ahead_m` of the path sent pass within `check_clearance_m` of a mapped obstacle. Shared
/// by the methods' configs (they derive from it, so the keys stay where they are in a scenario).
struct PathCheckConfig {
  double check_ahead_m = 5.0;      ///< predicted-path check length ...
  double check_clearance_m = 1.0;  ///< ... and clearance from mapped obstacles

  /// The path-check keys (a derived config's table includes them: `PathCheckConfig::fields(s, v)`).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("check_ahead_m", s.check_ahead_m, Limits::nonNegative());
    v.key("check_clearance_m", s.check_clearance_m, Limits::nonNegative());
  }
};

/// Take-off phases, stepped once per planning step.
class TakeoffSequence {
 public:
  /// `start`: body pose on the ground; climb by `altitude_m`, then fly `forward_m` ahead.
  TakeoffSequence(const Pose& start, double altitude_m, double forward_m);
  /// The same from a method's take-off configuration.
  TakeoffSequence(const Pose& start, const TakeoffConfig& config)
      : TakeoffSequence(start, config.takeoff_altitude_m, config.start_forward_m) {}

  /// True once both phases are done.
  bool done() const { return phase_ == Phase::kDone; }

  /// One planning step: the path to send now, if any (`path_finished`: the last one is done).
  std::optional<std::vector<Waypoint>> step(bool path_finished);

 private:
  enum class Phase { kClimb, kForward, kDone };
  Vec3 start_;
  double yaw_, altitude_m_, forward_m_;
  Phase phase_ = Phase::kClimb;
  bool sent_ = false;
};

/// The take-off as the first part of a method's plan(): while it is not done, the path it sends
/// now, if any (`send(waypoints)` makes the method's command); `explore()` once it is done.
template <class Send, class Explore>
std::optional<PathCommand> takeOffThenExplore(TakeoffSequence& takeoff, const VehicleState& s, Send&& send,
                                              Explore&& explore) {
  if (takeoff.done()) return explore();
  if (auto w = takeoff.step(s.path_finished)) return send(std::move(*w));
  return std::nullopt;
}

}  // namespace msb
