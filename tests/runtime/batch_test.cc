// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/parallel/batch.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/reduced_system.hpp"

#include <algorithm>
#include <cstddef>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gencoord/integrate/integrator.hpp"
#include "hand_models.hpp"

namespace gencoord {
namespace {

using test_models::HandCoupled;
using test_models::HandPendulum;

// seeded random states and one parameter set per state
struct PendulumBatch {
  std::vector<State<HandPendulum>> states;
  std::vector<HandPendulum::Params> params;
};

PendulumBatch pendulum_batch(std::size_t count) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> angle(-3.0, 3.0), rate(-2.0, 2.0), length(0.5, 2.0);
  PendulumBatch b;
  for (std::size_t i = 0; i < count; ++i) {
    State<HandPendulum> s;
    s.t = 0.01 * static_cast<double>(i);
    s.q[0] = angle(rng);
    s.v[0] = rate(rng);
    b.states.push_back(s);
    HandPendulum::Params p;
    p.l = length(rng);
    b.params.push_back(p);
  }
  return b;
}

// 1, 2 and more threads than states, and sizes that do not divide evenly
class BatchThreads : public ::testing::TestWithParam<int> {};

TEST_P(BatchThreads, QddotEqualsSerialExactly) {
  const int threads = GetParam();
  for (const std::size_t count :
       {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{1001}}) {
    const PendulumBatch b = pendulum_batch(count);
    std::vector<QVec<HandPendulum>> out;
    batch_qddot<HandPendulum>(b.states, b.params, &out, threads);
    ASSERT_EQ(out.size(), count);
    for (std::size_t i = 0; i < count; ++i)
      EXPECT_EQ(out[i], acceleration<HandPendulum>(b.params[i], b.states[i]))
          << "qddot mismatch at state " << i << " of " << count << ", " << threads << " threads";
  }
}

TEST_P(BatchThreads, SharedParamsEqualSerialExactly) {
  const int threads = GetParam();
  const PendulumBatch b = pendulum_batch(513);
  const std::vector<HandPendulum::Params> shared(1, b.params[3]);
  std::vector<QVec<HandPendulum>> out;
  batch_qddot<HandPendulum>(b.states, shared, &out, threads);
  for (std::size_t i = 0; i < b.states.size(); ++i)
    EXPECT_EQ(out[i], acceleration<HandPendulum>(shared[0], b.states[i]))
        << "qddot mismatch at state " << i;
}

TEST_P(BatchThreads, Rk4StepEqualsSerialExactly) {
  const int threads = GetParam();
  const PendulumBatch b = pendulum_batch(1001);
  std::vector<State<HandPendulum>> out;
  batch_step<HandPendulum>(Integrator::RK4, b.params, b.states, 1e-3, &out, threads);
  ASSERT_EQ(out.size(), b.states.size());
  for (std::size_t i = 0; i < b.states.size(); ++i) {
    const State<HandPendulum> serial =
        step(ReducedSystem<HandPendulum>(b.params[i]), Integrator::RK4, b.states[i], 1e-3);
    EXPECT_EQ(out[i].t, serial.t) << "t mismatch at state " << i;
    EXPECT_EQ(out[i].q, serial.q) << "q mismatch at state " << i;
    EXPECT_EQ(out[i].v, serial.v) << "v mismatch at state " << i;
  }
}

TEST_P(BatchThreads, StepInPlaceEqualsSerialExactly) {
  const int threads = GetParam();
  const PendulumBatch b = pendulum_batch(257);
  std::vector<State<HandPendulum>> states = b.states;
  batch_step<HandPendulum>(Integrator::BackwardEuler, b.params, states, 1e-2, &states, threads);
  for (std::size_t i = 0; i < states.size(); ++i) {
    const State<HandPendulum> serial = step(ReducedSystem<HandPendulum>(b.params[i]),
                                            Integrator::BackwardEuler, b.states[i], 1e-2);
    EXPECT_EQ(states[i].q, serial.q) << "q mismatch at state " << i;
    EXPECT_EQ(states[i].v, serial.v) << "v mismatch at state " << i;
  }
}

TEST_P(BatchThreads, ForEachRunsEveryIndexOnceAndEqualsSerial) {
  // runs of very different lengths, as in a sweep whose samples stop at an event
  const int threads = GetParam();
  const PendulumBatch b = pendulum_batch(301);
  auto run = [&](std::size_t i) {
    State<HandPendulum> s = b.states[i];
    const ReducedSystem<HandPendulum> system(b.params[i]);
    for (std::size_t k = 0; k < i % 17 * 10; ++k) s = step(system, Integrator::RK4, s, 1e-3);
    return s;
  };
  std::vector<State<HandPendulum>> out(b.states.size());
  std::vector<int> calls(b.states.size(), 0);
  batch_for_each(b.states.size(), threads, [&](std::size_t i) {
    ++calls[i];
    out[i] = run(i);
  });
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_EQ(calls[i], 1) << "index " << i;
    const State<HandPendulum> serial = run(i);
    EXPECT_EQ(out[i].q, serial.q) << "index " << i << ", " << threads << " threads";
    EXPECT_EQ(out[i].v, serial.v) << "index " << i << ", " << threads << " threads";
  }
}

INSTANTIATE_TEST_SUITE_P(Threads, BatchThreads, ::testing::Values(1, 2, 5));

TEST(Batch, ForEachRethrowsTheLowestFailureAfterEveryIndex) {
  for (const int threads : {1, 2, 5}) {
    std::vector<int> ran(50, 0);
    try {
      batch_for_each(ran.size(), threads, [&](std::size_t i) {
        ran[i] = 1;
        if (i == 7 || i == 30) throw std::runtime_error(std::to_string(i));
      });
      ADD_FAILURE() << "no exception with " << threads << " threads";
    } catch (const std::runtime_error& error) {
      EXPECT_STREQ(error.what(), "7") << threads << " threads";
    }
    EXPECT_EQ(std::count(ran.begin(), ran.end(), 1), 50) << threads << " threads";
  }
  EXPECT_NO_THROW(batch_for_each(0, 2, [](std::size_t) { throw std::runtime_error("never"); }));
  EXPECT_THROW(batch_for_each(3, 0, [](std::size_t) {}), std::invalid_argument);
}

TEST(Batch, FailureInAnyChunkIsRethrownAfterJoin) {
  // an indefinite mass matrix in the second half: the second thread's chunk throws
  std::vector<State<HandCoupled>> states(10);
  std::vector<HandCoupled::Params> params(10);
  params[8].c = 5.0;
  std::vector<QVec<HandCoupled>> out;
  for (const int threads : {1, 2})
    EXPECT_THROW(batch_qddot<HandCoupled>(states, params, &out, threads), DynamicsError)
        << threads << " threads";
}

TEST(Batch, RejectsMismatchedSizesAndZeroThreads) {
  const PendulumBatch b = pendulum_batch(4);
  std::vector<QVec<HandPendulum>> out;
  const std::vector<HandPendulum::Params> three(3);
  EXPECT_THROW(batch_qddot<HandPendulum>(b.states, three, &out, 2), std::invalid_argument);
  EXPECT_THROW(batch_qddot<HandPendulum>(b.states, b.params, &out, 0), std::invalid_argument);
}

TEST(Batch, DefaultThreadCountIsPositive) { EXPECT_GE(default_batch_threads(), 1); }

}  // namespace
}  // namespace gencoord
