// SPDX-License-Identifier: BSD-3-Clause
// Dense kernels for the small matrices of the derivative path (a mass matrix of up to 24
// speeds, its inverse applied to the residual's Jacobians), compiled once in the runtime
// library with the instruction sets of the models' kernels (AVX2 and FMA, and AVX-512 where
// cmake/simd.cmake finds them). At these sizes Eigen's fixed-size factor, triangular solves
// and products are bound by the latency of long chains of scalar steps, and they are compiled
// in the user's translation unit for the baseline instruction set; here every column is a few
// 4-wide vectors and independent columns are interleaved (bench/derivatives_bench.cc times
// the whole path).
#pragma once

namespace gencoord {

/// The largest order that small_spd_inverse() and small_product() take.
inline constexpr int kSmallDenseMaxOrder = 24;

/// inverse = A^-1 for a symmetric positive definite n x n A, 1 <= n <= kSmallDenseMaxOrder,
/// by an LDL^T factorization (no square roots). Both column-major; only A's lower triangle is
/// read, and inverse is written whole. They must not overlap.
/// \return false, leaving inverse unspecified, when a pivot is not positive: A is not
///         positive definite or holds a NaN.
bool small_spd_inverse(int n, const double* A, double* inverse);

/// C = alpha S B for an n x n S, an n x m B and an n x m C, all column-major,
/// 1 <= n <= kSmallDenseMaxOrder, m >= 0; C must not overlap S or B.
void small_product(int n, int m, const double* S, const double* B, double alpha, double* C);

}  // namespace gencoord
