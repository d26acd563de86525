// Perception logs round-trip, and map-replay is deterministic (identical map.ply twice).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/common/rng.h"
#include "tools/results/perception_log.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

// Frames of a camera moving along +x past a wall of points at y = 8 (optical axis +y).
std::vector<SlamPointsFrame> syntheticFrames() {
  RngStream rng(3, "log_test");
  std::vector<Vec3> wall;
  for (int i = 0; i < 300; ++i) wall.emplace_back(rng.uniform(-10, 30), 8 + rng.uniform(-0.2, 0.2), rng.uniform(0, 6));
  std::vector<SlamPointsFrame> frames;
  Mat3 R;  // optical frame: z = world +y, x = world +x, y = world −z
  R.col(0) = Vec3::UnitX();
  R.col(1) = -Vec3::UnitZ();
  R.col(2) = Vec3::UnitY();
  for (int k = 0; k < 40; ++k) {
    SlamPointsFrame f;
    f.tick = k * 34;
    f.t_s = f.tick * 0.002;
    f.T_W_C.linear() = R;
    f.T_W_C.translation() = Vec3(0.5 * k, 0, 2);
    for (size_t i = 0; i < wall.size(); ++i) {
      const Vec3 c = f.T_W_C.inverse() * wall[i];
      if (c.z() < 0.5 * c.norm()) continue;
      SlamPoint p;
      p.track_id = i + 1;
      p.p_W = wall[i];
      p.cov_W = Mat3::Identity() * 0.01;
      p.depth_m = c.norm();
      p.anchor_tick = f.tick;
      p.anchor_pixel = Vec2(100 + i, 50);
      f.points.push_back(p);
    }
    frames.push_back(f);
  }
  return frames;
}

std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(PerceptionLog, RoundTripAndMapReplayIsDeterministic) {
  const fs::path d = fs::path(::testing::TempDir()) / "msb_map_replay";
  fs::remove_all(d);
  fs::create_directories(d);
  const auto frames = syntheticFrames();
  {
    PerceptionLogWriter w((d / "a.log").string(), {{"world", "synthetic"}, {"camera_scale", 1.0}});
    for (const auto& f : frames) w.write(f, f.T_W_C);
    w.close();
  }
  const PerceptionLog log = PerceptionLog::read((d / "a.log").string());
  ASSERT_EQ(log.frames.size(), frames.size());
  EXPECT_EQ(log.header["world"], "synthetic");
  for (size_t k = 0; k < frames.size(); ++k) {
    ASSERT_EQ(log.frames[k].points.points.size(), frames[k].points.size());
    EXPECT_EQ(log.frames[k].points.tick, frames[k].tick);
    EXPECT_TRUE(log.frames[k].points.T_W_C.isApprox(frames[k].T_W_C, 1e-12));
    for (size_t i = 0; i < frames[k].points.size(); ++i) {
      EXPECT_EQ(log.frames[k].points.points[i].track_id, frames[k].points[i].track_id);
      EXPECT_EQ(log.frames[k].points.points[i].p_W, frames[k].points[i].p_W);
      EXPECT_EQ(log.frames[k].points.points[i].anchor_pixel, frames[k].points[i].anchor_pixel);
    }
  }
  // A truncated log is an error, not a silent partial replay.
  const std::string bytes = readBytes(d / "a.log");
  std::ofstream(d / "cut.log", std::ios::binary) << bytes.substr(0, bytes.size() - 10);
  EXPECT_THROW(PerceptionLog::read((d / "cut.log").string()), std::runtime_error);

  // map-replay twice: identical maps; DBOF off changes nothing here but must be accepted.
  const std::string exe = std::string(MSB_BINARY_DIR) + "/bin/msbench";
  for (const char* run : {"r1", "r2"})
    ASSERT_EQ(std::system(("'" + exe + "' map-replay '" + (d / "a.log").string() + "' --out '" + (d / run).string() +
                           "' > /dev/null")
                              .c_str()),
              0);
  // The log's world "synthetic" is no world here: no safety statistics, and the summary says why
  // (before: nothing said).
  const std::string summary = readBytes(d / "r1" / "summary.json");
  EXPECT_NE(summary.find("\"map_safety\": null"), std::string::npos) << summary;
  EXPECT_NE(summary.find("world 'synthetic' cannot be resolved here"), std::string::npos) << summary;
  const std::string ply = readBytes(d / "r1" / "map.ply");
  EXPECT_GT(ply.size(), 1000u);
  EXPECT_EQ(ply, readBytes(d / "r2" / "map.ply"));
  EXPECT_NE(ply.find("element vertex"), std::string::npos);
  EXPECT_EQ(std::system(("'" + exe + "' map-replay '" + (d / "a.log").string() + "' --out '" + (d / "r3").string() +
                         "' --set switches.dbof=false > /dev/null")
                            .c_str()),
            0);
  EXPECT_NE(std::system(("'" + exe + "' map-replay '" + (d / "a.log").string() + "' --out '" + (d / "r4").string() +
                         "' --set map.colour=blue > /dev/null 2>&1")
                            .c_str()),
            0);
  // One spelling: the scenario's method.switches.dbof is switches.dbof here; map.dbof is refused
  // with the right spelling in the message.
  const std::string err = (d / "r5.err").string();
  EXPECT_NE(std::system(("'" + exe + "' map-replay '" + (d / "a.log").string() + "' --out '" + (d / "r5").string() +
                         "' --set map.dbof=false 2> '" + err + "'")
                            .c_str()),
            0);
  EXPECT_NE(readBytes(err).find("switches.dbof"), std::string::npos) << readBytes(err);
}

}  // namespace
}  // namespace msb
