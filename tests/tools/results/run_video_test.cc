// video.mp4 (RunVideo): the frames and size it documents, decoded by ffprobe; an unfinished
// video leaves nothing; an encoder that cannot write (a file-size limit standing in for a full
// disk) is reported and no file is kept.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "tests/tools/cli_helpers.h"
#include "tools/results/run_video.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / ("msb_video_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// A camera frame of noise (the encoder cannot compress it away).
CameraFrame noiseFrame(int w, int h) {
  CameraFrame f;
  f.width = w, f.height = h;
  f.pixels.resize(size_t(w) * h);
  std::mt19937 rng(7);
  for (auto& p : f.pixels) p = uint8_t(rng() & 0xff);
  return f;
}

MissionResult smallRun() {
  MissionResult r;
  r.exploration_box = {Vec3(-20, -10, 0), Vec3(20, 10, 5)};
  r.final_map.free_space.push_back({1, Vec3(0, 0, 1), 4.0, FreeSpaceElement::Footprint::kDisk});
  r.columns.markDisk(Vec2(0, 0), 4.0);
  r.flight.sim_time_s = 12;
  return r;
}

class RunVideoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (findFfmpeg().empty()) GTEST_SKIP() << "ffmpeg is not installed (apt-get install ffmpeg)";
  }
};

TEST_F(RunVideoTest, FramesAndSizeAreAsDocumented) {
  const fs::path d = tempDir("frames");
  VideoSettings s;
  s.fps = 5, s.height = 360, s.speedup = 10;
  const MissionResult r = smallRun();
  const CameraFrame cam = noiseFrame(376, 240);
  RunVideo video(d / "video.mp4", s, "test", 60, r.exploration_box, nullptr, cam.width, cam.height);
  EXPECT_EQ(video.periodTicks(250), 500);  // speedup / fps = 2 simulated seconds a frame
  // Height as set; the camera panel keeps the image's aspect, the map the box's (with margins).
  EXPECT_EQ(video.height(), 360);
  EXPECT_EQ(video.width() % 2, 0);
  EXPECT_GT(video.width(), 360 * 376 / 240);
  video.addFinalFrames(r, &cam);  // the end, held 2 s: 2 × fps frames
  EXPECT_EQ(video.finish(), "");
  EXPECT_EQ(video.frames(), 10);
  EXPECT_EQ(msb_test::probeVideo(d / "video.mp4"), "" + std::to_string(video.width()) + ",360,10");
  EXPECT_FALSE(fs::exists(d / "video.mp4.partial"));
  EXPECT_FALSE(fs::exists(d / "video.mp4.ffmpeg.log"));
}

TEST_F(RunVideoTest, AnUnfinishedVideoLeavesNothing) {
  const fs::path d = tempDir("unfinished");
  const MissionResult r = smallRun();
  {
    RunVideo video(d / "video.mp4", VideoSettings{}, "test", 60, r.exploration_box, nullptr, 376, 240);
    video.addFinalFrames(r, nullptr);
  }  // an interrupt unwinds here
  EXPECT_TRUE(fs::is_empty(d)) << fs::directory_iterator(d)->path();
}

TEST_F(RunVideoTest, AnEncoderThatCannotWriteIsReportedAndNothingIsKept) {
  const fs::path d = tempDir("full");
  VideoSettings s;
  s.height = 720;
  const MissionResult r = smallRun();
  const CameraFrame cam = noiseFrame(752, 480);
  // A 64 KB file-size limit (inherited by the encoder) stands in for a full disk.
  rlimit old{};
  getrlimit(RLIMIT_FSIZE, &old);
  rlimit small = old;
  small.rlim_cur = 64 * 1024;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string error;
  int frames = 0;
  {
    RunVideo video(d / "video.mp4", s, "test", 60, r.exploration_box, nullptr, cam.width, cam.height);
    for (int i = 0; i < 3; ++i) video.addFinalFrames(r, &cam);
    error = video.finish();
    frames = video.frames();
  }
  setrlimit(RLIMIT_FSIZE, &old);
  EXPECT_NE(error.find("ffmpeg"), std::string::npos) << error;
  EXPECT_GE(frames, 0);
  EXPECT_TRUE(fs::is_empty(d)) << fs::directory_iterator(d)->path();
}

TEST_F(RunVideoTest, AnUnwritableDirectoryFailsNamingThePath) {
  const fs::path file = tempDir("missing") / "no_such_dir" / "video.mp4";
  try {
    RunVideo video(file, VideoSettings{}, "test", 60, smallRun().exploration_box, nullptr, 376, 240);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace msb
