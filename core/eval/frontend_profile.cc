#include "core/eval/frontend_profile.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace msb {

namespace {

constexpr double kBandEdges[] = {0.0, 5.0, 10.0, 20.0, 1e9};
constexpr int kBands = 4;
constexpr double kMovedM = 0.3;

// The q-quantile of `v` (sorted here; nearest rank).
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

}  // namespace

FrontEndProfiler::FrontEndProfiler(const WorldTruth& truth, int every)
    : truth_(truth), every_(std::max(1, every)), errors_(kBands) {}

void FrontEndProfiler::addFrame(const SlamPointsFrame& frame, const Pose& T_W_C_true, int64_t pose_tick) {
  if (pose_tick != frame.tick)
    throw std::logic_error("front-end profile: SLAM points of tick " + std::to_string(frame.tick) +
                           " paired with the true camera pose of tick " + std::to_string(pose_tick));
  if (frames_++ % every_ != 0) return;
  // Estimate frame -> true frame with this frame's VIO error.
  const Pose true_from_est = T_W_C_true * frame.T_W_C.inverse();
  const Vec3 camera = frame.T_W_C.translation();
  for (const SlamPoint& p : frame.points) {
    if (!p.p_W.allFinite()) continue;
    const double depth = (p.p_W - camera).norm();
    const double error = std::abs(truth_.nearest(true_from_est * p.p_W, 25.0).distance_m);
    int band = 0;
    while (band + 1 < kBands && depth >= kBandEdges[band + 1]) ++band;
    errors_[static_cast<size_t>(band)].push_back(error);
    // The track's published estimate over its life (estimate frame, as the method sees it).
    TrackMotion& t = tracks_[p.track_id];
    if (t.seen++ == 0) t.first = p.p_W;
    t.max_move_m = std::max(t.max_move_m, (p.p_W - t.first).norm());
  }
}

FrontEndProfile FrontEndProfiler::result() const {
  FrontEndProfile out;
  for (int b = 0; b < kBands; ++b) {
    const std::vector<double>& e = errors_[static_cast<size_t>(b)];
    DepthBandErrors band{kBandEdges[b], kBandEdges[b + 1], static_cast<long>(e.size())};
    if (!e.empty()) {
      band.median_m = quantile(e, 0.5);
      band.p90_m = quantile(e, 0.9);
      const auto over = [&](double x) {
        return double(std::count_if(e.begin(), e.end(), [x](double v) { return v > x; })) / double(e.size());
      };
      band.share_over_half_m = over(0.5);
      band.share_over_2_m = over(2.0);
    }
    out.points += band.points;
    out.bands.push_back(band);
  }
  std::vector<double> moves;
  for (const auto& [id, t] : tracks_)
    if (t.seen >= 2) moves.push_back(t.max_move_m);
  out.tracks = static_cast<long>(moves.size());
  if (!moves.empty()) {
    out.moved_share =
        double(std::count_if(moves.begin(), moves.end(), [](double m) { return m > kMovedM; })) / double(moves.size());
    out.median_motion_m = quantile(moves, 0.5);
  }
  return out;
}

}  // namespace msb
