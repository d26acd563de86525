#include "core/methods/monospheres/map/open_area_depth.h"

#include <algorithm>
#include <cmath>

namespace msb {

void OpenAreaDepthConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

OpenAreaDepth::OpenAreaDepth(const OpenAreaDepthConfig& config, const FisheyeCamera& camera)
    : config_(checkValid(config)), camera_(camera) {}

std::vector<Vec3> OpenAreaDepth::candidates(const Pose& T_W_C) const {
  std::vector<Vec3> out;
  const double f = config_.central_fraction, W = camera_.width(), H = camera_.height();
  for (int i = 0; i < config_.grid; ++i)
    for (int j = 0; j < config_.grid; ++j) {
      const Vec2 px(W * (0.5 - 0.5 * f + f * (j + 0.5) / config_.grid),
                    H * (0.5 - 0.5 * f + f * (i + 0.5) / config_.grid));
      out.push_back(T_W_C * (config_.range_m * camera_.unproject(px)));
    }
  return out;
}

bool OpenAreaDepth::inCentralView(const Pose& T_W_C, const Vec3& p_W) const {
  const Vec3 c = T_W_C.inverse() * p_W;
  if (c.z() <= 0.0) return false;
  const Vec2 px = camera_.project(c);
  const double f = config_.central_fraction, W = camera_.width(), H = camera_.height();
  return std::abs(px.x() - 0.5 * W) <= 0.5 * f * W && std::abs(px.y() - 0.5 * H) <= 0.5 * f * H;
}

std::vector<Vec3> OpenAreaDepth::update(const Pose& T_W_C, OvdePoseBuffer& poses) const {
  // Pose buffer: add when moved or turned enough since the newest buffered pose.
  if (poses.empty()) {
    poses.push_back(T_W_C);
  } else {
    const Pose& last = poses.back();
    const double moved = (T_W_C.translation() - last.translation()).norm();
    const double turned = Eigen::AngleAxisd(last.linear().transpose() * T_W_C.linear()).angle();
    if (moved > config_.min_translation_m || turned > config_.min_rotation_deg * M_PI / 180.0) {
      poses.push_back(T_W_C);
      if (int(poses.size()) > config_.max_poses) poses.pop_front();
    }
  }
  std::vector<Vec3> active;
  const double min_cos = std::cos(config_.min_parallax_rad);
  const bool whole_buffer = config_.visibility == "whole_buffer";
  for (const Vec3& X : candidates(T_W_C)) {
    // Camera centres that saw X in their central view, continuously back from now.
    std::vector<Vec3> centres = {T_W_C.translation()};
    bool seen_by_all = true;
    for (auto it = poses.rbegin(); it != poses.rend(); ++it) {
      if (!inCentralView(*it, X)) {
        seen_by_all = false;
        break;
      }
      centres.push_back(it->translation());
    }
    if (whole_buffer && !seen_by_all) continue;
    bool parallax = false;
    for (size_t a = 0; a < centres.size() && !parallax; ++a)
      for (size_t b = a + 1; b < centres.size() && !parallax; ++b) {
        const Vec3 ra = (X - centres[a]).normalized(), rb = (X - centres[b]).normalized();
        parallax = ra.dot(rb) <= min_cos;
      }
    if (parallax) active.push_back(X);
  }
  return active;
}

std::vector<Vec3> OpenAreaDepth::updatePublished(const Pose& T_W_C, OvdePoseBuffer& poses,
                                                 std::vector<bool>& active) const {
  // The egocentric points: pinhole rays through a grid × grid lattice of the central image,
  // its edges included (trim = the margin outside the central fraction), at range_m.
  const double trim = 0.5 * (1.0 - config_.central_fraction), W = camera_.width(), H = camera_.height();
  const int n = config_.grid;
  std::vector<Vec3> ego;
  for (int x = 0; x < n; ++x)
    for (int y = 0; y < n; ++y) {
      const double u = trim * W + x * (1.0 - 2.0 * trim) * W / std::max(n - 1, 1);
      const double v = trim * H + y * (1.0 - 2.0 * trim) * H / std::max(n - 1, 1);
      ego.push_back(config_.range_m *
                    Vec3((u - camera_.cx()) / camera_.fx(), (v - camera_.cy()) / camera_.fy(), 1.0).normalized());
    }
  active.resize(ego.size(), false);
  auto activePoints = [&] {
    std::vector<Vec3> out;
    for (size_t k = 0; k < ego.size(); ++k)
      if (active[k]) out.push_back(T_W_C * ego[k]);
    return out;
  };
  // Buffer the pose when it moved or its optical axis turned enough; otherwise nothing changes.
  bool add = poses.empty();
  if (!add) {
    const Pose& last = poses.back();
    const double axis_turn = std::acos(std::clamp(T_W_C.linear().col(2).dot(last.linear().col(2)), -1.0, 1.0));
    add = (T_W_C.translation() - last.translation()).norm() > config_.min_translation_m ||
          axis_turn > config_.min_rotation_deg * M_PI / 180.0;
  }
  if (!add) return activePoints();
  poses.push_back(T_W_C);
  if (int(poses.size()) > config_.max_poses) poses.pop_front();
  if (poses.size() < 2) return activePoints();
  // Each point against every older buffered pose, oldest first.
  for (size_t k = 0; k < ego.size(); ++k) {
    bool parallax_in_run = false;
    for (size_t i = 0; i + 1 < poses.size(); ++i) {
      const Pose T_rel = poses[i].inverse() * T_W_C;
      const Vec3 there = T_rel * ego[k];
      // Visible there: the pinhole projection inside the central image (no test of the depth's
      // sign, as published); the run ends at the first pose that does not see the point.
      const Vec2 px(camera_.fx() * there.x() / there.z() + camera_.cx(),
                    camera_.fy() * there.y() / there.z() + camera_.cy());
      const bool visible =
          px.x() >= trim * W && px.x() <= (1 - trim) * W && px.y() >= trim * H && px.y() <= (1 - trim) * H;
      if (!visible) break;
      const Vec3 moved = ego[k] + T_rel.translation();
      const double cos = ego[k].dot(moved) / (ego[k].norm() * there.norm());
      parallax_in_run = parallax_in_run || std::acos(std::clamp(cos, -1.0, 1.0)) >= config_.min_parallax_rad;
    }
    active[k] = parallax_in_run;
  }
  return activePoints();
}

}  // namespace msb
