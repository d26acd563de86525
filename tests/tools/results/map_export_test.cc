// map.ply → binary PLYs: the odom copy holds map.ply's vertices (to float precision) with the
// kind's colour, the world copy is them moved by the correction, both headers name their frame;
// a file msbench did not write as a map is refused naming its line.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "core/common/input_file.h"
#include "tools/results/map_export.h"
#include "tools/results/ply_files.h"

namespace msb {
namespace {

constexpr char kMap[] =
    "ply\nformat ascii 1.0\ncomment msbench map (VIO frame, ROS frame_id odom)\nelement vertex 3\n"
    "property float x\nproperty float y\nproperty float z\nproperty float radius\nproperty uchar kind\nend_header\n"
    "1.0000 2.0000 3.0000 1.5000 0\n4.0000 5.0000 6.0000 0 1\n-1.0000 0.0000 2.0000 0 2\n";

// The float properties of vertex i of a binary PLY with `stride` bytes per vertex.
float floatAt(const std::string& ply, int i, int stride, int k) {
  const size_t body = ply.find("end_header\n") + 11;
  float f = 0;
  std::memcpy(&f, ply.data() + body + size_t(i) * stride + 4 * k, 4);
  return f;
}

TEST(MapExport, TheOdomCopyHoldsMapPlysVerticesAndTheWorldCopyIsMovedByTheCorrection) {
  Pose T = Pose::Identity();
  T.translation() = Vec3(10, -2, 0.5);
  T.linear() = Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix();
  const MapPlys m = mapPlysFromMapPly(kMap, "map.ply", T);
  EXPECT_EQ(m.free_space, 1);
  EXPECT_EQ(m.obstacles, 1);
  EXPECT_EQ(m.frontiers, 1);
  EXPECT_NE(m.odom.find("comment msbench map, frame_id odom"), std::string::npos);
  EXPECT_NE(m.world.find("comment msbench map, frame_id map"), std::string::npos);
  EXPECT_NE(m.odom.find("format binary_little_endian 1.0\n"), std::string::npos);
  const int stride = 4 * 4 + 1 + 3;  // x y z radius, kind, rgb
  EXPECT_EQ(m.odom.size() - (m.odom.find("end_header\n") + 11), size_t(3 * stride));
  EXPECT_EQ(floatAt(m.odom, 1, stride, 0), 4.0f);
  EXPECT_EQ(floatAt(m.odom, 0, stride, 3), 1.5f);  // the sphere's radius
  const Vec3 moved = T * Vec3(4, 5, 6);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(floatAt(m.world, 1, stride, k), moved[k], 1e-5);
  EXPECT_TRUE(mapPlysFromMapPly(kMap, "map.ply", std::nullopt).world.empty());
}

TEST(MapExport, AFileThatIsNotMsbenchsMapIsRefusedNamingItsLine) {
  const auto error = [](const std::string& text) {
    try {
      mapPlysFromMapPly(text, "m.ply", std::nullopt);
    } catch (const InputFileError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  std::string s = kMap;
  EXPECT_NE(error("ply\nformat binary_little_endian 1.0\n").find("m.ply: line 2"), std::string::npos);
  EXPECT_NE(error(s.substr(0, s.rfind("-1.0000"))).find("ends after 2 of its 3 vertices"), std::string::npos);
  EXPECT_NE(error(std::string(kMap).replace(s.find("0 2\n"), 3, "0 7")).find("line 13: kind must be"),
            std::string::npos);
  EXPECT_NE(error(std::string(kMap).replace(s.find("radius"), 6, "colour")).find("properties"), std::string::npos);
  EXPECT_NE(error(std::string(kMap).replace(s.find("4.0000"), 6, "nan")).find("line 12"), std::string::npos);
}

TEST(PlyFiles, AMeshHasItsFacesAsListsOfThreeIntsAndAPropertyOfTheWrongSizeIsRefused) {
  const std::string m = binaryPlyMesh({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}}, {"frame_id map"});
  EXPECT_NE(m.find("element face 1\nproperty list uchar int vertex_indices\n"), std::string::npos);
  EXPECT_EQ(m.size() - (m.find("end_header\n") + 11), size_t(3 * 12 + 1 + 12));
  PlyCloud c;
  c.xyz = {Vec3::Zero()};
  c.kind = {1, 2};
  EXPECT_THROW(binaryPly(c), std::invalid_argument);
}

}  // namespace
}  // namespace msb
