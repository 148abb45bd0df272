// SPDX-License-Identifier: BSD-3-Clause
// The robots' residual Jacobians and forward-dynamics derivatives as generated: the arms' in
// closed form (python/gencoord/derive/tree_derivatives.py), the quadrupeds' by forward mode
// through Newton-Euler. At random states dr/dq and dr/dv equal central differences of the
// generated inverse_dynamics, and dynamics_derivatives' a, da/dq and da/dv equal central
// differences of the acceleration, each to 1e-7 of the largest entry (the differences' own
// error is near 1e-10 there), and its Mt^-1 equals Eigen's Cholesky solve to 1e-12.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "gencoord/gencoord.hpp"
#include "gencoord/model/dynamics_derivatives.hpp"
#include "generated/floating_quadruped.hpp"
#include "generated/iiwa14.hpp"
#include "generated/quadruped.hpp"
#include "generated/ur5e.hpp"

namespace gencoord {
namespace {

constexpr double kRelative = 1e-7;
constexpr int kStates = 20;

void expect_close(const std::string& what, const Eigen::MatrixXd& actual,
                  const Eigen::MatrixXd& expected, double relative = kRelative) {
  ASSERT_EQ(actual.rows(), expected.rows()) << what;
  ASSERT_EQ(actual.cols(), expected.cols()) << what;
  const double scale = std::max(1.0, expected.cwiseAbs().maxCoeff());
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), relative * scale) << what;
}

template <class M>
State<M> random_derivative_state(std::mt19937& rng) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), rate(-2.0, 2.0);
  State<M> s;
  for (int i = 0; i < M::nq; ++i) s.q[i] = angle(rng);
  if constexpr (has_generalized_speeds_v<M>) {
    for (const int start : M::quaternion_starts) s.q.template segment<4>(start).normalize();
  }
  for (int i = 0; i < nv_of_v<M>; ++i) s.v[i] = rate(rng);
  return s;
}

template <class M>
void check_residual_jacobians(const std::string& robot) {
  const typename M::Params p;
  std::mt19937 rng(7);
  for (int k = 0; k < kStates; ++k) {
    const State<M> s = random_derivative_state<M>(rng);
    VVec<M> qdd;
    for (int i = 0; i < nv_of_v<M>; ++i) qdd[i] = std::uniform_real_distribution<>(-5, 5)(rng);
    VQMat<M> r_D_q;
    VMat<M> r_D_v;
    M::residual_jacobians(s.q, s.v, qdd, s.t, p, &r_D_q, &r_D_v);
    VQMat<M> fd_q;
    VMat<M> fd_v;
    central_difference_jacobians<M>(
        [&](const QVec<M>& q, const VVec<M>& v, double t) {
          return VVec<M>(M::inverse_dynamics(q, v, qdd, t, p));
        },
        s.q, s.v, s.t, &fd_q, &fd_v);
    expect_close(robot + " dr/dq", r_D_q, fd_q);
    expect_close(robot + " dr/dv", r_D_v, fd_v);
  }
}

template <class M>
void check_dynamics_derivatives(const std::string& robot) {
  const typename M::Params p;
  std::mt19937 rng(11);
  for (int k = 0; k < kStates; ++k) {
    const State<M> s = random_derivative_state<M>(rng);
    const auto generated = dynamics_derivatives<M>(p, s.q, s.v, s.t);
    const auto differences =
        dynamics_derivatives<M>(p, s.q, s.v, s.t, JacobianSource::FiniteDifference);
    expect_close(robot + " a", generated.a, differences.a);
    expect_close(robot + " da/dq", generated.a_D_q, differences.a_D_q);
    expect_close(robot + " da/dv", generated.a_D_v, differences.a_D_v);
    // Mt^-1 from the Cholesky factor by rows (small sizes) against Eigen's solve
    expect_close(robot + " da/dtau", generated.a_D_tau, differences.a_D_tau, 1e-12);
  }
}

TEST(RobotDerivatives, ResidualJacobiansEqualCentralDifferences) {
  check_residual_jacobians<models::Iiwa14>("iiwa14");
  check_residual_jacobians<models::Ur5e>("ur5e");
  check_residual_jacobians<models::Quadruped>("quadruped");
}

TEST(RobotDerivatives, DynamicsDerivativesEqualCentralDifferences) {
  check_dynamics_derivatives<models::Iiwa14>("iiwa14");
  check_dynamics_derivatives<models::Ur5e>("ur5e");
  check_dynamics_derivatives<models::FloatingQuadruped>("floating quadruped");
}

}  // namespace
}  // namespace gencoord
