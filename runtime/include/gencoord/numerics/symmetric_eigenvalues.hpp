// SPDX-License-Identifier: BSD-3-Clause
// The largest eigenvalue of a dense symmetric matrix, compiled once in the runtime library:
// Eigen's symmetric eigensolver is the costliest template a program including the maximal
// model would otherwise compile.
#pragma once

#include <Eigen/Core>

namespace gencoord {

/// The largest eigenvalue of the symmetric matrix A (its lower triangle is read); -infinity
/// for an empty A.
double largest_symmetric_eigenvalue(const Eigen::MatrixXd& A);

}  // namespace gencoord
