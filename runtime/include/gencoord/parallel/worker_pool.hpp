// SPDX-License-Identifier: BSD-3-Clause
// A small pool of persistent worker threads for batched evaluation (batch.hpp).
//
// Starting a std::thread costs tens of microseconds, as much as a whole batch of a few
// thousand qddot calls of a small model; the pool starts its workers once and wakes them per
// batch, and lets them spin briefly between batches. One batch runs at a time (run()
// serializes callers); task c of a batch always runs task(c), so which thread runs it never
// changes a result. A task that starts a batch of its own (a batched call inside a batched
// call) runs that inner batch on its own thread: the pool is busy with the outer one, and
// waiting for it would never end.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
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
      stopping_.store(true);
    }
    wake_.notify_all();
    for (auto& thread : threads_) thread.join();
  }

  /// Threads a batch can use: the workers and the caller.
  int threads() const { return static_cast<int>(threads_.size()) + 1; }

  /// Runs task(0) ... task(count - 1), task 0 on the calling thread and task c on worker c;
  /// returns when all are done. count must not exceed threads(). Tasks must not throw.
  void run(std::size_t count, const std::function<void(std::size_t)>& task) {
    if (inside_task()) {  // nested: the outer batch holds the pool (and maybe this thread)
      for (std::size_t c = 0; c < count; ++c) task(c);
      return;
    }
    std::lock_guard<std::mutex> one_batch_at_a_time(run_mutex_);
    {
      // a worker reads the generation with its task and count under this lock, so a worker
      // a batch did not need cannot mix that batch's generation with the next one's task
      std::lock_guard<std::mutex> lock(mutex_);
      task_ = &task;
      count_ = count;
      remaining_.store(count > 0 ? count - 1 : 0);
      generation_.fetch_add(1);
    }
    wake_.notify_all();
    if (count > 0) {
      const InsideTask inside;
      task(0);
    }
    if (!spin_until([this] { return remaining_.load() == 0; })) {
      std::unique_lock<std::mutex> lock(mutex_);
      done_.wait(lock, [this] { return remaining_.load() == 0; });
    }
  }

 private:
  // Whether this thread is running a task of some pool's batch (one flag for every pool: a
  // nested batch on another pool also runs serially, which is merely slower).
  static bool& inside_task() {
    thread_local bool inside = false;
    return inside;
  }
  struct InsideTask {
    InsideTask() : previous(inside_task()) { inside_task() = true; }
    ~InsideTask() { inside_task() = previous; }
    InsideTask(const InsideTask&) = delete;
    InsideTask& operator=(const InsideTask&) = delete;
    bool previous;
  };

  // Waits for `ready` by spinning for about kSpin before the caller blocks: waking a
  // sleeping thread takes tens of microseconds (more on a virtual machine), as long as a
  // small batch, and sweeps run batch after batch.
  template <class Ready>
  static bool spin_until(const Ready& ready) {
    constexpr auto kSpin = std::chrono::microseconds(200);
    const auto until = std::chrono::steady_clock::now() + kSpin;
    for (int k = 0;; ++k) {
      if (ready()) return true;
      if (k % 64 == 63 && std::chrono::steady_clock::now() > until) return false;
      std::this_thread::yield();
    }
  }

  void work(std::size_t index) {
    std::size_t seen = 0;
    for (;;) {
      const auto news = [&] { return stopping_.load() || generation_.load() != seen; };
      const bool spun = spin_until(news);
      const std::function<void(std::size_t)>* task = nullptr;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        if (!spun) wake_.wait(lock, news);
        if (stopping_.load()) return;
        seen = generation_.load();
        if (index >= count_) continue;  // this batch needs fewer threads
        task = task_;
      }
      {
        const InsideTask inside;
        (*task)(index);
      }
      if (remaining_.fetch_sub(1) == 1) {
        std::lock_guard<std::mutex> lock(mutex_);  // the caller checks under it: no lost wake-up
        done_.notify_one();
      }
    }
  }

  std::vector<std::thread> threads_;
  std::mutex run_mutex_;  // held for a whole batch
  std::mutex mutex_;      // for the waits on wake_ and done_
  std::condition_variable wake_, done_;
  const std::function<void(std::size_t)>* task_ = nullptr;  // guarded by mutex_
  std::size_t count_ = 0;                                   // guarded by mutex_
  std::atomic<std::size_t> remaining_{0};
  std::atomic<std::size_t> generation_{0};
  std::atomic<bool> stopping_{false};
};

/// The pool the batch functions share: hardware_concurrency() - 1 workers, started on first
/// use and joined at exit.
inline WorkerPool& shared_worker_pool() {
  static WorkerPool pool(static_cast<int>(std::thread::hardware_concurrency()) - 1);
  return pool;
}

}  // namespace gencoord
