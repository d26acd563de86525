#include "tools/results/run_video.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

#include <opencv2/imgproc.hpp>

extern char** environ;

namespace msb {

namespace fs = std::filesystem;

std::string findFfmpeg() {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / "ffmpeg";
    if (access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) return candidate.string();
  }
  return "";
}

void clearStaleVideoStaging(const fs::path& dir) {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.size() != 21 || name.rfind(".msbench-video-", 0) != 0 || !e.is_directory() || e.is_symlink()) continue;
    bool ours = true;  // only the encoder's own files inside, none a link
    for (const auto& f : fs::directory_iterator(e.path(), ec)) {
      const std::string n = f.path().filename().string();
      ours = ours && (n == "video.mp4" || n == "ffmpeg.log") && f.is_regular_file() && !f.is_symlink();
    }
    if (ours && !ec) fs::remove_all(e.path(), ec);
  }
}

namespace {

// An even number of pixels at least `lo` (the encoder's 4:2:0 chroma needs even sizes).
int evenPixels(double v, int lo) { return std::max(lo, 2 * int(std::lround(v / 2.0))); }

// "30 s", "0.5 s": a limit in words.
std::string secondsText(double s) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g s", s);
  return text;
}

// The last lines of the encoder's log, on one line.
std::string logTail(const fs::path& log) {
  std::ifstream in(log);
  std::string line, tail;
  std::vector<std::string> lines;
  while (std::getline(in, line))
    if (!line.empty()) lines.push_back(line);
  for (size_t i = lines.size() > 3 ? lines.size() - 3 : 0; i < lines.size(); ++i)
    tail += (tail.empty() ? "" : " | ") + lines[i];
  return tail.empty() ? "no message" : tail;
}

}  // namespace

