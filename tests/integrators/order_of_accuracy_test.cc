// SPDX-License-Identifier: BSD-3-Clause
// Measured order of accuracy of every integrator on generated models: the error of (q, v)
// against an RK4 run at a much finer step (the largest at five equally spaced times), for five
// halving step sizes; the fitted log-log slope must be the nominal order within 0.15.
//
// Models: the nonlinear pendulum (amplitude 1 rad), the double pendulum (moderate amplitude,
// t = 1), and two with a time-dependent parameterization X(q, t):
//  - the bead on a rotating hoop: X depends on t but its reduced equations do not (Mt, Ft + Fi
//    are invariant under the rotation), so it checks the time-dependent kernels, not the
//    integrators' clocks;
//  - the Kapitza pendulum (models/kapitza_pendulum.py, pivot shaken vertically): its
//    reduced equations depend on t, so an integrator that evaluates a stage or half step at the
//    wrong time loses order. A deliberately misclocked trapezoidal rule shows the test notices.
#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "convergence.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/bead_on_rotating_hoop.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/kapitza_pendulum.hpp"
#include "generated/pendulum.hpp"

namespace gencoord::testing {
namespace {

using models::BeadOnRotatingHoop;
using models::DoublePendulum;
using DrivenPendulum = models::KapitzaPendulum;
using models::Pendulum;

constexpr double kTolerance = 0.15;  // on the fitted slope
// RK4 reference steps over the horizon: its error is far below every tested error
constexpr long long kReferenceSteps = kSamples << 13;

// One integrator and its step range: steps over the horizon at the coarsest size, then 2x,
// 4x, 8x, 16x. Ranges are picked so every size is in the asymptotic regime (local slopes
// within the tolerance) and the finest error stays far above round-off and the reference's
// own error (see the printed tables).
struct OrderCase {
  Integrator integrator;
  long long coarsest_steps;
};

void PrintTo(const OrderCase& c, std::ostream* os) {
  *os << to_string(c.integrator) << " from " << c.coarsest_steps << " steps";
}

// the same step ranges serve every model here (all have frequencies of a few rad/s)
const std::vector<OrderCase> kCases = {
    {Integrator::ForwardEuler, 400},    {Integrator::SymplecticEuler, 400},
    {Integrator::BackwardEuler, 400},   {Integrator::Trapezoidal, 50},
    {Integrator::ImplicitMidpoint, 50}, {Integrator::RK4, 40},
};

std::string case_name(const ::testing::TestParamInfo<OrderCase>& info) {
  return to_string(info.param.integrator);
}

// The experiment for one model: its parameters, initial state and horizon.
template <class M>
struct Experiment {
  ParamsOf<M> p;
  State<M> initial;
  double duration;

