#include "sim/physics/trajectory_tracker.h"

#include <algorithm>
#include <cmath>

namespace msb {

TrajectoryLimits TrajectoryLimits::preset(const std::string& name) {
  if (name == "medium") return {4.0, 2.0, 10.0, 1.0};
  if (name == "fast") return {8.0, 4.0, 20.0, 2.0};
  throw ConfigError("limits", "unknown preset '" + name + "' (expected medium or fast)");
}

void TrajectoryLimits::validate(ConfigChecker& c) const { checkFields(*this, c); }

void TrajectoryTrackerConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.nonNegative("heading_min_speed_mps", heading_min_speed_mps);
  c.positive("arrive_tolerance_m", arrive_tolerance_m);
}

TrajectoryTracker::TrajectoryTracker(const TrajectoryTrackerConfig& config, const Vec3& start_m, double yaw_rad)
    : config_(checkValid(config)) {
  ref_.position_m = start_m;
  ref_.yaw_rad = wrapAngle(yaw_rad);
  heading_unwrapped_ = ref_.yaw_rad;
  if (config_.generator == "mrs") mrs_.emplace(config_.mrs);
}

void TrajectoryTracker::setPath(const std::vector<Waypoint>& waypoints) {
  if (mrs_) return generate(waypoints);
  points_ = {ref_.position_m};
  headings_ = {std::nullopt};
  for (const auto& w : waypoints) {
    // Merge coincident waypoints, keeping the later heading.
    if ((w.position_m - points_.back()).norm() < 1e-6) {
      if (w.heading_rad) headings_.back() = w.heading_rad;
      continue;
    }
    points_.push_back(w.position_m);
    headings_.push_back(w.heading_rad);
  }
  cumulative_.assign(points_.size(), 0.0);
  for (size_t i = 1; i < points_.size(); ++i)
    cumulative_[i] = cumulative_[i - 1] + (points_[i] - points_[i - 1]).norm();

  // Corner speeds: rounding radius from the turn angle and the available cut length.
  const auto& lim = config_.limits;
  corner_speed_.assign(points_.size(), lim.max_speed_mps);
  for (size_t i = 1; i + 1 < points_.size(); ++i) {
    const Vec3 a = (points_[i] - points_[i - 1]).normalized();
    const Vec3 b = (points_[i + 1] - points_[i]).normalized();
    const double theta = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
    if (theta < 1e-4) continue;
    const double cut = std::min({config_.corner_cut_m, 0.5 * (cumulative_[i] - cumulative_[i - 1]),
                                 0.5 * (cumulative_[i + 1] - cumulative_[i])});
    const double radius = cut / (2.0 * std::tan(0.5 * std::min(theta, 3.0)));
    // Half the acceleration limit: the other half absorbs the reference's velocity lag.
    corner_speed_[i] = std::min(lim.max_speed_mps, std::sqrt(0.5 * lim.max_accel_mps2 * radius));
  }
  corner_speed_.back() = 0.0;
  segment_ = 0;
  s_proj_ = 0.0;
  finished_ = points_.size() < 2 && !headings_.back();
}

Vec3 TrajectoryTracker::pointAt(double s) const {
  if (points_.size() < 2) return points_.front();
  const auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  const size_t i = std::clamp<size_t>(it - cumulative_.begin(), 1, points_.size() - 1);
  const double len = cumulative_[i] - cumulative_[i - 1];
  const double t = std::clamp((s - cumulative_[i - 1]) / len, 0.0, 1.0);
  return points_[i - 1] + t * (points_[i] - points_[i - 1]);
}

double TrajectoryTracker::speedLimit(double s, double end_dist) const {
  // Braking uses 60 % of the acceleration limit: margin for the jerk limit and lag.
  const double a_brake = 0.6 * config_.limits.max_accel_mps2;
  double v = config_.limits.max_speed_mps;
  for (size_t i = segment_ + 1; i < points_.size(); ++i) {
    double d = std::max(0.0, cumulative_[i] - s);
    if (i + 1 == points_.size()) d = std::max(d, end_dist);  // overshoot: brake towards the end
    if (2.0 * a_brake * d > v * v) break;                    // this and later corners cannot bind
    v = std::min(v, std::sqrt(corner_speed_[i] * corner_speed_[i] + 2.0 * a_brake * d));
  }
  return v;
}

