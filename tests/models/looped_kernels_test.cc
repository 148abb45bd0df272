// SPDX-License-Identifier: BSD-3-Clause
// A large tree's looped kernels (python/gencoord/derive/looped.py) compute what the unrolled ones
// compute.
//
// The build generates the 5-link chain (a tree of particles) and the 7-joint arm of
// models/iiwa14.urdf (a tree of bodies) a second time with --loop-min-nq 1, so their Mt,
// J and residual Jacobians are loops over the O(nq) products, whatever their size. Each
// looped kernel equals the unrolled one (composite bodies; the arm's residual Jacobians in closed
// form, tree_derivatives.py, against forward mode through Newton-Euler here) to 1e-12
// relative at random states, and each product equals the unrolled matrix times the vector.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Core>

#include "generated/chain_looped_5.hpp"
#include "generated/iiwa14.hpp"
#include "generated/iiwa14_looped.hpp"
#include "generated/n_link_chain_5.hpp"

namespace gencoord::testing {
namespace {

constexpr double kRelative = 1e-12;

template <class A, class B>
void expect_close(const std::string& what, const A& unrolled, const B& looped) {
  ASSERT_EQ(unrolled.rows(), looped.rows()) << what;
  ASSERT_EQ(unrolled.cols(), looped.cols()) << what;
  const double scale = std::max(1.0, unrolled.cwiseAbs().maxCoeff());
  for (int i = 0; i < unrolled.rows(); ++i) {
    for (int j = 0; j < unrolled.cols(); ++j) {
      EXPECT_LE(std::abs(unrolled(i, j) - looped(i, j)), kRelative * scale)
          << what << " (" << i << ", " << j << "): unrolled " << unrolled(i, j) << ", looped "
          << looped(i, j);
    }
  }
}

template <class Unrolled, class Looped>
void check_looped_kernels() {
  static_assert(Unrolled::nq == Looped::nq && Unrolled::nx == Looped::nx);
  constexpr int nq = Unrolled::nq;
  using QVec = Eigen::Matrix<double, nq, 1>;
  using QMat = Eigen::Matrix<double, nq, nq>;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uniform(-1.2, 1.2);
  const auto random = [&] {
    QVec vector;
    for (int i = 0; i < nq; ++i) vector[i] = uniform(rng);
    return vector;
  };
  const typename Unrolled::Params up;
  const typename Looped::Params lp;
  for (int state = 0; state < 20; ++state) {
    SCOPED_TRACE("state " + std::to_string(state));
    const QVec q = random(), v = random(), a = random(), direction = random();
    const double t = uniform(rng);
    const QMat mass = Unrolled::mass_matrix(q, t, up);
    expect_close("mass_matrix", mass, Looped::mass_matrix(q, t, lp));
    expect_close("mass_matrix_product", QVec(mass * a), Looped::mass_matrix_product(q, a, t, lp));
    const auto jacobian = Unrolled::jacobian(q, t, up);
    expect_close("jacobian", jacobian, Looped::jacobian(q, t, lp));
    expect_close("jacobian_product", decltype(Unrolled::positions(q, t, up))(jacobian * direction),
                 Looped::jacobian_product(q, direction, t, lp));

    QMat unrolled_mass, looped_mass;
    QVec unrolled_force, looped_force;
    Unrolled::dynamics(q, v, t, up, &unrolled_mass, &unrolled_force);
    Looped::dynamics(q, v, t, lp, &looped_mass, &looped_force);
    expect_close("dynamics (Mt)", unrolled_mass, looped_mass);
    expect_close("dynamics (f)", unrolled_force, looped_force);

    QMat unrolled_dq, unrolled_dv, looped_dq, looped_dv;
    Unrolled::residual_jacobians(q, v, a, t, up, &unrolled_dq, &unrolled_dv);
    Looped::residual_jacobians(q, v, a, t, lp, &looped_dq, &looped_dv);
    expect_close("residual_jacobians (dr/dq)", unrolled_dq, looped_dq);
    expect_close("residual_jacobians (dr/dv)", unrolled_dv, looped_dv);
    expect_close("residual_derivative_q", QVec(unrolled_dq * direction),
                 Looped::residual_derivative_q(q, v, a, direction, t, lp));
    expect_close("residual_derivative_v", QVec(unrolled_dv * direction),
                 Looped::residual_derivative_v(q, v, a, direction, t, lp));
  }
}

TEST(LoopedKernels, FiveLinkChainLoopsComputeTheUnrolledKernels) {
  check_looped_kernels<models::NLinkChain5, models::ChainLooped5>();
}

TEST(LoopedKernels, ArmLoopsComputeTheUnrolledKernels) {
  check_looped_kernels<models::Iiwa14, models::Iiwa14Looped>();
}

}  // namespace
}  // namespace gencoord::testing