RunVideo::RunVideo(const fs::path& file, const VideoSettings& settings, const std::string& name, double duration_s,
                   const Aabb& box, const WorldTruth* truth, int camera_w, int camera_h)
    : file_(file), settings_(settings), name_(name), duration_s_(duration_s), box_(box), truth_(truth) {
  const std::string ffmpeg = findFfmpeg();
  if (ffmpeg.empty())
    throw std::runtime_error(
        "video: the ffmpeg program is not installed (apt-get install ffmpeg); run without --video");
  // The encoder's output and log: in a directory of msbench's own beside `file`.
  const fs::path dir = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  std::string pattern = (dir / ".msbench-video-XXXXXX").string();
  if (!mkdtemp(pattern.data()))
    throw std::runtime_error("video: cannot write " + file.string() + ": " + std::strerror(errno));
  dir_ = pattern, partial_ = dir_ / "video.mp4", log_ = dir_ / "ffmpeg.log";
  // Layout: caption band on top; the fisheye image (its aspect) left of the map (the box's).
  const int panel_h = settings.height - caption_h_;
  camera_panel_w_ = evenPixels(double(std::max(camera_w, 1)) * panel_h / std::max(camera_h, 1), 2);
  // The box with room around it: methods fly beyond it (the metric counts all they explore).
  const Vec2 margin = Vec2::Constant(10.0 + 0.15 * (box.max - box.min).head<2>().maxCoeff());
  const Vec2 lo = box.min.head<2>() - margin, hi = box.max.head<2>() + margin;
  const double aspect = std::clamp((hi.x() - lo.x()) / (hi.y() - lo.y()), 0.5, 2.0);
  const int map_w = evenPixels(panel_h * aspect, 2);
  width_ = camera_panel_w_ + map_w, height_ = settings.height;
  background_ = fixedCanvas(lo, hi, map_w, panel_h);
  drawTopdownBackground(background_, truth);

  // The encoder reads raw BGR frames from a socket (a write to a dead encoder fails with EPIPE
  // instead of raising SIGPIPE in msbench); its messages go to a log read on failure.
  int sv[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
    throw std::runtime_error(std::string("video: socketpair: ") + std::strerror(errno));
  char size[32], fps[16];
  std::snprintf(size, sizeof(size), "%dx%d", width_, height_);
  std::snprintf(fps, sizeof(fps), "%d", settings.fps);
  std::vector<std::string> args = {
      ffmpeg,     "-hide_banner", "-nostats",    "-loglevel", "error",      "-y",   "-f",  "rawvideo",
      "-pix_fmt", "bgr24",        "-video_size", size,        "-framerate", fps,    "-i",  "pipe:0",
      "-an",      "-c:v",         "libx264",     "-preset",   "veryfast",   "-crf", "27",  "-pix_fmt",
      "yuv420p",  "-threads",     "1",           "-movflags", "+faststart", "-f",   "mp4", partial_.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, sv[1], 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, log_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0644);
  const int rc = posix_spawn(&pid_, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(sv[1]);
  if (rc != 0) {
    close(sv[0]);
    pid_ = 0;
    std::error_code ec;
    fs::remove_all(dir_, ec);
    throw std::runtime_error("video: cannot start " + ffmpeg + " writing " + file.string() + ": " + std::strerror(rc));
  }
  fd_ = sv[0];
  fcntl(fd_, F_SETFL, fcntl(fd_, F_GETFL) | O_NONBLOCK);  // every wait on it is bounded (waitWritable)
}

RunVideo::~RunVideo() {
  if (pid_ > 0) kill(pid_, SIGKILL);
  if (pid_ > 0) waitpid(pid_, nullptr, 0);  // killed: reaped at once
  if (fd_ >= 0) close(fd_);
  std::error_code ec;
  fs::remove_all(dir_, ec);  // msbench's own directory (what a failed or uncommitted video left)
}

void RunVideo::waitWritable() {
  pollfd p{fd_, POLLOUT, 0};
  poll(&p, 1, 100);
  if (wait_hook_) wait_hook_();
}

void RunVideo::stopEncoder(bool kill_it) {
  if (fd_ >= 0) close(fd_), fd_ = -1;
  if (pid_ <= 0) return;
  if (kill_it) kill(pid_, SIGKILL);
  // Reaped within the stall limit, the wait hook called meanwhile; a stuck encoder is killed.
  int status = 0;
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    const pid_t got = waitpid(pid_, &status, WNOHANG);
    if (got == pid_ || (got < 0 && errno != EINTR)) break;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > stall_limit_s_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, &status, 0);
      if (error_.empty()) error_ = "the encoder (ffmpeg) did not finish within " + secondsText(stall_limit_s_);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (wait_hook_) {
      try {
        wait_hook_();
      } catch (...) {
        kill(pid_, SIGKILL);
        waitpid(pid_, nullptr, 0);
        pid_ = 0;
        throw;
      }
    }
  }
  pid_ = 0;
  if (!kill_it && error_.empty() && !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    char what[64];
    if (WIFSIGNALED(status))
      std::snprintf(what, sizeof(what), "killed by signal %d", WTERMSIG(status));
    else
      std::snprintf(what, sizeof(what), "exited with status %d", WEXITSTATUS(status));
    error_ = std::string("the encoder (ffmpeg) ") + what + ": " + logTail(log_);
  }
}

int64_t RunVideo::periodTicks(int physics_hz) const {
  return std::max<int64_t>(1, std::llround(settings_.speedup / settings_.fps * physics_hz));
}

