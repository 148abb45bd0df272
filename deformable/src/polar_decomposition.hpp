// SPDX-License-Identifier: BSD-3-Clause
// The polar decomposition F = R S of a 2 x 2 or 3 x 3 deformation gradient, with what the
// co-rotated material's Hessian needs of it. Inline: it is most of an element's force, which
// runs once per element and step. Private to the library.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>

namespace gencoord::deformable::detail {

// F = R S with R a proper rotation and S symmetric, in the principal frame: F = U diag(s) V^T
// with U, V proper rotations, so that R = U V^T; an inverted F has its smallest stretch
// negative. One twist per pair of principal axes (i, j): T = U (e_i e_j^T - e_j e_i^T) V^T /
// sqrt(2), a unit vector of dP/dF's eigenbasis, with dR/dF's eigenvalue 2 / (s_i + s_j).
template <int Dim>
struct Polar {
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  static constexpr int kTwists = Dim == 2 ? 1 : 3;
  Mat rotation;
  double trace_s = 0.0;  // tr S = sum of the signed stretches
  std::array<Mat, kTwists> twists;
  std::array<double, kTwists> stretch_sums{};  // s_i + s_j of each twist's pair
};

inline Polar<2> polar(const Eigen::Matrix2d& f) {
  // the rotation nearest to F: angle atan2(F10 - F01, F00 + F11), and tr S the length of
  // that vector, which is s_0 + s_1 (the one twist's pair)
  Polar<2> out;
  const double a = f(0, 0) + f(1, 1), b = f(1, 0) - f(0, 1);
  const double r = std::hypot(a, b);
  const double c = r > 0.0 ? a / r : 1.0, s = r > 0.0 ? b / r : 0.0;
  out.rotation << c, -s, s, c;
  out.trace_s = r;
  Eigen::Matrix2d turn;
  turn << 0.0, -1.0, 1.0, 0.0;
  out.twists[0] = turn * out.rotation / std::sqrt(2.0);
  out.stretch_sums[0] = r;
  return out;
}

// V by cyclic Jacobi rotations on F^T F (accurate eigenvectors, a few sweeps for 3 x 3), then
// U from the columns of B = F V, which are orthogonal: Gram-Schmidt on the two longest and
// u_2 = u_0 x u_1, so that U is proper and the smallest stretch u_2 . b_2 is negative for an
// inverted F. An element's whole force costs less than Eigen's JacobiSVD of its F alone
// (bench/element_force_bench.cc).
inline Polar<3> polar(const Eigen::Matrix3d& f) {
  Eigen::Matrix3d a = f.transpose() * f;
  Eigen::Matrix3d v = Eigen::Matrix3d::Identity();
  constexpr int pairs[3][3] = {{0, 1, 2}, {0, 2, 1}, {1, 2, 0}};  // p, q and the third axis
  for (int sweep = 0; sweep < 10; ++sweep) {
    const double off = a(0, 1) * a(0, 1) + a(0, 2) * a(0, 2) + a(1, 2) * a(1, 2);
    if (!(off > 1e-33 * a.diagonal().squaredNorm())) break;  // also on NaN
    for (const auto& pair : pairs) {
      const int p = pair[0], q = pair[1], r = pair[2];
      const double apq = a(p, q);
      if (apq == 0.0) continue;
      // the rotation J (c, s in (p, q), -s in (q, p)) that zeroes (p, q) of J^T A J (Golub
      // and Van Loan, the symmetric Schur decomposition), applied entry by entry
      const double tau = (a(q, q) - a(p, p)) / (2.0 * apq);
      const double t = std::abs(tau) > 1e150
                           ? 0.5 / tau
                           : std::copysign(1.0, tau) / (std::abs(tau) + std::sqrt(1.0 + tau * tau));
      const double c = 1.0 / std::sqrt(1.0 + t * t), sn = t * c;
      a(p, p) -= t * apq;
      a(q, q) += t * apq;
      a(p, q) = a(q, p) = 0.0;
      const double arp = a(r, p), arq = a(r, q);
      a(r, p) = a(p, r) = c * arp - sn * arq;
      a(r, q) = a(q, r) = sn * arp + c * arq;
      for (int k = 0; k < 3; ++k) {
        const double vkp = v(k, p), vkq = v(k, q);
        v(k, p) = c * vkp - sn * vkq;
        v(k, q) = sn * vkp + c * vkq;
      }
    }
  }
  Eigen::Matrix3d b = f * v;
  // columns by decreasing length; a swap negates one column to keep V proper
  auto order = [&](int i, int k) {
    if (b.col(i).squaredNorm() >= b.col(k).squaredNorm()) return;
    b.col(i).swap(b.col(k));
    v.col(i).swap(v.col(k));
    b.col(k) *= -1.0;
    v.col(k) *= -1.0;
  };
  order(0, 1);
  order(0, 2);
  order(1, 2);
  Eigen::Matrix3d u;
  const double n0 = b.col(0).norm();
  u.col(0) = n0 > 0.0 ? Eigen::Vector3d(b.col(0) / n0) : Eigen::Vector3d::UnitX();
  Eigen::Vector3d u1 = b.col(1) - u.col(0).dot(b.col(1)) * u.col(0);
  const double n1 = u1.norm();
  u.col(1) = n1 > 0.0 ? Eigen::Vector3d(u1 / n1) : Eigen::Vector3d(u.col(0).unitOrthogonal());
  u.col(2) = u.col(0).cross(u.col(1));
  const Eigen::Vector3d stretch(n0, u.col(1).dot(b.col(1)), u.col(2).dot(b.col(2)));
  Polar<3> out;
  out.rotation = u * v.transpose();
  out.trace_s = stretch.sum();
  constexpr int twist_pairs[3][2] = {{0, 1}, {1, 2}, {0, 2}};
  for (int t = 0; t < 3; ++t) {
    const int i = twist_pairs[t][0], j = twist_pairs[t][1];
    Eigen::Matrix3d turn = Eigen::Matrix3d::Zero();
    turn(i, j) = -1.0;
    turn(j, i) = 1.0;
    out.twists[t] = u * turn * v.transpose() / std::sqrt(2.0);
    out.stretch_sums[t] = stretch(i) + stretch(j);
  }
  return out;
}

}  // namespace gencoord::deformable::detail