const TrajectoryReference& TrajectoryTracker::update(double dt) {
  if (mrs_) {
    followSamples(dt);
    return ref_;
  }
  if (points_.empty()) points_ = {ref_.position_m}, headings_ = {std::nullopt}, cumulative_ = {0.0};
  advanceProjection();
  const Carrot carrot = desiredVelocity();
  integrateTowards(carrot.v_des, dt);
  const double yaw_err = steerHeading(dt);
  const bool at_end = carrot.s >= cumulative_.back() && carrot.dist < 0.5;
  finished_ =
      at_end && carrot.dist < config_.arrive_tolerance_m && ref_.velocity_mps.norm() < 0.05 && std::abs(yaw_err) < 0.02;
  return ref_;
}

bool TrajectoryTracker::sharpAfter(size_t seg) const {
  const size_t nseg = points_.size() - 1;
  if (seg + 1 >= nseg) return false;
  const Vec3 in = (points_[seg + 1] - points_[seg]).normalized();
  const Vec3 out = (points_[seg + 2] - points_[seg + 1]).normalized();
  return (in + out).norm() < 1.0;
}

void TrajectoryTracker::advanceProjection() {
  // Advance the projection of the reference onto the path (monotonic along the path). A rounded
  // corner never reaches the end of its segment, so the next segment takes over once the
  // reference crosses the corner's bisector plane. Sharp turns (> 120°, e.g. reversals) are not
  // rounded: the look-ahead stops at the vertex and the next segment starts once the reference
  // is there.
  const Vec3& p = ref_.position_m;
  const size_t nseg = points_.size() - 1;
  while (nseg > 0) {
    const Vec3& A = points_[segment_];
    const Vec3& B = points_[segment_ + 1];
    const Vec3 AB = B - A;
    const double t = std::clamp((p - A).dot(AB) / AB.squaredNorm(), 0.0, 1.0);
    s_proj_ = std::max(s_proj_, cumulative_[segment_] + t * AB.norm());
    if (segment_ + 1 < nseg) {
      const Vec3 in = AB.normalized(), out = (points_[segment_ + 2] - B).normalized();
      Vec3 n = in + out;
      if (n.norm() < 0.2) n = in;  // (nearly) reversing: pass the vertex first
      const bool at_sharp_vertex = sharpAfter(segment_) && (p - B).norm() < 0.3;
      if (t >= 1.0 || (p - B).dot(n) >= 0.0 || at_sharp_vertex) {
        ++segment_;
        s_proj_ = std::max(s_proj_, cumulative_[segment_]);
        continue;
      }
    }
    break;
  }
}

TrajectoryTracker::Carrot TrajectoryTracker::desiredVelocity() const {
  // Desired velocity: towards the look-ahead point, at the speed that can still brake for
  // every corner and the end; a proportional approach once the look-ahead reaches the end.
  const auto& lim = config_.limits;
  const Vec3& p = ref_.position_m;
  const Vec3& v = ref_.velocity_mps;
  const double total = cumulative_.back();
  const double lookahead = config_.lookahead_base_m + config_.lookahead_per_speed_s * v.norm();
  const double s_limit = sharpAfter(segment_) ? cumulative_[segment_ + 1] : total;
  Carrot c;
  c.s = std::min(s_proj_ + lookahead, s_limit);
  const Vec3 to_carrot = pointAt(c.s) - p;
  c.dist = to_carrot.norm();
  // The limit is taken where the reference will be once its velocity has caught up
  // (first-order velocity lag plus acceleration build-up under the jerk limit).
  const double lag_s = 1.0 / config_.velocity_gain_per_s + lim.max_accel_mps2 / lim.max_jerk_mps3;
  double speed = speedLimit(s_proj_ + v.norm() * lag_s, (points_.back() - p).norm());
  if (c.s >= s_limit) speed = std::min(speed, 1.2 * c.dist + 0.3 * (s_limit < total));
  c.v_des = c.dist > 1e-9 ? Vec3(to_carrot / c.dist * speed) : Vec3::Zero();
  return c;
}

