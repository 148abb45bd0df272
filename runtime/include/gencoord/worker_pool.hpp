// A small pool of persistent worker threads for batched evaluation (batch.hpp).
//
// Starting a std::thread costs tens of microseconds, as much as a whole batch of a few
// thousand qddot calls of a small model; the pool starts its workers once and wakes them per
// batch. One batch runs at a time (run() serializes callers); task c of a batch always runs
// task(c), so which thread runs it never changes a result.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace gencoord {

class WorkerPool {
 public:
  /// Starts `workers` threads (0 is allowed: run() then does everything itself).
  explicit WorkerPool(int workers) {
    threads_.reserve(static_cast<std::size_t>(std::max(workers, 0)));
    for (int w = 0; w < workers; ++w) threads_.emplace_back([this, w] { work(w + 1); });
  }

  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  ~WorkerPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    for (auto& thread : threads_) thread.join();
  }

  /// Threads a batch can use: the workers and the caller.
  int threads() const { return static_cast<int>(threads_.size()) + 1; }

  /// Runs task(0) ... task(count - 1), task 0 on the calling thread and task c on worker c;
  /// returns when all are done. count must not exceed threads(). Tasks must not throw.
  void run(std::size_t count, const std::function<void(std::size_t)>& task) {
    std::lock_guard<std::mutex> one_batch_at_a_time(run_mutex_);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      task_ = &task;
      count_ = count;
      remaining_ = count > 0 ? count - 1 : 0;
      ++generation_;
    }
    wake_.notify_all();
    if (count > 0) task(0);
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return remaining_ == 0; });
    task_ = nullptr;
  }

 private:
  void work(std::size_t index) {
    std::size_t seen = 0;
    for (;;) {
      const std::function<void(std::size_t)>* task = nullptr;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
        if (stopping_) return;
        seen = generation_;
        if (index >= count_) continue;  // this batch needs fewer threads
        task = task_;
      }
      (*task)(index);
      std::lock_guard<std::mutex> lock(mutex_);
      if (--remaining_ == 0) done_.notify_one();
    }
  }

  std::vector<std::thread> threads_;
  std::mutex run_mutex_;  // held for a whole batch
  std::mutex mutex_;      // guards the fields below
  std::condition_variable wake_, done_;
  const std::function<void(std::size_t)>* task_ = nullptr;
  std::size_t count_ = 0;
  std::size_t remaining_ = 0;
  std::size_t generation_ = 0;
  bool stopping_ = false;
};

/// The pool the batch functions share: hardware_concurrency() - 1 workers, started on first
/// use and joined at exit.
inline WorkerPool& shared_worker_pool() {
  static WorkerPool pool(static_cast<int>(std::thread::hardware_concurrency()) - 1);
  return pool;
}

}  // namespace gencoord
