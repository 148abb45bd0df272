// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/numerics/sparse_lu.hpp"

#include <Eigen/SparseLU>

namespace gencoord {

struct SparseLuSolver::Factorization {
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  bool analysed = false;
};

SparseLuSolver::SparseLuSolver() : lu_(std::make_unique<Factorization>()) {}
SparseLuSolver::~SparseLuSolver() = default;
SparseLuSolver::SparseLuSolver(const SparseLuSolver&) : SparseLuSolver() {}
SparseLuSolver& SparseLuSolver::operator=(const SparseLuSolver& other) {
  if (this != &other) lu_ = std::make_unique<Factorization>();
  return *this;
}
SparseLuSolver::SparseLuSolver(SparseLuSolver&&) noexcept = default;
SparseLuSolver& SparseLuSolver::operator=(SparseLuSolver&&) noexcept = default;

bool SparseLuSolver::solve(const Eigen::SparseMatrix<double>& A,
                           const Eigen::Ref<const Eigen::VectorXd>& b,
                           Eigen::Ref<Eigen::VectorXd> x) {
  if (!lu_) lu_ = std::make_unique<Factorization>();  // moved from
  if (!lu_->analysed) {
    lu_->lu.analyzePattern(A);
    lu_->analysed = true;
  }
  lu_->lu.factorize(A);
  if (lu_->lu.info() != Eigen::Success) return false;
  x = lu_->lu.solve(b);
  return true;
}

}  // namespace gencoord
