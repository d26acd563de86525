#include "sim/physics/mrs_trajectory_generator.h"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>

#include "sim/physics/polynomial_trajectory.h"

namespace msb {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTimeLowerBound = 0.01;  // kOptimizationTimeLowerBound
constexpr double kGradientStep = 0.1;     // getCostAndGradientMellinger's increment_time

// A waypoint of the generator: x, y, z, heading.
using Wp = Eigen::Vector4d;

// The smallest angle between two headings.
double headingDistance(double a, double b) { return std::abs(wrapAngle(a - b)); }

// The MRS Path with the current state prepended (optimize()), each waypoint's heading filled as
// the authors' planner fills it where msbench's has none, and unwrapped along the path.
std::vector<Wp> generatorWaypoints(const MrsInitialState& init, const std::vector<Waypoint>& in) {
  std::vector<Wp> out;
  const auto& ref = init.reference;
  out.push_back(Wp(ref.position_m.x(), ref.position_m.y(), ref.position_m.z(), ref.yaw_rad));
  double last = ref.yaw_rad;
  for (size_t i = 0; i < in.size(); ++i) {
    double h = last;
    if (in[i].heading_rad) {
      h = *in[i].heading_rad;
    } else if (i + 1 < in.size()) {
      // Front-flight heading: towards the next waypoint (local_navigator_module.py).
      const Vec3 d = in[i + 1].position_m - in[i].position_m;
      if (Vec2(d.x(), d.y()).norm() > 1e-6) h = std::atan2(d.y(), d.x());
    }
    // Unwrapped (sradians::unwrap against the previous heading).
    const double u = last + wrapAngle(h - last);
    out.push_back(Wp(in[i].position_m.x(), in[i].position_m.y(), in[i].position_m.z(), u));
    last = u;
  }
  return out;
}

// preprocessPath(): inner waypoints closer than `min_dist` to the last kept one are dropped.
std::vector<Wp> preprocess(const std::vector<Wp>& in, double min_dist) {
  std::vector<Wp> out;
  for (size_t i = 0; i < in.size(); ++i) {
    if (i > 0 && i + 1 < in.size() && (in[i].head<3>() - out.back().head<3>()).norm() < min_dist) continue;
    out.push_back(in[i]);
  }
  return out;
}

// The limits along a segment of inclination `incl` (estimateSegmentTimes*): the horizontal or
// vertical limit projected on the segment, whichever binds.
double alongSegment(double incl, double horizontal, double vertical) {
  if (std::abs(incl) > std::atan2(vertical, horizontal)) return std::abs(vertical / std::sin(incl));
  return std::abs(horizontal / std::cos(incl));
}

double inclination(const Wp& a, const Wp& b) {
  return std::atan2(b.z() - a.z(), std::hypot(b.x() - a.x(), b.y() - a.y()));
}

// The heading part of both estimates: 1.5·(Δψ/ω [less the ramps] + 2ω/α for Δψ > 45°).
double headingFixTime(double dist_rad, const MrsConstraints& c, double ramp_factor) {
  const double w = c.heading_speed_radps, a = c.heading_accel_radps2;
  double vel_t = (dist_rad - ramp_factor * w * w / a) / w;
  if (vel_t < 0) vel_t = dist_rad / w;
  const double acc_t = dist_rad > kPi / 4 ? 2.0 * w / a : 0.0;
  return 1.5 * (vel_t + acc_t);
}

// estimateSegmentTimesBaca(): acceleration ramps weighted by how much the path turns.
std::vector<double> bacaTimes(const std::vector<Wp>& w, const MrsConstraints& c) {
  std::vector<double> times;
  for (size_t i = 0; i + 1 < w.size(); ++i) {
    const double incl = inclination(w[i], w[i + 1]);
    const double v = alongSegment(incl, c.horizontal_speed_mps, c.vertical_speed_mps);
    const double a = alongSegment(incl, c.horizontal_accel_mps2, c.vertical_accel_mps2);
    const double j = alongSegment(incl, c.horizontal_jerk_mps3, c.vertical_jerk_mps3);
    const double dist = (w[i + 1].head<3>() - w[i].head<3>()).norm();
    auto turn = [&](const Wp& p, const Wp& q, const Wp& r) {
      const double s = (q.head<3>() - p.head<3>()).normalized().dot((r.head<3>() - q.head<3>()).normalized());
      return 1.0 - std::max(0.0, s);
    };
    const double c1 = i == 0 ? 1.0 : turn(w[i - 1], w[i], w[i + 1]);
    const double c2 = i + 2 == w.size() ? 1.0 : turn(w[i], w[i + 1], w[i + 2]);
    const double ramp = v / a + a / j, cap = std::sqrt(2.0 * dist / a);
    double t = dist / v + std::min(c1 * ramp, cap) + std::min(c2 * ramp, cap);
    t = std::max(t, 0.01);
    times.push_back(std::max(t, headingFixTime(headingDistance(w[i](3), w[i + 1](3)), c, 2.0)));
  }
  return times;
}

// The vertices: the first carries the tracker's state, the last rests, inner ones fix position.
std::vector<PolyVertex> vertices(const std::vector<Wp>& w, const MrsInitialState& init) {
  std::vector<PolyVertex> v(w.size());
  for (size_t i = 0; i < w.size(); ++i) v[i].fixed[0] = Vec4(w[i]);
  const auto& r = init.reference;
  v.front().fixed[1] = Vec4(r.velocity_mps.x(), r.velocity_mps.y(), r.velocity_mps.z(), r.yaw_rate_radps);
  v.front().fixed[2] = Vec4(r.accel_mps2.x(), r.accel_mps2.y(), r.accel_mps2.z(), init.yaw_accel_radps2);
  v.front().fixed[3] = Vec4(init.jerk_mps3.x(), init.jerk_mps3.y(), init.jerk_mps3.z(), 0.0);
  v.back().fixed[1] = v.back().fixed[2] = Vec4::Zero();  // makeStartOrEnd up to acceleration
  return v;
}

// Mellinger's outer loop (objectiveFunctionTimeMellingerOuterLoop): the trajectory cost, its
// gradient by forward differences that keep the total time.
struct Mellinger {
  const std::vector<PolyVertex>* vertices;
  std::vector<double> last;  // the last evaluated times: the optimiser leaves the polynomial there
  bool failed = false;
};

double mellingerObjective(unsigned n, const double* x, double* grad, void* data) {
  auto& m = *static_cast<Mellinger*>(data);
  std::vector<double> t(x, x + n);
  m.last = t;
  PolynomialTrajectory p;
  if (!p.solve(*m.vertices, t)) return m.failed = true, HUGE_VAL;
  const double cost = p.cost();
  if (grad == nullptr) return cost;
  for (unsigned k = 0; k < n; ++k) {
    grad[k] = 0.0;
    if (n == 1) continue;
    std::vector<double> tb = t;
    for (unsigned i = 0; i < n; ++i)
      tb[i] = std::max(kTimeLowerBound, tb[i] + (i == k ? kGradientStep : -kGradientStep / (n - 1.0)));
    PolynomialTrajectory q;
    if (!q.solve(*m.vertices, tb)) return m.failed = true, HUGE_VAL;
    grad[k] = (q.cost() - cost) / kGradientStep;
  }
  return cost;
}

// Runs NLopt's LD_LBFGS as the generator sets it up; returns the times it left, or nullopt.
std::optional<std::vector<double>> redistributeTimes(const std::vector<PolyVertex>& v, std::vector<double> t,
                                                     int max_evaluations) {
  Mellinger m{&v, t};
  nlopt_opt opt = nlopt_create(NLOPT_LD_LBFGS, unsigned(t.size()));
  nlopt_set_lower_bounds1(opt, kTimeLowerBound);
  nlopt_set_upper_bounds1(opt, std::numeric_limits<double>::max());
  nlopt_set_min_objective(opt, mellingerObjective, &m);
  nlopt_set_ftol_rel(opt, 0.05);
  nlopt_set_xtol_rel(opt, 0.1);
  nlopt_set_maxeval(opt, max_evaluations);
  double f = HUGE_VAL;
  nlopt_optimize(opt, t.data(), &f);
  nlopt_destroy(opt);
  // Any stop after an evaluation goes on with the polynomial where the optimiser left it.
  if (m.failed || f == HUGE_VAL) return std::nullopt;
  return m.last;
}

// The largest horizontal, vertical and heading magnitudes of derivative 1…3 over a segment
// (sampled: the generator finds them by root finding).
std::array<double, 9> segmentMaxima(const PolynomialTrajectory& p, size_t seg) {
  std::array<double, 9> m{};
  constexpr int kSamples = 32;
  for (int i = 0; i <= kSamples; ++i) {
    const double t = p.times()[seg] * i / kSamples;
    for (int d = 1; d <= 3; ++d) {
      const Vec4 q = p.segmentAt(seg, t, d);
      m[size_t(d - 1)] = std::max(m[size_t(d - 1)], std::hypot(q(0), q(1)));
      m[size_t(d + 2)] = std::max(m[size_t(d + 2)], std::abs(q(2)));
      m[size_t(d + 5)] = std::max(m[size_t(d + 5)], std::abs(q(3)));
    }
  }
  return m;
}

// scaleSegmentTimesToMeetConstraints(): each segment stretched by the worst of v, √a, ∛j.
std::vector<double> scaledTimes(const PolynomialTrajectory& p, const MrsConstraints& c) {
  const std::array<double, 9> lim = {c.horizontal_speed_mps, c.horizontal_accel_mps2, c.horizontal_jerk_mps3,
                                     c.vertical_speed_mps,   c.vertical_accel_mps2,   c.vertical_jerk_mps3,
                                     c.heading_speed_radps,  c.heading_accel_radps2,  c.heading_jerk_radps3};
  std::vector<double> t = p.times();
  for (size_t s = 0; s < t.size(); ++s) {
    const auto m = segmentMaxima(p, s);
    double f = 1.0;
    for (size_t k = 0; k < 9; ++k) {
      const double viol = m[k] / lim[k];
      f = std::max(f, k % 3 == 0 ? viol : k % 3 == 1 ? std::sqrt(viol) : std::cbrt(viol));
    }
    t[s] *= f;
  }
  return t;
}

MrsSample sampleAt(const PolynomialTrajectory& p, double t) {
  const Vec4 x = p.at(t, 0), v = p.at(t, 1), a = p.at(t, 2), j = p.at(t, 3);
  return {x.head<3>(), v.head<3>(), a.head<3>(), j.head<3>(), x(3), v(3), a(3)};
}

// The distance of a point from a segment (distFromSegment).
double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len = ab.norm();
  if (len < 1e-12) return (p - a).norm();
  const double s = ab.dot(p - a) / len;
  if (s < 0) return (p - a).norm();
  if (s > len) return (p - b).norm();
  return (p - (a + ab / len * s)).norm();
}

}  // namespace

