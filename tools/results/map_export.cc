#include "tools/results/map_export.h"

#include <cmath>
#include <sstream>
#include <vector>

#include "core/common/input_file.h"
#include "core/common/strict_number.h"
#include "tools/results/ply_files.h"

namespace msb {

namespace {

// The properties of msbench's map.ply, in order, and the colour of each kind.
constexpr char kProperties[] =
    "property float x\nproperty float y\nproperty float z\nproperty float radius\nproperty uchar kind\nend_header";
constexpr std::array<std::array<uint8_t, 3>, 3> kColours = {{{60, 180, 75}, {230, 25, 75}, {0, 130, 200}}};

// Reads the header up to end_header; returns the vertex count.
size_t readHeader(std::istringstream& in, const std::string& where, int& line_no) {
  std::string line, rest;
  const auto bad = [&](const std::string& why) {
    return InputFileError(where + ": line " + std::to_string(line_no) + ": " + why);
  };
  if (++line_no, !std::getline(in, line) || line != "ply") throw bad("not a PLY file");
  if (++line_no, !std::getline(in, line) || line != "format ascii 1.0")
    throw bad("not the ASCII map.ply msbench writes");
  while (++line_no, std::getline(in, line) && line.rfind("comment", 0) == 0) {
  }
  int64_t n = -1;
  std::string why;
  if (line.rfind("element vertex ", 0) != 0 || !parseInteger(line.substr(15), &n, &why) || n < 0)
    throw bad("expected 'element vertex N'");
  for (std::string want; std::getline(in, line) && (++line_no, true);) {
    rest += (rest.empty() ? "" : "\n") + line;
    if (line == "end_header") break;
  }
  if (rest != kProperties) throw bad("not the properties of the map.ply msbench writes (x y z radius kind)");
  return size_t(n);
}

// One map.ply row: x y z radius kind, all finite, kind 0..2.
void readRow(const std::string& line, const std::string& at, Vec3& p, double& radius, int& kind) {
  std::istringstream c(line);
  std::vector<double> v;
  for (std::string cell; c >> cell;) {
    double x = 0;
    std::string why;
    if (!parseNumber(cell, &x, &why)) throw InputFileError(at + ": " + why);
    v.push_back(x);
  }
  if (v.size() != 5)
    throw InputFileError(at + ": expected 5 numbers (x y z radius kind), got " + std::to_string(v.size()));
  if (v[4] != 0 && v[4] != 1 && v[4] != 2) throw InputFileError(at + ": kind must be 0, 1 or 2");
  p = Vec3(v[0], v[1], v[2]);
  radius = v[3];
  kind = int(v[4]);
}

// The comments naming a PLY's frame and kinds.
std::vector<std::string> comments(const std::string& frame) {
  return {"msbench map, frame_id " + frame,
          "units m; kind 0 free space (radius: sphere radius or cell half side, green), "
          "1 obstacle point (red), 2 frontier (blue)"};
}

}  // namespace

MapPlys mapPlysFromMapPly(const std::string& ply, const std::string& where, const std::optional<Pose>& T_true_est) {
  std::istringstream in(ply);
  int line_no = 0;
  const size_t n = readHeader(in, where, line_no);
  PlyCloud odom;
  odom.comments = comments("odom (the VIO frame the method mapped in)");
  MapPlys out;
  for (size_t i = 0; i < n; ++i) {
    std::string line;
    ++line_no;
    if (!std::getline(in, line))
      throw InputFileError(where + ": ends after " + std::to_string(i) + " of its " + std::to_string(n) + " vertices");
    Vec3 p;
    double radius = 0;
    int kind = 0;
    readRow(line, where + ": line " + std::to_string(line_no), p, radius, kind);
    odom.xyz.push_back(p);
    odom.radius.push_back(float(radius));
    odom.kind.push_back(uint8_t(kind));
    odom.rgb.push_back(kColours[kind]);
    (kind == 0 ? out.free_space : kind == 1 ? out.obstacles : out.frontiers) += 1;
  }
  out.odom = binaryPly(odom);
  if (T_true_est) {
    PlyCloud world = odom;
    world.comments = comments("map (the world frame: moved by the estimate-to-truth correction at the run's end)");
    for (Vec3& p : world.xyz) p = *T_true_est * p;
    out.world = binaryPly(world);
  }
  return out;
}

}  // namespace msb
