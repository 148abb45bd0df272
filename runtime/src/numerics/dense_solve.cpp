// SPDX-License-Identifier: BSD-3-Clause
#include "gencoord/numerics/dense_solve.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace gencoord {

namespace {

// The largest system whose LU works on the stack (8 KiB of matrix).
constexpr int kStackSize = 32;
using StackMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kStackSize, kStackSize>;
using StackVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kStackSize, 1>;

template <class Matrix, class Vector>
void lu_solve_in(Eigen::Ref<const Eigen::MatrixXd> A, Eigen::Ref<const Eigen::VectorXd> b,
                 Eigen::Ref<Eigen::VectorXd> x) {
  const Eigen::PartialPivLU<Matrix> lu{Matrix(A)};
  x = lu.solve(Vector(b));
}

}  // namespace

bool lu_solve(Eigen::Ref<const Eigen::MatrixXd> A, Eigen::Ref<const Eigen::VectorXd> b,
              Eigen::Ref<Eigen::VectorXd> x) {
  if (b.size() <= kStackSize) {
    lu_solve_in<StackMatrix, StackVector>(A, b, x);
  } else {
    lu_solve_in<Eigen::MatrixXd, Eigen::VectorXd>(A, b, x);
  }
  return true;
}

bool cholesky_factor(Eigen::Ref<Eigen::MatrixXd> A) {
  const Eigen::LLT<Eigen::Ref<Eigen::MatrixXd>> in_place(A);  // factors A's own storage
  return in_place.info() == Eigen::Success;
}

void cholesky_solve(Eigen::Ref<const Eigen::MatrixXd> L, Eigen::Ref<Eigen::MatrixXd> B) {
  L.triangularView<Eigen::Lower>().solveInPlace(B);
  L.transpose().triangularView<Eigen::Upper>().solveInPlace(B);
}

}  // namespace gencoord
