// The loop's perception pipeline (docs/architecture.md §2): each rendered frame's perception is a
// job — tracks, SLAM points, then the exploration method's map update and plan due on the frame's
// tick, from the state snapshotted then — and its results are used `depth` frames later
// (perception.latency_frames). Depth 0 uses a frame's results on its own tick; depth k ≥ 1 lets
// a second thread (perception.threads = 2) run the work while the loop renders. One rule for
// every depth: on a camera tick the loop uses what is due, launches the frame's job, and uses
// what is due again (with depth 0, the job it just launched). Results never depend on threads.
// "Change when the map updates" is this file and its test (tests/tools/engine/closed_loop_test.cc).
#pragma once

#include <chrono>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "core/common/messages.h"
#include "core/explorer/explorer.h"
#include "core/perception/feature_tracker.h"
#include "core/perception/slam_points.h"
#include "tools/engine/compute_clock.h"
#include "tools/engine/job_worker.h"
#include "tools/engine/records.h"

namespace msb {

class LandmarkJitter;

/// Wall time of the stages of one tick (ms; recorded, never used).
struct TickTiming {
  double render_ms = 0, tracker_ms = 0, triangulation_ms = 0, map_ms = 0, planning_ms = 0;
};

/// One frame's perception: what it reads (fixed at launch) and what it produced.
struct PerceptionJob {
  int64_t frame_index = 0, tick = 0;
  std::shared_ptr<const CameraFrame> frame;
  Pose camera_estimate;                    ///< the VIO's camera pose of the frame
  bool map_due = false;                    ///< the explorer's map update is due on its tick
  bool plan_due = false;                   ///< its planning step is due on its tick
  std::optional<VehicleState> plan_state;  ///< the state a planning step starting now plans from
  uint64_t worker_id = 0;                  ///< its task number on the worker
  bool done = false;                       ///< (one thread) it has run
  TrackFrame tracks;                       ///< outputs ...
  SlamPointsFrame points;
  std::optional<PathCommand> cmd;
  int64_t cmd_delay_ticks = 0;  ///< ticks after its use that `cmd` takes effect (its compute)
  bool map_updated = false;
  TickTiming timing;
  std::exception_ptr error;  ///< what the job threw (rethrown when used)
};

/// How the method's calls are charged (tools/engine/compute_clock.h).
struct ComputeSetup {
  ComputeTiming timing;             ///< the scenario's `timing` section
  std::vector<ComputeCall> replay;  ///< charged: the latencies to replay (empty: measure)
  double machine_factor = 1.0;      ///< charged: reference seconds per CPU second here
  int physics_hz = 500;             ///< ticks per second
  int64_t frame_ticks = 1;          ///< ticks between camera frames
};

/// The stages a job runs, borrowed from the loop (they outlive the pipeline).
struct PerceptionStages {
  FeatureSource* features = nullptr;
  SlamPointEstimator* slam = nullptr;
  LandmarkJitter* jitter = nullptr;  ///< front-end degradation (may be null)
  Explorer* explorer = nullptr;      ///< null for a scripted flight
  /// Throws for a path the method may not send (core/explorer/output_limits.h).
  std::function<void(const PathCommand&, const VehicleState&)> check_path;
  ComputeSetup compute;  ///< how the explorer's calls are charged
};

/// The jobs in flight, their worker and their order (see file comment).
class PerceptionPipeline {
 public:
  /// `depth` frames between a job's launch and its use; `second_thread` (depth ≥ 1) runs jobs on
  /// a worker thread.
  PerceptionPipeline(int depth, bool second_thread, PerceptionStages stages);
  ~PerceptionPipeline();
  PerceptionPipeline(const PerceptionPipeline&) = delete;
  PerceptionPipeline& operator=(const PerceptionPipeline&) = delete;

  /// Starts a frame's job (on the worker, or later on this thread).
  void launch(std::unique_ptr<PerceptionJob> job);
  /// The job due at frame `frame_index` (launched `depth` frames before it), run to completion
  /// and kept until the next call; null when none is due. A job that threw drops every later
  /// job (abandon()) and its error is rethrown.
  const PerceptionJob* takeDue(int64_t frame_index);
  /// Waits until every job launched so far has run.
  void sync();
  /// Drops the jobs not started; a job running on the worker completes; none is used.
  void abandon();
  /// abandon() that waits at most `limit` for a job running on the worker; false if it is still
  /// running (stuck): the pipeline, the worker and what the job uses must then never be freed.
  bool abandonWithin(std::chrono::milliseconds limit);
  /// Called every JobWorker::kHookPeriod while the loop waits for the worker (e.g. to look for
  /// interrupts: what it throws leaves the wait; the caller then abandons).
  void setWaitHook(std::function<void()> hook) {
    if (worker_) worker_->setWaitHook(std::move(hook));
  }
  /// Rethrows the first error among the jobs still in flight (once).
  void rethrowPending();
  /// Milliseconds the loop thread waited for the worker (records only).
  double waitMs() const { return wait_ms_; }
  /// The explorer's calls so far with their charged latencies (after sync()).
  const std::vector<ComputeCall>& computeCalls() const { return calls_; }

 private:
  void run(PerceptionJob& j);
  // The explorer's calls that start on the job's tick (tools/engine/compute_clock.h).
  void runMethodCalls(PerceptionJob& j);
  // Runs a method's call `call` ("plan()") of the job's tick: what it throws names the call.
  void namedCall(const char* call, int64_t tick, const std::function<void()>& f) const;
  // A call's latency in ticks by the setup's mode; `cpu_s`: its measured CPU time.
  int64_t latencyTicks(ComputeCall& call, double cpu_s);
  void complete(PerceptionJob& j);

  int depth_ = 0;
  PerceptionStages stages_;
  double wait_ms_ = 0;
  ComputeClock clock_;                               // the method's computer (touched by the job running)
  std::vector<ComputeCall> calls_;                   // every call, as charged
  std::deque<std::unique_ptr<PerceptionJob>> jobs_;  // launched, not yet used (FIFO)
  std::unique_ptr<PerceptionJob> used_;              // the job whose results were used last
  std::unique_ptr<JobWorker> worker_;                // last: stopped before the rest goes
};

/// Frames to render into: the loop's current frame when nobody else holds it (a perception job,
/// a Python view), else a pooled one nobody holds, else a new one.
class FramePool {
 public:
  /// A frame nobody but the caller holds; `held` joins the pool when someone else holds it.
  std::shared_ptr<CameraFrame> renderTarget(std::shared_ptr<CameraFrame> held);

 private:
  std::vector<std::shared_ptr<CameraFrame>> pool_;
};

}  // namespace msb
