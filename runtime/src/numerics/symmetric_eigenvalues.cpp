// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/numerics/symmetric_eigenvalues.hpp"

#include <limits>

#include <Eigen/Eigenvalues>

namespace gencoord {

double largest_symmetric_eigenvalue(const Eigen::MatrixXd& A) {
  if (A.size() == 0) return -std::numeric_limits<double>::infinity();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A, Eigen::EigenvaluesOnly);
  return eig.eigenvalues().maxCoeff();
}

}  // namespace gencoord
