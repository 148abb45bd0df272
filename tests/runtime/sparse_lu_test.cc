// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/numerics/sparse_lu.hpp"

#include <utility>
#include <vector>

#include <gtest/gtest.h>

namespace gencoord {
namespace {

Eigen::SparseMatrix<double> tridiagonal(int n, double diagonal) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, diagonal);
    if (i > 0) entries.emplace_back(i, i - 1, -1.0);
    if (i + 1 < n) entries.emplace_back(i, i + 1, -1.0);
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// Matrices of one pattern with other values, through the kept ordering, through copies
// (which start anew) and moves.
TEST(SparseLuSolver, SolvesMatricesOfOnePatternThroughCopiesAndMoves) {
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(6, 1.0, 2.0);
  SparseLuSolver solver;
  for (double diagonal : {3.0, 4.0, 10.0}) {
    const Eigen::SparseMatrix<double> A = tridiagonal(6, diagonal);
    Eigen::VectorXd x(6);
    ASSERT_TRUE(solver.solve(A, b, x));
    EXPECT_LT((A * x - b).norm(), 1e-13) << diagonal;
    SparseLuSolver copy(solver);
    Eigen::Matrix<double, 6, 1> fixed;  // a fixed-size vector, as the maximal model's
    ASSERT_TRUE(copy.solve(A, b, fixed));
    EXPECT_LT((fixed - x).norm(), 1e-14);
    SparseLuSolver moved(std::move(copy));
    ASSERT_TRUE(moved.solve(A, b, fixed));
    EXPECT_LT((fixed - x).norm(), 1e-14);
    copy = solver;  // a moved-from solver assigned to, and used again
    ASSERT_TRUE(copy.solve(A, b, fixed));
  }
}

TEST(SparseLuSolver, ASingularMatrixLeavesTheSolutionUntouched) {
  SparseLuSolver solver;
  Eigen::SparseMatrix<double> A = tridiagonal(4, 2.0);
  A.coeffRef(0, 0) = 1.0;  // rows sum to zero: (1, 1, 1, 1) is in its kernel
  A.coeffRef(3, 3) = 1.0;
  Eigen::VectorXd x = Eigen::VectorXd::Constant(4, 7.0);
  EXPECT_FALSE(solver.solve(A, Eigen::VectorXd::Ones(4), x));
  EXPECT_EQ(x, Eigen::VectorXd::Constant(4, 7.0));
}

}  // namespace
}  // namespace gencoord