std::optional<MrsConstraints> MrsConstraints::preset(const std::string& name) {
  // mrs_uav_managers config/public/constraint_manager/constraints.yaml (ascending = descending).
  if (name == "slow") return MrsConstraints{1.0, 1.0, 20.0, 1.0, 1.0, 20.0, 0.5, 1.0, 10.0};
  if (name == "medium") return MrsConstraints{4.0, 2.0, 40.0, 2.0, 1.0, 40.0, 1.0, 1.0, 20.0};
  if (name == "fast") return MrsConstraints{8.0, 4.0, 60.0, 4.0, 2.0, 60.0, 2.0, 2.0, 40.0};
  return std::nullopt;
}

MrsTrajectoryGenerator::MrsTrajectoryGenerator(const MrsGeneratorConfig& config) : config_(checkValid(config)) {}

double MrsTrajectoryGenerator::euclideanSegmentTime(const Eigen::Vector4d& a, const Eigen::Vector4d& b) const {
  const auto& c = config_.constraints;
  const double v = alongSegment(inclination(a, b), c.horizontal_speed_mps, c.vertical_speed_mps);
  const double t = std::max((b.head<3>() - a.head<3>()).norm() / v, 0.01);
  return std::max(t, headingFixTime(headingDistance(a(3), b(3)), c, 1.0));
}

