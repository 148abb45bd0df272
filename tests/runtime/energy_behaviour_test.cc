// SPDX-License-Identifier: BSD-3-Clause
// Long-run energy behaviour on the (nonlinear) pendulum, 1e5 steps of dt = 0.01:
// implicit midpoint and symplectic Euler keep the energy error bounded (no secular drift),
// backward Euler dissipates energy and forward Euler injects it.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "hand_models.hpp"

namespace gencoord {
namespace {

using test_models::HandPendulum;

constexpr long kSteps = 100000;
constexpr double kDt = 0.01;

struct EnergyRun {
  double e0 = 0;             // initial energy
  double swing = 0;          // e0 - min potential: the energy of the swing
  double max_dev_first = 0;  // max |E - e0| over the first tenth of the run
  double max_dev_last = 0;   // max |E - e0| over the last tenth
  double mean_first = 0;     // mean E over the first tenth
  double mean_last = 0;      // mean E over the last tenth
};

EnergyRun run(Integrator integrator) {
  const HandPendulum::Params p;
  State<HandPendulum> s;
  s.q[0] = 1.0;  // a large swing: the nonlinearity matters
  EnergyRun r;
  r.e0 = HandPendulum::energy(s.q, s.v, s.t, p);
  r.swing = r.e0 - (-p.m * p.g * p.l);
  long k = 0, first_count = 0, last_count = 0;
  const ReducedSystem<HandPendulum> system(p);
  simulate(system, s, {integrator, kDt, kSteps * kDt}, [&](const State<HandPendulum>& x) {
    const double e = HandPendulum::energy(x.q, x.v, x.t, p);
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
  r.mean_first /= static_cast<double>(first_count);
  r.mean_last /= static_cast<double>(last_count);
  std::cout << "[ energy   ] " << to_string(integrator) << ": E0 " << r.e0 << ", max|dE| first "
            << r.max_dev_first << ", last " << r.max_dev_last << ", mean E first " << r.mean_first
            << ", last " << r.mean_last << '\n';
  return r;
}

TEST(EnergyBehaviour, ImplicitMidpointIsBoundedWithoutDrift) {
  const EnergyRun r = run(Integrator::ImplicitMidpoint);
  EXPECT_LT(r.max_dev_first, 1e-3 * r.swing);
  EXPECT_LT(r.max_dev_last, 1.1 * r.max_dev_first);
}

TEST(EnergyBehaviour, SymplecticEulerIsBoundedWithoutDrift) {
  const EnergyRun r = run(Integrator::SymplecticEuler);
  EXPECT_LT(r.max_dev_first, 0.1 * r.swing);
  EXPECT_LT(r.max_dev_last, 1.1 * r.max_dev_first);
}

TEST(EnergyBehaviour, BackwardEulerLosesEnergy) {
  const EnergyRun r = run(Integrator::BackwardEuler);
  EXPECT_LT(r.mean_last, r.e0 - 0.5 * r.swing);
  EXPECT_LT(r.mean_last, r.mean_first);
}

TEST(EnergyBehaviour, ForwardEulerGainsEnergy) {
  const EnergyRun r = run(Integrator::ForwardEuler);
  EXPECT_GT(r.mean_last, r.e0 + r.swing);
  EXPECT_GT(r.mean_last, r.mean_first);
  EXPECT_GT(r.max_dev_last, 2.0 * r.max_dev_first);
}

}  // namespace
}  // namespace gencoord
