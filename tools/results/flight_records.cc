#include "tools/results/flight_records.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/common/png.h"
#include "sim/physics/mjcf_files.h"

namespace msb {

std::string encodePng(const CameraFrame& frame) {
  return msb::encodePng(ImageView{frame.pixels.data(), frame.width, frame.height, 1, static_cast<size_t>(frame.width)});
}

std::string trajectoryCsv(const std::vector<TrajectoryRow>& rows) {
  // est_qw..est_qz (the VIO's full orientation) last: the columns before them keep their places.
  std::string s =
      "t,x,y,z,qw,qx,qy,qz,vx,vy,vz,est_x,est_y,est_z,est_yaw,ref_x,ref_y,ref_z,ref_yaw,est_qw,est_qx,est_qy,est_qz\n";
  char line[768];
  for (const auto& r : rows) {
    std::snprintf(line, sizeof(line),
                  "%.3f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,"
                  "%.9g,%.9g,%.9g,%.9g\n",
                  r.t_s, r.position_m.x(), r.position_m.y(), r.position_m.z(), r.orientation.w(), r.orientation.x(),
                  r.orientation.y(), r.orientation.z(), r.velocity_mps.x(), r.velocity_mps.y(), r.velocity_mps.z(),
                  r.est_position_m.x(), r.est_position_m.y(), r.est_position_m.z(), r.est_yaw_rad, r.ref_position_m.x(),
                  r.ref_position_m.y(), r.ref_position_m.z(), r.ref_yaw_rad, r.est_orientation.w(),
                  r.est_orientation.x(), r.est_orientation.y(), r.est_orientation.z());
    s += line;
  }
  return s;
}

std::string imuCsv(const std::vector<ImuSample>& samples) {
  std::string s = "t,ax,ay,az,gx,gy,gz\n";
  char line[256];
  for (const auto& m : samples) {
    std::snprintf(line, sizeof(line), "%.3f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", m.t_s, m.accel_mps2.x(), m.accel_mps2.y(),
                  m.accel_mps2.z(), m.gyro_radps.x(), m.gyro_radps.y(), m.gyro_radps.z());
    s += line;
  }
  return s;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const size_t k = std::min(v.size() - 1, size_t(q * (v.size() - 1) + 0.5));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return v[k];
}

void addWorldInputs(std::vector<NamedPath>& in, const FlightSpec& spec) {
  if (spec.world_path.empty() || !spec.world_name.empty()) return;
  const std::vector<std::string> files = mjcfInputFiles(spec.world_path);
  in.push_back({"its world file", files.front()});
  for (size_t i = 1; i < files.size(); ++i) in.push_back({"a file its world includes", files[i]});
}

std::vector<NamedPath> flightInputs(const std::string& flight_file, const FlightSpec& spec) {
  std::vector<NamedPath> in = {{"FILE.yaml", flight_file}};
  addWorldInputs(in, spec);
  return in;
}

}  // namespace msb
