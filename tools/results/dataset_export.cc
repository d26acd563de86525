#include "tools/results/dataset_export.h"

#include <cmath>
#include <cstdio>

namespace msb {

namespace {

// printf into a std::string (the texts are small; one line at a time).
template <class... A>
std::string format(const char* fmt, A... a) {
  char line[512];
  std::snprintf(line, sizeof(line), fmt, a...);
  return line;
}

// A 4×4 transform as EuRoC's T_BS block (row-major `data`).
std::string eurocMatrix(const Pose& T) {
  std::string s = "T_BS:\n  cols: 4\n  rows: 4\n  data: [";
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) s += format("%.9g%s", T.matrix()(r, c), r == 3 && c == 3 ? "]\n" : ", ");
  return s;
}

// A 4×4 transform as Kalibr's list of rows.
std::string kalibrMatrix(const Pose& T) {
  std::string s;
  for (int r = 0; r < 4; ++r)
    s += format("  - [%.9g, %.9g, %.9g, %.9g]\n", T.matrix()(r, 0), T.matrix()(r, 1), T.matrix()(r, 2),
                T.matrix()(r, 3));
  return s;
}

// [fu, fv, pu, pv] and [k1, k2, k3, k4] of the image as rendered.
std::string intrinsics(const FisheyeCamera& c) {
  return format("[%.9g, %.9g, %.9g, %.9g]", c.fx(), c.fy(), c.cx(), c.cy());
}
std::string distortion(const FisheyeCamera& c) {
  return format("[%.9g, %.9g, %.9g, %.9g]", c.k()[0], c.k()[1], c.k()[2], c.k()[3]);
}

}  // namespace

int64_t nanoseconds(double t_s) { return std::llround(t_s * 1e9); }

std::string eurocImuCsv(const std::vector<ImuSample>& samples) {
  std::string s =
      "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],"
      "a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  for (const ImuSample& m : samples)
    s += format("%lld,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", static_cast<long long>(nanoseconds(m.t_s)), m.gyro_radps.x(),
                m.gyro_radps.y(), m.gyro_radps.z(), m.accel_mps2.x(), m.accel_mps2.y(), m.accel_mps2.z());
  return s;
}

std::string eurocGroundTruthCsv(const std::vector<TrajectoryRow>& rows) {
  std::string s =
      "#timestamp [ns],p_RS_R_x [m],p_RS_R_y [m],p_RS_R_z [m],q_RS_w [],q_RS_x [],q_RS_y [],q_RS_z [],"
      "v_RS_R_x [m s^-1],v_RS_R_y [m s^-1],v_RS_R_z [m s^-1]\n";
  for (const TrajectoryRow& r : rows)
    s += format("%lld,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", static_cast<long long>(nanoseconds(r.t_s)),
                r.position_m.x(), r.position_m.y(), r.position_m.z(), r.orientation.w(), r.orientation.x(),
                r.orientation.y(), r.orientation.z(), r.velocity_mps.x(), r.velocity_mps.y(), r.velocity_mps.z());
  return s;
}

std::string eurocCameraCsv(const std::vector<int64_t>& stamps_ns) {
  std::string s = "#timestamp [ns],filename\n";
  for (const int64_t ns : stamps_ns)
    s += format("%lld,%lld.png\n", static_cast<long long>(ns), static_cast<long long>(ns));
  return s;
}

std::string eurocCameraSensorYaml(const FisheyeCamera& camera, double rate_hz) {
  return "# General sensor definitions.\nsensor_type: camera\ncomment: msbench fisheye camera (rendered, mono8)\n\n"
         "# Sensor extrinsics wrt. the body-frame.\n" +
         eurocMatrix(camera.T_B_C()) + "\n# Camera specific definitions.\n" + format("rate_hz: %.9g\n", rate_hz) +
         format("resolution: [%d, %d]\n", camera.width(), camera.height()) +
         "camera_model: pinhole\nintrinsics: " + intrinsics(camera) +
         "  # fu, fv, cu, cv\ndistortion_model: equidistant\ndistortion_coefficients: " + distortion(camera) + "\n";
}

