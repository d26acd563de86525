#include "core/perception/slam_points.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace msb {

void SlamPointsConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(max_dist_m > min_dist_m, "max_dist_m", "must exceed min_dist_m");
}

SlamPointEstimator::SlamPointEstimator(const SlamPointsConfig& config, const FisheyeCamera& camera,
                                       double frame_rate_hz)
    : config_(checkValid(config)),
      camera_(camera),
      window_clones_(std::max(2, int(std::lround(config.max_clones * frame_rate_hz / config.reference_rate_hz)))) {
  if (!(frame_rate_hz > 0))
    throw ConfigError("camera_stream.rate_hz", "the SLAM-point window needs a positive frame rate");
}

namespace {

// Orthonormal pair perpendicular to a unit vector.
void tangentBasis(const Vec3& b, Vec3* e1, Vec3* e2) {
  const Vec3 helper = std::abs(b.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  *e1 = b.cross(helper).normalized();
  *e2 = b.cross(*e1);
}

}  // namespace

bool SlamPointEstimator::refine(const std::vector<std::pair<Vec2, Pose>>& obs, double init_depth,
                                SlamPoint* out) const {
  if (obs.size() < 2 || !(init_depth > 0)) return false;
  const Pose& T_W_A = obs.front().second;
  const Vec3 b0 = camera_.unproject(obs.front().first);
  Vec3 e1, e2;
  tangentBasis(b0, &e1, &e2);
  // Gauss–Newton on θ = (a, c, ρ), from the point at init_depth along the anchor ray.
  Vec3 theta(0.0, 0.0, 1.0 / init_depth);
  std::vector<Pose> T_C_A(obs.size());
  for (size_t i = 0; i < obs.size(); ++i) T_C_A[i] = obs[i].second.inverse() * T_W_A;
  auto jacobianOfPoint = [&](const Vec3& q, double rho) {
    Eigen::Matrix3d d;
    d.col(0) = e1 / rho;
    d.col(1) = e2 / rho;
    d.col(2) = -q / (rho * rho);
    return d;
  };
  Eigen::Matrix3d H;
  for (int it = 0; it < config_.max_iterations; ++it) {
    H.setZero();
    Vec3 g = Vec3::Zero();
    const Vec3 q = b0 + theta.x() * e1 + theta.y() * e2;
    const Eigen::Matrix3d dp_dtheta = jacobianOfPoint(q, theta.z());
    for (size_t i = 0; i < obs.size(); ++i) {
      Eigen::Matrix<double, 2, 3> Jpi;
      const Vec2 r = obs[i].first - camera_.project(T_C_A[i] * (q / theta.z()), &Jpi);
      const Eigen::Matrix<double, 2, 3> J = Jpi * T_C_A[i].linear() * dp_dtheta;
      H += J.transpose() * J;
      g += J.transpose() * r;
    }
    const Vec3 step = H.ldlt().solve(g);
    if (!step.allFinite()) return false;
    theta += step;
    if (theta.z() <= 1e-6) return false;
    if (step.norm() < 1e-9) break;
  }
  // Residuals and information at the solution.
  const Vec3 q = b0 + theta.x() * e1 + theta.y() * e2;
  const double rho = theta.z();
  const Eigen::Matrix3d dp_dtheta = jacobianOfPoint(q, rho);
  H.setZero();
  double sq_err = 0;
  for (size_t i = 0; i < obs.size(); ++i) {
    const Vec3 p_C = T_C_A[i] * (q / rho);
    if (p_C.norm() < config_.min_dist_m) return false;
    Eigen::Matrix<double, 2, 3> Jpi;
    const Vec2 r = obs[i].first - camera_.project(p_C, &Jpi);
    const Eigen::Matrix<double, 2, 3> J = Jpi * T_C_A[i].linear() * dp_dtheta;
    H += J.transpose() * J;
    sq_err += r.squaredNorm();
  }
  const Eigen::Matrix3d cov_theta = config_.pixel_sigma_px * config_.pixel_sigma_px * H.inverse();
  if (!cov_theta.allFinite()) return false;
  const double depth = q.norm() / rho;
  out->p_W = T_W_A * (q / rho);
  const Eigen::Matrix3d J_W = T_W_A.linear() * dp_dtheta;
  out->cov_W = J_W * cov_theta * J_W.transpose();
  out->depth_m = depth;
  out->depth_std_m = std::sqrt(std::max(0.0, cov_theta(2, 2))) / rho * depth;
  out->reprojection_rms_px = std::sqrt(sq_err / double(obs.size()));
  out->observations = int(obs.size());
  out->T_W_anchor = T_W_A;
  out->anchor_pixel = obs.front().first;
  return out->reprojection_rms_px <= config_.max_reprojection_rms_px;
}

bool SlamPointEstimator::initialise(const std::vector<std::pair<Vec2, Pose>>& obs, SlamPoint* out) const {
  if (obs.size() < 2) return false;
  // Linear triangulation in the anchor frame: Σ (I − b bᵀ) p = Σ (I − b bᵀ) c_i over the
  // bearings b and camera centres c_i of the observations.
  const Pose T_A_W = obs.front().second.inverse();
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Vec3 rhs = Vec3::Zero();
  std::vector<Vec3> centres_A(obs.size());
  for (size_t i = 0; i < obs.size(); ++i) {
    const Pose T_A_Ci = T_A_W * obs[i].second;
    const Vec3 b = (T_A_Ci.linear() * camera_.unproject(obs[i].first)).normalized();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - b * b.transpose();
    centres_A[i] = T_A_Ci.translation();
    A += P;
    rhs += P * centres_A[i];
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(A);
  const Vec3 s = svd.singularValues();
  if (!(s(2) > 0) || s(0) / s(2) > config_.max_cond_number) return false;  // rays (nearly) parallel
  const Vec3 p_lin = A.colPivHouseholderQr().solve(rhs);
  if (!p_lin.allFinite() || p_lin.z() < config_.min_dist_m || p_lin.z() > config_.max_dist_m) return false;
  // Gauss–Newton from the linear solution's depth along the anchor ray.
  const Vec3 b0 = camera_.unproject(obs.front().first);
  if (!refine(obs, p_lin.dot(b0), out)) return false;
  // Depth range and the baseline ratio: |p| over the largest distance of a camera centre from
  // the line of sight (the transverse baseline), in the anchor frame.
  const Vec3 p_A = T_A_W * out->p_W;
  if (p_A.z() < config_.min_dist_m || p_A.z() > config_.max_dist_m) return false;
  const Vec3 u = p_A.normalized();
  double baseline = 0.0;
  for (const Vec3& c : centres_A) baseline = std::max(baseline, (c - c.dot(u) * u).norm());
  return baseline > 0 && p_A.norm() / baseline <= config_.max_baseline;
}

bool SlamPointEstimator::refineFeature(TrackState& s, SlamPoint* out) const {
  std::vector<std::pair<Vec2, Pose>> obs;
  obs.reserve(s.slam_obs.size());
  for (const Observation& o : s.slam_obs) obs.emplace_back(o.pixel, o.T_W_C);
  return refine(obs, s.depth, out);
}

SlamPointsFrame SlamPointEstimator::update(const TrackFrame& tracks, const Pose& T_W_C) {
  SlamPointsFrame out;
  out.tick = tracks.tick;
  out.t_s = tracks.t_s;
  out.T_W_C = T_W_C;
  out.tracks = int(tracks.tracks.size());
  if (!started_) started_ = true, start_t_s_ = tracks.t_s;
  addObservations(tracks, T_W_C);
  std::map<uint64_t, SlamPoint> points;
  const int in_state = refineInState(points);
  initialiseMaxTracks(tracks.t_s, in_state, points);
  for (auto& [id, p] : points) out.points.push_back(p);
  return out;
}

void SlamPointEstimator::addObservations(const TrackFrame& tracks, const Pose& T_W_C) {
  // Lost tracks end (a SLAM feature with them: marginalised); tracked ones get this frame's
  // observation.
  std::map<uint64_t, TrackState> next;
  for (const Track& t : tracks.tracks) {
    auto it = tracks_.find(t.id);
    TrackState s = it == tracks_.end() ? TrackState{} : std::move(it->second);
    const Observation o{t.pixel, T_W_C, tracks.tick};
    if (it == tracks_.end()) s.first_tick = tracks.tick;
    if (s.slam) {
      // The initialisation window stays (the EKF never loses that information; without it a
      // hover would leave only observations from one place); later ones are the most recent.
      s.slam_obs.push_back(o);
      if (int(s.slam_obs.size()) > std::max(config_.max_observations, window_clones_ + 2))
        s.slam_obs.erase(s.slam_obs.begin() + window_clones_ + 1);
    } else {
      s.window.push_back(o);
    }
    next.emplace(t.id, std::move(s));
  }
  tracks_ = std::move(next);
}

int SlamPointEstimator::refineInState(std::map<uint64_t, SlamPoint>& points) {
  // SLAM features in the state: refined with the new observation. A failed update is OpenVINS'
  // χ² rejection: the observation is not used, the feature keeps its estimate, and the failure
  // counts for the feature's whole life (UpdaterSLAM never resets update_fail_count); the second
  // failure marginalises it (VioManager: update_fail_count > 1) and its track starts a new window.
  int in_state = 0;
  for (auto& [id, s] : tracks_) {
    if (!s.slam) continue;
    SlamPoint p;
    if (refineFeature(s, &p)) {
      s.depth = p.depth_m;
      s.last = p;
    } else {
      s.slam_obs.pop_back();  // this frame's observation, rejected
      if (++s.fail_count > 1) {
        const int64_t first_tick = s.first_tick;
        s = TrackState{};
        s.first_tick = first_tick;
        continue;
      }
      p = s.last;
    }
    p.track_id = id;
    p.anchor_tick = s.slam_obs.front().tick;
    points[id] = p;
    ++in_state;
  }
  return in_state;
}

void SlamPointEstimator::initialiseMaxTracks(double t_s, int in_state, std::map<uint64_t, SlamPoint>& points) {
  // Max tracks: observed in every clone of the window. After the start-up delay the longest-
  // lived become SLAM features (at most max_slam_in_update, room in the state permitting); every
  // other max track, and every refused one, starts a new window.
  std::vector<uint64_t> max_tracks;
  for (const auto& [id, s] : tracks_)
    if (!s.slam && int(s.window.size()) > window_clones_) max_tracks.push_back(id);
  std::stable_sort(max_tracks.begin(), max_tracks.end(),
                   [&](uint64_t a, uint64_t b) { return tracks_.at(a).first_tick < tracks_.at(b).first_tick; });
  int room = 0;
  if (t_s - start_t_s_ >= config_.dt_slam_delay_s - 1e-9)
    room = std::min(config_.max_slam_in_update, config_.max_slam - in_state);
  for (const uint64_t id : max_tracks) {
    TrackState& s = tracks_.at(id);
    if (room > 0) {
      --room;  // the update's budget counts attempts, as OpenVINS' delayed initialisation does
      // The window's observations, anchored at the newest.
      std::vector<std::pair<Vec2, Pose>> obs;
      obs.emplace_back(s.window.back().pixel, s.window.back().T_W_C);
      for (size_t i = 0; i + 1 < s.window.size(); ++i) obs.emplace_back(s.window[i].pixel, s.window[i].T_W_C);
      SlamPoint p;
      if (initialise(obs, &p)) {
        s.slam = true;
        s.depth = p.depth_m;
        s.slam_obs = {s.window.back()};
        s.slam_obs.insert(s.slam_obs.end(), s.window.begin(), s.window.end() - 1);
        s.window.clear();
        s.last = p;
        p.track_id = id;
        p.anchor_tick = s.slam_obs.front().tick;
        points[id] = p;
        continue;
      }
    }
    s.window.clear();
  }
}

}  // namespace msb
