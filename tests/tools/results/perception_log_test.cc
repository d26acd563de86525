// The perception log reader: seeded mutation fuzzing (tests/tools/fuzz_helpers.h) and the frame
// checksum.
#include <gtest/gtest.h>

#include "tests/tools/fuzz_helpers.h"
#include "tools/results/perception_log.h"

namespace msb {
namespace {

using namespace fuzz_test;

TEST(Fuzz, PerceptionLogs) {
  const fs::path d = dir("log");
  // A small valid log: three frames of a few points.
  {
    PerceptionLogWriter w((d / "seed.log").string(), nlohmann::json{{"camera_scale", 0.5}, {"world", "test"}});
    for (int f = 0; f < 3; ++f) {
      SlamPointsFrame frame;
      frame.tick = f * 33;
      frame.t_s = f / 15.0;
      for (int k = 0; k < 4; ++k) {
        SlamPoint p;
        p.track_id = uint64_t(k + 1);
        p.p_W = Vec3(3 + k, 0.5 * k, 1);
        p.depth_m = 3.0 + k;  // as the front end makes it: the reader checks contents
        p.anchor_tick = frame.tick;
        frame.points.push_back(p);
      }
      w.write(frame, Pose::Identity());
    }
    w.close();
  }
  fuzz(readFile(d / "seed.log"), d / "f.log", 2000, "fuzz_log", [](const std::string& p) { PerceptionLog::read(p); });
}

TEST(PerceptionLogFormat, AFlippedByteFailsTheChecksumOfItsFrame) {
  const fs::path d = dir("checksum");
  {
    PerceptionLogWriter w((d / "a.log").string(), nlohmann::json{{"camera_scale", 1}});
    for (int f = 0; f < 2; ++f) {
      SlamPointsFrame frame;
      frame.tick = f;
      SlamPoint p;
      p.track_id = 7;
      p.p_W = Vec3(1, 2, 3);
      p.depth_m = 3.7;  // a point as the front end makes it (the reader checks contents too)
      frame.points.push_back(p);
      w.write(frame, Pose::Identity());
    }
    w.close();
  }
  ASSERT_EQ(PerceptionLog::read((d / "a.log").string()).frames.size(), 2u);
  std::string bytes = readFile(d / "a.log");
  bytes[bytes.size() - 20] ^= 0x10;  // inside the last frame's payload
  std::ofstream(d / "b.log", std::ios::binary) << bytes;
  try {
    PerceptionLog::read((d / "b.log").string());
    FAIL() << "a corrupt frame was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("checksum mismatch in frame 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace msb
