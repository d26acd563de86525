// video.mp4 (RunVideo): the frames and size it documents, decoded by ffprobe; an unfinished
// video leaves nothing; an encoder that cannot write (a file-size limit standing in for a full
// disk), exits 0 over a broken file, never reads or never exits is reported, within its limit, and
// no file is kept; staging follows no link.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <chrono>
#include <cstdlib>
#include <fstream>

#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "tests/tools/cli_helpers.h"
#include "tools/results/run_video.h"

namespace msb {
namespace {

namespace fs = std::filesystem;
using msb_test::FakeEncoder;

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
  EXPECT_FALSE(fs::exists(d / "video.mp4"));  // checked, not yet committed
  EXPECT_EQ(video.commit(), "");
  EXPECT_EQ(msb_test::probeVideo(d / "video.mp4"), "" + std::to_string(video.width()) + ",360,10");
  EXPECT_EQ(mp4Problem(d / "video.mp4", 10), "");
  EXPECT_NE(mp4Problem(d / "video.mp4", 11), "");
}

// The encoder writes into a directory msbench made: links at the names older builds used, and a
// user's files there, are never followed, truncated or removed.
TEST_F(RunVideoTest, StagingNeverFollowsALinkOrTouchesAUsersFile) {
  const fs::path d = tempDir("links");
  std::ofstream(d / "mine.txt") << "a user's file";
  for (const char* name : {"video.mp4.partial", "video.mp4.ffmpeg.log", ".video.mp4.replay"})
    fs::create_symlink(d / "mine.txt", d / name);
  const MissionResult r = smallRun();
  {
    RunVideo video(d / "video.mp4", VideoSettings{}, "test", 60, r.exploration_box, nullptr, 376, 240);
    video.addFinalFrames(r, nullptr);
    EXPECT_EQ(video.finish(), "");
    EXPECT_EQ(video.commit(), "");
  }
  EXPECT_EQ(msb_test::readText(d / "mine.txt"), "a user's file");
  int entries = 0;
  for (const auto& e : fs::directory_iterator(d)) {
    ++entries;
    EXPECT_EQ(e.path().filename().string().rfind(".msbench-video-", 0), std::string::npos) << e.path();
  }
  EXPECT_EQ(entries, 5);  // mine.txt, the three links, video.mp4: no staging left
}

// An encoder that exits 0 over a file without its index (as ffmpeg does after a failed write)
// makes no video: the file is checked, not the exit status.
TEST_F(RunVideoTest, AnEncoderThatExitsCleanlyOverABrokenFileMakesNoVideo) {
  const fs::path d = tempDir("broken");
  const FakeEncoder fake(d / "bin", "cat > /dev/null; for a; do out=$a; done; printf 'junk' > \"$out\"; exit 0");
  const MissionResult r = smallRun();
  RunVideo video(d / "video.mp4", VideoSettings{}, "test", 60, r.exploration_box, nullptr, 376, 240);
  video.addFinalFrames(r, nullptr);
  const std::string error = video.finish();
  EXPECT_NE(error.find("not a whole video"), std::string::npos) << error;
  EXPECT_NE(video.commit(), "");
  EXPECT_FALSE(fs::exists(d / "video.mp4"));
}

// An encoder that never reads (stuck, or stopped with SIGSTOP) blocks nothing: each wait calls
// the hook, and an interrupt thrown there ends the video at once, leaving nothing.
TEST_F(RunVideoTest, AStuckEncoderNeverBlocksAnInterrupt) {
  const fs::path d = tempDir("stuck");
  const FakeEncoder fake(d / "bin", "exec sleep 600");
  const MissionResult r = smallRun();
  const auto start = std::chrono::steady_clock::now();
  {
    RunVideo video(d / "video.mp4", VideoSettings{}, "test", 60, r.exploration_box, nullptr, 376, 240);
    int waits = 0;
    video.setWaitHook([&] {
      if (++waits == 5) throw std::runtime_error("interrupted");
    });
    EXPECT_THROW(video.addFinalFrames(r, nullptr), std::runtime_error);
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  for (const auto& e : fs::directory_iterator(d)) EXPECT_EQ(e.path().filename(), "bin") << e.path();
}

// An encoder that reads every frame but never exits is killed at the stall limit: the video is
// given up, named, and nothing is kept.
TEST_F(RunVideoTest, AnEncoderThatNeverExitsIsKilledAtTheLimit) {
  const fs::path d = tempDir("never_exits");
  const FakeEncoder fake(d / "bin", "cat > /dev/null; exec sleep 600");
  const MissionResult r = smallRun();
  const auto start = std::chrono::steady_clock::now();
  RunVideo video(d / "video.mp4", VideoSettings{}, "test", 60, r.exploration_box, nullptr, 376, 240);
  video.setStallLimit(0.5);
  video.addFinalFrames(r, nullptr);
  const std::string error = video.finish();
  EXPECT_NE(error.find("did not finish within 0.5 s"), std::string::npos) << error;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  EXPECT_NE(video.commit(), "");
  EXPECT_FALSE(fs::exists(d / "video.mp4"));
}

// An encoder that stops reading (stuck, or stopped with SIGSTOP) ends the video at the stall
// limit, not the caller: the frames after it are dropped, the error says why, nothing is kept.
TEST_F(RunVideoTest, AnEncoderThatStopsReadingEndsTheVideoNotTheRun) {
  const fs::path d = tempDir("stops_reading");
  const FakeEncoder fake(d / "bin", "exec sleep 600");
  const MissionResult r = smallRun();
  const CameraFrame cam = noiseFrame(752, 480);
  const auto start = std::chrono::steady_clock::now();
  RunVideo video(d / "video.mp4", VideoSettings{}, "test", 60, r.exploration_box, nullptr, cam.width, cam.height);
  video.setStallLimit(0.5);
  for (int i = 0; i < 3; ++i) video.addFinalFrames(r, &cam);  // far more than a pipe holds
  const std::string error = video.finish();
  EXPECT_NE(error.find("read no frame for 0.5 s"), std::string::npos) << error;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  EXPECT_NE(video.commit(), "");
  for (const auto& e : fs::directory_iterator(d)) EXPECT_EQ(e.path().filename(), "bin") << e.path();
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
