#include "tools/loop/perception_pipeline.h"

#include <utility>

#include "core/common/wall_time.h"
#include "core/perception/frontend_degradation.h"

namespace msb {

PerceptionPipeline::PerceptionPipeline(int depth, bool second_thread, PerceptionStages stages)
    : depth_(depth), stages_(std::move(stages)) {
  if (second_thread && depth_ > 0) worker_ = std::make_unique<JobWorker>();
}

PerceptionPipeline::~PerceptionPipeline() = default;

void PerceptionPipeline::launch(std::unique_ptr<PerceptionJob> job) {
  PerceptionJob* p = job.get();
  jobs_.push_back(std::move(job));
  if (worker_) p->worker_id = worker_->submit([this, p] { run(*p); });
}

void PerceptionPipeline::run(PerceptionJob& j) {
  // Tracks, SLAM points, then the explorer's map update and plan due on the frame's tick.
  try {
    auto t0 = WallClock::now();
    j.tracks = stages_.features->process(*j.frame);
    j.timing.tracker_ms = msSince(t0);
    t0 = WallClock::now();
    j.points = stages_.slam->update(j.tracks, j.camera_estimate);
    if (stages_.jitter) stages_.jitter->apply(j.points);
    j.timing.triangulation_ms = msSince(t0);
    if (j.map_due) {
      t0 = WallClock::now();
      stages_.explorer->observe(j.points);
      j.timing.map_ms = msSince(t0);
      j.map_updated = true;
    }
    if (j.plan_state) {
      t0 = WallClock::now();
      j.cmd = stages_.explorer->plan(*j.plan_state);
      j.timing.planning_ms = msSince(t0);
      if (j.cmd) stages_.check_path(*j.cmd, *j.plan_state);
    }
  } catch (...) {
    j.error = std::current_exception();
  }
  j.done = true;
}

void PerceptionPipeline::complete(PerceptionJob& job) {
  if (worker_) {
    const auto t0 = WallClock::now();
    worker_->wait(job.worker_id);
    wait_ms_ += msSince(t0);
    return;
  }
  for (auto& q : jobs_) {  // one thread: the jobs run in order, when first needed
    if (!q->done) run(*q);
    if (q.get() == &job) return;
  }
}

const PerceptionJob* PerceptionPipeline::takeDue(int64_t frame_index) {
  if (jobs_.empty() || jobs_.front()->frame_index > frame_index - depth_) return nullptr;
  complete(*jobs_.front());
  used_ = std::move(jobs_.front());
  jobs_.pop_front();
  if (used_->error) {  // the method failed: no later job of it runs
    abandon();
    std::rethrow_exception(used_->error);
  }
  return used_.get();
}

void PerceptionPipeline::sync() {
  if (!jobs_.empty()) complete(*jobs_.back());
}

void PerceptionPipeline::abandon() {
  if (worker_) {
    worker_->cancelPending();
    worker_->waitAll();
  }
  jobs_.clear();
}

bool PerceptionPipeline::abandonWithin(std::chrono::milliseconds limit) {
  if (worker_) {
    worker_->cancelPending();
    if (!worker_->waitAllFor(limit)) return false;
  }
  jobs_.clear();
  return true;
}

void PerceptionPipeline::rethrowPending() {
  for (auto& job : jobs_)
    if (job->error) std::rethrow_exception(std::exchange(job->error, nullptr));
}

std::shared_ptr<CameraFrame> FramePool::renderTarget(std::shared_ptr<CameraFrame> held) {
  if (held.use_count() == 1) return held;
  // The held frame joins the pool; one of the pool's frames nobody else holds is reused (every
  // pixel is rendered again), else a new one.
  pool_.push_back(std::move(held));
  for (size_t i = 0; i + 1 < pool_.size(); ++i)
    if (pool_[i].use_count() == 1) {
      std::shared_ptr<CameraFrame> f = std::move(pool_[i]);
      pool_.erase(pool_.begin() + std::ptrdiff_t(i));
      return f;
    }
  return std::make_shared<CameraFrame>();
}

}  // namespace msb
