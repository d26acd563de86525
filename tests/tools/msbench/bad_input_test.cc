// Hostile but fair input to every verb: each class of bad input exits 2 with a message naming
// the file and the key (or the flag), and nothing is written or deleted — a sentinel file beside
// the output survives. Interrupts stop a run at the end of a tick and leave nothing behind.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "cli_helpers.h"

namespace {

namespace fs = std::filesystem;

using msb_test::kExe;
using msb_test::readText;
using msb_test::run;

const std::string kSrc = MSB_SOURCE_DIR;

// A test directory with a copy of the test world, a flight file and a sentinel.
struct Dir {
  explicit Dir(const std::string& name) : d(msb_test::tempDir("msb_bad_", name)) {
    fs::copy_file(kSrc + "/worlds/test/world.xml", d / "w.xml");
    write("f.yaml", "world: w.xml\nduration_s: 2\ncamera_stream: {save_every_n: 0}\n"
                    "trajectory: {waypoints: [[0, 0, 1]]}\n");
    write("sentinel", "keep me");
  }
  void write(const std::string& name, const std::string& text) const { std::ofstream(d / name) << text; }
  std::string p(const std::string& name) const { return "'" + (d / name).string() + "'"; }
  std::string log() const { return readText(d / "log"); }
  // Runs msbench and checks: exit code, fragments in the output, nothing new in the directory.
  void expectRefused(const std::string& args, std::initializer_list<std::string> fragments, int code = 2) const {
    std::set<fs::path> before;
    for (const auto& e : fs::recursive_directory_iterator(d)) before.insert(e.path());
    EXPECT_EQ(run(args, d / "log"), code) << args << "\n" << log();
    for (const auto& f : fragments) EXPECT_NE(log().find(f), std::string::npos) << args << "\nmissing: " << f << "\n" << log();
    for (const auto& e : fs::recursive_directory_iterator(d)) {
      if (e.path() == d / "log") continue;
      EXPECT_TRUE(before.count(e.path())) << args << ": wrote " << e.path();
    }
    EXPECT_EQ(readText(d / "sentinel"), "keep me");
  }
  fs::path d;
};

TEST(BadInput, YamlNumbersListsAndDuplicateKeys) {
  const Dir t("yaml");
  t.write("nan.yaml", "world: w.xml\nstart: {position: [0, .nan, 0.05]}\n");
  t.expectRefused("fly " + t.p("nan.yaml") + " --out " + t.p("o"), {"nan.yaml", "start.position[1]", "not a number"});
  t.write("inf.yaml", "world: w.xml\ntrajectory: {waypoints: [[0, 0, 1], [1e308, 0, 1]]}\n");
  t.expectRefused("fly " + t.p("inf.yaml") + " --out " + t.p("o"), {"inf.yaml", "waypoints[1][0]", "out of range"});
  t.write("k.yaml", "world: w.xml\ncamera: {k: [0.1, 0.2, inf, 0.0]}\n");
  t.expectRefused("fly " + t.p("k.yaml") + " --out " + t.p("o"), {"k.yaml", "camera.k[2]"});
  t.write("short.yaml", "world: w.xml\nstart: {position: [0, 0]}\n");
  t.expectRefused("fly " + t.p("short.yaml") + " --out " + t.p("o"), {"start.position", "a list of 3 numbers, got a list of 2"});
  t.write("seed.yaml", "world: w.xml\nseed: 99999999999999999999999\n");
  t.expectRefused("fly " + t.p("seed.yaml") + " --out " + t.p("o"), {"seed.yaml", "seed", "out of range"});
  t.write("dup.yaml", "world: w.xml\nduration_s: 3\nduration_s: 4\n");
  t.expectRefused("fly " + t.p("dup.yaml") + " --out " + t.p("o"), {"dup.yaml", "duration_s", "given twice", "lines 2 and 3"});
  // The same rules in scenarios, and --set values are named as such.
  t.write("s.yaml", "base: " + kSrc + "/scenarios/missions/monospheres.yaml\nworld: w.xml\nseed: 1\nseed: 2\n");
  t.expectRefused("run " + t.p("s.yaml") + " --out " + t.p("o"), {"s.yaml", "seed", "given twice"});
  t.write("s2.yaml", "base: " + kSrc + "/scenarios/missions/monospheres.yaml\nworld: w.xml\n");
  t.expectRefused("run " + t.p("s2.yaml") + " --set duration_s=nan --out " + t.p("o"), {"--set", "duration_s"});
  t.expectRefused("run " + t.p("s2.yaml") + " --set 'start={position: [0, 0, 1], position: [1, 1, 1]}' --out " + t.p("o"),
                  {"--set start", "given twice"});
  // One quantity, one key: the planner's minimum radius is the map's.
  t.expectRefused("run " + t.p("s2.yaml") + " --set method.planner.safety.r_min_m=2 --out " + t.p("o"),
                  {"method.planner.safety.r_min_m", "method.map.r_min_m"});
}

TEST(BadInput, CommandLineFlags) {
  const Dir t("flags");
  t.write("s.yaml", "base: " + kSrc + "/scenarios/missions/monospheres.yaml\nworld: w.xml\n");
  t.expectRefused("run " + t.p("s.yaml") + " --seed '' --out " + t.p("o"), {"--seed", "empty"});
  t.expectRefused("run " + t.p("s.yaml") + " --duration '' --out " + t.p("o"), {"--duration", "empty"});
  t.expectRefused("run " + t.p("s.yaml") + " --seed 99999999999999999999999 --out " + t.p("o"), {"seed", "out of range"});
  t.expectRefused("run " + t.p("s.yaml") + " --seed 1 --seed 2 --out " + t.p("o"), {"--seed given twice"});
  t.expectRefused("render-probe --out " + t.p("x.png") + " --pose 1,2,3,4,5", {"--pose", "got 5 values"});
  t.expectRefused("render-probe --out " + t.p("x.png") + " --pose 1,2,nan,4", {"--pose", "value 3"});
  t.expectRefused("world build sparse --seed -1", {"--seed", "negative"});
}

TEST(BadInput, OutputDirectoriesAreNeverLost) {
  const Dir t("out");
  // The current directory, a parent and / are refused, --overwrite or not.
  for (const char* out : {".", "..", "/"})
    t.expectRefused("fly " + t.p("f.yaml") + " --out " + out + " --overwrite", {"refusing"});
  // A regular file, a foreign non-empty directory, a foreign DIR.partial: refused, untouched.
  t.expectRefused("fly " + t.p("f.yaml") + " --out " + t.p("sentinel") + " --overwrite", {"not a directory"});
  fs::create_directory(t.d / "mine");
  t.write("mine/notes.txt", "precious");
  t.expectRefused("fly " + t.p("f.yaml") + " --out " + t.p("mine"), {"not empty"});
  t.expectRefused("fly " + t.p("f.yaml") + " --out " + t.p("mine") + " --overwrite", {"not written by msbench"});
  EXPECT_EQ(readText(t.d / "mine" / "notes.txt"), "precious");
  fs::create_directory(t.d / "res.partial");
  t.write("res.partial/draft", "draft");
  t.expectRefused("fly " + t.p("f.yaml") + " --out " + t.p("res"), {"res.partial", "not written by msbench"});
  EXPECT_EQ(readText(t.d / "res.partial" / "draft"), "draft");
  // A trailing slash names the same directory; msbench's own result is replaced with --overwrite.
  ASSERT_EQ(run("fly " + t.p("f.yaml") + " --out '" + (t.d / "ok").string() + "/'", t.d / "log"), 0) << t.log();
  EXPECT_TRUE(fs::is_regular_file(t.d / "ok" / "metrics.json"));
  EXPECT_FALSE(fs::exists(t.d / "ok.partial"));
  t.expectRefused("fly " + t.p("f.yaml") + " --out " + t.p("ok"), {"not empty", "--overwrite"});
  EXPECT_EQ(run("fly " + t.p("f.yaml") + " --out " + t.p("ok") + " --overwrite", t.d / "log"), 0) << t.log();
  // A stale staging directory of a killed msbench run is cleared by the next run.
  fs::create_directory(t.d / "stale.partial");
  t.write("stale.partial/.msbench-output", "msbench");
  EXPECT_EQ(run("fly " + t.p("f.yaml") + " --out " + t.p("stale"), t.d / "log"), 0) << t.log();
  EXPECT_FALSE(fs::exists(t.d / "stale.partial"));
  // Output files: --record is checked before the run, render-probe --out too.
  t.write("s.yaml", "base: " + kSrc + "/scenarios/missions/monospheres.yaml\nworld: w.xml\nduration_s: 1\n");
  t.expectRefused("run " + t.p("s.yaml") + " --record /nonexistent/dir/log --out " + t.p("r"), {"--record", "does not exist"});
  t.expectRefused("run " + t.p("s.yaml") + " --record " + t.p("sentinel") + " --out " + t.p("r"), {"--record", "exists"});
  t.expectRefused("render-probe --out " + t.p("sentinel"), {"--out", "exists"});
}

TEST(BadInput, WorldsAndLogs) {
  const Dir t("worlds");
  // A world whose text mentions </mujoco> in a trailing comment is still a world (parsed, not
  // searched); a broken world is a configuration error before anything is written.
  std::ofstream(t.d / "w.xml", std::ios::app) << "<!-- </mujoco> -->\n";
  EXPECT_EQ(run("fly " + t.p("f.yaml") + " --out " + t.p("ok"), t.d / "log"), 0) << t.log();
  t.write("broken.xml", "<mujoco><worldbody><geom type='box'/></worldbody>");
  t.write("b.yaml", "world: broken.xml\ntrajectory: {waypoints: [[0, 0, 1]]}\n");
  t.expectRefused("fly " + t.p("b.yaml") + " --out " + t.p("o"), {"broken.xml", "world"});
  t.write("bs.yaml", "base: " + kSrc + "/scenarios/missions/monospheres.yaml\nworld: broken.xml\n");
  t.expectRefused("run " + t.p("bs.yaml") + " --out " + t.p("o"), {"broken.xml", "world"});
  // Perception logs: not a log, a log with absurd values, a truncated one.
  t.expectRefused("map-replay /dev/zero --out " + t.p("o"), {"/dev/zero"}, 1);
  t.write("notalog", "hello");
  t.expectRefused("map-replay " + t.p("notalog") + " --out " + t.p("o"), {"notalog", "bad magic"}, 1);
  std::string log = "MSBLOG1\n{\"camera_scale\": 1}\n";
  const int64_t tick = 0;
  const double huge[16] = {0, 1e300, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0};
  log.append(reinterpret_cast<const char*>(&tick), sizeof(tick));
  log.append(reinterpret_cast<const char*>(huge), sizeof(huge));
  t.write("huge.log", log);
  t.expectRefused("map-replay " + t.p("huge.log") + " --out " + t.p("o"), {"huge.log", "out of range", "frame 0"}, 1);
  t.write("trunc.log", log.substr(0, log.size() - 5));
  t.expectRefused("map-replay " + t.p("trunc.log") + " --out " + t.p("o"), {"trunc.log", "frame 0"}, 1);
  t.expectRefused("map-replay " + t.p("notalog") + " --map-rate-hz 0 --out " + t.p("o"), {"--map-rate-hz"});
  t.expectRefused("map-replay " + t.p("notalog") + " --map-rate-hz -5 --out " + t.p("o"), {"--map-rate-hz"});
}

// Starts msbench, sends `sig` once it is running, returns its exit code.
int runAndSignal(const std::string& args, int sig, const fs::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string cmd = "exec '" + kExe + "' " + args + " > '" + log.string() + "' 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

TEST(BadInput, InterruptsLeaveNothingBehind) {
  const Dir t("signals");
  // The square is flown 40 times (~750 s simulated, more than the 600 s duration): the flight must
  // still be running when the signal comes, however fast the machine (one square is ~19 s
  // simulated, about 2 s of wall time without the tracker).
  std::string square_40 = "[0, 0, 1]";
  for (int i = 0; i < 40; ++i) square_40 += ", [10, 0, 1], [10, 10, 1], [0, 0, 1]";
  t.write("long.yaml", "world: w.xml\nduration_s: 600\ncamera_stream: {save_every_n: 0}\n"
                       "trajectory: {waypoints: [" + square_40 + "]}\n");
  t.write("m.yaml", "base: " + kSrc + "/scenarios/missions/monospheres.yaml\nworld: w.xml\n"
                    "start: {position: [0, 0, 0.05], yaw_deg: 0}\nexploration_box: {min: [-19, -19, 0], max: [19, 19, 4]}\n");
  EXPECT_EQ(runAndSignal("fly " + t.p("long.yaml") + " --out " + t.p("f"), SIGINT, t.d / "log"), 130) << t.log();
  EXPECT_NE(t.log().find("interrupted"), std::string::npos) << t.log();
  EXPECT_EQ(runAndSignal("run " + t.p("m.yaml") + " --quiet --record " + t.p("rec.log") + " --out " + t.p("r"), SIGTERM,
                         t.d / "log"),
            143)
      << t.log();
  for (const char* gone : {"f", "f.partial", "r", "r.partial", "rec.log", "rec.log.tmp"})
    EXPECT_FALSE(fs::exists(t.d / gone)) << gone;
  EXPECT_EQ(readText(t.d / "sentinel"), "keep me");
}

}  // namespace
