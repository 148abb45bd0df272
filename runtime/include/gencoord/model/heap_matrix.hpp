// SPDX-License-Identifier: BSD-3-Clause
// HeapMatrix: a matrix of sizes fixed by the model whose entries live on the heap.
//
// A generated model's vectors and matrices are fixed-size Eigen objects, which Eigen keeps on
// the stack and refuses above 128 KiB (a 100-link planar chain's 200 x 100 Jacobian already
// is 160 KiB). For such a size the generator writes HeapMatrix<Scalar, rows, cols> instead
// (python/gencoord/cxx/storage.py): default-constructed it has its size, like a fixed-size matrix,
// and Zero(), Ones(), Identity() and Constant(value) take no sizes, so the runtime's code is the
// same for both. Everything else is Eigen's dynamic-size Matrix it derives from; Eigen's
// expressions and decompositions see that base (LLT<PlainOf<QMat<M>>>, model_traits.hpp), never
// a HeapMatrix.
#pragma once

#include <type_traits>

#include <Eigen/Core>

namespace gencoord {

template <typename Scalar, int Rows, int Cols>
class HeapMatrix : public Eigen::Matrix<Scalar, Eigen::Dynamic, Cols == 1 ? 1 : Eigen::Dynamic> {
 public:
  using Base = Eigen::Matrix<Scalar, Eigen::Dynamic, Cols == 1 ? 1 : Eigen::Dynamic>;

  using Base::Base;  // Eigen's sized and copying constructors
  HeapMatrix() : Base(Rows, Cols) {}
  // implicit from any Eigen expression, as Eigen::Matrix is
  template <typename Other>
  HeapMatrix(const Eigen::EigenBase<Other>& other) : Base(other.derived()) {}  // NOLINT
  template <typename Other>
  HeapMatrix& operator=(const Eigen::EigenBase<Other>& other) {
    Base::operator=(other.derived());
    return *this;
  }

  // the sized factories stay callable; the ones without sizes get the model's
  using Base::Constant;
  using Base::Identity;
  using Base::Ones;
  using Base::Zero;
  static auto Zero() { return Base::Zero(Rows, Cols); }
  static auto Ones() { return Base::Ones(Rows, Cols); }
  static auto Identity() { return Base::Identity(Rows, Cols); }
  static auto Constant(const Scalar& value) { return Base::Constant(Rows, Cols, value); }
};

/// Rows x Cols entries: fixed-size within Eigen's stack limit, a HeapMatrix beyond it; for the
/// runtime's own matrices of model sizes (the generator decides the model's types itself).
template <typename Scalar, int Rows, int Cols>
using SizedMatrix =
    std::conditional_t<(static_cast<long long>(Rows) * Cols * sizeof(Scalar) <=
                        EIGEN_STACK_ALLOCATION_LIMIT),
                       Eigen::Matrix<Scalar, Rows, Cols>, HeapMatrix<Scalar, Rows, Cols>>;

}  // namespace gencoord
