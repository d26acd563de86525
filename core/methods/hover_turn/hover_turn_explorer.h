// hover_turn: the smallest exploration method, an example and a template for new methods
// (docs/architecture.md, "Adding a method"). It takes off, turns on the spot in steps of
// `turn_step_deg` (one full turn), then descends to `land_altitude_m` above the start and holds
// there. (Touching the ground in flight is a contact and ends a run, so it stops just above it.)
// Its map is one free-space sphere around the hover point, as large as the nearest SLAM point
// seen during the turn allows: the ball that holds no observed point. It answers to no row of
// the paper; a smoke test of the Explorer interface.
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/common/config_fields.h"
#include "core/explorer/counters.h"
#include "core/explorer/explorer.h"

namespace msb {

/// The settings of hover_turn (`method.type: hover_turn`).
struct HoverTurnConfig {
  double takeoff_altitude_m = 2.0;  ///< climb above the start
  double turn_step_deg = 45.0;      ///< heading step of the turn (a full turn in 360/step steps)
  double land_altitude_m = 0.3;     ///< final hover height above the start
  double max_radius_m = 5.0;        ///< cap of the free-space sphere
  double margin_m = 0.5;            ///< kept between the sphere and the nearest point

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("takeoff_altitude_m", s.takeoff_altitude_m, Limits::range(0.3, 50.0));
    v.key("turn_step_deg", s.turn_step_deg, Limits::range(1.0, 180.0));
    v.key("land_altitude_m", s.land_altitude_m, Limits::range(0.1, 50.0));
    v.key("max_radius_m", s.max_radius_m, Limits::positive());
    v.key("margin_m", s.margin_m, Limits::nonNegative());
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// The example method's counters (metrics.json → counters), each named once beside its enumerator.
enum class HoverTurnCounter { kTurnSteps, kPointsSeen, kCount };
/// The JSON names of HoverTurnCounter, in its order.
inline constexpr std::array<const char*, size_t(HoverTurnCounter::kCount)> kHoverTurnCounterNames = {"turn_steps",
                                                                                                     "points_seen"};

/// Take off, turn once, descend; one free-space sphere around the hover point.
class HoverTurnExplorer : public Explorer {
 public:
  /// Throws ConfigError if the config is invalid.
  HoverTurnExplorer(const HoverTurnConfig& config, const ExplorerContext& context);

  void observe(const SlamPointsFrame& frame) override;
  std::optional<PathCommand> plan(const VehicleState& vehicle) override;
  ExplorerSnapshot snapshot() const override;
  std::map<std::string, double> counters() const override;

 private:
  enum class Phase { kClimb, kTurn, kDescend, kHold };

  // Configuration (fixed for the explorer's life) ...
  const HoverTurnConfig config_;
  const Vec3 hover_m_;  ///< the turn's position (start + takeoff altitude)
  const double start_yaw_rad_;
  // ... and state.
  Phase phase_ = Phase::kClimb;
  bool sent_ = false;  ///< the current phase's path was sent
  int turn_steps_done_ = 0;
  double nearest_point_m_;  ///< distance of the nearest SLAM point seen during the turn
  int points_seen_ = 0;
};

}  // namespace msb
