// Geometric tracking controller on SE(3) (Lee, Leok, McClamroch 2010) with X-quadrotor motor
// allocation. It reads a state estimate (in the closed loop: the drifting VIO estimate) and a
// TrajectoryReference, and outputs per-motor thrust commands.
//
//   e_x = x − x_d,  e_v = v − v_d
//   F_d = −k_x e_x − k_v e_v + m g e3 + m a_d        (desired force, world frame)
//   b3_d = F_d/|F_d|, b1_c = (cos ψ_d, sin ψ_d, 0), b2_d = b3_d × b1_c/|·|, b1_d = b2_d × b3_d
//   f = F_d · R e3                                    (collective thrust)
//   e_R = ½ vee(R_dᵀ R − Rᵀ R_d),  e_Ω = Ω − Rᵀ R_d Ω_d,  Ω_d = (0, 0, ψ̇_d) in the desired frame
//   M = −k_R e_R − k_Ω e_Ω + Ω × J Ω
// Allocation inverts [f, M] = A · [f_FL, f_FR, f_BR, f_BL] and clamps to the motor range; yaw
// torque (rotor drag only, weak) is scaled down to what the motors can still give once thrust,
// roll and pitch are served.
#pragma once

#include "core/common/config_fields.h"
#include "core/common/messages.h"
#include "sim/physics/quadrotor_model.h"

namespace msb {

/// Controller gains (defaults tuned for the X2-like vehicle with 30 ms motor lag).
struct Se3ControllerConfig {
  Vec3 k_position = Vec3(7.0, 7.0, 10.0);  ///< N/m
  Vec3 k_velocity = Vec3(5.5, 5.5, 7.0);   ///< N·s/m
  Vec3 k_attitude = Vec3(8.0, 5.5, 0.6);   ///< N·m/rad (yaw: ω_n ≈ 3 rad/s)
  Vec3 k_rate = Vec3(0.75, 0.5, 0.3);      ///< N·m·s/rad
  double max_tilt_deg = 40.0;              ///< limit on the commanded tilt

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("k_position", s.k_position, Limits::positive());
    v.key("k_velocity", s.k_velocity, Limits::positive());
    v.key("k_attitude", s.k_attitude, Limits::positive());
    v.key("k_rate", s.k_rate, Limits::positive());
    v.key("max_tilt_deg", s.max_tilt_deg, Limits::range(5.0, 80.0));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;
};

/// SE(3) geometric controller plus motor allocation.
class Se3Controller {
 public:
  /// Builds the allocation matrix from the vehicle geometry. Throws ConfigError if invalid.
  Se3Controller(const Se3ControllerConfig& config, const QuadrotorConfig& vehicle);

  /// Motor thrust commands (N, FL FR BR BL) for the state and reference.
  Vec4 compute(const Odometry& state, const TrajectoryReference& ref) const;

 private:
  Se3ControllerConfig config_;
  QuadrotorConfig vehicle_;
  Eigen::Matrix4d allocation_inv_;
};

}  // namespace msb