cv::Mat RunVideo::compose(const CameraFrame* frame, const TopdownView& view, const WorldTruth* truth) {
  const int panel_h = height_ - caption_h_;
  cv::Mat img(height_, width_, CV_8UC3, cv::Scalar(32, 32, 32));
  // The fisheye image as the tracker saw it (grey), scaled to the panel.
  if (frame && frame->width > 0 && frame->height > 0 &&
      frame->pixels.size() >= size_t(frame->width) * size_t(frame->height)) {
    const cv::Mat grey(frame->height, frame->width, CV_8UC1, const_cast<uint8_t*>(frame->pixels.data()));
    cv::Mat scaled;
    cv::resize(grey, scaled, cv::Size(camera_panel_w_, panel_h), 0, 0, cv::INTER_AREA);
    cv::cvtColor(scaled, img(cv::Rect(0, caption_h_, camera_panel_w_, panel_h)), cv::COLOR_GRAY2BGR);
  }
  // The map over the precomputed background.
  TopdownCanvas canvas = background_;
  canvas.img = background_.img.clone();
  drawTopdownMap(canvas, view, truth);
  drawTopdownScaleBar(canvas);
  canvas.img.copyTo(img(cv::Rect(camera_panel_w_, caption_h_, canvas.w, canvas.h)));
  // Caption: name, time, coverage (and how the run ended, on its final frames).
  const double in_box = double(view.columns.countInside(view.box.min.head<2>(), view.box.max.head<2>())) *
                        view.columns.cellM() * view.columns.cellM();
  char text[256];
  std::snprintf(text, sizeof(text), "%s   t = %.0f / %.0f s   A = %.0f m2 (%.0f m2 in box)%s%s", name_.c_str(),
                view.t_s, duration_s_, view.columns.areaM2(), in_box, finished_frame_ ? "   " : "",
                finished_frame_ ? runStatusName(view.status) : "");
  cv::putText(img, text, cv::Point(10, 22), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  // Second line: the method's progress counters.
  cv::putText(img, counters_text_, cv::Point(10, caption_h_ - 9), cv::FONT_HERSHEY_SIMPLEX, 0.5,
              cv::Scalar(200, 200, 200), 1, cv::LINE_AA);
  return img;
}

void RunVideo::send(const cv::Mat& img) {
  if (fd_ < 0 || !error_.empty()) return;
  const auto* data = img.ptr<uint8_t>(0);
  const size_t n = img.total() * img.elemSize();
  auto last_progress = std::chrono::steady_clock::now();
  for (size_t off = 0; off < n;) {
    const ssize_t w = ::send(fd_, data + off, n - off, MSG_NOSIGNAL);
    if (w > 0) {
      off += size_t(w), last_progress = std::chrono::steady_clock::now();
      continue;
    }
    const bool later = w < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR);
    const double stalled_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_progress).count();
    if (later && stalled_s <= stall_limit_s_) {
      try {
        waitWritable();  // bounded; an interrupt throws out of it
      } catch (...) {
        stopEncoder(/*kill=*/true);
        throw;
      }
      continue;
    }
    abandon(later ? "the encoder (ffmpeg) read no frame for " + secondsText(stall_limit_s_)
                  : std::string("the encoder (ffmpeg) stopped reading frames (") + std::strerror(errno) + ")");
    return;
  }
  ++frames_;
}

void RunVideo::abandon(const std::string& why) {
  if (error_.empty()) error_ = why;
  const std::string tail = logTail(log_);
  stopEncoder(/*kill=*/true);
  if (!tail.empty() && error_.find(tail) == std::string::npos) error_ += ": " + tail;
  std::error_code ec;
  fs::remove_all(dir_, ec);  // its space goes back to the run's other files (a full disk)
}

void RunVideo::addFrame(const Mission& mission) {
  const ExplorerSnapshot snap = mission.explorer().snapshot();  // waits for the perception in flight
  setCountersText(mission.explorer().counters());
  const FlightResult& flight = mission.loop().result();
  const std::shared_ptr<const CameraFrame> frame = mission.loop().sharedFrame();
  const double t_s = frame ? frame->t_s : 0.0;
  const TopdownView view{box_, flight.trajectory, snap, mission.columns(), flight.collision, t_s, flight.status};
  send(compose(frame.get(), view, nullptr));
}

void RunVideo::setCountersText(const std::map<std::string, double>& counters) {
  counters_text_.clear();
  for (const std::string& name : caption_counters_) {
    const auto it = counters.find(name);
    if (it == counters.end()) continue;
    char value[48];
    std::snprintf(value, sizeof value, "%s%s %.0f", counters_text_.empty() ? "" : "   ", name.c_str(), it->second);
    counters_text_ += value;
  }
}

void RunVideo::addFinalFrames(const MissionResult& r, const CameraFrame* last_frame) {
  finished_frame_ = true;
  setCountersText(r.counters);
  const TopdownView view{
      box_, r.flight.trajectory, r.final_map, r.columns, r.flight.collision, r.flight.sim_time_s, r.flight.status};
  const cv::Mat img = compose(last_frame, view, truth_);
  for (int i = 0; i < 2 * settings_.fps; ++i) send(img);
}

