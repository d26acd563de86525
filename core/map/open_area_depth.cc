#include "core/map/open_area_depth.h"

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

}  // namespace msb
