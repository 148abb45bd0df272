// SPDX-License-Identifier: BSD-3-Clause
// A model whose Mt and J pass Eigen's stack limit (oscillator_bank.py, n = 130): the generated
// types are gencoord::HeapMatrix, and the runtime integrates it explicitly and implicitly, maps
// it to maximal coordinates and checks it, against the oscillators' closed forms.
#include <cmath>
#include <type_traits>

#include <gtest/gtest.h>

#include "gencoord/gencoord.hpp"
#include "gencoord/maximal/model.hpp"
#include "gencoord/maximal/state.hpp"
#include "generated/oscillator_bank_130.hpp"

namespace gencoord {
namespace {

using M = models::OscillatorBank130;

// w_i^2 = k_i / (L m), k_i = k (1 + i / n)
double omega_squared(const M::Params& p, int i) {
  return p.k * (1.0 + static_cast<double>(i) / M::nq) / (p.L * p.m);
}

State<M> initial_state() {
  State<M> s;
  for (int i = 0; i < M::nq; ++i) s.q(i) = M::initial_q[i];
  return s;
}

TEST(HeapMatrixModel, TypesPastTheStackLimitAreOnTheHeap) {
  static_assert(std::is_same_v<QMat<M>, HeapMatrix<double, M::nq, M::nq>>);
  static_assert(std::is_same_v<XJac<M>, HeapMatrix<double, M::nx, M::nq>>);
  static_assert(std::is_same_v<QVec<M>, Eigen::Matrix<double, M::nq, 1>>);
  static_assert(assert_model_v<M>);
  const QMat<M> zero = QMat<M>::Zero();  // sized like a fixed-size matrix
  EXPECT_EQ(zero.rows(), M::nq);
  EXPECT_EQ(zero.cols(), M::nq);
  EXPECT_EQ(QMat<M>().size(), M::nq * M::nq);
}

TEST(HeapMatrixModel, KernelsAreTheOscillators) {
  const M::Params p;
  const State<M> s = initial_state();
  const QMat<M> Mt = M::mass_matrix(s.q, s.t, p);
  EXPECT_EQ((Mt - p.m * QMat<M>::Identity()).cwiseAbs().maxCoeff(), 0.0);
  const XJac<M> J = M::jacobian(s.q, s.t, p);
  XJac<M> expected = XJac<M>::Zero();
  for (int i = 0; i < M::nq; ++i) expected(2 * i, i) = 1.0;
  EXPECT_EQ((J - expected).cwiseAbs().maxCoeff(), 0.0);
  const QVec<M> a = acceleration<M>(p, s.q, s.v, s.t);
  for (int i = 0; i < M::nq; ++i)
    EXPECT_NEAR(a(i), -omega_squared(p, i) * s.q(i), 1e-12 * omega_squared(p, i)) << i;
}

// q_i(t) = q_i(0) cos(w_i t): RK4's error at dt = 1e-3 over 1 s is about (w dt)^4 w t / 120
TEST(HeapMatrixModel, Rk4FollowsTheClosedForm) {
  const M::Params p;
  const State<M> start = initial_state();
  const State<M> end =
      simulate(ReducedSystem<M>(p), start, {Integrator::RK4, 1e-3, 1.0}, IgnoreStates{});
  for (int i = 0; i < M::nq; ++i) {
    const double w = std::sqrt(omega_squared(p, i));
    EXPECT_NEAR(end.q(i), start.q(i) * std::cos(w), 1e-8) << i;
  }
}

// one backward Euler step of a linear oscillator: q1 = (q0 + h v0) / (1 + h^2 w^2), solved by
// Newton on the generated residual Jacobians (the LLT of the heap-stored Mt)
TEST(HeapMatrixModel, BackwardEulerStepIsTheLinearSolve) {
  const M::Params p;
  State<M> s = initial_state();
  for (int i = 0; i < M::nq; ++i) s.v(i) = 0.01 * i;
  const double h = 0.05;
  const State<M> next = backward_euler_step(ReducedSystem<M>(p), s, h);
  for (int i = 0; i < M::nq; ++i) {
    const double q1 = (s.q(i) + h * s.v(i)) / (1.0 + h * h * omega_squared(p, i));
    EXPECT_NEAR(next.q(i), q1, 1e-12) << i;
    EXPECT_NEAR(next.v(i), (q1 - s.q(i)) / h, 1e-10) << i;
  }
}

// the maximal model keeps each bob on its line with the manifold spring (a projector of nx^2
// entries, heap-stored too): on the line it adds nothing to the springs' force
TEST(HeapMatrixModel, MaximalModelAgreesOnTheManifold) {
  const M::Params p;
  State<M> s = initial_state();
  s.v.setConstant(0.2);
  const MaximalState<M> xs = to_maximal<M>(p, s);
  const MaximalModel<M> model(p, 1e6);
  EXPECT_NEAR(model.energy(xs), M::energy(s.q, s.v, s.t, p), 1e-10);
  const XVec<M> f = model.force(xs.q, xs.v, xs.t);
  for (int i = 0; i < M::nq; ++i) {
    EXPECT_NEAR(f(2 * i), -p.m * omega_squared(p, i) * s.q(i), 1e-9) << i;
    EXPECT_NEAR(f(2 * i + 1), 0.0, 1e-9) << i;
  }
}

}  // namespace
}  // namespace gencoord