namespace {

// One pass of findTrajectory(): times, redistribution, scaling, sampling; nullopt on failure.
std::optional<std::vector<MrsSample>> optimised(const std::vector<Wp>& w, const MrsInitialState& init,
                                                const MrsGeneratorConfig& cfg, const MrsTrajectoryGenerator& gen,
                                                double baca_s) {
  const std::vector<PolyVertex> v = vertices(w, init);
  std::vector<double> t;
  for (size_t i = 0; i + 1 < w.size(); ++i) t.push_back(gen.euclideanSegmentTime(w[i], w[i + 1]));
  const auto times = redistributeTimes(v, t, cfg.max_evaluations);
  PolynomialTrajectory p;
  if (!times || !p.solve(v, *times)) return std::nullopt;
  if (!p.solve(v, scaledTimes(p, cfg.constraints))) return std::nullopt;
  // Sampled every dt from the start; a sampling 3× longer or shorter than the estimate fails.
  std::vector<MrsSample> s;
  const size_t n = size_t(p.duration() / cfg.sampling_dt_s) + 1;
  for (size_t i = 0; i < n; ++i) s.push_back(sampleAt(p, double(i) * cfg.sampling_dt_s));
  const double len = double(s.size()) * cfg.sampling_dt_s;
  if (len > 1.0 && (len > 3.0 * baca_s || len < 0.33 * baca_s)) return std::nullopt;
  return s;
}

// findTrajectoryFallback(): constant-velocity interpolation over the Baca times.
std::vector<MrsSample> fallbackSamples(const std::vector<Wp>& w, const std::vector<double>& baca, double dt) {
  std::vector<MrsSample> s;
  for (size_t i = 0; i + 1 < w.size(); ++i) {
    int n = baca[i] > 0.1 ? int(std::ceil(baca[i] / dt)) : 0;
    if (n > 0 && i + 2 == w.size()) ++n;  // the last segment hits its end
    for (int j = 0; j < n; ++j) {
      const Wp p = w[i] + (w[i + 1] - w[i]) * (double(j) / double(std::max(1, n - (i + 2 == w.size()))));
      MrsSample m;
      m.position_m = p.head<3>();
      m.heading_rad = p(3);
      s.push_back(m);
    }
  }
  if (s.empty()) s.push_back({w.back().head<3>(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), w.back()(3), 0, 0});
  // Velocities by differences (the fallback's samples carry positions only).
  for (size_t i = 0; i + 1 < s.size(); ++i) s[i].velocity_mps = (s[i + 1].position_m - s[i].position_m) / dt;
  return s;
}

// validateTrajectorySpatial(): which segments a sample leaves by more than `max_dev`.
std::vector<bool> unsafeSegments(const std::vector<MrsSample>& s, const std::vector<Wp>& w, double max_dev,
                                 bool check_first, double& worst) {
  std::vector<bool> bad(w.size() - 1, false);
  size_t k = 0;
  worst = 0.0;
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    const Vec3 a = w[k].head<3>(), b = w[k + 1].head<3>();
    const double d = segmentDistance(s[i].position_m, a, b);
    if (k > 0 || check_first || w.size() <= 2) {
      worst = std::max(worst, d);
      if (d > max_dev) bad[k] = true;
    }
    if (segmentDistance(b, s[i].position_m, s[i + 1].position_m) < 0.05 && k + 2 < w.size()) ++k;
  }
  return bad;
}

