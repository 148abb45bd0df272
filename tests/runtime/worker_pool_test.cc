// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/parallel/worker_pool.hpp"

#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace gencoord {
namespace {

TEST(WorkerPool, RunsEveryTaskOnceForEveryBatchSize) {
  WorkerPool pool(3);
  ASSERT_EQ(pool.threads(), 4);
  for (std::size_t count = 0; count <= 4; ++count) {
    std::vector<int> runs(count, 0);
    pool.run(count, [&](std::size_t c) { ++runs[c]; });
    for (std::size_t c = 0; c < count; ++c)
      EXPECT_EQ(runs[c], 1) << "task " << c << " of " << count;
  }
}

TEST(WorkerPool, TaskZeroRunsOnTheCaller) {
  WorkerPool pool(1);
  std::thread::id ran_on;
  pool.run(2, [&](std::size_t c) {
    if (c == 0) ran_on = std::this_thread::get_id();
  });
  EXPECT_EQ(ran_on, std::this_thread::get_id());
}

// many short batches of changing sizes: a missed wake-up would hang, a doubled one would
// count a task twice
TEST(WorkerPool, ManyBatchesInARow) {
  WorkerPool pool(2);
  std::atomic<long> total{0};
  long expected = 0;
  for (int batch = 0; batch < 20000; ++batch) {
    const std::size_t count = 1 + static_cast<std::size_t>(batch % 3);
    pool.run(count, [&](std::size_t c) { total += static_cast<long>(c) + 1; });
    expected += static_cast<long>(count * (count + 1) / 2);
  }
  EXPECT_EQ(total.load(), expected);
}

TEST(WorkerPool, CallersFromSeveralThreadsTakeTurns) {
  WorkerPool pool(1);
  std::atomic<long> total{0};
  std::vector<std::thread> callers;
  for (int k = 0; k < 3; ++k)
    callers.emplace_back([&] {
      for (int batch = 0; batch < 2000; ++batch)
        pool.run(2, [&](std::size_t c) { total += static_cast<long>(c) + 1; });
    });
  for (auto& caller : callers) caller.join();
  EXPECT_EQ(total.load(), 3L * 2000 * 3);
}

// a task that starts a batch (on the caller's thread and on a worker) runs it itself instead
// of waiting for the pool its own batch holds, which would hang
TEST(WorkerPool, BatchInsideABatchTaskRunsOnThatTask) {
  WorkerPool pool(2);
  std::vector<std::vector<int>> inner_runs(3, std::vector<int>(3, 0));
  std::vector<std::thread::id> outer_thread(3), inner_thread(9);
  pool.run(3, [&](std::size_t c) {
    outer_thread[c] = std::this_thread::get_id();
    pool.run(3, [&](std::size_t d) {
      ++inner_runs[c][d];
      inner_thread[3 * c + d] = std::this_thread::get_id();
    });
  });
  for (std::size_t c = 0; c < 3; ++c) {
    for (std::size_t d = 0; d < 3; ++d) {
      EXPECT_EQ(inner_runs[c][d], 1) << "inner task " << d << " of outer task " << c;
      EXPECT_EQ(inner_thread[3 * c + d], outer_thread[c]);
    }
  }
  // and the pool still runs batches in parallel afterwards
  std::vector<std::thread::id> ran_on(3);
  pool.run(3, [&](std::size_t c) { ran_on[c] = std::this_thread::get_id(); });
  EXPECT_NE(ran_on[1], std::this_thread::get_id());
}

TEST(WorkerPool, NoWorkersRunsOnTheCaller) {
  WorkerPool pool(0);
  int runs = 0;
  pool.run(1, [&](std::size_t) { ++runs; });
  EXPECT_EQ(runs, 1);
}

}  // namespace
}  // namespace gencoord
