// The simulated vehicle: an X-frame quadrotor like the Skydio X2 (docs/architecture.md §4), written as an MJCF
// fragment and spliced into a world file to make the model MuJoCo compiles.
#pragma once

#include <array>
#include <string>

#include "core/common/config_fields.h"
#include "core/common/types.h"

namespace msb {

/// Physical parameters of the quadrotor.
struct QuadrotorConfig {
  double mass_kg = 1.325;                         ///< total mass
  Vec3 inertia_kgm2 = Vec3(0.037, 0.025, 0.061);  ///< principal inertia (body axes)
  double arm_length_m = 0.23;                     ///< centre to rotor axis
  double rotor_radius_m = 0.13;                   ///< collision disc of each rotor
  double max_thrust_n = 13.0;                     ///< per motor
  double yaw_torque_per_thrust_m = 0.0201;        ///< reaction torque coefficient, N·m/N
  double motor_time_constant_s = 0.03;            ///< first-order motor lag

  /// The keys, each once with the values it accepts (core/common/config_fields.h).
  template <class Self, class V>
  static void fields(Self& s, V& v) {
    v.key("mass_kg", s.mass_kg, Limits::positive());
    v.key("inertia_kgm2", s.inertia_kgm2, Limits::positive());
    v.key("arm_length_m", s.arm_length_m, Limits::range(0.05, 2.0));
    v.key("rotor_radius_m", s.rotor_radius_m, Limits::range(0.01, 1.0));
    v.key("max_thrust_n", s.max_thrust_n, Limits::positive());
    v.key("yaw_torque_per_thrust_m", s.yaw_torque_per_thrust_m, Limits::nonNegative());
    v.key("motor_time_constant_s", s.motor_time_constant_s, Limits::range(0.004, 0.5));
  }

  /// Records invalid fields.
  void validate(ConfigChecker& c) const;

  /// Rotor positions in the body frame: FL, FR, BR, BL (X configuration).
  std::array<Vec3, 4> rotorPositions() const;
  /// Yaw-torque sign of each rotor (+1: positive torque about body z per newton of thrust).
  static constexpr std::array<double, 4> kYawSign = {-1.0, +1.0, -1.0, +1.0};
};

/// Names used in the generated MJCF.
namespace mjcf_names {
inline constexpr const char* kVehicleBody = "vehicle";
inline constexpr const char* kImuSite = "vehicle_imu";
inline constexpr const char* kAccelSensor = "vehicle_accel";
inline constexpr const char* kGyroSensor = "vehicle_gyro";
}  // namespace mjcf_names

/// MuJoCo geom group of the vehicle's own geoms (hidden from the onboard camera).
inline constexpr int kVehicleGeomGroup = 3;

/// The model MuJoCo compiles: a wrapper that includes the world file `world_file_name` (a
/// <mujoco> document, resolved next to the wrapper) and adds the simulation options, the vehicle
/// body, its actuators and sensors.
std::string composeModelXml(const std::string& world_file_name, const QuadrotorConfig& vehicle, const Pose& start_T_W_B,
                            double timestep_s);

}  // namespace msb
