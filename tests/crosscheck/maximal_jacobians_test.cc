// SPDX-License-Identifier: BSD-3-Clause
// The generated sparse force Jacobians d(F_ext + F_pen)/dx and /dxdot against central
// differences of external_forces + penalty_forces, at random states off the manifold (so the
// penalty springs are stretched) with penalty damping on.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "gencoord/maximal/model.hpp"
#include "gencoord/maximal/state.hpp"
#include "test_models.hpp"

namespace gencoord {
namespace {

using crosscheck_testing::random_state;
using crosscheck_testing::random_vector;

template <class M>
class MaximalJacobianTest : public ::testing::Test {};

using JacobianModels =
    ::testing::Types<models::Pendulum, models::Pendulum3d, models::DoublePendulum,
                     models::SpringPendulum, models::CartPole, models::BeadOnRotatingHoop,
                     models::NLinkChain5>;
TYPED_TEST_SUITE(MaximalJacobianTest, JacobianModels);

template <class M>
XVec<M> generated_force(const ParamsOf<M>& p, const XVec<M>& x, const XVec<M>& xdot, double t,
                        double kappa, double damping) {
  using Max = MaximalOf<M>;
  return Max::external_forces(x, xdot, t, p) + Max::penalty_forces(x, xdot, t, kappa, damping, p);
}

TYPED_TEST(MaximalJacobianTest, MatchesCentralDifferences) {
  using M = TypeParam;
  using Max = MaximalOf<M>;
  const ParamsOf<M> p;
  const double kappa = 1e3, damping = 0.7, h = 1e-6;
  std::mt19937 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const MaximalState<M> s0 = to_maximal<M>(p, random_state<M>(rng));
    const XVec<M> x = s0.q + 0.05 * random_vector<XVec<M>>(rng);
    const XVec<M> xdot = s0.v + 0.5 * random_vector<XVec<M>>(rng);
    const double t = s0.t;
    // dense from the sparse nonzeros
    Eigen::Matrix<double, M::nx, M::nx> Kx = Eigen::Matrix<double, M::nx, M::nx>::Zero(),
                                        Kv = Eigen::Matrix<double, M::nx, M::nx>::Zero();
    const auto vx = Max::force_jacobian_x(x, xdot, t, kappa, damping, p);
    const auto vv = Max::force_jacobian_xdot(x, xdot, t, kappa, damping, p);
    for (int k = 0; k < Max::jacobian_x_nonzeros; ++k)
      Kx(Max::jacobian_x_rows[k], Max::jacobian_x_cols[k]) += vx[k];
    for (int k = 0; k < Max::jacobian_xdot_nonzeros; ++k)
      Kv(Max::jacobian_xdot_rows[k], Max::jacobian_xdot_cols[k]) += vv[k];
    const double scale = 1.0 + std::max(Kx.cwiseAbs().maxCoeff(), Kv.cwiseAbs().maxCoeff());
    for (int c = 0; c < M::nx; ++c) {
      XVec<M> e = XVec<M>::Zero();
      e[c] = h;
      const XVec<M> dx = (generated_force<M>(p, x + e, xdot, t, kappa, damping) -
                          generated_force<M>(p, x - e, xdot, t, kappa, damping)) /
                         (2 * h);
      const XVec<M> dv = (generated_force<M>(p, x, xdot + e, t, kappa, damping) -
                          generated_force<M>(p, x, xdot - e, t, kappa, damping)) /
                         (2 * h);
      for (int r = 0; r < M::nx; ++r) {
        EXPECT_NEAR(Kx(r, c), dx[r], 1e-6 * scale)
            << M::name << " dF/dx mismatch at (" << r << ", " << c << "), trial " << trial;
        EXPECT_NEAR(Kv(r, c), dv[r], 1e-6 * scale)
            << M::name << " dF/dxdot mismatch at (" << r << ", " << c << "), trial " << trial;
      }
    }
  }
}

// the runtime's assembled Jacobian (triplets, duplicates summed) equals the generated one
TYPED_TEST(MaximalJacobianTest, TripletsAssembleTheGeneratedJacobian) {
  using M = TypeParam;
  const ParamsOf<M> p;
  std::mt19937 rng(5);
  const MaximalState<M> s = to_maximal<M>(p, random_state<M>(rng));
  const MaximalModel<M> model(p, 1e4, 0.3);
  const Eigen::MatrixXd K = model.force_jacobian_x_dense(s.q, s.v, s.t);
  const double h = 1e-6;
  for (int c = 0; c < M::nx; ++c) {
    XVec<M> e = XVec<M>::Zero();
    e[c] = h;
    const XVec<M> d = (generated_force<M>(p, s.q + e, s.v, s.t, 1e4, 0.3) -
                       generated_force<M>(p, s.q - e, s.v, s.t, 1e4, 0.3)) /
                      (2 * h);
    for (int r = 0; r < M::nx; ++r)
      EXPECT_NEAR(K(r, c), d[r], 1e-5 * (1.0 + K.cwiseAbs().maxCoeff()))
          << M::name << " at (" << r << ", " << c << ")";
  }
}

}  // namespace
}  // namespace gencoord
