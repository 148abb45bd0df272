// SPDX-License-Identifier: BSD-3-Clause
// A sparse LU solver compiled once in the runtime library: Eigen's SparseLU does not depend on
// the model, and is among the costliest templates a program with the maximal model would
// otherwise compile.
#pragma once

#include <memory>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace gencoord {

/// Solves A x = b for square sparse matrices A of one pattern: the pattern (its fill-reducing
/// ordering) is analysed on the first solve and kept. A copy starts without it (a
/// factorization is not copied), and so does the target of an assignment.
class SparseLuSolver {
 public:
  SparseLuSolver();
  ~SparseLuSolver();
  SparseLuSolver(const SparseLuSolver&);
  SparseLuSolver& operator=(const SparseLuSolver&);
  SparseLuSolver(SparseLuSolver&&) noexcept;
  SparseLuSolver& operator=(SparseLuSolver&&) noexcept;

  /// Factorizes A and writes its solution of A x = b to x; false, x untouched, if A is
  /// singular.
  bool solve(const Eigen::SparseMatrix<double>& A, const Eigen::Ref<const Eigen::VectorXd>& b,
             Eigen::Ref<Eigen::VectorXd> x);

 private:
  struct Factorization;
  std::unique_ptr<Factorization> lu_;
};

}  // namespace gencoord
