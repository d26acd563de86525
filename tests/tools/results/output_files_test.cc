// The one output-replacement routine every command goes through (checkNoOverlap, then
// StagedOutputDir): a seeded property test over generated trees of directories, symlinks,
// `..` and trailing slashes, with an input file somewhere and msbench-marked outputs here and
// there. Whatever the path, either the output is refused before anything changes, or it is
// written at outputPathOf(path) — and the input is never lost.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "core/common/config_check.h"
#include "core/common/rng.h"
#include "tests/tools/cli_helpers.h"
#include "tools/results/output_files.h"

namespace msb {
namespace {

namespace fs = std::filesystem;

std::string readAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A tree: dirs d0..d3 (d1, d2 inside d0), symlinks l0 -> d0/d1 and d3/l1 -> d0; a marked msbench
// run output in some directories; the input file in one of them.
struct Tree {
  fs::path root, input;
};

Tree makeTree(const fs::path& root, RngStream& rng) {
  fs::remove_all(root);
  for (const char* d : {"d0/d1", "d0/d2", "d3"}) fs::create_directories(root / d);
  fs::create_directory_symlink(root / "d0" / "d1", root / "l0");
  fs::create_directory_symlink(root / "d0", root / "d3" / "l1");
  const std::vector<fs::path> dirs = {root / "d0", root / "d0" / "d1", root / "d0" / "d2", root / "d3"};
  for (const fs::path& d : dirs)
    if (rng.uniformInt(2) == 0) {
      fs::create_directories(d / "res");
      std::ofstream(d / "res" / ".msbench-output") << "This directory was written by msbench (run).\n";
      std::ofstream(d / "res" / "metrics.json") << "{}\n";
    }
  Tree t{root, dirs[rng.uniformInt(dirs.size())] / (rng.uniformInt(2) ? "res" : "") / "scenario.yaml"};
  fs::create_directories(t.input.parent_path());
  std::ofstream(t.input) << "the input\n";
  return t;
}

// A path from the root through generated components (names, symlinks, `.`, `..`).
std::string makePath(const fs::path& root, RngStream& rng) {
  static const char* const kParts[] = {"d0", "d1", "d2", "d3", "l0", "l1", "..", ".", "res", "new"};
  std::string p = root.string();
  const int n = 1 + int(rng.uniformInt(4));
  for (int i = 0; i < n; ++i) p += std::string("/") + kParts[rng.uniformInt(10)];
  if (rng.uniformInt(3) == 0) p += "/";
  return p;
}

TEST(OutputFiles, NoGeneratedOutputPathEverLosesTheInputOrWritesElsewhere) {
  const fs::path root = msb_test::tempDir("msb_outprop_", "tree");
  RngStream rng(20261127, "output-paths");
  int written = 0, refused = 0;
  for (int i = 0; i < 400; ++i) {
    const Tree t = makeTree(root / "t", rng);
    const std::string out = makePath(root / "t", rng);
    const fs::path expected = outputPathOf(out);
    try {
      checkNoOverlap({{"SCENARIO", t.input}}, {{"--out", out}});
      StagedOutputDir dir(out, /*overwrite=*/true);
      writeFileAtomic(dir.staging() / "metrics.json", "{\"new\": true}\n");
      dir.commit();
      ++written;
      EXPECT_EQ(dir.finalDir(), expected) << out;
      EXPECT_EQ(readAll(expected / "metrics.json"), "{\"new\": true}\n") << out << " -> " << expected;
    } catch (const UsageError&) {
      ++refused;
    }
    ASSERT_TRUE(fs::is_regular_file(t.input)) << "case " << i << ": --out " << out << " lost " << t.input;
    EXPECT_EQ(readAll(t.input), "the input\n") << out;
  }
  // Both outcomes occur: the generator reaches the refusals and the replacements.
  EXPECT_GT(written, 40);
  EXPECT_GT(refused, 40);
}

// Runs `body` in a forked child (another process, as a second msbench would be) and returns
// its exit code: the child exits with what `body` returns.
int inAnotherProcess(const std::function<int()>& body) {
  const pid_t child = fork();
  if (child == 0) _exit(body());
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// One writer per output: a second StagedOutputDir (another process) is refused naming the pid
// and leaves the first one's live staging as it is; the lock goes with its holder.
TEST(OutputLock, ASecondWriterIsRefusedAndTheFirstsStagingIsKept) {
  const fs::path root = msb_test::tempDir("msb_lock_", "second");
  const fs::path out = root / "run";
  StagedOutputDir first(out, false);
  std::ofstream(first.staging() / "metrics.json") << "{}";
  // Another process: 0 when refused as expected, 1 when not refused.
  const int parent = getpid();
  EXPECT_EQ(
      inAnotherProcess([&] {
        try {
          StagedOutputDir second(out, true);
          return 1;
        } catch (const UsageError& e) {
          const std::string what = e.what();
          return what.find("another msbench process (pid " + std::to_string(parent) + ")") != std::string::npos ? 0 : 2;
        }
      }),
      0);
  EXPECT_TRUE(fs::exists(first.staging() / "metrics.json"));
  first.commit();
  EXPECT_TRUE(fs::exists(out / "metrics.json"));
}

TEST(OutputLock, ALockFileOfADeadWriterIsTakenOverAndAForeignFileIsNeverTaken) {
  const fs::path root = msb_test::tempDir("msb_lock_", "stale");
  const fs::path out = root / "run";
  // A holder that died (the kernel released its lock).
  std::ofstream(root / "run.lock") << "msbench output lock, pid 999999";
  { StagedOutputDir again(out, false); }
  EXPECT_FALSE(fs::exists(root / "run.lock"));  // removed at release
  // A user's file of that name — text, empty, or digits — and a link are never taken or removed.
  for (const std::string& mine : {std::string("my notes, not a lock"), std::string(), std::string("12345")}) {
    std::ofstream(root / "run.lock") << mine;
    EXPECT_THROW(StagedOutputDir(out, false), UsageError) << "'" << mine << "'";
    EXPECT_EQ(readAll(root / "run.lock"), mine);
  }
  fs::remove(root / "run.lock");
  std::ofstream(root / "target") << "msbench output lock, pid 1";
  fs::create_symlink(root / "target", root / "run.lock");
  EXPECT_THROW(StagedOutputDir(out, false), UsageError);
  EXPECT_TRUE(fs::is_symlink(root / "run.lock"));
  EXPECT_EQ(readAll(root / "target"), "msbench output lock, pid 1");
}

TEST(StagedOutputDir, ATargetThatGainedAUserFileWhileTheRunFlewIsKept) {
  const fs::path root = msb_test::tempDir("msb_lock_", "late");
  const fs::path out = root / "run";
  {
    StagedOutputDir first(out, false);
    first.commit();
  }
  StagedOutputDir again(out, true);
  std::ofstream(out / "notes.txt") << "written by the user while the run flew";
  EXPECT_THROW(again.commit(), std::runtime_error);
  EXPECT_EQ(readAll(out / "notes.txt"), "written by the user while the run flew");
  EXPECT_TRUE(fs::exists(again.staging()));  // the run's results stay staged
}

// A write that fails (here: past RLIMIT_FSIZE, as on a full disk) never replaces the file it was
// to replace, leaves no temporary and names the path and the OS error.
TEST(WriteFileAtomic, AFailedWriteKeepsTheOldFileAndLeavesNoTemporary) {
  const fs::path root = msb_test::tempDir("msb_write_", "full");
  const fs::path file = root / "golden.json";
  std::ofstream(file) << "the golden msbench wrote before";
  EXPECT_EQ(inAnotherProcess([&] {
              signal(SIGXFSZ, SIG_IGN);
              const rlimit limit{1024, 1024};
              setrlimit(RLIMIT_FSIZE, &limit);
              try {
                writeFileAtomic(file, std::string(64 * 1024, 'x'));
                return 1;
              } catch (const std::runtime_error& e) {
                const std::string what = e.what();
                return what.find(file.string() + ": cannot write it") == 0 &&
                               what.find("File too large") != std::string::npos &&
                               what.find("the file was not changed") != std::string::npos
                           ? 0
                           : 2;
              }
            }),
            0);
  EXPECT_EQ(readAll(file), "the golden msbench wrote before");
  for (const auto& e : fs::directory_iterator(root)) EXPECT_EQ(e.path(), file) << "left behind: " << e.path();
}

}  // namespace
}  // namespace msb