// Splits every unsafe segment at its midpoint (the first only when it is checked).
std::vector<Wp> split(const std::vector<Wp>& w, const std::vector<bool>& bad, bool check_first) {
  std::vector<Wp> out;
  for (size_t i = 0; i + 1 < w.size(); ++i) {
    out.push_back(w[i]);
    if (bad[i] && (i > 0 || check_first || w.size() <= 2)) out.push_back(0.5 * (w[i] + w[i + 1]));
  }
  out.push_back(w.back());
  return out;
}

}  // namespace

MrsTrajectory MrsTrajectoryGenerator::generate(const MrsInitialState& init, const std::vector<Waypoint>& path) const {
  std::vector<Wp> original = preprocess(generatorWaypoints(init, path), config_.min_waypoint_distance_m);
  if (original.size() < 2) original.push_back(original.back());  // a path of nothing: hold where the tracker is
  std::vector<Wp> w = original;
  MrsTrajectory out;
  out.dt_s = config_.sampling_dt_s;
  const bool check_first = !init.moving;
  auto baca = [&] {
    const auto b = bacaTimes(w, config_.constraints);
    return std::accumulate(b.begin(), b.end(), 0.0);
  };
  out.baca_estimate_s = baca();
  std::optional<std::vector<MrsSample>> s = optimised(w, init, config_, *this, out.baca_estimate_s);
  // Split segments that leave the path and solve again; any failure falls back (the third of
  // the generator's n_attempts).
  for (int k = 0; s && k < config_.max_deviation_iterations; ++k) {
    const auto bad = unsafeSegments(*s, w, config_.max_deviation_m, check_first, out.max_deviation_m);
    if (std::none_of(bad.begin(), bad.end(), [](bool b) { return b; })) break;
    w = split(w, bad, check_first);
    ++out.deviation_splits;
    s = optimised(w, init, config_, *this, baca());
  }
  if (!s) {
    w = original;
    s = fallbackSamples(w, bacaTimes(w, config_.constraints), config_.sampling_dt_s);
    out.fallback = true;
  }
  out.samples = std::move(*s);
  out.waypoints = w.size();
  return out;
}

}  // namespace msb
