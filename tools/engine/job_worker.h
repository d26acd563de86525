// One background thread that runs submitted tasks in submission order: the perception stage of
// the pipelined loop (docs/performance.md, "Two cores"). The loop decides what each task reads
// and when its result is used; the worker only decides when it runs, so results never depend on
// thread timing.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

namespace msb {

/// A FIFO task thread. Tasks must not throw (the loop stores a task's exception with its job).
class JobWorker {
 public:
  JobWorker();
  /// Drops the tasks not yet started, waits for the running one and joins the thread.
  ~JobWorker();
  JobWorker(const JobWorker&) = delete;
  JobWorker& operator=(const JobWorker&) = delete;

  /// Queues `task`; returns its number (1, 2, ... in submission order).
  uint64_t submit(std::function<void()> task);
  /// Blocks until task number `id` (and every task before it) has run; calls the wait hook every
  /// `kHookPeriod` meanwhile (what it throws leaves wait()).
  void wait(uint64_t id);
  /// Blocks until every submitted task has run (no hook).
  void waitAll();
  /// Waits up to `limit` for every submitted task; false if one is still running then.
  bool waitAllFor(std::chrono::milliseconds limit);
  /// Sets the hook wait() calls while it waits (e.g. to look for interrupts; empty: none).
  void setWaitHook(std::function<void()> hook) { hook_ = std::move(hook); }
  /// How often wait() calls the hook.
  static constexpr std::chrono::milliseconds kHookPeriod{100};
  /// Drops the tasks not yet started (they count as run for wait()); a running one completes.
  void cancelPending();

 private:
  void serve();

  std::mutex mutex_;
  std::condition_variable queued_, finished_;
  std::deque<std::function<void()>> queue_;
  uint64_t submitted_ = 0, done_ = 0;
  bool stop_ = false;
  std::function<void()> hook_;  // called by wait() every kHookPeriod, outside the lock
  std::thread thread_;          // last: started once the members above exist
};

}  // namespace msb
