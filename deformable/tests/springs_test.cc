// SPDX-License-Identifier: BSD-3-Clause
// Spring force and Jacobian: the 1D rod formula, and the analytic Jacobians against
// central finite differences.
#include "gencoord/deformable/springs.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <random>

namespace gencoord::deformable {
namespace {

TEST(SpringsTest, OneDimensionalForceIsTheLinearStrainSpring) {
  SpringParams p{0.3, 2.0, 0.5};  // L, k, d
  const auto s =
      spring_force<1>(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(1.45),
                      Eigen::Matrix<double, 1, 1>(0.2), Eigen::Matrix<double, 1, 1>(-0.1), p);
  // k (x_j - x_i - L) / L + d (v_j - v_i) / L = 2 * 0.15 / 0.3 + 0.5 * (-0.3) / 0.3
  EXPECT_NEAR(s.f_i(0), 1.0 - 0.5, 1e-14);
  EXPECT_NEAR(s.strain, 0.5, 1e-14);
}

TEST(SpringsTest, ForceIsAlongTheSpringWithStrainTimesStiffness) {
  SpringParams p{2.0, 10.0, 0.0};
  const Eigen::Vector2d xi(0, 0), xj(3, 4), zero(0, 0);
  const auto s = spring_force<2>(xi, xj, zero, zero, p);
  // length 5, strain (5 - 2) / 2 = 1.5, force 15 toward j
  EXPECT_NEAR(s.f_i.x(), 15.0 * 0.6, 1e-12);
  EXPECT_NEAR(s.f_i.y(), 15.0 * 0.8, 1e-12);
}

template <int Dim>
void CheckJacobianAgainstFiniteDifferences(std::uint64_t seed) {
  using Vec = Eigen::Matrix<double, Dim, 1>;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto random_vec = [&] {
    Vec v;
    for (int a = 0; a < Dim; ++a) v(a) = u(rng);
    return v;
  };
  for (int trial = 0; trial < 200; ++trial) {
    const Vec xi = random_vec(), xj = random_vec(), vi = random_vec(), vj = random_vec();
    SpringParams p{0.5 + 0.5 * (u(rng) + 1.0), 1.0 + u(rng) * 0.5, 0.3};
    const auto s = spring_force<Dim>(xi, xj, vi, vj, p);
    const auto jac = spring_jacobian<Dim>(s, p, /*definite=*/false);
    const double h = 1e-6;
    for (int c = 0; c < Dim; ++c) {
      Vec e = Vec::Zero();
      e(c) = h;
      // the damping's position derivative is neglected by design: compare with d = 0
      SpringParams elastic = p;
      elastic.damping = 0.0;
      const Vec fd_x = (spring_force<Dim>(xi, xj + e, vi, vj, elastic).f_i -
                        spring_force<Dim>(xi, xj - e, vi, vj, elastic).f_i) /
                       (2 * h);
      const Vec fd_v = (spring_force<Dim>(xi, xj, vi, vj + e, p).f_i -
                        spring_force<Dim>(xi, xj, vi, vj - e, p).f_i) /
                       (2 * h);
      for (int r = 0; r < Dim; ++r) {
        EXPECT_NEAR(jac.f_i_D_d(r, c), fd_x(r), 1e-6 * (1.0 + std::abs(fd_x(r))))
            << "d f/d x mismatch at (" << r << ", " << c << "), trial " << trial;
        EXPECT_NEAR(jac.f_i_D_dv(r, c), fd_v(r), 1e-6 * (1.0 + std::abs(fd_v(r))))
            << "d f/d v mismatch at (" << r << ", " << c << "), trial " << trial;
      }
    }
  }
}

TEST(SpringsTest, JacobianMatchesFiniteDifferences1D) {
  CheckJacobianAgainstFiniteDifferences<1>(1);
}
TEST(SpringsTest, JacobianMatchesFiniteDifferences2D) {
  CheckJacobianAgainstFiniteDifferences<2>(2);
}
TEST(SpringsTest, JacobianMatchesFiniteDifferences3D) {
  CheckJacobianAgainstFiniteDifferences<3>(3);
}

TEST(SpringsTest, DefiniteJacobianIsNegativeSemiDefiniteInCompression) {
  SpringParams p{1.0, 5.0, 0.0};
  const Eigen::Vector3d xi(0, 0, 0), xj(0.3, 0.2, 0.1), zero(0, 0, 0);
  const auto s = spring_force<3>(xi, xj, zero, zero, p);
  const auto jac = spring_jacobian<3>(s, p, /*definite=*/true);
  // f_i_D_d is the coupling block; the node's own block is -f_i_D_d, which must be <= 0
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(jac.f_i_D_d);
  EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-12);
  const auto raw = spring_jacobian<3>(s, p, /*definite=*/false);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> raw_eig(raw.f_i_D_d);
  EXPECT_LT(raw_eig.eigenvalues().minCoeff(), 0.0) << "compressed spring should be indefinite";
}

}  // namespace
}  // namespace gencoord::deformable
