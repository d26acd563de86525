#include "core/camera/fisheye_camera.h"

#include <cmath>

namespace msb {

void FisheyeCameraConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(cx_px <= width_px, "cx_px", "must not exceed width_px");
  c.require(cy_px <= height_px, "cy_px", "must not exceed height_px");
  c.require(scale == 1.0 || scale == 0.5 || scale == 0.25, "scale", "must be 1, 0.5 or 0.25");
  // The camera sits on the vehicle: its centre within a metre of the body origin.
  c.require(mount_position_B_m.norm() <= 1.0, "mount_position_B_m",
            "must lie within 1 m of the body origin (the camera is mounted on the vehicle)");
}

FisheyeCamera::FisheyeCamera(const FisheyeCameraConfig& config)
    : config_(checkValid(config)),
      width_(static_cast<int>(std::lround(config.width_px * config.scale))),
      height_(static_cast<int>(std::lround(config.height_px * config.scale))),
      fx_(config.fx_px * config.scale),
      fy_(config.fy_px * config.scale),
      cx_(config.cx_px * config.scale),
      cy_(config.cy_px * config.scale),
      half_fov_rad_(0.5 * config.fov_deg * M_PI / 180.0) {
  // Optical frame (z fwd, x right, y down) in the FLU body frame, then tilt about body y.
  Mat3 R_B_C;
  R_B_C << 0, 0, 1,  //
      -1, 0, 0,      //
      0, -1, 0;
  const double pitch = config.mount_pitch_down_deg * M_PI / 180.0;
  T_B_C_ = Pose::Identity();
  T_B_C_.linear() = Eigen::AngleAxisd(pitch, Vec3::UnitY()).toRotationMatrix() * R_B_C;
  T_B_C_.translation() = config.mount_position_B_m;
}

double FisheyeCamera::distort(double theta) const {
  const double t2 = theta * theta;
  const auto& k = config_.k;
  return theta * (1.0 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3]))));
}

double FisheyeCamera::undistort(double theta_d) const {
  // Newton on f(θ) = distort(θ) − θd, starting from θ = θd (distortion is small).
  const auto& k = config_.k;
  double theta = theta_d;
  for (int i = 0; i < 20; ++i) {
    const double t2 = theta * theta;
    const double f = distort(theta) - theta_d;
    const double df = 1.0 + t2 * (3 * k[0] + t2 * (5 * k[1] + t2 * (7 * k[2] + t2 * 9 * k[3])));
    const double step = f / df;
    theta -= step;
    if (std::abs(step) < 1e-14) break;
  }
  return theta;
}

Vec2 FisheyeCamera::project(const Vec3& p_C) const { return project(p_C, nullptr); }

Vec2 FisheyeCamera::project(const Vec3& p, Eigen::Matrix<double, 2, 3>* J) const {
  const double r2 = p.x() * p.x() + p.y() * p.y();
  const double r = std::sqrt(r2);
  const double theta = std::atan2(r, p.z());
  const double theta_d = distort(theta);
  // Near the axis θd/r → 1/z (limit of the equidistant scaling).
  const double s = r > 1e-12 ? theta_d / r : 1.0 / p.z();
  const Vec2 px(fx_ * s * p.x() + cx_, fy_ * s * p.y() + cy_);
  if (J) {
    if (r < 1e-9) {
      // On the axis the model is locally a pinhole with focal f.
      const double iz = 1.0 / p.z();
      *J << fx_ * iz, 0, -fx_ * p.x() * iz * iz, 0, fy_ * iz, -fy_ * p.y() * iz * iz;
    } else {
      const auto& k = config_.k;
      const double t2 = theta * theta;
      const double dthd_dth = 1.0 + t2 * (3 * k[0] + t2 * (5 * k[1] + t2 * (7 * k[2] + t2 * 9 * k[3])));
      const double rho2 = r2 + p.z() * p.z();
      // dθ/dx = z x / (r ρ²), dθ/dy = z y / (r ρ²), dθ/dz = −r / ρ².
      const Vec3 dth(p.z() * p.x() / (r * rho2), p.z() * p.y() / (r * rho2), -r / rho2);
      // ds/dp = (θd'(θ) dθ/dp · r − θd dr/dp) / r², dr/dp = (x/r, y/r, 0).
      const Vec3 dr(p.x() / r, p.y() / r, 0.0);
      const Vec3 ds = (dthd_dth * dth * r - theta_d * dr) / r2;
      J->row(0) = fx_ * (ds.transpose() * p.x());
      J->row(1) = fy_ * (ds.transpose() * p.y());
      (*J)(0, 0) += fx_ * s;
      (*J)(1, 1) += fy_ * s;
    }
  }
  return px;
}

Vec3 FisheyeCamera::unproject(const Vec2& px) const {
  const double mx = (px.x() - cx_) / fx_;
  const double my = (px.y() - cy_) / fy_;
  const double theta_d = std::sqrt(mx * mx + my * my);
  if (theta_d < 1e-14) return Vec3::UnitZ();
  const double theta = undistort(theta_d);
  const double st = std::sin(theta) / theta_d;
  return Vec3(mx * st, my * st, std::cos(theta));
}

bool FisheyeCamera::inImage(const Vec2& px) const {
  return px.x() >= -0.5 && px.y() >= -0.5 && px.x() < width_ - 0.5 && px.y() < height_ - 0.5;
}

bool FisheyeCamera::inFieldOfView(const Vec3& p_C) const {
  const double r = std::hypot(p_C.x(), p_C.y());
  if (std::atan2(r, p_C.z()) > half_fov_rad_) return false;
  return inImage(project(p_C));
}

bool FisheyeCamera::pixelInFov(const Vec2& px) const {
  const double mx = (px.x() - cx_) / fx_;
  const double my = (px.y() - cy_) / fy_;
  return undistort(std::sqrt(mx * mx + my * my)) <= half_fov_rad_;
}

}  // namespace msb
