// SPDX-License-Identifier: BSD-3-Clause
// The sparse symmetric positive definite solves of backward Euler's step matrix: conjugate
// gradients with the stopping rule of ImplicitOptions, and the failure of a Cholesky
// factorization as an error. Private to the library.
#pragma once

#include <Eigen/SparseCore>

#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable::detail {

/// Solves A x = b by Jacobi-preconditioned conjugate gradients, A symmetric positive definite
/// with A >= M (the diagonal `masses`), stopping when
///     |r|_{M^-1} <= max(tolerance |b|_{M^-1}, 64 eps |v|_M)
/// (|y|_{M^-1}^2 = sum y_k^2 / m_k, |v|_M^2 = sum m_k v_k^2, v = `velocities`, none if its size
/// is not b's, eps the double epsilon): since A >= M, the error of x in the kinetic-energy
/// norm is then at most that bound. The floor is the rounding of v + x: it stops a solve whose
/// right-hand side is rounding noise of the forces. A zero b gives x = 0 after no iteration.
/// The iteration runs on b scaled to |b|_inf = 1, so a tiny b (subnormal near rest) loses no
/// more than its own digits.
/// \param[in,out] x      the start (warm start) if its size is b's and its residual is below
///                       |b|, else zero; the solution.
/// \param[out]    stats  iterations, the relative residual |r|_{M^-1} / |b|_{M^-1}, unknowns.
/// \throws LinearSolveError if the rule is not met in options.max_iterations iterations or
///         the solution is not finite.
void solve_by_conjugate_gradient(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                                 const Eigen::VectorXd& masses, const Eigen::VectorXd& velocities,
                                 const ImplicitOptions& options, Eigen::VectorXd* x,
                                 ImplicitStats* stats);

/// Throws the LinearSolveError of a failed Cholesky factorization or a non-finite solution.
[[noreturn]] void throw_cholesky_failure(ImplicitStats* stats);

}  // namespace gencoord::deformable::detail