  std::vector<State<M>> reference() const {
    return sampled_run<M>(p, initial, Integrator::RK4, duration, kReferenceSteps);
  }
};

template <class M>
void expect_nominal_order(const Experiment<M>& e, const std::vector<State<M>>& reference,
                          const OrderCase& c) {
  const OrderMeasurement m = measure_order<M>(M::name, e.p, e.initial, reference, c.integrator,
                                              e.duration, c.coarsest_steps);
  EXPECT_NEAR(m.slope, order(c.integrator), kTolerance)
      << M::name << ", " << to_string(c.integrator) << ": errors " << m.errors.front() << " .. "
      << m.errors.back();
  // the finest error must be well above round-off, or the slope measures noise
  EXPECT_GT(m.errors.back(), 1e-11) << "finest step too small to measure the order";
}

// --- pendulum: amplitude 1 rad, one swing period is about 2.1 s ---------------------------------

Experiment<Pendulum> pendulum_experiment() {
  Experiment<Pendulum> e{Pendulum::Params{}, State<Pendulum>{}, 2.0};
  e.initial.q[0] = 1.0;
  e.initial.v[0] = 0.5;
  return e;
}

class PendulumOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(PendulumOrder, FittedSlopeIsNominal) {
  static const Experiment<Pendulum> e = pendulum_experiment();
  static const std::vector<State<Pendulum>> reference = e.reference();
  expect_nominal_order<Pendulum>(e, reference, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Integrators, PendulumOrder, ::testing::ValuesIn(kCases), case_name);

// --- double pendulum: moderate amplitude, t = 1 -------------------------------------------------

Experiment<DoublePendulum> double_pendulum_experiment() {
  Experiment<DoublePendulum> e{DoublePendulum::Params{}, State<DoublePendulum>{}, 1.0};
  e.initial.q << 0.8, -0.5;
  e.initial.v << 0.3, 0.0;
  return e;
}

class DoublePendulumOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(DoublePendulumOrder, FittedSlopeIsNominal) {
  static const Experiment<DoublePendulum> e = double_pendulum_experiment();
  static const std::vector<State<DoublePendulum>> reference = e.reference();
  expect_nominal_order<DoublePendulum>(e, reference, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Integrators, DoublePendulumOrder, ::testing::ValuesIn(kCases), case_name);

// --- bead on a rotating hoop: X(q, t) rotates with the hoop ------------------------------------

Experiment<BeadOnRotatingHoop> bead_experiment() {
  Experiment<BeadOnRotatingHoop> e{BeadOnRotatingHoop::Params{}, State<BeadOnRotatingHoop>{}, 2.0};
  e.p.c = 0.3;  // some damping, so the velocity dependence is exercised too
  e.initial.q[0] = 0.3;
  e.initial.v[0] = 1.0;
  return e;
}

class BeadOnRotatingHoopOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(BeadOnRotatingHoopOrder, FittedSlopeIsNominal) {
  static const Experiment<BeadOnRotatingHoop> e = bead_experiment();
  static const std::vector<State<BeadOnRotatingHoop>> reference = e.reference();
  expect_nominal_order<BeadOnRotatingHoop>(e, reference, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Integrators, BeadOnRotatingHoopOrder, ::testing::ValuesIn(kCases),
                         case_name);

// --- driven pendulum: the reduced equations depend on t ------------------------------------

Experiment<DrivenPendulum> driven_experiment() {
  Experiment<DrivenPendulum> e{DrivenPendulum::Params{}, State<DrivenPendulum>{}, 2.0};
  e.p.a = 0.1;
  e.p.omega = 5.0;
  e.initial.q[0] = 1.0;
  e.initial.v[0] = 0.0;
  return e;
}

class DrivenPendulumOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(DrivenPendulumOrder, FittedSlopeIsNominal) {
  static const Experiment<DrivenPendulum> e = driven_experiment();
  static const std::vector<State<DrivenPendulum>> reference = e.reference();
  expect_nominal_order<DrivenPendulum>(e, reference, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Integrators, DrivenPendulumOrder, ::testing::ValuesIn(kCases), case_name);

// --- the time check can fail ----------------------------------------------------------------

// The trapezoidal rule with a clock bug: the backward-Euler half step starts from the
// forward-Euler half state but with its time not advanced, so the implicit end evaluation is
// at t0 + h/2 instead of t0 + h. A first-order error in t: O(h) on a t-dependent model.
template <class M>
std::vector<State<M>> misclocked_trapezoidal_run(const Experiment<M>& e, long long steps) {
  const double h = e.duration / static_cast<double>(steps);
  std::vector<State<M>> samples;
  State<M> s = e.initial;
  for (long long k = 1; k <= steps; ++k) {
    State<M> half = forward_euler_step(ReducedSystem<M>(e.p), s, 0.5 * h);
    half.t = s.t;  // the bug
    s = backward_euler_step(ReducedSystem<M>(e.p), half, 0.5 * h);
    s.t = e.initial.t + static_cast<double>(k) * h;
    if (k % (steps / kSamples) == 0) samples.push_back(s);
  }
  return samples;
}

template <class M>
double misclocked_trapezoidal_slope(const Experiment<M>& e, long long coarsest_steps) {
  const std::vector<State<M>> reference = e.reference();
  std::vector<double> dts, errors;
  for (int k = 0; k < 5; ++k) {
    const long long steps = coarsest_steps << k;
    dts.push_back(e.duration / static_cast<double>(steps));
    errors.push_back(trajectory_error<M>(misclocked_trapezoidal_run<M>(e, steps), reference));
  }
  const double slope = fit_loglog(dts, errors).slope;
  std::printf("[ order    ] %s, misclocked trapezoidal: fitted slope %.3f, errors %.4e .. %.4e\n",
              M::name, slope, errors.front(), errors.back());
  return slope;
}

TEST(TimeHandling, MisclockedTrapezoidalIsFirstOrderOnTheDrivenPendulum) {
  // the correct rule measures 2 on the same model above; the bug must be caught
  EXPECT_NEAR(misclocked_trapezoidal_slope<DrivenPendulum>(driven_experiment(), 50), 1.0,
              kTolerance);
}

TEST(TimeHandling, BeadOnRotatingHoopCannotSeeAClockBug) {
  // documents why the driven pendulum is needed: the bead's reduced equations do not depend
  // on t, so the same bug keeps order 2 there
  EXPECT_NEAR(misclocked_trapezoidal_slope<BeadOnRotatingHoop>(bead_experiment(), 50), 2.0,
              kTolerance);
}

}  // namespace
}  // namespace gencoord::testing
