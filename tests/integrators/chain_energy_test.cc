// SPDX-License-Identifier: BSD-3-Clause
// Energy conservation of RK4 on the generated 5-link chain released from horizontal, 10 s:
// the chain's counterpart of the double-pendulum test in tests/models/closed_forms_test.cc
// (|dE| / (E0 - E_rest) < 1e-8). The chain whips faster than the double pendulum (angular
// velocities up to about 18 rad/s), so it needs a smaller step: measured 1.6e-8 at dt = 1e-3,
// 1.1e-9 at 5e-4 (the step used: a 9x margin), 6.9e-11 at 2.5e-4.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/n_link_chain_5.hpp"

namespace gencoord::testing {
namespace {

using models::NLinkChain5;

// max over the run of |E - E0| / (E0 - E_rest), and the largest |v| seen
struct ChainRun {
  double relative_drift = 0;
  double max_speed = 0;
};

ChainRun run_chain(double dt) {
  const NLinkChain5::Params p;
  State<NLinkChain5> s;
  s.q.setConstant(M_PI / 2);  // every link horizontal, at rest
  const QVec<NLinkChain5> zero = QVec<NLinkChain5>::Zero();
  const double e0 = NLinkChain5::energy(s.q, s.v, s.t, p);
  const double e_rest = NLinkChain5::energy(zero, zero, 0.0, p);
  double worst = 0.0;
  ChainRun r;
  simulate(ReducedSystem<NLinkChain5>(p), s, {Integrator::RK4, dt, 10.0},
           [&](const State<NLinkChain5>& x) {
             worst = std::max(worst, std::abs(NLinkChain5::energy(x.q, x.v, x.t, p) - e0));
             r.max_speed = std::max(r.max_speed, x.v.lpNorm<Eigen::Infinity>());
           });
  r.relative_drift = worst / (e0 - e_rest);
  std::printf(
      "[ energy   ] n_link_chain_5 from horizontal, RK4, dt %g, 10 s: E0 - E_rest %.4f, "
      "max|dE| / (E0 - E_rest) %.3e, max |v|_inf %.1f rad/s\n",
      dt, e0 - e_rest, r.relative_drift, r.max_speed);
  return r;
}

TEST(NLinkChain5Energy, Rk4ConservesEnergyFromHorizontal) {
  EXPECT_LT(run_chain(5e-4).relative_drift, 1e-8);
}

// the energy error is RK4's truncation error, not round-off or a kernel defect: halving the
// step divides it by about 2^4
TEST(NLinkChain5Energy, Rk4EnergyErrorShrinksAtFourthOrder) {
  const double coarse = run_chain(1e-3).relative_drift, fine = run_chain(5e-4).relative_drift;
  const double measured = std::log2(coarse / fine);
  std::printf("[ energy   ] n_link_chain_5: energy error order from dt 1e-3 -> 5e-4: %.3f\n",
              measured);
  EXPECT_NEAR(measured, 4.0, 0.3);
}

}  // namespace
}  // namespace gencoord::testing
