// Helpers for tests that run the msbench executable: a fresh directory per test, running a
// command line with its output captured, reading a result file.
#pragma once

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace msb_test {

namespace fs = std::filesystem;

/// The built msbench executable.
inline const std::string kExe = std::string(MSB_BINARY_DIR) + "/bin/msbench";

/// An empty directory "<prefix><name>" under the test temp dir.
inline fs::path tempDir(const std::string& prefix, const std::string& name) {
  const fs::path d = fs::path(::testing::TempDir()) / (prefix + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// Runs msbench with arguments; returns its exit code (stdout/stderr to `log`).
inline int run(const std::string& args, const fs::path& log) {
  const std::string cmd = "'" + kExe + "' " + args + " > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Runs msbench with arguments (output to `log`), sends it `sig` after `delay_ms` and returns its
/// exit code (128 + the signal when the signal killed it).
inline int runAndSignal(const std::string& args, int sig, const fs::path& log, int delay_ms = 2500) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string cmd = "exec '" + kExe + "' " + args + " > '" + log.string() + "' 2>&1";
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
  kill(pid, sig);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// A stand-in `ffmpeg` first on PATH while it lives, running `body` (sh).
struct FakeEncoder {
  std::string old_path = std::getenv("PATH") ? std::getenv("PATH") : "";
  FakeEncoder(const fs::path& dir, const std::string& body) {
    fs::create_directories(dir);
    std::ofstream(dir / "ffmpeg") << "#!/bin/sh\n" << body << "\n";
    fs::permissions(dir / "ffmpeg", fs::perms::owner_all);
    setenv("PATH", (dir.string() + ":" + old_path).c_str(), 1);
  }
  ~FakeEncoder() { setenv("PATH", old_path.c_str(), 1); }
  FakeEncoder(const FakeEncoder&) = delete;
  FakeEncoder& operator=(const FakeEncoder&) = delete;
};

/// The whole file as a string (empty if missing).
inline std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// "frames,width,height" of a video's first stream as ffprobe decodes it ("" without ffprobe).
inline std::string probeVideo(const fs::path& video) {
  const std::string cmd =
      "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames,width,height "
      "-of csv=p=0 '" +
      video.string() + "'";
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char buf[256];
    while (std::fgets(buf, sizeof(buf), p)) out += buf;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == ',')) out.pop_back();
  return out;
}

}  // namespace msb_test
