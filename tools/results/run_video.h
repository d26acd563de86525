// video.mp4 of a run (docs/video.md): the fisheye frame beside the top-down map as it grows, a
// caption with time and coverage, encoded by the `ffmpeg` program (Debian's ffmpeg) through a
// socket, so the msbench binary links no codec library. Nothing of the run depends on it.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "core/common/messages.h"
#include "tools/engine/mission.h"
#include "tools/results/topdown.h"

namespace msb {

/// The `ffmpeg` program on PATH, or "" when it is not installed.
std::string findFfmpeg();

/// Removes from `dir` what a killed writer of a video there left: directories named
/// `.msbench-video-XXXXXX` holding only the encoder's files (video.mp4, ffmpeg.log). Call it with
/// the video's OutputLock held (so none is in use); anything else is left as it is.
void clearStaleVideoStaging(const std::filesystem::path& dir);

/// A run's video being written. The frames go to a private directory msbench makes beside `file`
/// (mkdtemp: no fixed name in a user's directory, no link followed); finish() checks the encoder
/// ended cleanly and that the MP4 is whole (its `moov` index present, one sample per frame sent);
/// commit() then renames it to `file`. Every wait on the encoder is bounded (kStallLimitS) and
/// calls the wait hook (an interrupt ends it at once). Destroyed uncommitted (an interrupt, an
/// error, a failed check), it kills the encoder and removes its directory.
class RunVideo {
 public:
  /// Starts the encoder. `name` heads the caption (the run's name and method: runCaption()); `box` fixes the map
  /// panel's extent; `truth` (may be null) draws the true obstacles faint beneath the map; `camera_w/h` is the fisheye
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
  /// Ends the stream and checks the video. Returns "" when it is whole, else why no video is kept
  /// (the encoder failed or stalled, the file is not a whole MP4: a full disk, a file-size limit);
  /// nothing is kept then.
  std::string finish();
  /// Renames the checked video to `file` (after finish() returned ""); "" or why it could not.
  std::string commit();
  /// Gives up the video (kills the encoder, removes what it wrote: its space goes back to the
  /// run's other files); `why` becomes its error.
  void abandon(const std::string& why);
  /// The method's counters the caption's second line shows (its progress counters), by name.
  void setCaptionCounters(std::vector<std::string> names) { caption_counters_ = std::move(names); }
  /// Called about every 100 ms while waiting on the encoder; what it throws ends the wait.
  void setWaitHook(std::function<void()> hook) { wait_hook_ = std::move(hook); }
  /// Seconds a write to the encoder, or its exit, may take before it counts as stuck.
  static constexpr double kStallLimitS = 30.0;
  /// Sets that limit (tests shorten it; msbench keeps kStallLimitS).
  void setStallLimit(double seconds) { stall_limit_s_ = seconds; }
  /// Frames sent so far.
  int frames() const { return frames_; }
  /// Frame size in pixels.
  int width() const { return width_; }
  int height() const { return height_; }
  /// The settings it was made with.
  const VideoSettings& settings() const { return settings_; }

 private:
  // The caption's counters line from `counters` (caption_counters_ in order).
  void setCountersText(const std::map<std::string, double>& counters);
  cv::Mat compose(const CameraFrame* frame, const TopdownView& view, const WorldTruth* truth);
  void send(const cv::Mat& img);
  // Closes the encoder's input and reaps it within the stall limit (kill: at once).
  void stopEncoder(bool kill);
  // Waits up to 100 ms for `fd_` to accept bytes; calls the wait hook.
  void waitWritable();

  std::filesystem::path file_, dir_, partial_, log_;
  std::function<void()> wait_hook_;
  double stall_limit_s_ = kStallLimitS;
  VideoSettings settings_;
  std::string name_;
  double duration_s_ = 0;
  Aabb box_;
  const WorldTruth* truth_ = nullptr;
  TopdownCanvas background_;  // truth footprints and grid, drawn once
  int width_ = 0, height_ = 0, caption_h_ = 52, camera_panel_w_ = 0;
  std::vector<std::string> caption_counters_;  // the counters the caption shows
  std::string counters_text_;                  // their values at the latest frame
  int frames_ = 0;
  int fd_ = -1;    // the encoder's stdin
  pid_t pid_ = 0;  // the encoder
  std::string error_;
  bool finished_ = false;
  bool finished_frame_ = false;  // the run's end: the caption says how it ended
};

/// Why `path` is not a whole MP4 of `frames` video samples ("" when it is): its top-level boxes
/// read to the end, a `moov` box, and in it a sample-size table (`stsz`) counting `frames`.
std::string mp4Problem(const std::filesystem::path& path, int frames);

/// Ends a run's video: the run's end held 2 s (`last_frame`: the latest camera image), then the
/// encoder. Returns metrics.json's `video` — the file's name (`final_path`'s), frames, size, fps,
/// speed-up and the wall seconds spent (`wall_s` so far plus these) — or, when the encoder failed,
/// `file: null` and the error, which stderr also names with `final_path`.
nlohmann::json finishRunVideo(RunVideo& video, const MissionResult& r, const CameraFrame* last_frame, double wall_s,
                              const std::filesystem::path& final_path);

}  // namespace msb