std::string RunVideo::finish() {
  stopEncoder(/*kill=*/!error_.empty());
  finished_ = true;
  // An encoder that exits 0 after a failed write (a full disk, a file-size limit) leaves an MP4
  // without its index: the file is checked, not the exit status alone.
  if (error_.empty())
    if (const std::string problem = mp4Problem(partial_, frames_); !problem.empty())
      error_ = "the encoder's output is not a whole video (" + problem + ")";
  std::error_code ec;
  if (!error_.empty()) fs::remove_all(dir_, ec);  // nothing of a failed video stays
  return error_;
}

std::string RunVideo::commit() {
  if (!finished_ || !error_.empty()) return error_.empty() ? "not finished" : error_;
  std::error_code ec;
  fs::rename(partial_, file_, ec);  // replaces a link at `file_`, never follows it
  if (ec) error_ = "cannot rename it to " + file_.string() + ": " + ec.message();
  fs::remove_all(dir_, ec);  // the encoder's log and the directory
  return error_;
}

namespace {

// A big-endian unsigned integer of `n` bytes at `p`.
uint64_t bigEndian(const unsigned char* p, int n) {
  uint64_t v = 0;
  for (int i = 0; i < n; ++i) v = (v << 8) | p[i];
  return v;
}

// The sample count of the first `stsz` box under [begin, end) of `data`, searching the container
// boxes on the way (moov, trak, mdia, minf, stbl); -1 if none.
int64_t stszCount(const std::string& data, size_t begin, size_t end) {
  for (size_t at = begin; at + 8 <= end;) {
    const auto* p = reinterpret_cast<const unsigned char*>(data.data() + at);
    uint64_t size = bigEndian(p, 4);
    size_t header = 8;
    if (size == 1 && at + 16 <= end) size = bigEndian(p + 8, 8), header = 16;
    if (size == 0) size = end - at;
    if (size < header || at + size > end) return -1;
    const std::string type = data.substr(at + 4, 4);
    if (type == "stsz" && size >= header + 12) return int64_t(bigEndian(p + header + 8, 4));
    if (type == "moov" || type == "trak" || type == "mdia" || type == "minf" || type == "stbl")
      if (const int64_t n = stszCount(data, at + header, at + size); n >= 0) return n;
    at += size;
  }
  return -1;
}

}  // namespace

std::string mp4Problem(const fs::path& path, int frames) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  if (!in || !(bytes << in.rdbuf())) return "cannot read " + path.filename().string();
  const std::string data = bytes.str();
  // The top-level boxes must tile the file, one of them `moov`.
  bool moov = false;
  for (size_t at = 0; at < data.size();) {
    if (at + 8 > data.size()) return "a box cut off at byte " + std::to_string(at);
    const auto* p = reinterpret_cast<const unsigned char*>(data.data() + at);
    uint64_t size = bigEndian(p, 4);
    if (size == 1 && at + 16 <= data.size()) size = bigEndian(p + 8, 8);
    if (size == 0) size = data.size() - at;
    if (size < 8 || at + size > data.size()) return "a box cut off at byte " + std::to_string(at);
    moov = moov || data.compare(at + 4, 4, "moov") == 0;
    at += size;
  }
  if (!moov) return "no moov index: the encoder did not finish the file";
  const int64_t samples = stszCount(data, 0, data.size());
  if (samples != frames) return std::to_string(samples) + " frames in its index, " + std::to_string(frames) + " sent";
  return "";
}

nlohmann::json finishRunVideo(RunVideo& video, const MissionResult& r, const CameraFrame* last_frame, double wall_s,
                              const fs::path& final_path) {
  const auto start = std::chrono::steady_clock::now();
  video.addFinalFrames(r, last_frame);
  std::string error = video.finish();
  if (error.empty()) error = video.commit();
  wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!error.empty()) {
    std::fprintf(stderr, "msbench run: video %s not written: %s\n", final_path.c_str(), error.c_str());
    return {{"file", nullptr}, {"error", error}, {"wall_time_s", wall_s}};
  }
  const VideoSettings& s = video.settings();
  return {{"file", final_path.filename().string()},
          {"frames", video.frames()},
          {"width", video.width()},
          {"height", video.height()},
          {"fps", s.fps},
          {"speedup", s.speedup},
          {"wall_time_s", wall_s}};
}

}  // namespace msb
