// The inputs added after the YAML ones, by class (docs/robustness.md, "Input classes"): world
// imports, salt files, compute replay logs and sweep layouts. Every class meets the same hostile
// files — a FIFO, a directory, a device, a link out of where it belongs, a file far too large —
// and its own nonsense; each case exits 2 (or 128 + signal) naming the file and the reason,
// writes nothing, and leaves what was there (the user's files, an earlier import) as it was. A new
// input joins by adding a row to kFileInputs and its own cases beside the others.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/png.h"
#include "tests/tools/cli_helpers.h"

namespace {

namespace fs = std::filesystem;
using msb_test::readText;

const std::string kSrc = MSB_SOURCE_DIR;
const std::string kScenario = kSrc + "/scenarios/missions/test_world_short.yaml";

// A test's directory: a world folder (MSBENCH_WORLDS_DIR) holding `boxes`, an imported box mesh
// with its material library and image, its checkout and a cache (MSBENCH_CACHE_DIR).
struct Dir {
  explicit Dir(const std::string& name) : d(msb_test::tempDir("msb_inputs_", name)) {
    fs::create_directories(d / "worlds" / "boxes");
    fs::create_directories(d / "cache");
    writeCheckout(d / "checkout");
    worldSpec("boxes", "");
    write("sentinel", "keep me");
  }
  void write(const fs::path& rel, const std::string& text) const {
    fs::create_directories((d / rel).parent_path());
    std::ofstream(d / rel) << text;
  }
  // worlds/NAME/spec.yaml: the box mesh, with `mesh_extra` in its entry.
  void worldSpec(const std::string& name, const std::string& mesh_extra) const {
    write("worlds/" + name + "/spec.yaml",
          "name: " + name +
              "\ndescription: an imported box\nseed: 1\nground: {size_m: [40, 40]}\n"
              "start: {position: [0, 0, 0], yaw_deg: 0}\nexploration_box: {min: [-15, -15, 0], max: [15, 15, 5]}\n"
              "source: {repository: test/fixture, commit: 0000000}\n"
              "meshes:\n  - {file: meshes/box.obj, name: box" +
              mesh_extra + "}\n");
  }
  // A box (2 x 2 x 2 m at (8, 8)) with texture coordinates, its .mtl and a grey image.
  void writeCheckout(const fs::path& c) const {
    fs::create_directories(c / "meshes");
    std::ofstream o(c / "meshes" / "box.obj");
    o << "mtllib box.mtl\no box\nusemtl paint\nvt 0 0\nvt 1 0\nvt 1 1\n";
    for (int k = 0; k < 8; ++k)
      o << "v " << 8 + (k & 1 ? 1 : -1) << " " << 8 + (k & 2 ? 1 : -1) << " " << (k & 4 ? 2 : 0) << "\n";
    const int f[12][3] = {{1, 3, 4}, {1, 4, 2}, {5, 6, 8}, {5, 8, 7}, {1, 2, 6}, {1, 6, 5},
                          {3, 7, 8}, {3, 8, 4}, {1, 5, 7}, {1, 7, 3}, {2, 4, 8}, {2, 8, 6}};
    for (const auto& t : f) o << "f " << t[0] << "/1 " << t[1] << "/2 " << t[2] << "/3\n";
    std::ofstream(c / "meshes" / "box.mtl") << "newmtl paint\nKd 0.8 0.8 0.8\nmap_Kd grey.png\n";
    // A 16 x 16 grey ramp.
    std::vector<uint8_t> px(256);
    for (size_t k = 0; k < px.size(); ++k) px[k] = uint8_t(k);
    msb::writePng(c / "meshes" / "grey.png", msb::ImageView{px.data(), 16, 16, 1, 16});
  }
  // Built by appending: GCC 12 warns falsely (-Wrestrict) on chained operator+ here.
  std::string p(const fs::path& rel) const {
    std::string q = "'";
    q.append((d / rel).string()).append("'");
    return q;
  }
  std::string env() const {
    return "MSBENCH_WORLDS_DIR='" + (d / "worlds").string() + "' MSBENCH_CACHE_DIR='" + (d / "cache").string() + "' ";
  }
  // Runs `env msbench args` (output to d/log); its exit code.
  int run(const std::string& args, const std::string& env_extra = "") const {
    const std::string cmd =
        env() + env_extra + " '" + msb_test::kExe + "' " + args + " > '" + (d / "log").string() + "' 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string log() const { return readText(d / "log"); }
  // Every path under the directory (but the log).
  std::set<fs::path> entries() const {
    std::set<fs::path> out;
    for (const auto& e : fs::recursive_directory_iterator(d))
      if (e.path() != d / "log") out.insert(e.path());
    return out;
  }
  // Runs and checks: exit code `code`, each fragment in the output, nothing added or removed,
  // the sentinel intact, within `limit_s` of wall time.
  void expectRefused(const std::string& args, std::initializer_list<std::string> fragments, int code = 2,
                     const std::string& env_extra = "", double limit_s = 20) const {
    const std::set<fs::path> before = entries();
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(run(args, env_extra), code) << args << "\n" << log();
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_LT(s, limit_s) << args << ": a refusal must not wait (" << s << " s)";
    for (const auto& f : fragments)
      EXPECT_NE(log().find(f), std::string::npos) << args << "\nmissing: " << f << "\n" << log();
    EXPECT_EQ(entries(), before) << args << ": wrote or removed files\n" << log();
    EXPECT_EQ(readText(d / "sentinel"), "keep me");
  }
  fs::path d;
};

// The hostile files every file input meets: (name, how to make it at `path`, what the message says).
struct Hostile {
  std::string name;
  std::function<void(const fs::path&)> make;
  std::string says;
};
std::vector<Hostile> hostileFiles() {
  return {{"fifo", [](const fs::path& p) { ASSERT_EQ(::mkfifo(p.c_str(), 0644), 0); }, "FIFO"},
          {"directory", [](const fs::path& p) { fs::create_directories(p); }, "directory"},
          {"device", [](const fs::path& p) { fs::create_symlink("/dev/zero", p); }, ""},
          {"huge",
           [](const fs::path& p) {
             std::ofstream{p};
             fs::resize_file(p, uintmax_t(1) << 30);
           },
           ""}};
}

// A file input of msbench's: how a run is pointed at `path` (the command and its environment).
struct FileInput {
  std::string name;
  std::function<std::pair<std::string, std::string>(const Dir&, const fs::path&)> command;  // (args, env)
  std::string names;  // what the message names besides the path
  bool size_limited;  // refuses a file far too large (a mesh may be large: only its kind is checked)
};
// A file of the import's checkout (meshes/NAME) replaced by a link to the hostile file.
FileInput importedFile(const std::string& what, const std::string& name) {
  return {what,
          [name](const Dir& t, const fs::path& p) {
            fs::remove_all(t.d / "checkout" / "meshes" / name);
            fs::create_symlink(p, t.d / "checkout" / "meshes" / name);
            return std::make_pair("world import boxes --from " + t.p("checkout"), std::string());
          },
          name, false};
}
const std::vector<FileInput>& fileInputs() {
  static const std::vector<FileInput> inputs = {
      {"salt file",
       [](const Dir& t, const fs::path& p) {
         return std::make_pair(
             "run '" + kScenario + "' --set world=urban --set held_out=true --quiet --out " + t.p("out"),
             "MSBENCH_WORLD_SALT= MSBENCH_WORLD_SALT_FILE='" + p.string() + "'");
       },
       "MSBENCH_WORLD_SALT_FILE", true},
      {"replay log",
       [](const Dir& t, const fs::path& p) {
         return std::make_pair("run '" + kScenario + "' --set timing.compute=charged --set timing.replay='" +
                                   p.string() + "' --quiet --out " + t.p("out"),
                               std::string());
       },
       "timing.replay", true},
      importedFile("mesh", "box.obj"),
      importedFile("material library", "box.mtl"),
      importedFile("image", "grey.png"),
  };
  return inputs;
}

TEST(InputClasses, EveryFileInputRefusesFifosDirectoriesDevicesAndHugeFilesAtOnce) {
  for (const FileInput& in : fileInputs())
    for (const Hostile& h : hostileFiles()) {
      if (h.name == "huge" && !in.size_limited) continue;
      SCOPED_TRACE(in.name + " / " + h.name);
      const Dir t("hostile");
      // The hostile file inside the checkout, so that only its kind is wrong (links to it are
      // inside too); a device is a link out of the checkout.
      const fs::path p = t.d / "checkout" / ("hostile_" + h.name);
      h.make(p);
      const auto [args, env] = in.command(t, p);
      // Nothing for the import's cache may appear either: the check runs against the whole tree.
      t.expectRefused(args, {in.names, h.says}, 2, env, 10);
    }
}

TEST(InputClasses, SaltFilesAreBoundedInSize) {
  const Dir t("salt");
  t.write("salt", std::string(5000, 'a'));
  t.expectRefused("run '" + kScenario + "' --set world=urban --set held_out=true --quiet --out " + t.p("out"),
                  {"MSBENCH_WORLD_SALT_FILE", "5000 bytes, more than the limit of 4096"}, 2,
                  "MSBENCH_WORLD_SALT= MSBENCH_WORLD_SALT_FILE='" + (t.d / "salt").string() + "'");
}

// Imports: the user's directory at the target is kept; an import msbench cannot remove whole is
// replaced without a moment the world does not build; nothing from outside the checkout is copied;
// an absent image without a stand-in is an error; a signal during a long import ends it at once.
TEST(InputClasses, AnImportReplacesOnlyItsOwnAndNeverLeavesTheWorldUnbuildable) {
  const Dir t("import");
  // A user's directory where the import would go.
  t.write("cache/sources/boxes/NOTES.txt", "mine");
  t.expectRefused("world import boxes --from " + t.p("checkout"), {"cache/sources/boxes", "refusing to replace it"});
  fs::remove_all(t.d / "cache" / "sources" / "boxes");
  // The first import copies the mesh, its material library and its image, and builds.
  ASSERT_EQ(t.run("world import boxes --from " + t.p("checkout")), 0) << t.log();
  EXPECT_NE(t.log().find("image meshes/grey.png"), std::string::npos) << t.log();
  for (const char* f : {"meshes/box.obj", "meshes/box.mtl", "meshes/grey.png", ".msbench-output"})
    EXPECT_TRUE(fs::is_regular_file(t.d / "cache" / "sources" / "boxes" / f)) << f;
  // A re-import over an import with a file that cannot be removed (immutable): the new import is
  // in place and builds; the old one is left aside, named.
  const fs::path locked = t.d / "cache" / "sources" / "boxes" / "meshes" / "grey.png";
  if (std::system(("chattr +i '" + locked.string() + "' 2>/dev/null").c_str()) == 0) {
    EXPECT_EQ(t.run("world import boxes --from " + t.p("checkout")), 0) << t.log();
    EXPECT_NE(t.log().find("could not be removed whole"), std::string::npos) << t.log();
    EXPECT_EQ(t.run("world build boxes"), 0) << t.log();
    for (const auto& e : fs::directory_iterator(t.d / "cache" / "sources"))
      std::system(("chattr -R -i '" + e.path().string() + "' 2>/dev/null").c_str());
  }
  EXPECT_EQ(t.run("world build boxes"), 0) << t.log();
  // A texture linked to a file outside the checkout: refused, the earlier import kept.
  fs::remove(t.d / "checkout" / "meshes" / "grey.png");
  t.write("outside.png", "secret");
  fs::create_symlink(t.d / "outside.png", t.d / "checkout" / "meshes" / "grey.png");
  t.expectRefused("world import boxes --from " + t.p("checkout"), {"grey.png", "outside the checkout"});
  EXPECT_EQ(t.run("world build boxes"), 0) << t.log();
  // The image absent and no stand-in (missing_texture: ""): an error, as docs/worlds.md says.
  fs::remove(t.d / "checkout" / "meshes" / "grey.png");
  t.worldSpec("bare", ", missing_texture: \"\"");
  t.expectRefused("world import bare --from " + t.p("checkout"), {"grey.png", "missing_texture"});
}

TEST(InputClasses, ASignalDuringALongImportEndsItWithinASecond) {
  const Dir t("signal");
  // A terrain of 80 x 80 cells takes seconds to read and cut.
  {
    std::ofstream o(t.d / "checkout" / "meshes" / "box.obj");
    const int n = 80;
    o << "o terrain\n";
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        o << "v " << -20 + 40.0 * i / n << " " << -20 + 40.0 * j / n << " " << 0.06 * ((i * 7 + j * 3) % 5) << "\n";
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = 1 + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
        o << "f " << a << " " << b << " " << d << "\nf " << a << " " << d << " " << c << "\n";
      }
  }
  const std::set<fs::path> before = t.entries();
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string cmd = "exec env " + t.env() + " '" + msb_test::kExe + "' world import boxes --from " +
                            t.p("checkout") + " > '" + (t.d / "log").string() + "' 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, WNOHANG), 0) << "the import ended before the signal; make the mesh larger";
  kill(pid, SIGINT);
  const auto t0 = std::chrono::steady_clock::now();
  waitpid(pid, &status, 0);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_LT(s, 1.0) << "the signal was honoured after " << s << " s";
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130) << t.log();
  EXPECT_NE(t.log().find("interrupted (SIGINT)"), std::string::npos) << t.log();
  EXPECT_EQ(t.entries(), before) << "the import left files behind";
}

