// SPDX-License-Identifier: BSD-3-Clause
// Lanczos iterations for the largest eigenvalue (largest_eigenvalue.hpp).
#include "largest_eigenvalue.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace gencoord::deformable::detail {

double largest_eigenvalue(const Eigen::SparseMatrix<double>& a, int steps) {
  const int n = static_cast<int>(a.rows());
  if (n == 0) return 0.0;
  // a deterministic start with a component along every mode
  Eigen::VectorXd q(n);
  for (int i = 0; i < n; ++i)
    q(i) =
        static_cast<double>((static_cast<std::uint32_t>(i) * 2654435761u) >> 8) / (1u << 24) - 0.5;
  q.normalize();
  Eigen::VectorXd previous = Eigen::VectorXd::Zero(n);
  std::vector<double> alpha, beta;
  double b = 0.0, scale = 0.0;
  for (int k = 0; k < std::min(steps, n); ++k) {
    Eigen::VectorXd w = a * q;
    const double al = q.dot(w);
    w -= al * q + b * previous;
    alpha.push_back(al);
    scale = std::max(scale, std::abs(al) + b);
    b = w.norm();
    // an invariant subspace: its Ritz values are exact
    if (!(b > 1e-14 * scale)) break;
    beta.push_back(b);
    previous.swap(q);
    q = w / b;
  }
  const int m = static_cast<int>(alpha.size());
  const Eigen::Map<const Eigen::VectorXd> diagonal(alpha.data(), m);
  const Eigen::Map<const Eigen::VectorXd> off_diagonal(beta.data(), m - 1);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz;
  ritz.computeFromTridiagonal(diagonal, off_diagonal, Eigen::EigenvaluesOnly);
  return ritz.eigenvalues().maxCoeff();
}

}  // namespace gencoord::deformable::detail
