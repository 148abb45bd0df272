// SPDX-License-Identifier: BSD-3-Clause
// The runtime library's small dense kernels (gencoord/numerics/small_dense.hpp) against
// Eigen's, at every order they take (each count of 4-row vectors, full and partly used), and
// their failure modes.
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "gencoord/numerics/small_dense.hpp"

namespace gencoord {
namespace {

constexpr double kSmallNaN = std::numeric_limits<double>::quiet_NaN();

Eigen::MatrixXd small_positive_definite(int n) {
  const Eigen::MatrixXd R = Eigen::MatrixXd::Random(n, n);
  return R * R.transpose() + n * Eigen::MatrixXd::Identity(n, n);
}

TEST(SmallDense, TheInverseEqualsEigensAtEveryOrder) {
  for (int n = 1; n <= kSmallDenseMaxOrder; ++n) {
    const Eigen::MatrixXd A = small_positive_definite(n);
    const Eigen::MatrixXd expected = A.llt().solve(Eigen::MatrixXd::Identity(n, n));
    Eigen::MatrixXd inverse(n, n);
    ASSERT_TRUE(small_spd_inverse(n, A.data(), inverse.data())) << "n = " << n;
    EXPECT_LT((inverse - expected).norm(), 1e-13 * expected.norm()) << "n = " << n;
  }
}

TEST(SmallDense, TheInverseReadsOnlyTheLowerTriangle) {
  for (const int n : {3, 7, 18}) {
    const Eigen::MatrixXd A = small_positive_definite(n);
    Eigen::MatrixXd lower = A;
    lower.triangularView<Eigen::StrictlyUpper>().setConstant(kSmallNaN);
    Eigen::MatrixXd inverse(n, n), expected(n, n);
    ASSERT_TRUE(small_spd_inverse(n, lower.data(), inverse.data()));
    ASSERT_TRUE(small_spd_inverse(n, A.data(), expected.data()));
    EXPECT_EQ(inverse, expected) << "n = " << n;
  }
}

TEST(SmallDense, AnIndefiniteOrNaNMatrixIsRefused) {
  Eigen::Matrix2d indefinite;
  indefinite << 1, 2, 2, 1;  // eigenvalues 3 and -1
  Eigen::Matrix2d inverse;
  EXPECT_FALSE(small_spd_inverse(2, indefinite.data(), inverse.data()));
  // a NaN anywhere in the lower triangle reaches a later pivot
  const int n = 9;
  const Eigen::MatrixXd A = small_positive_definite(n);
  Eigen::MatrixXd out(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = j; i < n; ++i) {
      Eigen::MatrixXd poisoned = A;
      poisoned(i, j) = kSmallNaN;
      EXPECT_FALSE(small_spd_inverse(n, poisoned.data(), out.data())) << i << ", " << j;
    }
}

TEST(SmallDense, TheProductEqualsEigensAndWritesOnlyItsColumns) {
  for (int n = 1; n <= kSmallDenseMaxOrder; ++n)
    for (const int m : {0, 1, 3, 4, 5, 9, 2 * n}) {
      const Eigen::MatrixXd S = Eigen::MatrixXd::Random(n, n);
      const Eigen::MatrixXd B = Eigen::MatrixXd::Random(n, m);
      const Eigen::MatrixXd expected = -2.5 * S * B;
      // C with one guard entry after it: nothing past n x m is written
      std::vector<double> C(static_cast<std::size_t>(n) * m + 1, 7.0);
      small_product(n, m, S.data(), B.data(), -2.5, C.data());
      const Eigen::Map<const Eigen::MatrixXd> product(C.data(), n, m);
      EXPECT_LT((product - expected).norm(), 1e-14 * (1.0 + expected.norm()))
          << "n = " << n << ", m = " << m;
      EXPECT_EQ(C.back(), 7.0) << "n = " << n << ", m = " << m;
    }
}

TEST(SmallDense, OrdersOutsideTheRangeAreRefused) {
  std::vector<double> data(25 * 25, 1.0), out(25 * 25);
  EXPECT_THROW(small_spd_inverse(0, data.data(), out.data()), std::invalid_argument);
  EXPECT_THROW(small_spd_inverse(25, data.data(), out.data()), std::invalid_argument);
  EXPECT_THROW(small_product(25, 1, data.data(), data.data(), 1.0, out.data()),
               std::invalid_argument);
}

}  // namespace
}  // namespace gencoord