void TrajectoryTracker::integrateTowards(const Vec3& v_des, double dt) {
  // Jerk- and acceleration-limited double integrator towards v_des.
  const auto& lim = config_.limits;
  Vec3& p = ref_.position_m;
  Vec3& v = ref_.velocity_mps;
  Vec3& a = ref_.accel_mps2;
  Vec3 a_des = config_.velocity_gain_per_s * (v_des - v);
  if (a_des.norm() > lim.max_accel_mps2) a_des *= lim.max_accel_mps2 / a_des.norm();
  Vec3 da = a_des - a;
  const double max_da = lim.max_jerk_mps3 * dt;
  if (da.norm() > max_da) da *= max_da / da.norm();
  a += da;
  v += a * dt;
  if (v.norm() > lim.max_speed_mps) v *= lim.max_speed_mps / v.norm();
  p += v * dt;
}

double TrajectoryTracker::steerHeading(double dt) {
  // Heading: the next waypoint's goal heading, else the direction of travel, else hold.
  const auto& lim = config_.limits;
  const Vec3& v = ref_.velocity_mps;
  const size_t next = std::min(segment_ + 1, points_.size() - 1);
  double target = ref_.yaw_rad;
  if (headings_[next]) {
    target = *headings_[next];
  } else if (Vec2(v.x(), v.y()).norm() > config_.heading_min_speed_mps) {
    target = std::atan2(v.y(), v.x());
  }
  const double yaw_err = wrapAngle(target - ref_.yaw_rad);
  double rate = std::clamp(config_.yaw_gain_per_s * yaw_err, -lim.max_yaw_rate_radps, lim.max_yaw_rate_radps);
  // Limit yaw acceleration to 4x the rate limit per second for a smooth heading.
  const double max_dr = 4.0 * lim.max_yaw_rate_radps * dt;
  rate = std::clamp(rate, ref_.yaw_rate_radps - max_dr, ref_.yaw_rate_radps + max_dr);
  ref_.yaw_rate_radps = rate;
  ref_.yaw_rad = wrapAngle(ref_.yaw_rad + rate * dt);
  return yaw_err;
}

void TrajectoryTracker::generate(const std::vector<Waypoint>& waypoints) {
  // From the tracker's current command, as the generator takes it (prepareInitialCondition).
  MrsInitialState init;
  init.reference = ref_;
  init.reference.yaw_rad = heading_unwrapped_;
  init.jerk_mps3 = jerk_;
  init.yaw_accel_radps2 = yaw_accel_;
  init.moving = !finished_;
  generated_ = mrs_->generate(init, waypoints);
  sample_t_s_ = 0.0;
  finished_ = false;
}

void TrajectoryTracker::followSamples(double dt) {
  // The reference between the two samples around the trajectory's time; the last one held at rest.
  const auto& s = generated_.samples;
  if (s.empty()) return;
  sample_t_s_ += dt;
  const double pos = sample_t_s_ / generated_.dt_s;
  const size_t i = size_t(std::floor(pos));
  if (i + 1 >= s.size()) {
    const MrsSample& e = s.back();
    ref_.position_m = e.position_m;
    ref_.velocity_mps = ref_.accel_mps2 = jerk_ = Vec3::Zero();
    heading_unwrapped_ = e.heading_rad;
    ref_.yaw_rate_radps = yaw_accel_ = 0.0;
    finished_ = true;
  } else {
    const double f = pos - double(i);
    const MrsSample &a = s[i], &b = s[i + 1];
    ref_.position_m = a.position_m + f * (b.position_m - a.position_m);
    ref_.velocity_mps = a.velocity_mps + f * (b.velocity_mps - a.velocity_mps);
    ref_.accel_mps2 = a.accel_mps2 + f * (b.accel_mps2 - a.accel_mps2);
    jerk_ = a.jerk_mps3 + f * (b.jerk_mps3 - a.jerk_mps3);
    heading_unwrapped_ = a.heading_rad + f * (b.heading_rad - a.heading_rad);
    ref_.yaw_rate_radps = a.heading_rate_radps + f * (b.heading_rate_radps - a.heading_rate_radps);
    yaw_accel_ = a.heading_accel_radps2 + f * (b.heading_accel_radps2 - a.heading_accel_radps2);
  }
  ref_.yaw_rad = wrapAngle(heading_unwrapped_);
}

}  // namespace msb
