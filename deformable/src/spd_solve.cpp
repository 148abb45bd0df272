// SPDX-License-Identifier: BSD-3-Clause
// Conjugate gradients for backward Euler's step matrix (spd_solve.hpp).
#include "spd_solve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "gencoord/deformable/errors.hpp"

namespace gencoord::deformable::detail {

namespace {
// the floor relative to the velocities: below it, adding dv to v is lost in rounding v
constexpr double kVelocityFloor = 64.0 * std::numeric_limits<double>::epsilon();
}  // namespace

void solve_by_conjugate_gradient(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                                 const Eigen::VectorXd& masses, const Eigen::VectorXd& velocities,
                                 const ImplicitOptions& options, Eigen::VectorXd* x,
                                 ImplicitStats* stats) {
  using Eigen::VectorXd;
  const Eigen::Index n = b.size();
  stats->unknowns = static_cast<int>(n);
  stats->iterations = 0;
  stats->residual = 0.0;
  double scale = 0.0;  // |b|_inf, NaN if b is not finite
  for (Eigen::Index k = 0; k < n; ++k)
    scale = std::isnan(b[k]) ? b[k] : std::max(scale, std::abs(b[k]));
  if (scale == 0.0) {
    x->setZero(n);
    return;
  }
  const VectorXd inverse_masses = masses.cwiseInverse();
  const auto norm_inverse_mass = [&](const VectorXd& y) {
    return std::sqrt(y.cwiseAbs2().dot(inverse_masses));
  };
  const VectorXd scaled_b = b / scale;
  const double b_norm = norm_inverse_mass(scaled_b);
  const double v_norm =
      velocities.size() == n ? std::sqrt(velocities.cwiseAbs2().dot(masses)) / scale : 0.0;
  const double target = std::max(options.tolerance * b_norm, kVelocityFloor * v_norm);

  VectorXd y = VectorXd::Zero(n);
  VectorXd r = scaled_b;
  if (x->size() == n) {
    // a warm start that is worse than none (the right-hand side collapsed) is dropped: its
    // residual would carry the rounding of A times it
    const VectorXd start = *x / scale;
    VectorXd start_r = scaled_b - A * start;
    if (norm_inverse_mass(start_r) < b_norm) {
      y = start;
      r = std::move(start_r);
    }
  }
  const VectorXd inverse_diagonal = A.diagonal().cwiseInverse();
  VectorXd z = inverse_diagonal.cwiseProduct(r);
  VectorXd p = z;
  VectorXd Ap(n);
  double rz = r.dot(z);
  double r_norm = norm_inverse_mass(r);
  int iterations = 0;
  while (r_norm > target && iterations < options.max_iterations) {
    Ap.noalias() = A * p;
    const double alpha = rz / p.dot(Ap);
    y += alpha * p;
    r -= alpha * Ap;
    z = inverse_diagonal.cwiseProduct(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
    r_norm = norm_inverse_mass(r);
    ++iterations;
    if (!std::isfinite(r_norm)) break;
  }
  *x = scale * y;
  stats->iterations = iterations;
  stats->residual = r_norm / b_norm;
  if (!(r_norm <= target) || !x->allFinite()) {
    std::ostringstream os;
    os << "backward Euler: conjugate gradients did not converge in " << iterations
       << " iterations (relative residual " << stats->residual << ", tolerance "
       << options.tolerance << ", " << n
       << " unknowns): raise ImplicitOptions::max_iterations, loosen "
          "ImplicitOptions::tolerance, take a smaller step, or use "
          "LinearSolver::kSparseCholesky";
    throw LinearSolveError(os.str(), iterations, stats->residual, static_cast<int>(n));
  }
}

void throw_cholesky_failure(ImplicitStats* stats) {
  stats->residual = std::numeric_limits<double>::infinity();
  std::ostringstream os;
  os << "backward Euler: the sparse Cholesky factorization (SimplicialLDLT) of the "
     << stats->unknowns << " x " << stats->unknowns
     << " step matrix failed or gave a non-finite solution: the matrix is not positive "
        "definite or not finite; check the object (masses, stiffnesses) and take a "
        "smaller step";
  throw LinearSolveError(os.str(), 0, stats->residual, stats->unknowns);
}

}  // namespace gencoord::deformable::detail
