// SPDX-License-Identifier: BSD-3-Clause
// The stiff chain (k = 1000 N m/rad joints): RK4 is limited by the fastest joint mode,
// |h omega_max| <= 2 sqrt(2) on the imaginary axis; backward Euler is stable far beyond it.
#include <cmath>
#include <complex>
#include <cstdio>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "gencoord/errors.hpp"
#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/inverse_dynamics.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/stiff_chain_10.hpp"

namespace gencoord {
namespace {

using Chain = models::StiffChain10;

// The linearization at rest, Mt a + D v + K q = 0 with K = dr/dq and D = dr/dv at
// (q, v, a) = 0 (K: joint springs plus gravity, the stiffness Hessian; D: joint dampers),
// from the generated residual Jacobians.
struct RestLinearization {
  QMat<Chain> Mt, K, D;
};

RestLinearization linearize_at_rest(const ParamsOf<Chain>& p) {
  const QVec<Chain> zero = QVec<Chain>::Zero();
  RestLinearization lin;
  residual_jacobians<Chain>(p, zero, zero, zero, 0.0, &lin.K, &lin.D);
  lin.Mt = Chain::mass_matrix(zero, 0.0, p);
  return lin;
}

// highest undamped angular frequency: omega_max^2 = largest eigenvalue of Mt^-1 K
double omega_max(const RestLinearization& lin) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<QMat<Chain>> eig(0.5 * (lin.K + lin.K.transpose()),
                                                                  lin.Mt);
  return std::sqrt(eig.eigenvalues().maxCoeff());
}

// largest h with |R(h lambda)| <= 1 for every eigenvalue lambda of the damped linearization
// y' = [[0, I], [-Mt^-1 K, -Mt^-1 D]] y, R(z) = 1 + z + z^2/2 + z^3/6 + z^4/24 (RK4)
double rk4_limit_damped(const RestLinearization& lin) {
  constexpr int n = Chain::nq;
  Eigen::Matrix<double, 2 * n, 2 * n> A = Eigen::Matrix<double, 2 * n, 2 * n>::Zero();
  A.topRightCorner<n, n>().setIdentity();
  A.bottomLeftCorner<n, n>() = -lin.Mt.ldlt().solve(lin.K);
  A.bottomRightCorner<n, n>() = -lin.Mt.ldlt().solve(lin.D);
  const Eigen::EigenSolver<Eigen::Matrix<double, 2 * n, 2 * n>> eig(A);
  auto stable = [&](double h) {
    for (int i = 0; i < 2 * n; ++i) {
      const std::complex<double> z = h * eig.eigenvalues()[i];
      if (std::abs(1.0 + z + z * z / 2.0 + z * z * z / 6.0 + z * z * z * z / 24.0) > 1.0 + 1e-12)
        return false;
    }
    return true;
  };
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 60; ++it) (stable(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

// a small displacement exciting every mode, alternating +-amplitude
State<Chain> perturbed_rest(double amplitude) {
  State<Chain> s;
  for (int i = 0; i < Chain::nq; ++i) s.q[i] = (i % 2 ? -amplitude : amplitude);
  return s;
}

// whether a run from perturbed_rest(amplitude) stays below `bound` (max |q|), finite, with
// the dynamics never failing; *max_q is the largest |q| seen
bool stays_bounded(Integrator integrator, double h, double duration, double amplitude, double bound,
                   double* max_q, StepStats* stats = nullptr) {
  const ParamsOf<Chain> p;
  State<Chain> s = perturbed_rest(amplitude);
  *max_q = amplitude;
  const long n = std::lround(duration / h);
  try {
    for (long k = 0; k < n; ++k) {
      s = step(ReducedSystem<Chain>(p), integrator, s, h, {}, stats);
      const double m = s.q.cwiseAbs().maxCoeff();
      if (!std::isfinite(m)) {
        *max_q = INFINITY;
        return false;
      }
      *max_q = std::max(*max_q, m);
      if (m > bound) return false;
    }
  } catch (const DynamicsError&) {
    *max_q = INFINITY;
    return false;
  }
  return true;
}

TEST(StiffChain, Rk4DivergesAboveItsStabilityLimitAndBackwardEulerIsStableAt100Times) {
  const ParamsOf<Chain> p;
  const RestLinearization lin = linearize_at_rest(p);
  const double w = omega_max(lin);
  const double h_undamped = 2.0 * std::sqrt(2.0) / w;  // RK4's stability interval on i R
  const double h_limit = rk4_limit_damped(lin);
  // the empirical limit of the linearized regime: from a 1e-6 rad perturbation, the largest
  // h (bisection) for which nothing grows 100-fold in 5 s. (From larger amplitudes a
  // slightly unstable fast mode saturates: its frequency drops as it grows, so the growth
  // criterion would blur the limit by a few per cent.)
  double lo = 0.5 * h_limit, hi = 2.0 * h_limit, max_q = 0.0;
  for (int it = 0; it < 12; ++it) {
    const double mid = 0.5 * (lo + hi);
    (stays_bounded(Integrator::RK4, mid, 5.0, 1e-6, 1e-4, &max_q) ? lo : hi) = mid;
  }
  std::printf(
      "stiff_chain_10 (k = %g N m/rad, c = %g N m s/rad): omega_max = %.1f rad/s; RK4 "
      "limit: undamped 2 sqrt(2) / omega_max = %.4e s, damped linearization %.4e s, "
      "empirical (1e-6 rad perturbation not growing 100x in 5 s) %.4e s\n",
      p.k, p.c, w, h_undamped, h_limit, lo);
  EXPECT_NEAR(lo / h_limit, 1.0, 0.01);

  // RK4 from a 0.01 rad perturbation: bounded below the limit, blows up above it
  double below = 0.0, above = 0.0;
  EXPECT_TRUE(stays_bounded(Integrator::RK4, 0.99 * h_limit, 5.0, 0.01, 0.015, &below));
  EXPECT_FALSE(stays_bounded(Integrator::RK4, 1.2 * h_limit, 5.0, 0.01, 1.0, &above));
  // backward Euler at 100 times the limit: bounded, and Newton converges
  StepStats stats;
  double be = 0.0;
  const double h_be = 100.0 * h_limit;
  EXPECT_TRUE(stays_bounded(Integrator::BackwardEuler, h_be, 20.0, 0.01, 0.011, &be, &stats));
  std::printf(
      "from 0.01 rad: RK4 at 0.99 x limit max |q| = %.3e rad over 5 s; at 1.2 x limit "
      "max |q| = %.3e rad (diverged); backward Euler at h = %.4e s (100 x limit) for "
      "20 s: max |q| = %.3e rad, %.2f Newton iterations per step (max %d)\n",
      below, above, h_be, be, double(stats.newton_iterations) / std::max(1L, stats.newton_solves),
      stats.max_newton_iterations);
}

}  // namespace
}  // namespace gencoord
