// SPDX-License-Identifier: BSD-3-Clause
// rk4_transition: the state it returns is an RK4 step, and its Jacobians are the map's own
// derivatives: equal to central differences of the map at random states and inputs, and at an
// equilibrium equal to the fourth-order Taylor polynomials of the matrix exponential, which
// RK4 is on a linear system.
#include <Eigen/Dense>

#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "gencoord/control/transition.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/cart_pole.hpp"
#include "generated/double_pendulum_on_cart.hpp"
#include "random_states.hpp"

namespace {

template <class M>
Eigen::VectorXd state_of(const gencoord::State<M>& s) {
  Eigen::VectorXd x(2 * M::nq);
  x << s.q, s.v;
  return x;
}

// dF/dx and dF/du by central differences of the map's state, step 1e-5
template <class M>
void central_differences(const gencoord::ParamsOf<M>& p, const Eigen::VectorXd& x,
                         const gencoord::InputVec<M>& u, double t, double h, Eigen::MatrixXd* A,
                         Eigen::MatrixXd* B) {
  const double step = 1e-5;
  A->resize(x.size(), x.size());
  B->resize(x.size(), u.size());
  for (int j = 0; j < x.size(); ++j) {
    Eigen::VectorXd plus = x, minus = x;
    plus[j] += step;
    minus[j] -= step;
    A->col(j) = (gencoord::rk4_transition<M>(p, plus, u, t, h).x -
                 gencoord::rk4_transition<M>(p, minus, u, t, h).x) /
                (2 * step);
  }
  for (int j = 0; j < u.size(); ++j) {
    gencoord::InputVec<M> plus = u, minus = u;
    plus[j] += step;
    minus[j] -= step;
    B->col(j) = (gencoord::rk4_transition<M>(p, x, plus, t, h).x -
                 gencoord::rk4_transition<M>(p, x, minus, t, h).x) /
                (2 * step);
  }
}

template <class M>
void expect_jacobians_match_central_differences() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> force(-5.0, 5.0);
  double worst = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    const auto p = gencoord::testing::sampled_params<M>(rng);
    const gencoord::State<M> s = gencoord::testing::random_state<M>(rng);
    gencoord::InputVec<M> u;
    for (int i = 0; i < u.size(); ++i) u[i] = force(rng);
    const double h = 0.02;
    const gencoord::Transition F = gencoord::rk4_transition<M>(p, state_of(s), u, s.t, h);
    Eigen::MatrixXd A, B;
    central_differences<M>(p, state_of(s), u, s.t, h, &A, &B);
    worst = std::max(worst, (F.A - A).cwiseAbs().maxCoeff() / A.cwiseAbs().maxCoeff());
    worst = std::max(worst, (F.B - B).cwiseAbs().maxCoeff() / B.cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-8) << M::name;
}

TEST(Rk4Transition, JacobiansMatchCentralDifferencesCartPole) {
  expect_jacobians_match_central_differences<gencoord::models::CartPole>();
}

TEST(Rk4Transition, JacobiansMatchCentralDifferencesDoublePendulumOnCart) {
  expect_jacobians_match_central_differences<gencoord::models::DoublePendulumOnCart>();
}

// The state is one RK4 step of the model: simulate() with the same step and the input held
// lands on the same state.
TEST(Rk4Transition, StateIsTheRuntimesRk4Step) {
  using M = gencoord::models::DoublePendulumOnCart;
  std::mt19937 rng(3);
  const gencoord::State<M> s = gencoord::testing::random_state<M>(rng);
  M::Params p;
  p.u = 1.5;
  const double h = 0.01;
  const gencoord::State<M> end =
      gencoord::simulate(gencoord::ReducedSystem<M>(p), s, {gencoord::Integrator::RK4, h, h});
  const gencoord::Transition F =
      gencoord::rk4_transition<M>(M::Params(), state_of(s), gencoord::InputVec<M>(1.5), s.t, h);
  EXPECT_LT((F.x - state_of(end)).cwiseAbs().maxCoeff(), 1e-14);
}

// At the upright equilibrium every stage sees the same A_c and B_c, so RK4's map is
// A = I + hA_c + (hA_c)^2/2 + (hA_c)^3/6 + (hA_c)^4/24 and B = h (I + hA_c/2 + (hA_c)^2/6 +
// (hA_c)^3/24) B_c, a closed form built here from linearize() alone.
TEST(Rk4Transition, AtAnEquilibriumIsTheTaylorPolynomialOfTheExponential) {
  using M = gencoord::models::CartPole;
  const M::Params p;
  const gencoord::QVec<M> zero = gencoord::QVec<M>::Zero();
  const gencoord::LinearizedDynamics c =
      gencoord::linearize<M>(p, zero, zero, gencoord::InputVec<M>::Zero(), 0.0);
  const double h = 0.05;
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(4, 4), hA = h * c.A;
  const Eigen::MatrixXd A = I + hA + hA * hA / 2 + hA * hA * hA / 6 + hA * hA * hA * hA / 24;
  const Eigen::MatrixXd B = h * (I + hA / 2 + hA * hA / 6 + hA * hA * hA / 24) * c.B;
  const gencoord::Transition F = gencoord::rk4_transition<M>(p, Eigen::VectorXd::Zero(4),
                                                             gencoord::InputVec<M>::Zero(), 0.0, h);
  EXPECT_LT((F.A - A).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_LT((F.B - B).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT(F.x.cwiseAbs().maxCoeff(), 1e-15);
}

TEST(Rk4Transition, WrongStateSizeThrows) {
  using M = gencoord::models::CartPole;
  EXPECT_THROW(gencoord::rk4_transition<M>(M::Params(), Eigen::VectorXd::Zero(3),
                                           gencoord::InputVec<M>::Zero(), 0.0, 0.01),
               std::invalid_argument);
}

}  // namespace
