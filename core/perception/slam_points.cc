#include "core/perception/slam_points.h"

#include <cmath>

namespace msb {

void SlamPointsConfig::validate(ConfigChecker& c) const {
  c.inRange("min_parallax_deg", min_parallax_deg, 0.1, 90.0);
  c.positive("pixel_sigma_px", pixel_sigma_px);
  c.positive("max_reprojection_rms_px", max_reprojection_rms_px);
  c.positive("max_relative_depth_std", max_relative_depth_std);
  c.require(max_depth_m > min_depth_m && min_depth_m > 0, "max_depth_m", "needs 0 < min_depth_m < max_depth_m");
  c.inRange("max_points", max_points, 1, 100000);
  c.inRange("max_observations", max_observations, 2, 1000);
  c.require(min_observations >= 2 && min_observations <= max_observations, "min_observations",
            "must be in [2, max_observations]");
  c.inRange("max_iterations", max_iterations, 1, 100);
}

SlamPointEstimator::SlamPointEstimator(const SlamPointsConfig& config, const FisheyeCamera& camera)
    : config_(checkValid(config)), camera_(camera) {}

namespace {

// Orthonormal pair perpendicular to a unit vector.
void tangentBasis(const Vec3& b, Vec3* e1, Vec3* e2) {
  const Vec3 helper = std::abs(b.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  *e1 = b.cross(helper).normalized();
  *e2 = b.cross(*e1);
}

}  // namespace

bool SlamPointEstimator::estimate(const std::vector<std::pair<Vec2, Pose>>& obs, double init_depth,
                                  SlamPoint* out) const {
  if (obs.size() < 2) return false;
  const Pose& T_W_A = obs.front().second;
  const Vec3 b0 = camera_.unproject(obs.front().first);
  Vec3 e1, e2;
  tangentBasis(b0, &e1, &e2);

  // Initial depth: closest approach of the anchor ray and the ray with the largest parallax.
  double depth = init_depth;
  if (!(depth > 0)) {
    const Vec3 d0 = T_W_A.linear() * b0;
    size_t best = 1;
    double best_cos = 2;
    for (size_t i = 1; i < obs.size(); ++i) {
      const double c = d0.dot(obs[i].second.linear() * camera_.unproject(obs[i].first));
      if (c < best_cos) best_cos = c, best = i;
    }
    const Vec3 d1 = obs[best].second.linear() * camera_.unproject(obs[best].first);
    const Vec3 w = T_W_A.translation() - obs[best].second.translation();
    const double a = d0.dot(d0), bb = d0.dot(d1), c = d1.dot(d1), d = d0.dot(w), e = d1.dot(w);
    const double den = a * c - bb * bb;
    if (den < 1e-12) return false;
    depth = (bb * e - c * d) / den;
    if (!(depth > config_.min_depth_m)) return false;
  }

  // Gauss–Newton on θ = (a, c, ρ).
  Vec3 theta(0.0, 0.0, 1.0 / depth);
  std::vector<Pose> T_C_A(obs.size());
  for (size_t i = 0; i < obs.size(); ++i) T_C_A[i] = obs[i].second.inverse() * T_W_A;
  Eigen::Matrix3d H;
  double sq_err = 0;
  for (int it = 0; it < config_.max_iterations; ++it) {
    H.setZero();
    Vec3 g = Vec3::Zero();
    sq_err = 0;
    const Vec3 q = b0 + theta.x() * e1 + theta.y() * e2;
    const double rho = theta.z();
    const Vec3 p_A = q / rho;
    Eigen::Matrix3d dp_dtheta;
    dp_dtheta.col(0) = e1 / rho;
    dp_dtheta.col(1) = e2 / rho;
    dp_dtheta.col(2) = -q / (rho * rho);
    for (size_t i = 0; i < obs.size(); ++i) {
      const Vec3 p_C = T_C_A[i] * p_A;
      Eigen::Matrix<double, 2, 3> Jpi;
      const Vec2 r = obs[i].first - camera_.project(p_C, &Jpi);
      const Eigen::Matrix<double, 2, 3> J = Jpi * T_C_A[i].linear() * dp_dtheta;
      H += J.transpose() * J;
      g += J.transpose() * r;
      sq_err += r.squaredNorm();
    }
    const Vec3 step = H.ldlt().solve(g);
    if (!step.allFinite()) return false;
    theta += step;
    if (theta.z() <= 1e-6) return false;
    if (step.norm() < 1e-9) break;
  }
  // Final residuals and information at the solution.
  const Vec3 q = b0 + theta.x() * e1 + theta.y() * e2;
  const double rho = theta.z();
  Eigen::Matrix3d dp_dtheta;
  dp_dtheta.col(0) = e1 / rho;
  dp_dtheta.col(1) = e2 / rho;
  dp_dtheta.col(2) = -q / (rho * rho);
  H.setZero();
  sq_err = 0;
  for (size_t i = 0; i < obs.size(); ++i) {
    const Vec3 p_C = T_C_A[i] * (q / rho);
    if (p_C.norm() < config_.min_depth_m) return false;
    Eigen::Matrix<double, 2, 3> Jpi;
    const Vec2 r = obs[i].first - camera_.project(p_C, &Jpi);
    const Eigen::Matrix<double, 2, 3> J = Jpi * T_C_A[i].linear() * dp_dtheta;
    H += J.transpose() * J;
    sq_err += r.squaredNorm();
  }
  const Eigen::Matrix3d cov_theta = config_.pixel_sigma_px * config_.pixel_sigma_px * H.inverse();
  if (!cov_theta.allFinite()) return false;
  const double depth_out = q.norm() / rho;
  const double rel_std = std::sqrt(std::max(0.0, cov_theta(2, 2))) / rho;
  const double rms = std::sqrt(sq_err / obs.size());
  out->p_W = T_W_A * (q / rho);
  const Eigen::Matrix3d J_W = T_W_A.linear() * dp_dtheta;
  out->cov_W = J_W * cov_theta * J_W.transpose();
  out->depth_m = depth_out;
  out->depth_std_m = rel_std * depth_out;
  out->reprojection_rms_px = rms;
  out->observations = int(obs.size());
  out->T_W_anchor = T_W_A;
  out->anchor_pixel = obs.front().first;
  return rms <= config_.max_reprojection_rms_px && rel_std <= config_.max_relative_depth_std &&
         depth_out >= config_.min_depth_m && depth_out <= config_.max_depth_m;
}

SlamPointsFrame SlamPointEstimator::update(const TrackFrame& tracks, const Pose& T_W_C) {
  SlamPointsFrame out;
  out.tick = tracks.tick;
  out.t_s = tracks.t_s;
  out.T_W_C = T_W_C;
  out.tracks = int(tracks.tracks.size());

  // Drop histories of tracks that ended; append this frame's observations.
  std::map<uint64_t, History> next;
  for (const auto& t : tracks.tracks) {
    auto it = histories_.find(t.id);
    History h = it == histories_.end() ? History{} : std::move(it->second);
    if (h.obs.empty()) h.anchor_tick = tracks.tick;
    h.obs.emplace_back(t.pixel, T_W_C);
    // Keep the anchor and the most recent observations.
    if (int(h.obs.size()) > config_.max_observations) h.obs.erase(h.obs.begin() + 1);
    next.emplace(t.id, std::move(h));
  }
  histories_ = std::move(next);

  const double min_cos = std::cos(config_.min_parallax_deg * M_PI / 180.0);
  for (auto& [id, h] : histories_) {
    if (int(h.obs.size()) < config_.min_observations) continue;
    // Parallax between the anchor ray and the latest ray (world frame).
    const Vec3 d0 = h.obs.front().second.linear() * camera_.unproject(h.obs.front().first);
    const Vec3 d1 = h.obs.back().second.linear() * camera_.unproject(h.obs.back().first);
    if (d0.dot(d1) > min_cos && h.last_depth <= 0) continue;
    SlamPoint p;
    if (!estimate(h.obs, h.last_depth, &p)) {
      h.last_depth = 0;
      continue;
    }
    h.last_depth = p.depth_m;
    if (d0.dot(d1) > min_cos) continue;  // parallax fell below the limit: keep warm, withhold
    p.track_id = id;
    p.anchor_tick = h.anchor_tick;
    out.points.push_back(p);
    if (int(out.points.size()) >= config_.max_points) break;
  }
  return out;
}

}  // namespace msb
