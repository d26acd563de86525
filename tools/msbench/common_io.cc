#include "tools/msbench/common_io.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/common/rng.h"

namespace msb {

namespace fs = std::filesystem;

nlohmann::json versionInfo() {
  return {{"msbench", MSB_VERSION},
          {"git_revision", MSB_GIT_REVISION},
          {"mujoco", mj_versionString()},
          {"opencv", CV_VERSION},
          {"eigen", std::to_string(EIGEN_WORLD_VERSION) + "." +
                        std::to_string(EIGEN_MAJOR_VERSION) + "." +
                        std::to_string(EIGEN_MINOR_VERSION)}};
}

nlohmann::json machineFingerprint(const std::string& gl_description) {
  // The first processor's model name and flags (all cores of a machine report the same).
  std::string model = "?", flags;
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);) {
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string key = line.substr(0, colon);
    key.erase(key.find_last_not_of(" \t") + 1);
    const std::string value = colon + 2 <= line.size() ? line.substr(colon + 2) : "";
    if (key == "model name" && model == "?") model = value;
    if (key == "flags" && flags.empty()) flags = value;
    if (model != "?" && !flags.empty()) break;
  }
  nlohmann::json j = {{"cpu_model", model},
                      {"cpu_flags_hash", hexHash(fnv1a64(flags.data(), flags.size()))},
                      {"compiler", std::string("gcc-compatible ") + __VERSION__},
                      {"mujoco", mj_versionString()},
                      {"opencv", CV_VERSION},
                      {"gl", gl_description}};
  const std::string all = j.dump();
  j["id"] = hexHash(fnv1a64(all.data(), all.size()));
  return j;
}

std::string encodePng(const CameraFrame& frame) {
  const cv::Mat img(frame.height, frame.width, CV_8UC1,
                    const_cast<uint8_t*>(frame.pixels.data()));
  std::vector<uchar> buf;
  if (!cv::imencode(".png", img, buf)) throw std::runtime_error("PNG encoding failed");
  return std::string(buf.begin(), buf.end());
}

std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows) {
  std::string s = "t,x,y,z,qw,qx,qy,qz,vx,vy,vz,est_x,est_y,est_z,est_yaw,ref_x,ref_y,ref_z,ref_yaw\n";
  char line[768];
  for (const auto& r : rows) {
    std::snprintf(line, sizeof(line),
                  "%.3f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n",
                  r.t_s, r.position_m.x(), r.position_m.y(), r.position_m.z(),
                  r.orientation.w(), r.orientation.x(), r.orientation.y(), r.orientation.z(),
                  r.velocity_mps.x(), r.velocity_mps.y(), r.velocity_mps.z(),
                  r.est_position_m.x(), r.est_position_m.y(), r.est_position_m.z(), r.est_yaw_rad,
                  r.ref_position_m.x(), r.ref_position_m.y(), r.ref_position_m.z(),
                  r.ref_yaw_rad);
    s += line;
  }
  return s;
}

std::string imuCsv(const std::vector<ImuSample>& samples) {
  std::string s = "t,ax,ay,az,gx,gy,gz\n";
  char line[256];
  for (const auto& m : samples) {
    std::snprintf(line, sizeof(line), "%.3f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", m.t_s,
                  m.accel_mps2.x(), m.accel_mps2.y(), m.accel_mps2.z(), m.gyro_radps.x(),
                  m.gyro_radps.y(), m.gyro_radps.z());
    s += line;
  }
  return s;
}

ProgressLine::ProgressLine(std::string command, double duration_s)
    : command_(std::move(command)), duration_s_(duration_s), start_(WallClock::now()) {}

void ProgressLine::update(const TickRecord& tick, int physics_hz) {
  if (!tick.completed || tick.tick == 0 || tick.tick % (10 * int64_t(physics_hz)) != 0) return;
  const double sim_s = double(tick.tick) / physics_hz;
  const double rtf = sim_s / std::max(secondsSince(start_), 1e-9);
  std::fprintf(stderr, "%s: t = %.0f / %.0f s simulated, real-time factor %.1f, ETA %.0f s\n", command_.c_str(),
               sim_s, duration_s_, rtf, (duration_s_ - sim_s) / rtf);
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const size_t k = std::min(v.size() - 1, size_t(q * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

double peakRssMb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::strtod(line.c_str() + 6, nullptr) / 1024.0;  // kB
  return 0.0;
}

std::string hexHash(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof(buf), "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace msb
