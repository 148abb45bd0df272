// SPDX-License-Identifier: BSD-3-Clause
// Dense solves compiled once in the runtime library: the implicit integrators' Newton systems
// and a scripted model's free blocks. Instantiated inline, Eigen's LU and Cholesky and their
// triangular solves cost about a fifth of the compile time of a model's Python module, once
// per matrix type of every system; behind Eigen::Ref they are built once per user. Up to 32
// unknowns the work matrices live on the stack, so a step of a fixed-size system allocates
// nothing.
#pragma once

#include <Eigen/Core>

namespace gencoord {

/// x = A^-1 b by LU with partial pivoting, for a square A of b's size; x must have that size.
/// A singular A gives a non-finite x. \return true (the integrators' solve() contract).
bool lu_solve(Eigen::Ref<const Eigen::MatrixXd> A, Eigen::Ref<const Eigen::VectorXd> b,
              Eigen::Ref<Eigen::VectorXd> x);

/// Overwrites the lower triangle of the symmetric A (only it is read) with its Cholesky factor
/// L, A = L L^T; the strict upper triangle is left as it was.
/// \return false when A is not positive definite (a pivot <= 0; NaN entries pass and give a
/// non-finite factor).
bool cholesky_factor(Eigen::Ref<Eigen::MatrixXd> A);

/// Overwrites B with A^-1 B, given the factor L of A from cholesky_factor() (its lower
/// triangle is read).
void cholesky_solve(Eigen::Ref<const Eigen::MatrixXd> L, Eigen::Ref<Eigen::MatrixXd> B);

}  // namespace gencoord
