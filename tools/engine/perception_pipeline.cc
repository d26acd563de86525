#include "tools/engine/perception_pipeline.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "core/common/config_fields.h"
#include "core/common/wall_time.h"
#include "core/perception/frontend_degradation.h"

namespace msb {

PerceptionPipeline::PerceptionPipeline(int depth, bool second_thread, PerceptionStages stages)
    : depth_(depth), stages_(std::move(stages)), clock_(stages_.compute.frame_ticks) {
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
    if (stages_.explorer) runMethodCalls(j);
  } catch (...) {
    j.error = std::current_exception();
  }
  j.done = true;
}

void PerceptionPipeline::namedCall(const char* call, int64_t tick, const std::function<void()>& f) const {
  // Errors that name themselves pass as they are (an output limit, a configuration error, a
  // Python method's traceback); any other error of the method is named by its call and tick.
  const auto named = [&](const char* what) {
    char at[64];
    std::snprintf(at, sizeof at, " at t = %.3f s (tick %lld) threw: ", double(tick) / stages_.compute.physics_hz,
                  static_cast<long long>(tick));
    return MethodCallError(std::string("the method's ") + call + at + what);
  };
  try {
    f();
  } catch (const MethodOutputError&) {
    throw;
  } catch (const MethodCallError&) {
    throw;
  } catch (const ConfigError&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw named(e.what());
  } catch (const std::logic_error& e) {
    throw named(e.what());
  }
}

void PerceptionPipeline::runMethodCalls(PerceptionJob& j) {
  // The calls asked for on this tick join those waiting; each that may start now runs (free:
  // all of them, map update first, on the frame's tick).
  if (j.map_due) clock_.ask(ComputeCall::Stage::kMap, j.tick);
  if (j.plan_due) clock_.ask(ComputeCall::Stage::kPlan, j.tick);
  const bool charged = stages_.compute.timing.compute == ComputeMode::kCharged;
  while (std::optional<ComputeCall> call = clock_.next(j.tick)) {
    const auto t0 = WallClock::now();
    const double cpu0 = charged ? threadCpuSeconds() + stages_.explorer->helperCpuSeconds() : 0.0;
    std::optional<PathCommand> cmd;
    if (call->stage == ComputeCall::Stage::kMap) {
      namedCall("observe()", j.tick, [&] { stages_.explorer->observe(j.points); });
      j.timing.map_ms += msSince(t0);
      j.map_updated = true;
    } else {
      namedCall("plan()", j.tick, [&] { cmd = stages_.explorer->plan(*j.plan_state); });
      j.timing.planning_ms += msSince(t0);
    }
    const double cpu_s = charged ? threadCpuSeconds() + stages_.explorer->helperCpuSeconds() - cpu0 : 0.0;
    clock_.charge(*call, latencyTicks(*call, cpu_s));
    calls_.push_back(*call);
    if (!cmd) continue;
    stages_.check_path(*cmd, *j.plan_state);
    j.cmd = std::move(cmd);
    j.cmd_delay_ticks = clock_.busyUntil() - j.tick;  // its output when the step ends
  }
}

int64_t PerceptionPipeline::latencyTicks(ComputeCall& call, double cpu_s) {
  const ComputeSetup& c = stages_.compute;
  const auto ticks = [&](double s) { return int64_t(std::ceil(s * double(c.physics_hz) - 1e-9)); };
  if (c.timing.compute == ComputeMode::kModelled) {
    const StageCostModel& m = call.stage == ComputeCall::Stage::kMap ? c.timing.map : c.timing.plan;
    try {
      return std::max<int64_t>(0, ticks(m.seconds(stages_.explorer->workCounters())));
    } catch (const std::runtime_error& e) {
      throw ConfigError(std::string("timing.") + stageName(call.stage) + ".per", e.what());
    }
  }
  if (c.timing.compute != ComputeMode::kCharged) return 0;
  if (c.timing.replay.empty()) {
    call.cpu_ns = int64_t(std::llround(cpu_s * 1e9));
    return std::max<int64_t>(0, ticks(cpu_s * c.machine_factor));
  }
  // A replay: the logged call of this index, which must be the same call.
  const size_t i = calls_.size();
  if (i >= c.replay.size())
    throw std::runtime_error(c.timing.replay + ": the replay asks for call " + std::to_string(i) + ", the log has " +
                             std::to_string(c.replay.size()) + " (the run went differently)");
  const ComputeCall& logged = c.replay[i];
  if (logged.stage != call.stage || logged.start_tick != call.start_tick)
    throw std::runtime_error(c.timing.replay + ": call " + std::to_string(i) + " is a " + stageName(call.stage) +
                             " at tick " + std::to_string(call.start_tick) + ", the log's a " +
                             stageName(logged.stage) + " at tick " + std::to_string(logged.start_tick));
  call.cpu_ns = logged.cpu_ns;
  return logged.latency_ticks;
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
