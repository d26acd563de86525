#include "sim/physics/se3_controller.h"

#include <algorithm>
#include <cmath>

namespace msb {

void Se3ControllerConfig::validate(ConfigChecker& c) const { checkFields(*this, c); }

namespace {
Vec3 vee(const Mat3& S) { return Vec3(S(2, 1), S(0, 2), S(1, 0)); }
}  // namespace

Se3Controller::Se3Controller(const Se3ControllerConfig& config, const QuadrotorConfig& vehicle)
    : config_(checkValid(config)), vehicle_(checkValid(vehicle)) {
  // Rows: collective thrust, roll torque (y·f), pitch torque (−x·f), yaw torque (sign·c·f).
  Eigen::Matrix4d A;
  const auto rotors = vehicle.rotorPositions();
  for (int i = 0; i < 4; ++i) {
    A(0, i) = 1.0;
    A(1, i) = rotors[i].y();
    A(2, i) = -rotors[i].x();
    A(3, i) = QuadrotorConfig::kYawSign[i] * vehicle.yaw_torque_per_thrust_m;
  }
  allocation_inv_ = A.inverse();
}

Vec4 Se3Controller::compute(const Odometry& s, const TrajectoryReference& r) const {
  const double m = vehicle_.mass_kg;
  const Mat3 R = s.T_W_B.linear();
  const Vec3 e3 = Vec3::UnitZ();

  // Desired force with tilt limit: the horizontal part is scaled down if it tilts too far.
  const Vec3 ex = s.T_W_B.translation() - r.position_m;
  const Vec3 ev = s.v_W_mps - r.velocity_mps;
  Vec3 F =
      -config_.k_position.cwiseProduct(ex) - config_.k_velocity.cwiseProduct(ev) + m * kGravity * e3 + m * r.accel_mps2;
  F.z() = std::max(F.z(), 0.2 * m * kGravity);
  const double max_h = F.z() * std::tan(config_.max_tilt_deg * M_PI / 180.0);
  const double h = std::hypot(F.x(), F.y());
  if (h > max_h) {
    F.x() *= max_h / h;
    F.y() *= max_h / h;
  }

  // Desired attitude from thrust direction and heading.
  const Vec3 b3 = F.normalized();
  const Vec3 b1c(std::cos(r.yaw_rad), std::sin(r.yaw_rad), 0.0);
  Vec3 b2 = b3.cross(b1c);
  if (b2.norm() < 1e-6) b2 = b3.cross(Vec3::UnitX());
  b2.normalize();
  Mat3 Rd;
  Rd.col(0) = b2.cross(b3);
  Rd.col(1) = b2;
  Rd.col(2) = b3;

  const double f = F.dot(R * e3);
  const Vec3 eR = 0.5 * vee(Rd.transpose() * R - R.transpose() * Rd);
  const Vec3 Omega_d = Rd.transpose() * Vec3(0.0, 0.0, r.yaw_rate_radps);
  const Vec3 eW = s.omega_B_radps - R.transpose() * Rd * Omega_d;
  const Vec3 J = vehicle_.inertia_kgm2;
  const Vec3 JW = J.cwiseProduct(s.omega_B_radps);
  Vec3 M = -config_.k_attitude.cwiseProduct(eR) - config_.k_rate.cwiseProduct(eW) + s.omega_B_radps.cross(JW);

  // Allocation. Thrust, roll and pitch come first; yaw torque (weak on a quadrotor: it comes
  // from rotor drag only) is scaled down to what the motors can still give.
  const double fmax = vehicle_.max_thrust_n;
  Vec4 u = allocation_inv_ * Vec4(f, M.x(), M.y(), 0.0);
  for (int i = 0; i < 4; ++i) u[i] = std::clamp(u[i], 0.0, fmax);
  const Vec4 yaw_column = allocation_inv_ * Vec4(0.0, 0.0, 0.0, M.z());
  double scale = 1.0;
  for (int i = 0; i < 4; ++i) {
    if (yaw_column[i] > 1e-12) scale = std::min(scale, (fmax - u[i]) / yaw_column[i]);
    if (yaw_column[i] < -1e-12) scale = std::min(scale, (0.0 - u[i]) / yaw_column[i]);
  }
  u += std::max(0.0, scale) * yaw_column;
  for (int i = 0; i < 4; ++i) u[i] = std::clamp(u[i], 0.0, fmax);
  return u;
}

}  // namespace msb