// Replay logs: checked whole before the run — a bad row, a machine factor that is no finite number
// above 0 — and only into the run they were measured in (its seed, its settings).
TEST(InputClasses, AReplayLogIsCheckedWholeAndOnlyReplaysItsOwnRun) {
  const Dir t("replay");
  ASSERT_EQ(t.run("run '" + kScenario + "' --set timing.compute=charged --duration 4 --quiet --out " + t.p("r")), 0)
      << t.log();
  fs::remove_all(t.d / "out");
  t.expectRefused("run " + t.p("r/config.yaml") + " --seed 2 --quiet --out " + t.p("out"),
                  {"compute_latency.csv", "seed 1, this run's seed is 2"});
  t.expectRefused("run " + t.p("r/config.yaml") + " --duration 3 --quiet --out " + t.p("out"),
                  {"compute_latency.csv", "scenario settings"});
  // Edited logs, each beside a copy of the run's config.yaml.
  const std::string log = readText(t.d / "r" / "compute_latency.csv");
  const size_t row = log.find("\n1,") + 1, row_end = log.find('\n', row);
  const std::string second = log.substr(row, row_end - row);
  auto edited = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::string text = log;
    text.replace(text.find(from), from.size(), to);
    fs::create_directories(t.d / name);
    fs::copy_file(t.d / "r" / "config.yaml", t.d / name / "config.yaml");
    std::ofstream(t.d / name / "compute_latency.csv") << text;
    return t.p(name + "/config.yaml");
  };
  const std::string mf = log.substr(log.find("machine_factor "), log.find("; seed") - log.find("machine_factor "));
  for (const char* f : {"nan", "inf", "-1", "0", "12abc", "0x10"})
    t.expectRefused("run " + edited(std::string("mf_") + f, mf, std::string("machine_factor ") + f) +
                        " --quiet --out " + t.p("out"),
                    {"compute_latency.csv", "line 1", "machine_factor"});
  const std::string head = second.substr(0, second.rfind(',') + 1);
  for (const auto& [tag, latency, says] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"max", "9223372036854775807", "outside 0...1800000 ticks"},
           {"abc", "0abc", "not an integer"},
           {"plus", "+0", "not a plain integer"}})
    t.expectRefused("run " + edited("row_" + tag, second, head + latency) + " --quiet --out " + t.p("out"),
                    {"compute_latency.csv", "line 4", says});
}

