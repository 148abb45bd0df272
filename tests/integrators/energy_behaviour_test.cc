// SPDX-License-Identifier: BSD-3-Clause
// Long-run energy behaviour of the integrators on the generated simple pendulum, 1e5 steps
// of dt = 0.01 (about 480 periods) from a 1 rad swing. Its mass matrix m l^2 is constant, so
// implicit midpoint and symplectic Euler are symplectic for it: their energy error stays
// bounded with no secular drift. Backward Euler dissipates energy, forward Euler injects it.
//
// "No drift" is asserted twice: the largest |E - E0| over the last tenth of the run is no
// larger than over the first tenth, and the least-squares slope of E(t) over the whole run,
// times its duration, is below 1% of that early oscillation. RK4, not symplectic, fails it.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/pendulum.hpp"

namespace gencoord::testing {
namespace {

using models::Pendulum;

constexpr long long kSteps = 100000;
constexpr double kDt = 0.01;

struct EnergyRun {
  double e0 = 0;             // initial energy
  double swing = 0;          // e0 - E_rest: the energy of the swing
  double max_dev_first = 0;  // max |E - e0| over the first tenth of the run
  double max_dev_last = 0;   // max |E - e0| over the last tenth
  double mean_first = 0;     // mean E over the first tenth
  double mean_last = 0;      // mean E over the last tenth
  double drift = 0;          // secular change: least-squares slope of E(t) times the duration
};

EnergyRun run(Integrator integrator) {
  const Pendulum::Params p;
  State<Pendulum> s;
  s.q[0] = 1.0;  // a large swing: the nonlinearity matters
  EnergyRun r;
  r.e0 = Pendulum::energy(s.q, s.v, s.t, p);
  const QVec<Pendulum> zero = QVec<Pendulum>::Zero();
  r.swing = r.e0 - Pendulum::energy(zero, zero, 0.0, p);
  const double duration = static_cast<double>(kSteps) * kDt;
  long long k = 0, first_count = 0, last_count = 0;
  double st = 0, se = 0, stt = 0, ste = 0;  // sums for the least-squares line E(t)
  const ReducedSystem<Pendulum> system(p);
  simulate(system, s, {integrator, kDt, duration}, [&](const State<Pendulum>& x) {
    const double e = Pendulum::energy(x.q, x.v, x.t, p);
    // centred on the middle of the run and on E0, so the sums do not cancel
    const double tc = x.t - 0.5 * duration, ec = e - r.e0;
    st += tc;
    se += ec;
    stt += tc * tc;
    ste += tc * ec;
    if (k <= kSteps / 10) {
      r.max_dev_first = std::max(r.max_dev_first, std::abs(e - r.e0));
      r.mean_first += e;
      ++first_count;
    }
    if (k >= kSteps - kSteps / 10) {
      r.max_dev_last = std::max(r.max_dev_last, std::abs(e - r.e0));
      r.mean_last += e;
      ++last_count;
    }
    ++k;
  });
  const double n = static_cast<double>(k);
  r.drift = (n * ste - st * se) / (n * stt - st * st) * duration;
  r.mean_first /= static_cast<double>(first_count);
  r.mean_last /= static_cast<double>(last_count);
  std::printf(
      "[ energy   ] %s, dt %g, %lld steps: E0 %.6f, swing %.6f; first tenth: max|dE| %.4e, "
      "mean E - E0 %.4e; last tenth: max|dE| %.4e, mean E - E0 %.4e; fitted drift over the run "
      "%.4e\n",
      to_string(integrator), kDt, kSteps, r.e0, r.swing, r.max_dev_first, r.mean_first - r.e0,
      r.max_dev_last, r.mean_last - r.e0, r.drift);
  return r;
}

// bounded: the energy error of the last tenth is no larger than that of the first, and the
// fitted secular change over the whole run is below 1% of the oscillation's amplitude
void expect_bounded_without_drift(const EnergyRun& r, double max_dev_bound) {
  EXPECT_LT(r.max_dev_first, max_dev_bound * r.swing);
  EXPECT_LT(r.max_dev_last, 1.1 * r.max_dev_first);
  EXPECT_LT(std::abs(r.drift), 1e-2 * r.max_dev_first);
}

TEST(PendulumEnergy, ImplicitMidpointIsBoundedWithoutDrift) {
  expect_bounded_without_drift(run(Integrator::ImplicitMidpoint), 1e-3);
}

TEST(PendulumEnergy, SymplecticEulerIsBoundedWithoutDrift) {
  expect_bounded_without_drift(run(Integrator::SymplecticEuler), 0.1);
}

// Not a stated property of the method, but it follows from the construction: n trapezoidal steps
// are FE(h/2) o [implicit midpoint]^(n-1) o BE(h/2), conjugate to implicit midpoint, so the energy
// error stays bounded too.
TEST(PendulumEnergy, TrapezoidalIsBoundedWithoutDrift) {
  expect_bounded_without_drift(run(Integrator::Trapezoidal), 1e-3);
}

// The drift check can fail: RK4 is far more accurate per step but not symplectic, and its
// slow energy loss is caught (|drift| is about 10x its early oscillation, not below 1%).
TEST(PendulumEnergy, Rk4DriftsSoTheDriftCheckCanFail) {
  const EnergyRun r = run(Integrator::RK4);
  EXPECT_LT(r.drift, 0.0);
  EXPECT_GT(std::abs(r.drift), 1e-2 * r.max_dev_first);
  EXPECT_GT(r.max_dev_last, 1.1 * r.max_dev_first);
}

TEST(PendulumEnergy, BackwardEulerLosesEnergy) {
  const EnergyRun r = run(Integrator::BackwardEuler);
  EXPECT_LT(r.mean_last, r.e0 - 0.5 * r.swing);
  EXPECT_LT(r.mean_last, r.mean_first);
  EXPECT_LT(r.drift, 0.0);
}

TEST(PendulumEnergy, ForwardEulerGainsEnergy) {
  const EnergyRun r = run(Integrator::ForwardEuler);
  EXPECT_GT(r.mean_last, r.e0 + r.swing);
  EXPECT_GT(r.mean_last, r.mean_first);
  EXPECT_GT(r.max_dev_last, 2.0 * r.max_dev_first);
  EXPECT_GT(r.drift, 0.0);
}

}  // namespace
}  // namespace gencoord::testing
