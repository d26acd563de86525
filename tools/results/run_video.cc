#include "tools/results/run_video.h"

#include <fcntl.h>
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

namespace {

// An even number of pixels at least `lo` (the encoder's 4:2:0 chroma needs even sizes).
int evenPixels(double v, int lo) { return std::max(lo, 2 * int(std::lround(v / 2.0))); }

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
    : file_(file),
      partial_(file.string() + ".partial"),
      log_(file.string() + ".ffmpeg.log"),
      settings_(settings),
      name_(name),
      duration_s_(duration_s),
      box_(box),
      truth_(truth) {
  const std::string ffmpeg = findFfmpeg();
  if (ffmpeg.empty())
    throw std::runtime_error(
        "video: the ffmpeg program is not installed (apt-get install ffmpeg); run without --video");
  const fs::path dir = file.parent_path().empty() ? fs::path(".") : file.parent_path();
  if (access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error("video: cannot write " + file.string() + ": " + std::strerror(errno));
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
  posix_spawn_file_actions_addopen(&actions, 2, log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int rc = posix_spawn(&pid_, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(sv[1]);
  if (rc != 0) {
    close(sv[0]);
    pid_ = 0;
    throw std::runtime_error("video: cannot start " + ffmpeg + " writing " + file.string() + ": " + std::strerror(rc));
  }
  fd_ = sv[0];
}

RunVideo::~RunVideo() {
  if (finished_) return;
  stopEncoder(/*kill=*/true);
  std::error_code ec;
  fs::remove(partial_, ec);
  fs::remove(log_, ec);
}

void RunVideo::stopEncoder(bool kill_it) {
  if (fd_ >= 0) close(fd_), fd_ = -1;
  if (pid_ <= 0) return;
  if (kill_it) kill(pid_, SIGKILL);
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
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
  cv::putText(img, text, cv::Point(10, caption_h_ - 10), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
  return img;
}

void RunVideo::send(const cv::Mat& img) {
  if (fd_ < 0 || !error_.empty()) return;
  const auto* data = img.ptr<uint8_t>(0);
  const size_t n = img.total() * img.elemSize();
  for (size_t off = 0; off < n;) {
    const ssize_t w = ::send(fd_, data + off, n - off, MSG_NOSIGNAL);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      error_ = std::string("the encoder (ffmpeg) stopped reading frames (") + std::strerror(errno) + ")";
      stopEncoder(/*kill=*/true);
      error_ += ": " + logTail(log_);
      std::error_code ec;
      fs::remove(partial_, ec);  // its space goes back to the run's other files (a full disk)
      return;
    }
    off += size_t(w);
  }
  ++frames_;
}

void RunVideo::addFrame(const Mission& mission) {
  const ExplorerSnapshot snap = mission.explorer().snapshot();  // waits for the perception in flight
  const FlightResult& flight = mission.loop().result();
  const std::shared_ptr<const CameraFrame> frame = mission.loop().sharedFrame();
  const double t_s = frame ? frame->t_s : 0.0;
  const TopdownView view{box_, flight.trajectory, snap, mission.columns(), flight.collision, t_s, flight.status};
  send(compose(frame.get(), view, nullptr));
}

void RunVideo::addFinalFrames(const MissionResult& r, const CameraFrame* last_frame) {
  finished_frame_ = true;
  const TopdownView view{
      box_, r.flight.trajectory, r.final_map, r.columns, r.flight.collision, r.flight.sim_time_s, r.flight.status};
  const cv::Mat img = compose(last_frame, view, truth_);
  for (int i = 0; i < 2 * settings_.fps; ++i) send(img);
}

std::string RunVideo::finish() {
  stopEncoder(/*kill=*/!error_.empty());
  finished_ = true;
  std::error_code ec;
  if (error_.empty()) {
    fs::rename(partial_, file_, ec);
    if (ec) error_ = "cannot rename " + partial_.string() + " to " + file_.string() + ": " + ec.message();
  }
  if (!error_.empty()) fs::remove(partial_, ec);
  fs::remove(log_, ec);
  return error_;
}

nlohmann::json finishRunVideo(RunVideo& video, const MissionResult& r, const CameraFrame* last_frame, double wall_s,
                              const fs::path& final_path) {
  const auto start = std::chrono::steady_clock::now();
  video.addFinalFrames(r, last_frame);
  const std::string error = video.finish();
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
