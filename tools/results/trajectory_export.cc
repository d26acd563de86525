#include "tools/results/trajectory_export.h"

#include <cmath>
#include <sstream>
#include <vector>

#include "core/common/input_file.h"
#include "core/common/strict_number.h"

namespace msb {

namespace {

// The header of trajectory.csv without and with the VIO's full orientation.
constexpr char kHeaderYawOnly[] = "t,x,y,z,qw,qx,qy,qz,vx,vy,vz,est_x,est_y,est_z,est_yaw,ref_x,ref_y,ref_z,ref_yaw";
constexpr char kOrientationColumns[] = ",est_qw,est_qx,est_qy,est_qz";

// The cells of a row, each checked to be a finite number.
std::vector<std::string> numericCells(const std::string& line, size_t want, const std::string& at) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string c; std::getline(in, c, ',');) cells.push_back(c);
  if (!line.empty() && line.back() == ',') cells.push_back("");
  if (cells.size() != want)
    throw InputFileError(at + ": expected " + std::to_string(want) + " cells, got " + std::to_string(cells.size()));
  for (const std::string& c : cells) {
    double v = 0;
    std::string why;
    if (!parseNumber(c, &v, &why) || !std::isfinite(v))
      throw InputFileError(at + ": '" + c + "' is not a finite number");
  }
  return cells;
}

// One TUM line from cells of a row: time, position (3 cells from p), quaternion w-first at q.
std::string tumLine(const std::vector<std::string>& c, size_t p, size_t q) {
  return c[0] + " " + c[p] + " " + c[p + 1] + " " + c[p + 2] + " " + c[q + 1] + " " + c[q + 2] + " " + c[q + 3] + " " +
         c[q] + "\n";
}

// A cell numericCells() has checked.
double number(const std::string& cell) {
  double v = 0;
  std::string why;
  parseNumber(cell, &v, &why);
  return v;
}

// The pose of cells p (position) and q (quaternion, w first) of a row.
Pose poseOf(const std::vector<std::string>& c, size_t p, size_t q) {
  Pose T = Pose::Identity();
  T.translation() = Vec3(number(c[p]), number(c[p + 1]), number(c[p + 2]));
  T.linear() = Quat(number(c[q]), number(c[q + 1]), number(c[q + 2]), number(c[q + 3])).normalized().toRotationMatrix();
  return T;
}

}  // namespace

TumTrajectories tumFromTrajectoryCsv(const std::string& csv, const std::string& where) {
  std::istringstream in(csv);
  std::string header;
  std::getline(in, header);
  const std::string full = std::string(kHeaderYawOnly) + kOrientationColumns;
  const bool with_orientation = header == full;
  if (!with_orientation && header != kHeaderYawOnly)
    throw InputFileError(where + ": line 1: not the header of a trajectory.csv msbench writes");
  const size_t cells = with_orientation ? 23 : 19;
  TumTrajectories out;
  out.truth = "# msbench truth: timestamp tx ty tz qx qy qz qw (body in the world frame, ROS map; s, m)\n";
  if (with_orientation)
    out.estimate = "# msbench VIO estimate: timestamp tx ty tz qx qy qz qw (body in the VIO frame, ROS odom; s, m)\n";
  int line_no = 1;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    const auto c = numericCells(line, cells, where + ": line " + std::to_string(line_no));
    out.truth += tumLine(c, 1, 4);                             // x y z, qw qx qy qz
    if (with_orientation) out.estimate += tumLine(c, 11, 19);  // est_x.., est_qw..
    if (with_orientation) out.T_true_est_final = poseOf(c, 1, 4) * poseOf(c, 11, 19).inverse();
    ++out.rows;
  }
  if (out.rows == 0) throw InputFileError(where + ": no rows");
  return out;
}

}  // namespace msb
