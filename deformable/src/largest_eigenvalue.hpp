// SPDX-License-Identifier: BSD-3-Clause
// The largest eigenvalue of a sparse symmetric matrix by Lanczos iterations, for the highest
// frequency behind the stable explicit step. Private to the library.
#pragma once

#include <Eigen/SparseCore>

namespace gencoord::deformable::detail {

/// The largest eigenvalue of the symmetric matrix a (both triangles stored), from below: the
/// largest Ritz value of at most `steps` Lanczos iterations from a fixed start vector with a
/// component along every eigenvector. Without reorthogonalization, so memory stays linear in
/// the size; lost orthogonality only repeats Ritz values that have converged. 0 for an empty
/// matrix.
double largest_eigenvalue(const Eigen::SparseMatrix<double>& a, int steps = 60);

}  // namespace gencoord::deformable::detail
