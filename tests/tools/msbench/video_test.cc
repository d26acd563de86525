// Videos of runs (msbench run --video, msbench video RUN; docs/video.md): the frames and size as
// documented, the run's hash unchanged by the video, a replay that adds the video to a finished
// run, a video that cannot be written (file-size limit) loses none of the run's other files, a
// stuck encoder holds up no interrupt, bad video settings write nothing.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_helpers.h"

namespace {

namespace fs = std::filesystem;
using msb_test::readText;
using msb_test::run;

const std::string kScenario = std::string(MSB_SOURCE_DIR) + "/scenarios/missions/test_world_short.yaml";

fs::path tempDir(const std::string& name) { return msb_test::tempDir("msb_video_cli_", name); }

bool haveFfmpeg() {
  return std::system("command -v ffmpeg >/dev/null 2>&1 && command -v ffprobe >/dev/null 2>&1") == 0;
}

nlohmann::json metrics(const fs::path& run_dir) { return nlohmann::json::parse(readText(run_dir / "metrics.json")); }

TEST(Video, ARunWithVideoKeepsItsHashAndTheVideoIsAsDocumented) {
  if (!haveFfmpeg()) GTEST_SKIP() << "ffmpeg is not installed (apt-get install ffmpeg)";
  const fs::path d = tempDir("run");
  ASSERT_EQ(
      run("run '" + kScenario + "' --duration 20 --quiet --video --out '" + (d / "v").string() + "'", d / "log_v"), 0)
      << readText(d / "log_v");
  ASSERT_EQ(run("run '" + kScenario + "' --duration 20 --quiet --out '" + (d / "p").string() + "'", d / "log_p"), 0)
      << readText(d / "log_p");
  const auto v = metrics(d / "v"), p = metrics(d / "p");
  EXPECT_EQ(v["determinism_hash"], p["determinism_hash"]);
  EXPECT_FALSE(p.contains("video"));
  EXPECT_FALSE(fs::exists(d / "p" / "video.mp4"));
  // One frame a simulated second (speedup 10 at 10 fps) for 20 s, then the end held 2 s (20).
  ASSERT_TRUE(v.contains("video")) << v.dump(2);
  EXPECT_EQ(v["video"]["file"], "video.mp4");
  EXPECT_EQ(v["video"]["frames"], 40);
  EXPECT_EQ(v["video"]["height"], 720);
  EXPECT_EQ(msb_test::probeVideo(d / "v" / "video.mp4"), std::to_string(v["video"]["width"].get<int>()) + ",720,40");
  EXPECT_NE(readText(d / "v" / "config.yaml").find("enabled: true"), std::string::npos);

  // The finished run without a video gets one from a replay; its record is not touched.
  const std::string before = readText(d / "p" / "metrics.json");
  ASSERT_EQ(run("video '" + (d / "p").string() + "' --quiet --set video.fps=5", d / "log_r"), 0)
      << readText(d / "log_r");
  EXPECT_NE(readText(d / "log_r").find("matches"), std::string::npos) << readText(d / "log_r");
  EXPECT_EQ(readText(d / "p" / "metrics.json"), before);
  EXPECT_EQ(msb_test::probeVideo(d / "p" / "video.mp4"), std::to_string(v["video"]["width"].get<int>()) + ",720,20");
  EXPECT_EQ(run("video '" + (d / "p").string() + "' --quiet", d / "log_again"), 2);  // exists: --overwrite
  // A config.yaml that is a FIFO is refused, not read (it would block).
  fs::create_directories(d / "f");
  fs::copy_file(d / "p" / "metrics.json", d / "f" / "metrics.json");
  fs::copy_file(d / "p" / "coverage.csv", d / "f" / "coverage.csv");
  ASSERT_EQ(mkfifo((d / "f" / "config.yaml").c_str(), 0600), 0);
  EXPECT_EQ(run("video '" + (d / "f").string() + "'", d / "log_fifo"), 2);
  EXPECT_NE(readText(d / "log_fifo").find("config.yaml: is a FIFO"), std::string::npos) << readText(d / "log_fifo");
  EXPECT_EQ(run("video '" + (d / "p").string() + "' --set duration_s=5", d / "log_set"), 2);
  EXPECT_NE(readText(d / "log_set").find("video.KEY"), std::string::npos) << readText(d / "log_set");
}

TEST(Video, AVideoThatCannotBeWrittenLosesNoneOfTheRunsFiles) {
  if (!haveFfmpeg()) GTEST_SKIP() << "ffmpeg is not installed (apt-get install ffmpeg)";
  const fs::path d = tempDir("full");
  // 150 KB per file: every result file fits, the video does not (a full disk for the encoder).
  const std::string cmd = "bash -c \"ulimit -f 150; '" + msb_test::kExe + "' run '" + kScenario +
                          "' --duration 20 --quiet --video --out '" + (d / "v").string() + "'\" > '" +
                          (d / "log").string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readText(d / "log");
  const auto m = metrics(d / "v");
  EXPECT_EQ(m["status"], "completed");
  ASSERT_TRUE(m.contains("video"));
  EXPECT_TRUE(m["video"]["file"].is_null());
  EXPECT_NE(m["video"]["error"].get<std::string>().find("ffmpeg"), std::string::npos) << m["video"].dump();
  EXPECT_NE(readText(d / "log").find((d / "v" / "video.mp4").string()), std::string::npos) << readText(d / "log");
  for (const char* f : {"config.yaml", "coverage.csv", "trajectory.csv", "topdown.png", "map.ply"})
    EXPECT_TRUE(fs::exists(d / "v" / f)) << f;
  for (const auto& e : fs::directory_iterator(d / "v"))
    EXPECT_EQ(e.path().filename().string().find("video"), std::string::npos) << e.path();
}

// An encoder that never reads (stuck, or stopped with SIGSTOP) holds up no signal: SIGINT ends
// `run --video` at once, the encoder is killed and nothing is left.
TEST(Video, AStuckEncoderNeverHoldsUpAnInterrupt) {
  const fs::path d = tempDir("stuck");
  const auto start = std::chrono::steady_clock::now();
  int code = 0;
  {
    const msb_test::FakeEncoder stuck(d / "bin", "exec sleep 6017");
    code = msb_test::runAndSignal(
        "run '" + kScenario + "' --duration 600 --quiet --video --out '" + (d / "v").string() + "'", SIGINT, d / "log",
        4000);
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(code, 130) << readText(d / "log");
  EXPECT_LT(s, 4.0 + 2.0) << readText(d / "log");
  EXPECT_FALSE(fs::exists(d / "v"));
  EXPECT_FALSE(fs::exists(d / "v.partial"));
  EXPECT_NE(std::system("pgrep -f '[s]leep 6017' > /dev/null"), 0) << "the encoder outlived msbench";
}

TEST(Video, BadVideoSettingsWriteNothing) {
  const fs::path d = tempDir("bad");
  for (const std::string set :
       {"video.height=721", "video.fps=0", "video.speedup=-1", "video.enabled=maybe", "video.colour=red"}) {
    EXPECT_EQ(run("run '" + kScenario + "' --quiet --set " + set + " --out '" + (d / "out").string() + "'", d / "log"),
              2)
        << set;
    EXPECT_NE(readText(d / "log").find(set.substr(6, set.find('=') - 6)), std::string::npos) << readText(d / "log");
    EXPECT_FALSE(fs::exists(d / "out")) << set;
  }
}

}  // namespace
