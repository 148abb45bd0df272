// SPDX-License-Identifier: BSD-3-Clause
// Implicit steps on generated Jacobians: da/dq, da/dv from the residual Jacobians agree with
// finite differences, and backward Euler converges in no more Newton iterations with them.
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <gtest/gtest.h>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/n_link_chain_10.hpp"

namespace gencoord {
namespace {

using models::DoublePendulum;
using models::NLinkChain10;

// the double pendulum without its generated Jacobians (a hand-written model's situation):
// the deleted declaration hides DoublePendulum::residual_jacobians
struct PendulumWithoutJacobians : DoublePendulum {
  static void residual_jacobians() = delete;
};

template <class M>
State<M> initial_state() {
  State<M> s;
  for (int i = 0; i < M::nq; ++i) {
    s.q[i] = M::initial_q[static_cast<std::size_t>(i)] + 0.1 * i;
    s.v[i] = 0.3 * std::sin(1.0 + i);
  }
  return s;
}

template <class M>
void expect_jacobians_agree(const State<M>& s) {
  const ParamsOf<M> p;
  QMat<M> gq, gv, fq, fv;
  acceleration_jacobians<M>(p, s.q, s.v, s.t, &gq, &gv, JacobianSource::Generated);
  acceleration_jacobians<M>(p, s.q, s.v, s.t, &fq, &fv, JacobianSource::FiniteDifference);
  const double scale = 1.0 + gq.cwiseAbs().maxCoeff() + gv.cwiseAbs().maxCoeff();
  for (int r = 0; r < M::nq; ++r)
    for (int c = 0; c < M::nq; ++c) {
      EXPECT_NEAR(gq(r, c), fq(r, c), 1e-7 * scale)
          << M::name << " da/dq at (" << r << ", " << c << ")";
      EXPECT_NEAR(gv(r, c), fv(r, c), 1e-7 * scale)
          << M::name << " da/dv at (" << r << ", " << c << ")";
    }
}

TEST(JacobianSource, GeneratedAccelerationJacobiansMatchFiniteDifferences) {
  expect_jacobians_agree<DoublePendulum>(initial_state<DoublePendulum>());
  expect_jacobians_agree<NLinkChain10>(initial_state<NLinkChain10>());
}

TEST(JacobianSource, AutoResolvesToGeneratedOnlyWhereTheModelEmitsThem) {
  static_assert(has_residual_jacobians_v<DoublePendulum>);
  static_assert(!has_residual_jacobians_v<PendulumWithoutJacobians>);
  EXPECT_EQ(resolve_jacobian_source<DoublePendulum>(JacobianSource::Auto),
            JacobianSource::Generated);
  EXPECT_EQ(resolve_jacobian_source<PendulumWithoutJacobians>(JacobianSource::Auto),
            JacobianSource::FiniteDifference);
  // asking for generated Jacobians a model does not have is an error, not a fallback
  NewtonOptions generated;
  generated.jacobian = JacobianSource::Generated;
  const State<PendulumWithoutJacobians> s = initial_state<PendulumWithoutJacobians>();
  EXPECT_THROW(backward_euler_step(ReducedSystem<PendulumWithoutJacobians>({}), s, 0.01, generated),
               std::invalid_argument);
  EXPECT_NO_THROW(backward_euler_step(ReducedSystem<PendulumWithoutJacobians>({}), s, 0.01));
}

// backward Euler runs with each Jacobian source; same Newton map, so the states agree
template <class M>
void compare_newton_iterations(double h, int steps) {
  const ParamsOf<M> p;
  NewtonOptions generated, fd;
  generated.jacobian = JacobianSource::Generated;
  fd.jacobian = JacobianSource::FiniteDifference;
  StepStats gen_stats, fd_stats;
  State<M> sg = initial_state<M>(), sf = sg;
  double max_diff = 0.0;
  for (int k = 0; k < steps; ++k) {
    sg = step(ReducedSystem<M>(p), Integrator::BackwardEuler, sg, h, generated, &gen_stats);
    sf = step(ReducedSystem<M>(p), Integrator::BackwardEuler, sf, h, fd, &fd_stats);
    max_diff = std::max(max_diff, (sg.q - sf.q).cwiseAbs().maxCoeff());
  }
  const double gen_mean = double(gen_stats.newton_iterations) / gen_stats.newton_solves;
  const double fd_mean = double(fd_stats.newton_iterations) / fd_stats.newton_solves;
  std::printf(
      "%s backward Euler h = %g, %d steps: Newton iterations generated %ld (mean %.2f, "
      "max %d), finite differences %ld (mean %.2f, max %d); max |q_gen - q_fd| = %.2e\n",
      M::name, h, steps, gen_stats.newton_iterations, gen_mean, gen_stats.max_newton_iterations,
      fd_stats.newton_iterations, fd_mean, fd_stats.max_newton_iterations, max_diff);
  EXPECT_LE(gen_stats.newton_iterations, fd_stats.newton_iterations) << M::name;
  EXPECT_LE(gen_stats.max_newton_iterations, fd_stats.max_newton_iterations) << M::name;
  EXPECT_LT(max_diff, 1e-8) << M::name;
}

TEST(JacobianSource, BackwardEulerNeedsNoMoreNewtonIterationsWithGeneratedJacobians) {
  compare_newton_iterations<DoublePendulum>(0.01, 300);
  compare_newton_iterations<NLinkChain10>(0.01, 100);
}

TEST(JacobianSource, ImplicitMidpointAndTrapezoidalUseTheSameJacobians) {
  // the composed steps pass the options through: both sources give the same state
  const ParamsOf<NLinkChain10> p;
  NewtonOptions generated, fd;
  generated.jacobian = JacobianSource::Generated;
  fd.jacobian = JacobianSource::FiniteDifference;
  const State<NLinkChain10> s = initial_state<NLinkChain10>();
  for (Integrator integrator : {Integrator::Trapezoidal, Integrator::ImplicitMidpoint}) {
    const State<NLinkChain10> a =
        step(ReducedSystem<NLinkChain10>(p), integrator, s, 0.02, generated);
    const State<NLinkChain10> b = step(ReducedSystem<NLinkChain10>(p), integrator, s, 0.02, fd);
    EXPECT_LT((a.q - b.q).cwiseAbs().maxCoeff(), 1e-10) << to_string(integrator);
    EXPECT_LT((a.v - b.v).cwiseAbs().maxCoeff(), 1e-8) << to_string(integrator);
  }
}

}  // namespace
}  // namespace gencoord
