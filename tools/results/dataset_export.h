// A run as a dataset for visual-inertial estimators (docs/interop.md): the EuRoC MAV layout
// (`mav0/cam0/data.csv` + PNGs named by nanosecond timestamps, `mav0/imu0/data.csv` gyro first,
// `mav0/state_groundtruth_estimate0/data.csv`, a `sensor.yaml` per sensor) and the fisheye
// calibration as Kalibr's camchain / IMU YAML and ROS's CameraInfo YAML. Each text is a pure
// function of the run's records and configuration, so the same run gives the same bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/camera/fisheye_camera.h"
#include "core/common/messages.h"
#include "sim/sensors/imu_model.h"
#include "tools/engine/records.h"

namespace msb {

/// A simulated time as integer nanoseconds (EuRoC's and ROS's stamps): the nearest integer to
/// t_s · 1e9 (exact for ticks of a physics rate that divides 1e9, as 1 kHz does).
int64_t nanoseconds(double t_s);

/// EuRoC `imu0/data.csv`: `#timestamp [ns],w_RS_S_x,…,a_RS_S_z`, gyroscope first, in the body
/// frame (the IMU sits at the body origin, unrotated).
std::string eurocImuCsv(const std::vector<ImuSample>& samples);

/// EuRoC `state_groundtruth_estimate0/data.csv`: timestamp [ns], the true body position,
/// orientation (w first) and velocity in the world frame, one row per trajectory row. The IMU
/// biases EuRoC appends are not recorded by a run, so the file has these 11 columns only.
std::string eurocGroundTruthCsv(const std::vector<TrajectoryRow>& rows);

/// EuRoC `cam0/data.csv`: `#timestamp [ns],filename`, one row per frame, `<ns>.png`.
std::string eurocCameraCsv(const std::vector<int64_t>& stamps_ns);

/// EuRoC `cam0/sensor.yaml`: T_BS (camera in body), rate, resolution, the pinhole projection
/// with equidistant distortion (Kannala–Brandt k1..k4) of the image as rendered (scale applied).
std::string eurocCameraSensorYaml(const FisheyeCamera& camera, double rate_hz);

/// EuRoC `imu0/sensor.yaml`: T_BS (identity), rate and the noise densities and random walks.
std::string eurocImuSensorYaml(const ImuConfig& imu);

/// EuRoC `state_groundtruth_estimate0/sensor.yaml`: the ground truth's rate and frame.
std::string eurocGroundTruthSensorYaml(double rate_hz);

/// Kalibr `camchain.yaml` (cam0: pinhole-equi, intrinsics [fu fv pu pv], T_cam_imu), as
/// OpenVINS, VINS-Fusion and Basalt read it.
std::string kalibrCamchainYaml(const FisheyeCamera& camera);

/// Kalibr `imu.yaml` (imu0: noise densities, random walks, update rate).
std::string kalibrImuYaml(const ImuConfig& imu);

/// ROS `camera_info.yaml` (camera_calibration_parsers' layout): K, D (equidistant), R, P.
std::string rosCameraInfoYaml(const FisheyeCamera& camera);

}  // namespace msb
