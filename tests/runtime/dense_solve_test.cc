// SPDX-License-Identifier: BSD-3-Clause
// The runtime library's dense solves (gencoord/numerics/dense_solve.hpp) against Eigen's own,
// on both sides of the stack-size switch, and their failure modes.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "gencoord/numerics/dense_solve.hpp"

namespace gencoord {
namespace {

Eigen::MatrixXd positive_definite(int n) {
  const Eigen::MatrixXd R = Eigen::MatrixXd::Random(n, n);
  return R * R.transpose() + n * Eigen::MatrixXd::Identity(n, n);
}

TEST(DenseSolve, LuSolveEqualsEigensOnTheStackAndOnTheHeap) {
  for (const int n : {1, 4, 32, 33, 60}) {
    const Eigen::MatrixXd A = Eigen::MatrixXd::Random(n, n) + n * Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd b = Eigen::VectorXd::Random(n);
    Eigen::VectorXd x(n);
    EXPECT_TRUE(lu_solve(A, b, x));
    EXPECT_LT((x - A.partialPivLu().solve(b)).norm(), 1e-12 * x.norm()) << "n = " << n;
    EXPECT_LT((A * x - b).norm(), 1e-12 * b.norm() * n) << "n = " << n;
  }
}

TEST(DenseSolve, ASingularLuGivesANonFiniteSolution) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d x;
  EXPECT_TRUE(lu_solve(A, Eigen::Vector3d::Ones(), x));
  EXPECT_FALSE(x.allFinite());
}

TEST(DenseSolve, CholeskySolvesAMatrixRightHandSide) {
  for (const int n : {1, 5, 40}) {
    const Eigen::MatrixXd A = positive_definite(n);
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, 3);
    Eigen::MatrixXd factor = A;
    ASSERT_TRUE(cholesky_factor(factor));
    Eigen::MatrixXd X = B;
    cholesky_solve(factor, X);
    EXPECT_LT((X - A.llt().solve(B)).norm(), 1e-12 * X.norm()) << "n = " << n;
  }
}

TEST(DenseSolve, CholeskyRefusesAnIndefiniteMatrix) {
  Eigen::Matrix2d A;
  A << 1, 2, 2, 1;  // eigenvalues 3 and -1
  EXPECT_FALSE(cholesky_factor(A));
}

}  // namespace
}  // namespace gencoord
