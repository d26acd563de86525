// Every command end to end through the shared output and reader code, with generated paths and
// files (issue 58): a seeded generator builds trees of directories, symlinks, `..`, `.` and
// trailing slashes with real msbench outputs planted here and there and the command's inputs in
// one place, and names an output somewhere in it; then it spoils one input file of a command at a
// time (a FIFO, a device, a directory, an oversized or deeply nested file, a key twice, truncated
// or corrupted bytes). Whatever comes, each command exits 0 or 2 within a time limit, never loses
// an input, writes only where outputPathOf says, and names the file it refused.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/common/rng.h"
#include "tests/tools/cli_helpers.h"
#include "tools/results/output_files.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

using msb_test::readText;

const std::string kSrc = MSB_SOURCE_DIR;

/// Cases per command (MSB_FUZZ_CASES overrides; the sanitizer build can run fewer).
int casesPerCommand(int fallback) {
  const char* env = std::getenv("MSB_FUZZ_CASES");
  return env ? std::max(1, std::atoi(env)) : fallback;
}

/// msbench under a time limit: its exit code, 124 or 137 when it had to be stopped.
int runLimited(const std::string& args, const fs::path& log, int seconds = 120) {
  const std::string cmd = "timeout -k 5 " + std::to_string(seconds) + " '" + msb_test::kExe + "' " + args + " > '" +
                          log.string() + "' 2>&1 < /dev/null";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// ---------------------------------------------------------------------------------------------
// The kit: valid inputs of every command and one real output of each, made once.

/// Inputs: w.xml, a flight f.yaml, a scenario s.yaml on a base b.yaml, a perception log in.log,
/// a sweep file sw.yaml and its sweep directory sw/, a golden g.json. Outputs: out/<command>.
const fs::path& kit() {
  static const fs::path k = [] {
    // One kit per test: ctest runs the tests of this file as parallel processes.
    const fs::path d =
        msb_test::tempDir("msb_cmdfuzz_kit_", ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::copy_file(kSrc + "/worlds/test/world.xml", d / "w.xml");
    writeText(d / "f.yaml",
              "world: w.xml\nduration_s: 2\ncamera_stream: {save_every_n: 0}\ntrajectory: {waypoints: [[0, 0, 1]]}\n");
    writeText(d / "b.yaml", "base: " + kSrc +
                                "/scenarios/missions/monospheres.yaml\nworld: w.xml\n"
                                "start: {position: [0, 0, 0.05], yaw_deg: 0}\n"
                                "exploration_box: {min: [-19, -19, 0], max: [19, 19, 4]}\nduration_s: 1\n");
    writeText(d / "s.yaml", "base: b.yaml\nduration_s: 1\n");
    writeText(d / "sw.yaml", "scenario: s.yaml\nseeds: [1]\n");
    fs::create_directory(d / "out");
    const auto make = [&](const std::string& args) {
      EXPECT_EQ(runLimited(args, d / "log"), 0) << args << "\n" << readText(d / "log");
    };
    make("vio-eval " + q(d / "f.yaml") + " --record " + q(d / "in.log") + " --out " + q(d / "out/vio-eval"));
    make("sweep " + q(d / "sw.yaml") + " --out " + q(d / "sw"));
    make("regress " + q(d / "sw") + " --update --against " + q(d / "g.json"));
    make("fly " + q(d / "f.yaml") + " --out " + q(d / "out/fly"));
    make("run " + q(d / "s.yaml") + " --quiet --out " + q(d / "out/run"));
    make("map-replay " + q(d / "in.log") + " --out " + q(d / "out/map-replay"));
    make("report " + q(d / "sw") + " --no-figures --out " + q(d / "out/report"));
    make("sweep " + q(d / "sw.yaml") + " --out " + q(d / "out/sweep"));
    make("world show sparse --out " + q(d / "out/world"));
    make("render-probe --world " + q(d / "w.xml") + " --out " + q(d / "out/render-probe"));
    make("regress " + q(d / "sw") + " --update --against " + q(d / "out/regress"));
    return d;
  }();
  return k;
}

// ---------------------------------------------------------------------------------------------
// Output paths: every writing command, from generated trees.

/// A writing command: the kit inputs it reads, and its arguments given where they were placed.
struct Writer {
  std::string name;                 ///< also the kit's out/<name> planted as an earlier output
  std::vector<std::string> inputs;  ///< files or directories of the kit
  std::function<std::string(const fs::path& in, const std::string& out)> args;
};

const std::vector<Writer>& writers() {
  static const std::vector<Writer> w = {
      {"fly", {"f.yaml", "w.xml"}, [](auto in, auto out) { return "fly " + q(in / "f.yaml") + " --out " + out; }},
      {"vio-eval",
       {"f.yaml", "w.xml"},
       [](auto in, auto out) { return "vio-eval " + q(in / "f.yaml") + " --annotate-every 0 --out " + out; }},
      {"run",
       {"s.yaml", "b.yaml", "w.xml"},
       [](auto in, auto out) { return "run " + q(in / "s.yaml") + " --quiet --out " + out; }},
      {"map-replay", {"in.log"}, [](auto in, auto out) { return "map-replay " + q(in / "in.log") + " --out " + out; }},
      {"report", {"sw"}, [](auto in, auto out) { return "report " + q(in / "sw") + " --no-figures --out " + out; }},
      {"sweep",
       {"sw.yaml", "s.yaml", "b.yaml", "w.xml"},
       [](auto in, auto out) { return "sweep " + q(in / "sw.yaml") + " --out " + out; }},
      {"world", {}, [](auto, auto out) { return "world show sparse --out " + out; }},
      {"render-probe",
       {"w.xml"},
       [](auto in, auto out) { return "render-probe --world " + q(in / "w.xml") + " --out " + out; }},
      {"regress", {"sw"}, [](auto in, auto out) { return "regress " + q(in / "sw") + " --update --against " + out; }},
  };
  return w;
}

/// What a tree holds: relative path -> "D", "L:target", "S" (FIFO, device), "F:bytes", or for
/// files over 1 MiB "B:size:" and their first 4 KiB (symlinks not followed, nothing blocks).
using Snapshot = std::map<std::string, std::string>;

/// The first 4 KiB of a file.
std::string head(const fs::path& p) {
  std::string bytes(4096, '\0');
  std::ifstream in(p, std::ios::binary);
  in.read(bytes.data(), std::streamsize(bytes.size()));
  bytes.resize(size_t(in.gcount()));
  return bytes;
}

Snapshot snapshot(const fs::path& root) {
  Snapshot s;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::recursive_directory_iterator(); ++it) {
    const fs::path& p = it->path();
    const std::string rel = p.lexically_relative(root).string();
    if (it->is_symlink())
      s[rel] = "L:" + fs::read_symlink(p).string();
    else if (it->is_directory())
      s[rel] = "D";
    else if (!it->is_regular_file())
      s[rel] = "S";
    else if (it->file_size() > (size_t(1) << 20))
      s[rel] = "B:" + std::to_string(it->file_size()) + ":" + head(p);
    else
      s[rel] = "F:" + readText(p);
  }
  return s;
}

/// A tree t/ with d0/d1, d0/d2, d3, symlinks l0 -> d0/d1 and d3/l1 -> d0; the command's own
/// earlier output planted as "res" in some directories; its inputs in one directory (maybe inside
/// a planted output). Returns the directory holding the inputs.
fs::path makeTree(const fs::path& t, const Writer& w, RngStream& rng) {
  fs::remove_all(t);
  for (const char* d : {"d0/d1", "d0/d2", "d3"}) fs::create_directories(t / d);
  fs::create_directory_symlink(t / "d0" / "d1", t / "l0");
  fs::create_directory_symlink(t / "d0", t / "d3" / "l1");
  const std::vector<fs::path> dirs = {t / "d0", t / "d0" / "d1", t / "d0" / "d2", t / "d3"};
  for (const fs::path& d : dirs)
    if (rng.uniformInt(2) == 0) fs::copy(kit() / "out" / w.name, d / "res", fs::copy_options::recursive);
  fs::path in = dirs[rng.uniformInt(dirs.size())];
  if (rng.uniformInt(3) == 0 && fs::is_directory(in / "res")) in /= "res";
  for (const std::string& name : w.inputs)
    fs::copy(kit() / name, in / name, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  return in;
}

/// A path from t through generated components; `..` only where it stays inside t.
std::string makePath(const fs::path& t, RngStream& rng) {
  static const char* const kParts[] = {"d0", "d1", "d2", "d3", "l0", "l1", "..", ".", "res", "new"};
  std::string p = t.string();
  int depth = 0;
  const int n = 1 + int(rng.uniformInt(4));
  for (int i = 0; i < n; ++i) {
    std::string part = kParts[rng.uniformInt(10)];
    if (part == ".." && depth == 0) part = "new";
    depth += part == ".." ? -1 : part == "." ? 0 : 1;
    p += "/" + part;
  }
  if (rng.uniformInt(3) == 0) p += "/";
  return p;
}

bool under(const std::string& path, const fs::path& dir) {
  const std::string d = dir.string();
  return path == d || path.rfind(d + "/", 0) == 0;
}

/// After one generated case: refused and nothing changed, or written at outputPathOf(out) and
/// nothing else changed — every input byte for byte where it was.
void checkCase(const fs::path& t, const Snapshot& before, const std::string& out, int code, const std::string& what) {
  ASSERT_TRUE(code == 0 || code == 2) << what << ": exit " << code;
  const Snapshot after = snapshot(t);
  if (code == 2) {
    EXPECT_EQ(after, before) << what << ": refused but changed the tree";
    return;
  }
  const fs::path o = outputPathOf(out);
  EXPECT_TRUE(fs::exists(o)) << what << ": no output at " << o;
  for (const auto& [rel, v] : before)
    if (!under((t / rel).string(), o)) {
      const auto it = after.find(rel);
      EXPECT_TRUE(it != after.end() && it->second == v)
          << what << ": changed or deleted " << rel << " (output " << o << ")";
    }
  for (const auto& [rel, v] : after) {
    // New entries: the output, and the missing parent directories msbench creates for it.
    if (!before.count(rel)) {
      EXPECT_TRUE(under((t / rel).string(), o) || (v == "D" && under(o.string(), t / rel)))
          << what << ": wrote " << rel;
    }
  }
}

TEST(CommandFuzz, NoGeneratedOutputPathLosesAnInputOrWritesElsewhereOnAnyCommand) {
  kit();
  const fs::path root = msb_test::tempDir("msb_cmdfuzz_", "out");
  RngStream rng(20261127, "command-output-paths");
  const int n = casesPerCommand(10);
  for (const Writer& w : writers()) {
    int written = 0;
    for (int i = 0; i < n; ++i) {
      const fs::path t = root / "t";
      const fs::path in = makeTree(t, w, rng);
      const std::string out = makePath(t, rng);
      const std::string args = w.args(in, q(out)) + (rng.uniformInt(2) ? " --overwrite" : "");
      const Snapshot before = snapshot(t);
      const int code = runLimited(args, root / "log");
      checkCase(t, before, out, code, args + "\n" + readText(root / "log"));
      written += code == 0;
    }
    std::printf("%-13s %d of %d generated outputs written, the rest refused\n", w.name.c_str(), written, n);
  }
}

// ---------------------------------------------------------------------------------------------
// Readers: one input file of a command spoilt at a time.

/// A reading command: the kit inputs it needs, the files among them that are read (each spoilt
/// in turn), and its arguments.
struct Reader {
  std::string name;
  std::vector<std::string> inputs, read;
  std::function<std::string(const fs::path& in)> args;
  int verdict_code = 2;  ///< exit code of a verdict on a spoilt run result (report 0, regress 1)
};

const std::vector<Reader>& readers() {
  static const std::vector<Reader> r = {
      {"fly",
       {"f.yaml", "w.xml"},
       {"f.yaml", "w.xml"},
       [](auto in) { return "fly " + q(in / "f.yaml") + " --out " + q(in / "o"); }},
      {"vio-eval",
       {"f.yaml", "w.xml"},
       {"f.yaml"},
       [](auto in) { return "vio-eval " + q(in / "f.yaml") + " --annotate-every 0 --out " + q(in / "o"); }},
      {"run",
       {"s.yaml", "b.yaml", "w.xml"},
       {"s.yaml", "b.yaml", "w.xml"},
       [](auto in) { return "run " + q(in / "s.yaml") + " --quiet --out " + q(in / "o"); }},
      {"map-replay",
       {"in.log"},
       {"in.log"},
       [](auto in) { return "map-replay " + q(in / "in.log") + " --out " + q(in / "o"); }},
      {"bench-map", {"in.log"}, {"in.log"}, [](auto in) { return "bench-map " + q(in / "in.log"); }},
      {"render-probe",
       {"w.xml"},
       {"w.xml"},
       [](auto in) { return "render-probe --world " + q(in / "w.xml") + " --out " + q(in / "o.png"); }},
      {"sweep",
       {"sw.yaml", "s.yaml", "b.yaml", "w.xml"},
       {"sw.yaml", "s.yaml"},
       [](auto in) { return "sweep " + q(in / "sw.yaml") + " --out " + q(in / "o"); }},
      {"sweep-resume",
       {"sw.yaml", "s.yaml", "b.yaml", "w.xml", "sw"},
       {"sw/sweep.json"},
       [](auto in) { return "sweep " + q(in / "sw.yaml") + " --out " + q(in / "sw"); }},
      {"report",
       {"sw"},
       {"sw/sweep.json", "sw/runs/s1/metrics.json", "sw/runs/s1/coverage.csv"},
       [](auto in) { return "report " + q(in / "sw") + " --no-figures --out " + q(in / "o"); },
       0},
      {"regress",
       {"sw", "g.json"},
       {"sw/sweep.json", "sw/runs/s1/metrics.json", "g.json"},
       // A run whose metrics.json is corrupt did not complete: a regression (exit 1), named.
       [](auto in) { return "regress " + q(in / "sw") + " --against " + q(in / "g.json"); },
       1},
  };
  return r;
}

/// Ways to spoil a file. The structural ones must be refused (exit 2, the file named); the
/// mutations may still leave a valid file, so they must only never crash, hang or lose anything.
enum class Spoil {
  kFifo,
  kDirectory,
  kDevice,
  kOversized,
  kDeep,
  kEmpty,
  kKeyTwice,
  kTruncated,
  kBadByte,
  kHugeNumber
};
constexpr Spoil kSpoils[] = {Spoil::kFifo,    Spoil::kDirectory, Spoil::kDevice,   Spoil::kOversized,
                             Spoil::kDeep,    Spoil::kEmpty,     Spoil::kKeyTwice, Spoil::kTruncated,
                             Spoil::kBadByte, Spoil::kHugeNumber};
const char* const kSpoilNames[] = {"fifo",  "directory", "device",    "oversized", "deep",
                                   "empty", "key twice", "truncated", "bad byte",  "huge number"};

bool mustRefuse(Spoil s, const fs::path& file) {
  const std::string ext = file.extension().string();
  if (s == Spoil::kKeyTwice) return ext == ".json" || ext == ".yaml";
  if (s == Spoil::kEmpty) return ext != ".csv";  // an empty coverage.csv is a run without samples
  return s < Spoil::kTruncated;
}

/// `text` with its first key given twice (JSON objects and YAML mappings; else unchanged).
std::string withKeyTwice(const std::string& text, const std::string& ext) {
  if (ext == ".yaml") return text.substr(0, text.find('\n') + 1) + text;
  if (ext != ".json") return text;
  const auto j = nlohmann::ordered_json::parse(text);
  const std::string first = nlohmann::json(j.begin().key()).dump() + ": " + j.begin().value().dump() + ", ";
  return "{" + first + text.substr(text.find('{') + 1);
}

/// Spoils `file` (a copy of a valid input) in way `s`.
void spoil(const fs::path& file, Spoil s, RngStream& rng) {
  const std::string text = readText(file), ext = file.extension().string();
  fs::remove_all(file);
  const size_t at = text.empty() ? 0 : rng.uniformInt(text.size());
  switch (s) {
    case Spoil::kFifo:
      ASSERT_EQ(mkfifo(file.c_str(), 0600), 0);
      break;
    case Spoil::kDirectory:
      fs::create_directory(file);
      break;
    case Spoil::kDevice:
      fs::create_symlink("/dev/zero", file);
      break;
    case Spoil::kOversized:
      writeText(file, text), fs::resize_file(file, size_t(300) << 20);
      break;
    case Spoil::kDeep:
      writeText(file, std::string(200000, '['));
      break;
    case Spoil::kEmpty:
      writeText(file, "");
      break;
    case Spoil::kKeyTwice:
      writeText(file, withKeyTwice(text, ext));
      break;
    case Spoil::kTruncated:
      writeText(file, text.substr(0, at));
      break;
    case Spoil::kBadByte:
      writeText(file, text.substr(0, at) + "\xff" + text.substr(std::min(at + 1, text.size())));
      break;
    case Spoil::kHugeNumber: {
      const size_t d = text.find_first_of("0123456789", at);
      writeText(file, d == std::string::npos ? text : text.substr(0, d) + "1e999" + text.substr(d));
      break;
    }
  }
}

TEST(CommandFuzz, EveryReaderOfEveryCommandRefusesSpoiltFilesNamingThem) {
  kit();
  const fs::path root = msb_test::tempDir("msb_cmdfuzz_", "read");
  RngStream rng(20261127, "command-input-files");
  for (const Reader& r : readers())
    for (const std::string& file : r.read)
      for (const Spoil s : kSpoils) {
        const fs::path in = root / "c";
        fs::remove_all(in);
        fs::create_directory(in);
        for (const std::string& name : r.inputs) fs::copy(kit() / name, in / name, fs::copy_options::recursive);
        spoil(in / file, s, rng);
        const Snapshot before = snapshot(in);
        const int code = runLimited(r.args(in), root / "log");
        const std::string log = readText(root / "log");
        const std::string what =
            r.name + " with " + file + " " + kSpoilNames[int(s)] + ": exit " + std::to_string(code) + "\n" + log;
        // A verdict: the spoilt run's results count as not complete, the file named (report: a
        // failed run, exit 0; regress: a regression, exit 1).
        const bool must = mustRefuse(s, in / file), verdict = code == r.verdict_code && code != 2;
        EXPECT_TRUE(code == 2 || verdict || (!must && code == 0)) << what;
        if (code == 2 || (verdict && (must || code != 0))) {
          EXPECT_NE(log.find(fs::path(file).filename().string()), std::string::npos) << what << "\n(file not named)";
        }
        if (code == 2) {
          EXPECT_EQ(snapshot(in), before) << what << "\n(refused but changed its directory)";
        }
      }
}

}  // namespace
}  // namespace msb
