// SPDX-License-Identifier: BSD-3-Clause
// Continuous-time algebraic Riccati equation (CARE) and the infinite-horizon LQR gain, for
// designing a state-feedback controller around a linearization of a model.
#pragma once

#include <Eigen/Core>

namespace gencoord {

/// The stabilizing solution X (symmetric, positive semidefinite when Q is) of
///   A^T X + X A - X B R^-1 B^T X + Q = 0,
/// the one for which A - B R^-1 B^T X has all its eigenvalues in the open left half-plane.
/// It exists when (A, B) is stabilizable and (Q, A) has no unobservable mode on the
/// imaginary axis.
/// \param[in] A  n x n, n >= 1
/// \param[in] B  n x m, m >= 1
/// \param[in] Q  n x n, symmetric positive semidefinite
/// \param[in] R  m x m, symmetric positive definite
/// \throws std::invalid_argument if a shape does not match, an entry is not finite, Q or R
///         is not symmetric, or R is not positive definite.
/// \throws std::runtime_error if there is no stabilizing solution (the Hamiltonian matrix has
///         eigenvalues on or too near the imaginary axis) or it could not be computed to
///         working accuracy.
Eigen::MatrixXd solve_continuous_are(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                     const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R);

/// The LQR gain K = R^-1 B^T X (m x n), X = solve_continuous_are(A, B, Q, R), so that the
/// feedback u = -K x of dx/dt = A x + B u minimizes the integral of x^T Q x + u^T R u.
/// \throws as solve_continuous_are.
Eigen::MatrixXd lqr_gain(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                         const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R);

}  // namespace gencoord