// Sweep layouts: a run directory that is a link to a run elsewhere is not the sweep's; a run id
// with control characters is shown inert in every page; pending runs are counted, not listed.
TEST(InputClasses, OddSweepLayoutsReportTheSweepAsItIs) {
  const Dir t("sweep");
  ASSERT_EQ(t.run("run '" + kScenario + "' --duration 3 --quiet --out " + t.p("elsewhere")), 0) << t.log();
  const std::string evil = "s2\nevil<img src=x onerror=alert(1)>\x1b[31m";
  nlohmann::json runs = nlohmann::json::array();
  runs.push_back(
      {{"id", "s1"}, {"seed", 1}, {"scenario", kScenario}, {"status", "complete"}, {"labels", {{"seed", "1"}}}});
  runs.push_back(
      {{"id", evil}, {"seed", 2}, {"scenario", kScenario}, {"status", "complete"}, {"labels", {{"seed", "2"}}}});
  for (int i = 3; i < 60; ++i) {
    std::string id = "s";  // appended: GCC 12 warns falsely (-Wrestrict) on "s" + std::to_string(i)
    id.append(std::to_string(i));
    runs.push_back({{"id", id},
                    {"seed", i},
                    {"scenario", kScenario},
                    {"status", "pending"},
                    {"labels", {{"seed", std::to_string(i)}}}});
  }
  fs::create_directories(t.d / "sw" / "runs");
  std::ofstream(t.d / "sw" / "sweep.json") << nlohmann::json{{"axes", {"seed"}}, {"runs", runs}}.dump();
  fs::create_symlink(t.d / "elsewhere", t.d / "sw" / "runs" / "s1");
  fs::copy(t.d / "elsewhere", t.d / "sw" / "runs" / evil);
  ASSERT_EQ(t.run("report " + t.p("sw") + " --out " + t.p("rep")), 0) << t.log();
  EXPECT_NE(t.log().find("run s1 counts as failed: runs/s1 is a link"), std::string::npos) << t.log();
  EXPECT_EQ(t.log().find('\x1b'), std::string::npos) << "a control character reached the terminal";
  const std::string md = readText(t.d / "rep" / "report.md"), html = readText(t.d / "rep" / "report.html");
  const std::string csv = readText(t.d / "rep" / "report_runs.csv");
  EXPECT_NE(md.find("1 failed"), std::string::npos) << md;
  for (const std::string* page : {&md, &html}) {
    EXPECT_EQ(page->find("<img src=x"), std::string::npos) << "the id's markup reached a page";
    EXPECT_EQ(page->find('\x1b'), std::string::npos);
    EXPECT_NE(page->find("s2evil&lt;img"), std::string::npos) << "the id is shown, inert, on one line";
  }
  EXPECT_NE(csv.find("\"s2\nevil<img src=x onerror=alert(1)>\x1b[31m\""), std::string::npos) << csv;
  // Pending runs: the first 20 by name, the rest counted.
  EXPECT_NE(md.find("| s22 | pending"), std::string::npos);
  EXPECT_EQ(md.find("| s23 | pending"), std::string::npos);
  EXPECT_NE(md.find("… and 37 more pending"), std::string::npos) << md;
}

