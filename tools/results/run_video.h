// video.mp4 of a run (docs/video.md): the fisheye frame beside the top-down map as it grows, a
// caption with time and coverage, encoded by the `ffmpeg` program (Debian's ffmpeg) through a
// socket, so the msbench binary links no codec library. Nothing of the run depends on it.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "core/common/messages.h"
#include "tools/loop/mission.h"
#include "tools/results/topdown.h"

namespace msb {

/// The `ffmpeg` program on PATH, or "" when it is not installed.
std::string findFfmpeg();

/// A run's video being written. The frames go to `file`.partial in the run's staging directory;
/// finish() renames it to `file` only when the encoder ended cleanly. Destroyed unfinished (an
/// interrupt, an error), it stops the encoder and removes what it wrote.
class RunVideo {
 public:
  /// Starts the encoder. `name` heads the caption; `box` fixes the map panel's extent; `truth`
  /// (may be null) draws the true obstacles faint beneath the map; `camera_w/h` is the fisheye
  /// image size. Throws std::runtime_error when ffmpeg is missing or cannot start.
  RunVideo(const std::filesystem::path& file, const VideoSettings& settings, const std::string& name, double duration_s,
           const Aabb& box, const WorldTruth* truth, int camera_w, int camera_h);
  ~RunVideo();
  RunVideo(const RunVideo&) = delete;
  RunVideo& operator=(const RunVideo&) = delete;

  /// Simulated ticks between frames (speedup / fps seconds) at `physics_hz`.
  int64_t periodTicks(int physics_hz) const;
  /// Adds the mission as it stands after a tick: its latest camera frame, map, trajectory and
  /// explored columns (waits for the perception in flight, which changes no result).
  void addFrame(const Mission& mission);
  /// Adds the run's end, held for 2 s of video: the final map, the collision and (with truth)
  /// the object hit.
  void addFinalFrames(const MissionResult& r, const CameraFrame* last_frame);
  /// Ends the stream. Returns "" when `file` is complete, else why no video was kept (the
  /// encoder failed: a full disk, an unwritable directory); nothing is left at `file` then.
  std::string finish();
  /// Frames sent so far.
  int frames() const { return frames_; }
  /// Frame size in pixels.
  int width() const { return width_; }
  int height() const { return height_; }
  /// The settings it was made with.
  const VideoSettings& settings() const { return settings_; }

 private:
  cv::Mat compose(const CameraFrame* frame, const TopdownView& view, const WorldTruth* truth);
  void send(const cv::Mat& img);
  void stopEncoder(bool kill);

  std::filesystem::path file_, partial_, log_;
  VideoSettings settings_;
  std::string name_;
  double duration_s_ = 0;
  Aabb box_;
  const WorldTruth* truth_ = nullptr;
  TopdownCanvas background_;  // truth footprints and grid, drawn once
  int width_ = 0, height_ = 0, caption_h_ = 32, camera_panel_w_ = 0;
  int frames_ = 0;
  int fd_ = -1;    // the encoder's stdin
  pid_t pid_ = 0;  // the encoder
  std::string error_;
  bool finished_ = false;
  bool finished_frame_ = false;  // the run's end: the caption says how it ended
};

/// Ends a run's video: the run's end held 2 s (`last_frame`: the latest camera image), then the
/// encoder. Returns metrics.json's `video` — the file's name (`final_path`'s), frames, size, fps,
/// speed-up and the wall seconds spent (`wall_s` so far plus these) — or, when the encoder failed,
/// `file: null` and the error, which stderr also names with `final_path`.
nlohmann::json finishRunVideo(RunVideo& video, const MissionResult& r, const CameraFrame* last_frame, double wall_s,
                              const std::filesystem::path& final_path);

}  // namespace msb
