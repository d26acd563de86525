// The calibration files are read back by independent readers: yaml-cpp parses each, and
// OpenCV's own fisheye model (cv::fisheye::projectPoints) with camera_info.yaml's K and D
// projects points as msbench's camera does; camchain's T_cam_imu undoes the camera mount. The
// EuRoC CSVs put the gyroscope first and stamp in integer nanoseconds.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <opencv2/calib3d.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tools/results/dataset_export.h"

namespace msb {
namespace {

// A half-resolution, pitched camera: scale and mount must reach the files.
FisheyeCamera testCamera() {
  FisheyeCameraConfig c;
  c.scale = 0.5;
  c.mount_pitch_down_deg = 15.0;
  return FisheyeCamera(c);
}

// The 4×4 matrix of a Kalibr list of rows.
Eigen::Matrix4d kalibrMatrix(const YAML::Node& rows) {
  Eigen::Matrix4d m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m(r, c) = rows[r][c].as<double>();
  return m;
}

TEST(DatasetExport, OpenCvsFisheyeModelWithTheCameraInfoProjectsAsMsbenchsCameraDoes) {
  const FisheyeCamera camera = testCamera();
  const YAML::Node info = YAML::Load(rosCameraInfoYaml(camera));
  EXPECT_EQ(info["image_width"].as<int>(), 376);
  EXPECT_EQ(info["image_height"].as<int>(), 240);
  EXPECT_EQ(info["distortion_model"].as<std::string>(), "equidistant");
  const std::vector<double> k = info["camera_matrix"]["data"].as<std::vector<double>>();
  const std::vector<double> d = info["distortion_coefficients"]["data"].as<std::vector<double>>();
  ASSERT_EQ(k.size(), 9u);
  ASSERT_EQ(d.size(), 4u);
  const cv::Matx33d K(k[0], k[1], k[2], k[3], k[4], k[5], k[6], k[7], k[8]);
  const cv::Vec4d D(d[0], d[1], d[2], d[3]);
  // Directions in front of the camera up to 85° off axis (OpenCV's θ = atan(r/z) needs z > 0).
  std::vector<cv::Point3d> points;
  for (double theta_deg = 0; theta_deg <= 85; theta_deg += 5)
    for (double phi_deg = 0; phi_deg < 360; phi_deg += 40) {
      const double t = theta_deg * M_PI / 180, p = phi_deg * M_PI / 180;
      points.emplace_back(3 * std::sin(t) * std::cos(p), 3 * std::sin(t) * std::sin(p), 3 * std::cos(t));
    }
  std::vector<cv::Point2d> pixels;
  cv::fisheye::projectPoints(points, pixels, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D);
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec2 ours = camera.project(Vec3(points[i].x, points[i].y, points[i].z));
    EXPECT_NEAR(pixels[i].x, ours.x(), 1e-6) << i;
    EXPECT_NEAR(pixels[i].y, ours.y(), 1e-6) << i;
  }
}

TEST(DatasetExport, KalibrsCamchainUndoesTheMountAndTheSensorYamlsNameTheModel) {
  const FisheyeCamera camera = testCamera();
  const YAML::Node chain = YAML::Load(kalibrCamchainYaml(camera))["cam0"];
  EXPECT_EQ(chain["camera_model"].as<std::string>(), "pinhole");
  EXPECT_EQ(chain["distortion_model"].as<std::string>(), "equidistant");
  EXPECT_EQ(chain["resolution"].as<std::vector<int>>(), (std::vector<int>{376, 240}));
  const std::vector<double> in = chain["intrinsics"].as<std::vector<double>>();
  EXPECT_EQ(in, (std::vector<double>{camera.fx(), camera.fy(), camera.cx(), camera.cy()}));
  // T_cam_imu · T_B_C = I (the IMU is the body frame).
  const Eigen::Matrix4d product = kalibrMatrix(chain["T_cam_imu"]) * camera.T_B_C().matrix();
  EXPECT_TRUE(product.isApprox(Eigen::Matrix4d::Identity(), 1e-8)) << product;

  const YAML::Node sensor = YAML::Load(eurocCameraSensorYaml(camera, 15.0));
  EXPECT_EQ(sensor["rate_hz"].as<double>(), 15.0);
  EXPECT_EQ(sensor["distortion_model"].as<std::string>(), "equidistant");
  const std::vector<double> t = sensor["T_BS"]["data"].as<std::vector<double>>();
  ASSERT_EQ(t.size(), 16u);
  EXPECT_NEAR(t[3], camera.T_B_C().translation().x(), 1e-9);
  EXPECT_NEAR(t[11], camera.T_B_C().translation().z(), 1e-9);

  ImuConfig imu;
  const YAML::Node k = YAML::Load(kalibrImuYaml(imu))["imu0"];
  EXPECT_EQ(k["gyroscope_noise_density"].as<double>(), imu.gyro_noise_density);
  EXPECT_EQ(k["update_rate"].as<double>(), imu.rate_hz);
  EXPECT_EQ(YAML::Load(eurocImuSensorYaml(imu))["accelerometer_random_walk"].as<double>(), imu.accel_random_walk);
}

TEST(DatasetExport, EurocCsvsStampInNanosecondsWithTheGyroscopeFirst) {
  ImuSample s;
  s.t_s = 1.005;
  s.accel_mps2 = Vec3(0.1, 0.2, 9.81);
  s.gyro_radps = Vec3(-0.5, 0.25, 1.5);
  EXPECT_EQ(eurocImuCsv({s}).substr(eurocImuCsv({s}).find('\n') + 1), "1005000000,-0.5,0.25,1.5,0.1,0.2,9.81\n");
  EXPECT_EQ(eurocCameraCsv({66000000, 133000000}),
            "#timestamp [ns],filename\n66000000,66000000.png\n133000000,133000000.png\n");
  TrajectoryRow r{};
  r.est_position_m = r.ref_position_m = Vec3::Zero();
  r.est_yaw_rad = r.ref_yaw_rad = 0;
  r.t_s = 0.1;
  r.position_m = Vec3(1, 2, 3);
  r.orientation = Quat(0.5, 0.5, 0.5, 0.5);
  r.velocity_mps = Vec3(4, 5, 6);
  const std::string gt = eurocGroundTruthCsv({r});
  EXPECT_EQ(gt.substr(gt.find('\n') + 1), "100000000,1,2,3,0.5,0.5,0.5,0.5,4,5,6\n");
  EXPECT_EQ(nanoseconds(179.999), 179999000000);
}

}  // namespace
}  // namespace msb
