// SPDX-License-Identifier: BSD-3-Clause
// The small dense kernels of numerics/small_dense.hpp. A column of up to 4 B rows is held as B
// vectors of 4 doubles (a GCC/Clang vector: one AVX2 register, or two SSE2 ones), its rows
// past n zero; the order n picks the instantiation with the fewest vectors. Lanes are chosen by
// comparing row indices, never by writing one lane of a vector held in memory, which would
// make the next load of the whole vector wait for the store.
#include "gencoord/numerics/small_dense.hpp"

#include <stdexcept>
#include <string>

namespace gencoord {
namespace {

typedef double Vec4 __attribute__((vector_size(32)));

// the row index of each lane of block 0; block b's are 4 b more. (Vectors are never passed or
// returned by value, whose ABI differs between builds with and without AVX: a scalar in an
// arithmetic operation or comparison with a vector stands for a vector of it.)
constexpr Vec4 kLaneRows = {0.0, 1.0, 2.0, 3.0};

// rows [from, n) of a column-major column as B vectors, zero elsewhere
template <int B>
inline void load_column(int n, const double* column, int from, Vec4* out) {
  for (int b = 0; b < B; ++b) {
    Vec4 x{};
    for (int lane = 0; lane < 4; ++lane) {
      const int row = 4 * b + lane;
      if (row >= from && row < n) x[lane] = column[row];
    }
    out[b] = x;
  }
}

template <int B>
inline void store_column(int n, const Vec4* in, double* column) {
  for (int b = 0; b < B; ++b)
    for (int lane = 0; lane < 4; ++lane)
      if (4 * b + lane < n) column[4 * b + lane] = in[b][lane];
}

// A = L D L^T right-looking: once column j is done, its outer product leaves the columns to its
// right, so the next pivot is one fused multiply-add away. Then X = L^-1 row by row and
// A^-1 = X^T D^-1 X, whose row r sums the rows of X from r down.
template <int B>
bool spd_inverse(int n, const double* A, double* inverse) {
  constexpr int kRows = 4 * B;
  Vec4 W[kRows][B];  // the columns still to factor, then the columns of L (below the diagonal)
  Vec4 X[kRows][B];  // the rows of L^-1
  double inverse_pivot[kRows];
  for (int j = 0; j < n; ++j) load_column<B>(n, A + j * n, j, W[j]);
  for (int j = 0; j < n; ++j) {
    const double pivot = W[j][j / 4][j % 4];
    if (!(pivot > 0.0)) return false;
    inverse_pivot[j] = 1.0 / pivot;
    Vec4 l[B];
    for (int b = 0; b < B; ++b)
      l[b] = kLaneRows + 4.0 * b > j ? W[j][b] * inverse_pivot[j] : Vec4{};
    for (int c = j + 1; c < n; ++c) {
      const double w = W[j][c / 4][c % 4];  // pivot times L(c, j)
      for (int b = 0; b < B; ++b) W[c][b] -= l[b] * w;
    }
    for (int b = 0; b < B; ++b) W[j][b] = l[b];
  }
  for (int i = 0; i < n; ++i) {
    for (int b = 0; b < B; ++b) X[i][b] = kLaneRows + 4.0 * b == i ? Vec4{} + 1.0 : Vec4{};
    for (int k = 0; k < i; ++k) {
      const double l_ik = W[k][i / 4][i % 4];
      for (int b = 0; b < B; ++b) X[i][b] -= l_ik * X[k][b];
    }
  }
  for (int r = 0; r < n; ++r) {
    Vec4 row[B] = {};
    for (int k = r; k < n; ++k) {
      const double s = X[k][r / 4][r % 4] * inverse_pivot[k];
      for (int b = 0; b < B; ++b) row[b] += s * X[k][b];
    }
    store_column<B>(n, row, inverse + r * n);  // symmetric: row r is column r
  }
  return true;
}

// C = alpha S B, U columns of C at a time so that U independent chains of fused multiply-adds
// overlap
template <int B>
void product(int n, int m, const double* S, const double* Bm, double alpha, double* C) {
  constexpr int kRows = 4 * B;
  constexpr int U = B <= 2 ? 4 : B <= 4 ? 2 : 1;
  Vec4 Sa[kRows][B];  // the columns of alpha S
  for (int k = 0; k < n; ++k) {
    load_column<B>(n, S + k * n, 0, Sa[k]);
    for (int b = 0; b < B; ++b) Sa[k][b] *= alpha;
  }
  int c = 0;
  for (; c + U <= m; c += U) {
    Vec4 out[U][B] = {};
    for (int k = 0; k < n; ++k)
      for (int u = 0; u < U; ++u) {
        const double x = Bm[(c + u) * n + k];
        for (int b = 0; b < B; ++b) out[u][b] += Sa[k][b] * x;
      }
    for (int u = 0; u < U; ++u) store_column<B>(n, out[u], C + (c + u) * n);
  }
  for (; c < m; ++c) {
    Vec4 out[B] = {};
    for (int k = 0; k < n; ++k) {
      const double x = Bm[c * n + k];
      for (int b = 0; b < B; ++b) out[b] += Sa[k][b] * x;
    }
    store_column<B>(n, out, C + c * n);
  }
}

void check_order(const char* function, int n) {
  static_assert(kSmallDenseMaxOrder == 4 * 6, "one instantiation per count of vectors");
  if (n < 1 || n > kSmallDenseMaxOrder)
    throw std::invalid_argument(std::string("gencoord::") + function + ": order " +
                                std::to_string(n) + " is outside 1.." +
                                std::to_string(kSmallDenseMaxOrder));
}

}  // namespace

// the instantiation for order n: the one with (n + 3) / 4 vectors a column
bool small_spd_inverse(int n, const double* A, double* inverse) {
  check_order("small_spd_inverse", n);
  static constexpr bool (*kByVectors[])(int, const double*, double*) = {
      spd_inverse<1>, spd_inverse<2>, spd_inverse<3>,
      spd_inverse<4>, spd_inverse<5>, spd_inverse<6>};
  return kByVectors[(n + 3) / 4 - 1](n, A, inverse);
}

void small_product(int n, int m, const double* S, const double* B, double alpha, double* C) {
  check_order("small_product", n);
  static constexpr void (*kByVectors[])(int, int, const double*, const double*, double, double*) = {
      product<1>, product<2>, product<3>, product<4>, product<5>, product<6>};
  kByVectors[(n + 3) / 4 - 1](n, m, S, B, alpha, C);
}

}  // namespace gencoord
