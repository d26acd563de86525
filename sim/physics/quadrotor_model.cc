#include "sim/physics/quadrotor_model.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace msb {

void QuadrotorConfig::validate(ConfigChecker& c) const {
  checkFields(*this, c);
  c.require(max_thrust_n * 4.0 > 1.5 * mass_kg * kGravity, "max_thrust_n",
            "four motors must lift at least 1.5x the weight");
}

std::array<Vec3, 4> QuadrotorConfig::rotorPositions() const {
  const double a = arm_length_m / std::sqrt(2.0);
  const double z = 0.04;
  return {Vec3(a, a, z), Vec3(a, -a, z), Vec3(-a, -a, z), Vec3(-a, a, z)};
}

namespace {

std::string vec(const Vec3& v) {
  std::ostringstream os;
  os.precision(17);
  os << v.x() << ' ' << v.y() << ' ' << v.z();
  return os.str();
}

// The vehicle body: free joint, explicit inertia, collision box + rotor discs, IMU and thrust
// sites. Vehicle geoms use contype 2 / conaffinity 1, world geoms the defaults (1/1), so
// vehicle–world pairs are tested and the vehicle never collides with itself.
std::string vehicleBody(const QuadrotorConfig& q, const Pose& T) {
  const Quat qr(T.linear());
  const std::array<const char*, 4> names = {"fl", "fr", "br", "bl"};
  const auto rotors = q.rotorPositions();
  std::ostringstream os;
  os.precision(17);
  os << "<body name=\"" << mjcf_names::kVehicleBody << "\" pos=\"" << vec(T.translation()) << "\" quat=\"" << qr.w()
     << ' ' << qr.x() << ' ' << qr.y() << ' ' << qr.z() << "\">\n"
     << "  <freejoint name=\"vehicle_root\"/>\n"
     << "  <inertial pos=\"0 0 0\" mass=\"" << q.mass_kg << "\" diaginertia=\"" << vec(q.inertia_kgm2) << "\"/>\n"
     << "  <geom name=\"vehicle_core\" type=\"box\" size=\"0.12 0.08 0.05\" contype=\"2\" "
        "conaffinity=\"1\" group=\""
     << kVehicleGeomGroup << "\" rgba=\"0.2 0.2 0.2 1\"/>\n";
  for (int i = 0; i < 4; ++i) {
    os << "  <geom name=\"vehicle_rotor_" << names[i] << "\" type=\"cylinder\" pos=\"" << vec(rotors[i]) << "\" size=\""
       << q.rotor_radius_m << " 0.015\" contype=\"2\" "
       << "conaffinity=\"1\" group=\"" << kVehicleGeomGroup << "\" rgba=\"0.3 0.3 0.3 1\"/>\n"
       << "  <site name=\"vehicle_thrust_" << names[i] << "\" pos=\"" << vec(rotors[i]) << "\"/>\n";
  }
  os << "  <site name=\"" << mjcf_names::kImuSite << "\" pos=\"0 0 0\"/>\n</body>\n";
  return os.str();
}

// Four thrust actuators with first-order lag (MuJoCo "filter" dynamics) and yaw reaction torque.
std::string actuators(const QuadrotorConfig& q) {
  const std::array<const char*, 4> names = {"fl", "fr", "br", "bl"};
  std::ostringstream os;
  os.precision(17);
  os << "<actuator>\n";
  for (int i = 0; i < 4; ++i) {
    os << "  <general name=\"motor_" << names[i] << "\" site=\"vehicle_thrust_" << names[i]
       << "\" dyntype=\"filter\" dynprm=\"" << q.motor_time_constant_s
       << "\" gaintype=\"fixed\" gainprm=\"1\" biastype=\"none\" ctrllimited=\"true\" "
       << "ctrlrange=\"0 " << q.max_thrust_n << "\" gear=\"0 0 1 0 0 "
       << QuadrotorConfig::kYawSign[i] * q.yaw_torque_per_thrust_m << "\"/>\n";
  }
  os << "</actuator>\n<sensor>\n"
     << "  <accelerometer name=\"" << mjcf_names::kAccelSensor << "\" site=\"" << mjcf_names::kImuSite << "\"/>\n"
     << "  <gyro name=\"" << mjcf_names::kGyroSensor << "\" site=\"" << mjcf_names::kImuSite << "\"/>\n</sensor>\n";
  return os.str();
}

}  // namespace

std::string composeModelXml(const std::string& world_file_name, const QuadrotorConfig& vehicle, const Pose& start_T_W_B,
                            double timestep_s) {
  // A wrapper model: the world by MuJoCo's own <include> (parsed, never searched as text),
  // then the simulation options, the vehicle body and its actuators and sensors.
  std::ostringstream xml;
  xml.precision(17);
  xml << "<mujoco model=\"msbench\">\n"
      << "<include file=\"" << world_file_name << "\"/>\n"
      << "<option timestep=\"" << timestep_s << "\" integrator=\"Euler\" gravity=\"0 0 -9.81\"/>\n"
      << "<worldbody>\n"
      << vehicleBody(vehicle, start_T_W_B) << "</worldbody>\n"
      << actuators(vehicle) << "</mujoco>\n";
  return xml.str();
}

}  // namespace msb
