#include "core/methods/hover_turn/hover_turn_explorer.h"

#include <algorithm>
#include <cmath>

namespace msb {

void HoverTurnConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

HoverTurnExplorer::HoverTurnExplorer(const HoverTurnConfig& config, const ExplorerContext& context)
    : config_(checkValid(config)),
      hover_m_(context.start.translation() + Vec3(0, 0, config.takeoff_altitude_m)),
      start_yaw_rad_(yawOf(context.start.linear())),
      nearest_point_m_(config.max_radius_m + config.margin_m) {}

void HoverTurnExplorer::observe(const SlamPointsFrame& frame) {
  // Only the turn maps: the sphere is centred at the hover point.
  if (phase_ != Phase::kTurn) return;
  for (const SlamPoint& p : frame.points) {
    nearest_point_m_ = std::min(nearest_point_m_, (p.p_W - hover_m_).norm());
    ++points_seen_;
  }
}

std::optional<PathCommand> HoverTurnExplorer::plan(const VehicleState& s) {
  // Each phase sends one path and moves on when the tracker has finished it.
  if (sent_ && !s.path_finished) return std::nullopt;
  if (sent_) {
    sent_ = false;
    if (phase_ == Phase::kClimb)
      phase_ = Phase::kTurn;
    else if (phase_ == Phase::kTurn && ++turn_steps_done_ * config_.turn_step_deg >= 360.0)
      phase_ = Phase::kDescend;
    else if (phase_ == Phase::kDescend)
      phase_ = Phase::kHold;
  }
  if (phase_ == Phase::kHold) return std::nullopt;
  Waypoint w{hover_m_, start_yaw_rad_};
  if (phase_ == Phase::kTurn)
    w.heading_rad =
        std::remainder(start_yaw_rad_ + (turn_steps_done_ + 1) * config_.turn_step_deg * M_PI / 180.0, 2.0 * M_PI);
  if (phase_ == Phase::kDescend) w.position_m.z() += config_.land_altitude_m - config_.takeoff_altitude_m;
  sent_ = true;
  return PathCommand{s.tick, {w}};
}

ExplorerSnapshot HoverTurnExplorer::snapshot() const {
  ExplorerSnapshot snap;
  // After the turn: the ball around the hover point that holds no observed point.
  const double r = std::min(config_.max_radius_m, nearest_point_m_ - config_.margin_m);
  if (turn_steps_done_ > 0 && r > 0.0) snap.free_space.push_back({0, hover_m_, r, FreeSpaceElement::Footprint::kDisk});
  return snap;
}

std::map<std::string, double> HoverTurnExplorer::counters() const {
  Counters<HoverTurnCounter> c(kHoverTurnCounterNames);
  c[HoverTurnCounter::kTurnSteps] = double(turn_steps_done_);
  c[HoverTurnCounter::kPointsSeen] = double(points_seen_);
  return c.toMap();
}

}  // namespace msb