std::string eurocImuSensorYaml(const ImuConfig& imu) {
  return "# General sensor definitions.\nsensor_type: imu\ncomment: msbench IMU (body origin)\n\n"
         "# Sensor extrinsics wrt. the body-frame.\n" +
         eurocMatrix(Pose::Identity()) + format("rate_hz: %.9g\n\n", imu.rate_hz) +
         "# inertial sensor noise model parameters (static)\n" +
         format("gyroscope_noise_density: %.9g     # [ rad / s / sqrt(Hz) ]\n", imu.gyro_noise_density) +
         format("gyroscope_random_walk: %.9g       # [ rad / s^2 / sqrt(Hz) ]\n", imu.gyro_random_walk) +
         format("accelerometer_noise_density: %.9g # [ m / s^2 / sqrt(Hz) ]\n", imu.accel_noise_density) +
         format("accelerometer_random_walk: %.9g   # [ m / s^3 / sqrt(Hz) ]\n", imu.accel_random_walk);
}

std::string eurocGroundTruthSensorYaml(double rate_hz) {
  return "# General sensor definitions.\nsensor_type: visual-inertial\n"
         "comment: msbench ground truth (the simulator's body pose, world frame)\n\n"
         "# Sensor extrinsics wrt. the body-frame.\n" +
         eurocMatrix(Pose::Identity()) + format("rate_hz: %.9g\n", rate_hz);
}

std::string kalibrCamchainYaml(const FisheyeCamera& camera) {
  return "cam0:\n  camera_model: pinhole\n  intrinsics: " + intrinsics(camera) +
         "\n  distortion_model: equidistant\n  distortion_coeffs: " + distortion(camera) +
         format("\n  resolution: [%d, %d]\n", camera.width(), camera.height()) + "  T_cam_imu:\n" +
         kalibrMatrix(camera.T_B_C().inverse()) + "  timeshift_cam_imu: 0.0\n  rostopic: /cam0/image_raw\n";
}

std::string kalibrImuYaml(const ImuConfig& imu) {
  return "imu0:\n  T_i_b:\n" + kalibrMatrix(Pose::Identity()) +
         format("  accelerometer_noise_density: %.9g\n", imu.accel_noise_density) +
         format("  accelerometer_random_walk: %.9g\n", imu.accel_random_walk) +
         format("  gyroscope_noise_density: %.9g\n", imu.gyro_noise_density) +
         format("  gyroscope_random_walk: %.9g\n", imu.gyro_random_walk) + "  model: calibrated\n" +
         "  rostopic: /imu0\n  time_offset: 0.0\n" + format("  update_rate: %.9g\n", imu.rate_hz);
}

std::string rosCameraInfoYaml(const FisheyeCamera& c) {
  return format("image_width: %d\nimage_height: %d\n", c.width(), c.height()) +
         "camera_name: cam0\ncamera_matrix:\n  rows: 3\n  cols: 3\n" +
         format("  data: [%.9g, 0, %.9g, 0, %.9g, %.9g, 0, 0, 1]\n", c.fx(), c.cx(), c.fy(), c.cy()) +
         "distortion_model: equidistant\ndistortion_coefficients:\n  rows: 1\n  cols: 4\n  data: " + distortion(c) +
         "\nrectification_matrix:\n  rows: 3\n  cols: 3\n  data: [1, 0, 0, 0, 1, 0, 0, 0, 1]\n"
         "projection_matrix:\n  rows: 3\n  cols: 4\n" +
         format("  data: [%.9g, 0, %.9g, 0, 0, %.9g, %.9g, 0, 0, 0, 1, 0]\n", c.fx(), c.cx(), c.fy(), c.cy());
}

}  // namespace msb
