// SPDX-License-Identifier: BSD-3-Clause
// The derivative path's Mt^-1 (detail::InverseMass) both ways, the small dense kernels at 6
// coordinates and Eigen's Cholesky factor at 30: dynamics_derivatives() and
// acceleration_jacobians() from the hand-written residual Jacobians against the closed forms
// and central differences, and the errors that acceleration() raises.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "gencoord/errors.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/dynamics_derivatives.hpp"
#include "hand_models.hpp"

namespace gencoord {
namespace {

using test_models::HandSpringChain;

template <class M>
class InverseMassTest : public ::testing::Test {};
using Chains = ::testing::Types<HandSpringChain<6>, HandSpringChain<30>>;
TYPED_TEST_SUITE(InverseMassTest, Chains);

static_assert(detail::InverseMass<HandSpringChain<6>>::kSmall);
static_assert(!detail::InverseMass<HandSpringChain<30>>::kSmall);

template <class M>
State<M> random_state(std::mt19937* rng) {
  std::uniform_real_distribution<double> value(-2.0, 2.0);
  State<M> s;
  for (int i = 0; i < M::nq; ++i) {
    s.q[i] = value(*rng);
    s.v[i] = value(*rng);
  }
  return s;
}

TYPED_TEST(InverseMassTest, DerivativesEqualTheClosedFormsAndCentralDifferences) {
  using M = TypeParam;
  const typename M::Params p;
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const State<M> s = random_state<M>(&rng);
    const auto Mt = M::mass_matrix(s.q, 0.0, p);
    const QMat<M> Mt_inverse = Mt.inverse();
    const auto out = dynamics_derivatives<M>(p, s.q, s.v, 0.0, JacobianSource::Generated);
    const QVec<M> a = Mt.llt().solve(M::forces(s.q, s.v, 0.0, p));
    EXPECT_LT((out.a - a).norm(), 1e-12 * a.norm());
    EXPECT_LT((out.a_D_tau - Mt_inverse).norm(), 1e-12 * Mt_inverse.norm());
    // a = Mt^-1 f: da/dq = -Mt^-1 (diag(0.2 q_i a_i) + k I), da/dv = -c Mt^-1
    QMat<M> r_D_q = p.k * QMat<M>::Identity();
    r_D_q.diagonal() += 0.2 * s.q.cwiseProduct(a);
    const QMat<M> a_D_q = -Mt_inverse * r_D_q;
    const QMat<M> a_D_v = -p.c * Mt_inverse;
    EXPECT_LT((out.a_D_q - a_D_q).norm(), 1e-12 * a_D_q.norm());
    EXPECT_LT((out.a_D_v - a_D_v).norm(), 1e-12 * a_D_v.norm());
    // the same through acceleration_jacobians(), generated and by central differences
    QMat<M> g_D_q, g_D_v, d_D_q, d_D_v;
    acceleration_jacobians<M>(p, s.q, s.v, 0.0, &g_D_q, &g_D_v, JacobianSource::Generated);
    acceleration_jacobians<M>(p, s.q, s.v, 0.0, &d_D_q, &d_D_v, JacobianSource::FiniteDifference);
    EXPECT_EQ(g_D_q, out.a_D_q);
    EXPECT_EQ(g_D_v, out.a_D_v);
    EXPECT_LT((d_D_q - a_D_q).cwiseAbs().maxCoeff(), 1e-7 * a_D_q.cwiseAbs().maxCoeff());
    EXPECT_LT((d_D_v - a_D_v).cwiseAbs().maxCoeff(), 1e-7 * a_D_v.cwiseAbs().maxCoeff());
  }
}

TYPED_TEST(InverseMassTest, AnIndefiniteMassMatrixOrNonFiniteForcesAreReported) {
  using M = TypeParam;
  std::mt19937 rng(8);
  const State<M> s = random_state<M>(&rng);
  const auto reason = [&](const typename M::Params& p) {
    try {
      dynamics_derivatives<M>(p, s.q, s.v, 0.0);
    } catch (const DynamicsError& error) {
      return error.reason();
    }
    ADD_FAILURE() << "no DynamicsError";
    return DynamicsError::Reason::kNonFiniteAcceleration;
  };
  typename M::Params indefinite;
  indefinite.coupling = 3.0;  // a 2 x 2 block 1 + 0.1 q^2 against 3 off the diagonal
  EXPECT_EQ(reason(indefinite), DynamicsError::Reason::kNotPositiveDefinite);
  typename M::Params nan_forces;
  nan_forces.f_bias = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(reason(nan_forces), DynamicsError::Reason::kNonFiniteForces);
}

}  // namespace
}  // namespace gencoord
