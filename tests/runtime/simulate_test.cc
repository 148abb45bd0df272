// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/reduced_system.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hand_models.hpp"

namespace gencoord {
namespace {

using test_models::HandPendulum;

TEST(Simulate, CallsObserverStepsPlusOneTimesAndEndsAtDuration) {
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.q[0] = 0.5;
  std::vector<double> times;
  std::vector<State<HandPendulum>> seen;
  const State<HandPendulum> end =
      simulate(ReducedSystem<HandPendulum>(p), s, {Integrator::RK4, 0.1, 1.0},
               [&](const State<HandPendulum>& x) {
                 times.push_back(x.t);
                 seen.push_back(x);
               });
  ASSERT_EQ(times.size(), 11u);
  for (std::size_t k = 0; k < times.size(); ++k)
    EXPECT_DOUBLE_EQ(times[k], 0.1 * static_cast<double>(k)) << "k = " << k;
  EXPECT_DOUBLE_EQ(end.t, 1.0);
  EXPECT_EQ(seen.front().q, s.q);
  EXPECT_EQ(seen.back().q, end.q);
  EXPECT_EQ(seen.back().v, end.v);
}

// An observer that returns bool ends the run when it returns true (an event); the state it
// was given is the final one.
TEST(Simulate, AnObserverThatReturnsTrueEndsTheRun) {
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.q[0] = 0.5;
  long calls = 0;
  const State<HandPendulum> end =
      simulate(ReducedSystem<HandPendulum>(p), s, {Integrator::RK4, 0.1, 1.0},
               [&](const State<HandPendulum>& x) {
                 ++calls;
                 return x.t > 0.25;
               });
  EXPECT_EQ(calls, 4);  // t = 0, 0.1, 0.2, 0.3
  EXPECT_DOUBLE_EQ(end.t, 0.3);
}

TEST(Simulate, StartsFromTheInitialTime) {
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.t = 2.0;
  long calls = 0;
  StepStats stats;
  const State<HandPendulum> end =
      simulate(ReducedSystem<HandPendulum>(p), s,
               {Integrator::BackwardEuler, 0.01, 0.5, {}, &stats}, [&](const auto&) { ++calls; });
  EXPECT_EQ(calls, 51);
  EXPECT_EQ(stats.steps, 50);
  EXPECT_EQ(stats.newton_solves, 50);
  EXPECT_DOUBLE_EQ(end.t, 2.5);
}

TEST(Simulate, ZeroDurationObservesOnlyTheInitialState) {
  const HandPendulum::Params p;
  long calls = 0;
  const State<HandPendulum> end =
      simulate(ReducedSystem<HandPendulum>(p), State<HandPendulum>{}, {Integrator::RK4, 0.1, 0.0},
               [&](const auto&) { ++calls; });
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(end.t, 0.0);
}

// A program that compiles only some integrators runs them as with every one compiled, and
// refuses the others with a message that names them.
TEST(Simulate, AnIntegratorSetCompilesOnlyItsMethods) {
  using ExplicitOnly = IntegratorSet<Integrator::SymplecticEuler, Integrator::RK4>;
  static_assert(includes(ExplicitOnly{}, Integrator::RK4));
  static_assert(!includes(ExplicitOnly{}, Integrator::BackwardEuler));
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.q[0] = 0.5;
  const ReducedSystem<HandPendulum> system(p);
  for (const Integrator method : {Integrator::SymplecticEuler, Integrator::RK4}) {
    const State<HandPendulum> some = simulate<ExplicitOnly>(system, s, {method, 0.01, 1.0});
    const State<HandPendulum> all = simulate(system, s, {method, 0.01, 1.0});
    EXPECT_EQ(some.q, all.q) << to_string(method);
    EXPECT_EQ(some.v, all.v) << to_string(method);
  }
  try {
    simulate<ExplicitOnly>(system, s, {Integrator::BackwardEuler, 0.01, 1.0});
    FAIL() << "backward Euler ran although the set leaves it out";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("backward_euler is not compiled into this program"),
              std::string::npos)
        << error.what();
  }
}

TEST(StepCount, RoundsAwayRoundOffOnly) {
  EXPECT_EQ(step_count(0.1, 1.0), 10);
  EXPECT_EQ(step_count(0.01, 1000.0), 100000);
  EXPECT_EQ(step_count(1.0 / 3.0, 1.0), 3);
  EXPECT_THROW(step_count(0.3, 1.0), StepSizeError);  // 3.33 steps
  EXPECT_THROW(step_count(0.0, 1.0), StepSizeError);
  EXPECT_THROW(step_count(-0.1, 1.0), StepSizeError);
  EXPECT_THROW(step_count(0.1, -1.0), StepSizeError);
}

}  // namespace
}  // namespace gencoord