// A video replay clears what a killed one left (its encoder directory) and nothing else; --video
// without an encoder blames the encoder, not the scenario; `-0` is called what it is.
TEST(InputClasses, VideoLeftoversEncodersAndSignedZeros) {
  const Dir t("video");
  ASSERT_EQ(t.run("run '" + kScenario + "' --duration 2 --quiet --out " + t.p("r")), 0) << t.log();
  t.write("r/.msbench-video-Ab12Cd/ffmpeg.log", "killed");
  t.write("r/.msbench-video-keepme/NOTES.txt", "a user's");
  if (std::system("command -v ffmpeg >/dev/null 2>&1") == 0) {
    ASSERT_EQ(t.run("video " + t.p("r") + " --quiet"), 0) << t.log();
    EXPECT_FALSE(fs::exists(t.d / "r" / ".msbench-video-Ab12Cd")) << "the killed replay's directory is still there";
    EXPECT_EQ(readText(t.d / "r" / ".msbench-video-keepme" / "NOTES.txt"), "a user's");
  }
  // No encoder on PATH: the flag and the encoder are named.
  t.expectRefused("run '" + kScenario + "' --video --quiet --out " + t.p("out"), {"--video", "video encoder"}, 2,
                  "PATH=/nonexistent");
  EXPECT_EQ(t.log().find("test_world_short.yaml"), std::string::npos) << t.log();
  t.expectRefused("run '" + kScenario + "' --seed -0 --quiet --out " + t.p("out"), {"'-0' carries a minus sign"});
}

TEST(InputClasses, ABoxBesideTheWorldOrASpawnInAnObjectIsRefusedBeforeAnythingIsWritten) {
  // Issue 91's inputs: a box with no part of its footprint over the ground (before, the run
  // started and failed 2 s in, exit 1, its record written), a spawn inside an object.
  const Dir t("boxes");
  t.expectRefused("run '" + kScenario + "' --quiet --out " + t.p("out") +
                      " --set 'exploration_box.min=[1000, 1000, 0]' --set 'exploration_box.max=[1010, 1010, 5]'",
                  {"exploration_box", "lies outside the world"});
  t.expectRefused("run '" + kScenario + "' --quiet --out " + t.p("out") + " --set 'start.position=[-2, 20, 2]'",
                  {"start.position", "inside geom 'wall_north_4'"});
}

}  // namespace
