// SPDX-License-Identifier: BSD-3-Clause
// GCC 12 warns (-Wmaybe-uninitialized, a false positive) inside Eigen's triangular
// matrix-vector product, which the eigenvalue and SVD checks below instantiate; the warning
// is placed at Eigen's lines, so it is silenced only while Eigen's headers are read.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <Eigen/Dense>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include "gencoord/control/lqr.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace gencoord {
namespace {

using Eigen::MatrixXd;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// ||A^T X + X A - X B R^-1 B^T X + Q|| over the size of its terms.
double relative_residual(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q, const MatrixXd& R,
                         const MatrixXd& X) {
  const MatrixXd G = B * R.llt().solve(B.transpose());
  const MatrixXd AtX = A.transpose() * X;
  const MatrixXd XGX = X * G * X;
  const double residual = (AtX + AtX.transpose() - XGX + Q).norm();
  return residual == 0.0 ? 0.0 : residual / (Q.norm() + 2.0 * AtX.norm() + XGX.norm());
}

double spectral_abscissa(const MatrixXd& M) {
  return Eigen::EigenSolver<MatrixXd>(M, false).eigenvalues().real().maxCoeff();
}

// Everything a stabilizing solution has to satisfy, and K = R^-1 B^T X from lqr_gain.
void expect_stabilizing_solution(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q,
                                 const MatrixXd& R) {
  const MatrixXd X = solve_continuous_are(A, B, Q, R);
  ASSERT_EQ(X.rows(), A.rows());
  ASSERT_EQ(X.cols(), A.rows());
  EXPECT_LT(relative_residual(A, B, Q, R, X), 1e-9);
  EXPECT_EQ((X - X.transpose()).cwiseAbs().maxCoeff(), 0.0);
  const double lowest = Eigen::SelfAdjointEigenSolver<MatrixXd>(X).eigenvalues().minCoeff();
  EXPECT_GE(lowest, -1e-12 * X.norm());
  const MatrixXd K = lqr_gain(A, B, Q, R);
  ASSERT_EQ(K.rows(), B.cols());
  ASSERT_EQ(K.cols(), A.rows());
  EXPECT_LE((K - R.llt().solve(B.transpose() * X)).norm(), 1e-12 * K.norm());
  EXPECT_LT(spectral_abscissa(A - B * K), 0.0);
}

// Stabilizing root of 2 a x - b^2 x^2 / r + q = 0, x = r (a + sqrt(a^2 + b^2 q / r)) / b^2,
// written for a <= 0 as q / (sqrt(...) - a) to avoid cancellation.
double scalar_care(double a, double b, double q, double r) {
  const double root = std::sqrt(a * a + b * b * q / r);
  return a > 0.0 ? r * (a + root) / (b * b) : q / (root - a);
}

MatrixXd scalar(double v) { return MatrixXd::Constant(1, 1, v); }

TEST(SolveContinuousAre, ScalarMatchesClosedForm) {
  struct Case {
    double a, b, q, r;
  };
  const Case cases[] = {
      {1.0, 1.0, 1.0, 1.0}, {-2.0, 0.5, 3.0, 0.7},  {3.0, 2.0, 0.5, 4.0},
      {0.0, 1.0, 1.0, 1.0}, {5.0, -3.0, 2.0, 0.01}, {-100.0, 1.0, 1.0, 1.0},
      {2.0, 1.0, 0.0, 1.0}, {-1.0, 1.0, 0.0, 1.0},  {40.0, 0.01, 1e4, 1e-3},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE("a = " + std::to_string(c.a) + ", b = " + std::to_string(c.b) +
                 ", q = " + std::to_string(c.q) + ", r = " + std::to_string(c.r));
    const double expected = scalar_care(c.a, c.b, c.q, c.r);
    const MatrixXd X = solve_continuous_are(scalar(c.a), scalar(c.b), scalar(c.q), scalar(c.r));
    EXPECT_NEAR(X(0, 0), expected, 1e-12 * std::abs(expected) + 1e-300);
    const MatrixXd K = lqr_gain(scalar(c.a), scalar(c.b), scalar(c.q), scalar(c.r));
    EXPECT_NEAR(K(0, 0), c.b * expected / c.r, 1e-12 * std::abs(c.b * expected / c.r) + 1e-300);
    EXPECT_LT(c.a - c.b * K(0, 0), 0.0);
  }
}

TEST(SolveContinuousAre, DoubleIntegratorMatchesClosedForm) {
  MatrixXd A(2, 2), B(2, 1);
  A << 0, 1, 0, 0;
  B << 0, 1;
  const MatrixXd X = solve_continuous_are(A, B, MatrixXd::Identity(2, 2), scalar(1.0));
  MatrixXd expected(2, 2);
  expected << std::sqrt(3.0), 1, 1, std::sqrt(3.0);
  EXPECT_LE((X - expected).cwiseAbs().maxCoeff(), 1e-13);
  const MatrixXd K = lqr_gain(A, B, MatrixXd::Identity(2, 2), scalar(1.0));
  EXPECT_NEAR(K(0, 0), 1.0, 1e-13);
  EXPECT_NEAR(K(0, 1), std::sqrt(3.0), 1e-13);
}

// Point masses on massless rods, hinged in a chain on a cart that the input pushes:
// state (x, theta_1.., xdot, thetadot_1..), angles from the upright, linearized there.
struct Linearization {
  MatrixXd A, B;
};

Linearization cart_pendulums(double cart, const Eigen::VectorXd& masses,
                             const Eigen::VectorXd& lengths) {
  const double g = 9.81;
  const Eigen::Index links = masses.size(), dofs = links + 1;
  // outboard[i]: the mass at and beyond joint i, which rod i carries
  Eigen::VectorXd outboard(links);
  for (Eigen::Index i = links; i-- > 0;)
    outboard[i] = masses[i] + (i + 1 < links ? outboard[i + 1] : 0.0);
  MatrixXd mass = MatrixXd::Zero(dofs, dofs), stiffness = MatrixXd::Zero(dofs, dofs);
  mass(0, 0) = cart + masses.sum();
  for (Eigen::Index i = 0; i < links; ++i) {
    mass(0, i + 1) = mass(i + 1, 0) = outboard[i] * lengths[i];
    for (Eigen::Index j = 0; j < links; ++j)
      mass(i + 1, j + 1) = outboard[std::max(i, j)] * lengths[i] * lengths[j];
    stiffness(i + 1, i + 1) = g * outboard[i] * lengths[i];  // gravity tips it over
  }
  const MatrixXd inverse_mass = mass.inverse();
  Linearization lin{MatrixXd::Zero(2 * dofs, 2 * dofs), MatrixXd::Zero(2 * dofs, 1)};
  lin.A.topRightCorner(dofs, dofs).setIdentity();
  lin.A.bottomLeftCorner(dofs, dofs) = inverse_mass * stiffness;
  lin.B.bottomRows(dofs) = inverse_mass.col(0);
  return lin;
}

TEST(SolveContinuousAre, CartPoleUpright) {
  const Linearization lin =
      cart_pendulums(1.5, Eigen::VectorXd::Constant(1, 0.2), Eigen::VectorXd::Constant(1, 0.8));
  ASSERT_GT(spectral_abscissa(lin.A), 3.0);  // the pole falls
  const Eigen::Vector4d weights(1.0, 20.0, 0.1, 0.1);
  expect_stabilizing_solution(lin.A, lin.B, weights.asDiagonal().toDenseMatrix(), scalar(0.01));
  // position only: the pole is observable through the cart's motion
  MatrixXd Q = MatrixXd::Zero(4, 4);
  Q(0, 0) = 1.0;
  expect_stabilizing_solution(lin.A, lin.B, Q, scalar(1.0));
}

TEST(SolveContinuousAre, CartDoublePendulumUpright) {
  const Linearization lin =
      cart_pendulums(1.0, Eigen::Vector2d(0.5, 0.3), Eigen::Vector2d(0.6, 0.4));
  ASSERT_GT(spectral_abscissa(lin.A), 5.0);
  expect_stabilizing_solution(lin.A, lin.B, MatrixXd::Identity(6, 6), scalar(0.1));
  MatrixXd Q = MatrixXd::Identity(6, 6) * 1e-3;
  Q.topLeftCorner(3, 3) *= 1e5;  // heavy angle weights, cheap rates
  expect_stabilizing_solution(lin.A, lin.B, Q, scalar(1e-2));
}

// Uniform in [-1, 1) from the generator's raw output, the same on every standard library.
double uniform(std::mt19937& generator) {
  return static_cast<double>(generator()) / 4294967296.0 * 2.0 - 1.0;
}

MatrixXd random_matrix(std::mt19937& generator, Eigen::Index rows, Eigen::Index cols) {
  return MatrixXd::NullaryExpr(rows, cols, [&] { return uniform(generator); });
}

TEST(SolveContinuousAre, RandomSixStatesTwoInputs) {
  std::mt19937 generator(20240611);
  int unstable_systems = 0;
  for (int trial = 0; trial < 10; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const MatrixXd A = 2.0 * random_matrix(generator, 6, 6);
    const MatrixXd B = random_matrix(generator, 6, 2);
    // Q of rank 3 in odd trials: positive semidefinite, not definite
    const MatrixXd C = random_matrix(generator, trial % 2 ? 3 : 6, 6);
    const MatrixXd D = random_matrix(generator, 2, 2);
    const MatrixXd Q = C.transpose() * C;
    const MatrixXd R = D.transpose() * D + 0.1 * MatrixXd::Identity(2, 2);
    // controllable, hence stabilizable: [B, AB, .., A^5 B] has full rank
    MatrixXd controllability(6, 12);
    controllability.leftCols(2) = B;
    for (int k = 1; k < 6; ++k)
      controllability.middleCols(2 * k, 2) = A * controllability.middleCols(2 * k - 2, 2);
    const Eigen::VectorXd sigma = Eigen::JacobiSVD<MatrixXd>(controllability).singularValues();
    ASSERT_GT(sigma(5), 1e-6 * sigma(0));
    if (spectral_abscissa(A) > 0.0) ++unstable_systems;
    expect_stabilizing_solution(A, B, Q, R);
  }
  EXPECT_GE(unstable_systems, 5);  // the draw exercises unstable A
}

// The cart-pole linearization with cart 1 kg, pole 0.1 kg at 0.5 m, g = 9.81 m/s^2.
TEST(SolveContinuousAre, CartPoleMatchesScipy) {
  MatrixXd A(4, 4), B(4, 1), Q(4, 4);
  A << 0, 0, 1, 0,      //
      0, 0, 0, 1,       //
      0, -0.981, 0, 0,  //
      0, 21.582, 0, 0;
  B << 0, 0, 1, -2;
  Q = Eigen::Vector4d(10, 100, 1, 1).asDiagonal();
  // SciPy 1.10.1 (scipy.linalg.solve_continuous_are), one line wrapped here:
  //   /usr/bin/python3 -c "import numpy as n,scipy.linalg as s;A=n.array([[0,0,1,0],[0,0,0,1],
  //   [0,-.981,0,0],[0,21.582,0,0]]);B=n.array([[0],[0],[1],[-2]]);print(*('%.17g'%v for v in
  //   s.solve_continuous_are(A,B,n.diag([10,100,1,1]),n.array([[.1]])).flat),sep=', ')"
  MatrixXd reference(4, 4);
  reference << 11.623369084441991, 14.736586709880047, 6.2551354436580962, 3.6275677218290476,
      14.736586709880047, 56.432799733404558, 13.501310915552825, 10.358349392890705,
      6.2551354436580962, 13.501310915552825, 5.768374313371198, 3.4653556109076984,
      3.6275677218290476, 10.358349392890705, 3.4653556109076984, 2.4695071409478531;
  const MatrixXd X = solve_continuous_are(A, B, Q, scalar(0.1));
  EXPECT_LE((X - reference).norm(), 1e-8 * reference.norm());
  EXPECT_LE((X - reference).cwiseAbs().maxCoeff(), 1e-8 * reference.cwiseAbs().maxCoeff());
}

// The message of the std::invalid_argument that `call` throws ("" if none).
std::string invalid_argument_message(const std::function<void()>& call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SolveContinuousAre, BadArgumentsThrowInvalidArgument) {
  const MatrixXd A = MatrixXd::Identity(2, 2), B = MatrixXd::Ones(2, 1);
  const MatrixXd Q = MatrixXd::Identity(2, 2), R = scalar(1.0);
  const auto care = [](const MatrixXd& a, const MatrixXd& b, const MatrixXd& q, const MatrixXd& r) {
    return invalid_argument_message([&] { solve_continuous_are(a, b, q, r); });
  };
  EXPECT_THAT(care(MatrixXd::Ones(2, 3), B, Q, R),
              StartsWith("gencoord: solve_continuous_are: A must be square"));
  EXPECT_THAT(care(MatrixXd(0, 0), MatrixXd(0, 1), MatrixXd(0, 0), R),
              HasSubstr("A must be square, n x n with n >= 1, got 0 x 0"));
  EXPECT_THAT(care(A, MatrixXd::Ones(3, 1), Q, R), HasSubstr("B must be 2 x m"));
  EXPECT_THAT(care(A, MatrixXd::Ones(3, 1), Q, R), HasSubstr("got 3 x 1"));
  EXPECT_THAT(care(A, MatrixXd(2, 0), Q, MatrixXd(0, 0)), HasSubstr("B must be 2 x m"));
  EXPECT_THAT(care(A, B, MatrixXd::Identity(3, 3), R), HasSubstr("Q must be 2 x 2"));
  EXPECT_THAT(care(A, B, MatrixXd::Identity(2, 1), R), HasSubstr("got 2 x 1"));
  EXPECT_THAT(care(A, B, Q, MatrixXd::Identity(2, 2)), HasSubstr("R must be 1 x 1"));
  EXPECT_THAT(care(A, MatrixXd::Ones(2, 2), Q, R), HasSubstr("R must be 2 x 2"));
  EXPECT_THAT(care(A, B, Q, scalar(0.0)), HasSubstr("R must be positive definite"));
  EXPECT_THAT(care(A, B, Q, scalar(-1.0)), HasSubstr("R must be positive definite"));
  MatrixXd skew = Q;
  skew(0, 1) = 0.5;
  EXPECT_THAT(care(A, B, skew, R), HasSubstr("Q must be symmetric"));
  MatrixXd not_finite = A;
  not_finite(1, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(care(not_finite, B, Q, R), HasSubstr("A has a non-finite entry"));
  EXPECT_THAT(invalid_argument_message([&] { lqr_gain(A, MatrixXd::Ones(3, 1), Q, R); }),
              StartsWith("gencoord: lqr_gain: B must be 2 x m"));
}

// The message of the std::runtime_error that solve_continuous_are throws ("" if none).
std::string runtime_error_message(const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q,
                                  const MatrixXd& R) {
  try {
    solve_continuous_are(A, B, Q, R);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(SolveContinuousAre, NoStabilizingSolutionThrowsRuntimeError) {
  const auto no_solution = StartsWith("gencoord: solve_continuous_are: no stabilizing solution");
  // an unstable mode the input does not reach
  EXPECT_THAT(runtime_error_message(scalar(1.0), scalar(0.0), scalar(1.0), scalar(1.0)),
              no_solution);
  MatrixXd A(2, 2), B(2, 1);
  A << 1, 0, 0, -1;
  B << 0, 1;
  EXPECT_THAT(runtime_error_message(A, B, MatrixXd::Identity(2, 2), scalar(1.0)), no_solution);
  // a mode on the imaginary axis that Q does not see: no feedback is optimal, none stabilizes
  A << 0, 1.3, -1.3, 0;
  EXPECT_THAT(runtime_error_message(A, B, MatrixXd::Zero(2, 2), scalar(1.0)), no_solution);
  EXPECT_THAT(runtime_error_message(scalar(0.0), scalar(1.0), scalar(0.0), scalar(1.0)),
              no_solution);
  // the same through lqr_gain
  EXPECT_THROW(lqr_gain(scalar(1.0), scalar(0.0), scalar(1.0), scalar(1.0)), std::runtime_error);
}

}  // namespace
}  // namespace gencoord
