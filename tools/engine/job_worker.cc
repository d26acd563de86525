#include "tools/engine/job_worker.h"

namespace msb {

JobWorker::JobWorker() : thread_([this] { serve(); }) {}

JobWorker::~JobWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    queue_.clear();
  }
  queued_.notify_all();
  thread_.join();
}

uint64_t JobWorker::submit(std::function<void()> task) {
  uint64_t id = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(std::move(task));
    id = ++submitted_;
  }
  queued_.notify_one();
  return id;
}

void JobWorker::wait(uint64_t id) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!hook_) return finished_.wait(lock, [&] { return done_ >= id; });
  while (!finished_.wait_for(lock, kHookPeriod, [&] { return done_ >= id; })) {
    lock.unlock();
    hook_();
    lock.lock();
  }
}

bool JobWorker::waitAllFor(std::chrono::milliseconds limit) {
  std::unique_lock<std::mutex> lock(mutex_);
  return finished_.wait_for(lock, limit, [&] { return done_ >= submitted_; });
}

void JobWorker::waitAll() {
  std::unique_lock<std::mutex> lock(mutex_);
  finished_.wait(lock, [&] { return done_ >= submitted_; });
}

void JobWorker::cancelPending() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ += queue_.size();
    queue_.clear();
  }
  finished_.notify_all();
}

void JobWorker::serve() {
  for (;;) {
    std::function<void()> task;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      queued_.wait(lock, [&] { return stop_ || !queue_.empty(); });
      if (stop_) return;
      task = std::move(queue_.front());
      queue_.pop_front();
    }
    task();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++done_;
    }
    finished_.notify_all();
  }
}

}  // namespace msb
