// SPDX-License-Identifier: BSD-3-Clause
// Local coordinates of the configurations of a model with generalized speeds (free and ball
// joints: unit quaternions in q, q' = G(q) v with nv < nq speeds).
//
// A deviation delta, one entry per speed, names the configuration q = retract(q0, delta):
//   q_N = q0_N + G_N(q0) delta       every coordinate N outside a quaternion (a free joint's
//                                    position moves along its body axes at q0)
//   q_k = q0_k (x) exp(delta_k)      each unit quaternion k, delta_k the entries of its three
//                                    angular speeds, exp(d) = (cos |d|/2, sin(|d|/2) d/|d|)
// Its derivative at delta = 0 is G(q0), so (delta, v) are coordinates of the state space
// near q0 in which q' = G(q) v reads delta' = v + O(delta): the linearization of a model with
// speeds in x = (delta, v) is square, 2 nv (control/linearize.hpp), as robotics users know it
// from integrating on the rotation group.
//
// In those coordinates delta' = F(delta, v), with, at delta = 0,
//   quaternion k:  delta_k' = J_r(delta_k)^-1 omega_k,  so  d delta_k'/d delta_k = -1/2 [omega_k]x,
//                  d delta_k'/d omega_k = I   (J_r, SO(3)'s right Jacobian, is I - 1/2 [d]x + ..)
//   the rest N:    delta_S' = G_NS(q0)^-1 (G(q) v)_N  (S the speeds that are no quaternion's;
//                  G_NS is square: an ordinary coordinate's unit rate, a free joint's R(q0)), so
//                  d delta_S'/d delta = G_NS^-1 d(G v)_N/dq G(q0),  d delta_S'/d v = G_NS^-1 G_N.
// G(q) v is a polynomial of degree at most 2 in q (R(q) is quadratic, the quaternion rate
// linear, an ordinary rate constant), so its central difference at any step is exact: the
// step taken is 1/2, where round-off is that of the rates themselves.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "gencoord/model/model_traits.hpp"

namespace gencoord {

/// The derivatives of the local coordinates' rate delta' = F(delta, v) at delta = 0 (see the
/// file comment), and G(q0) = dq/d delta there.
struct TangentRates {
  Eigen::MatrixXd G;             // nq x nv
  Eigen::MatrixXd rate_D_delta;  // d delta'/d delta, nv x nv
  Eigen::MatrixXd rate_D_v;      // d delta'/d v, nv x nv
};

/// G(q) of q' = G(q) v (nq x nv): column j the rates of unit speed j (coordinate_rates is
/// linear in v).
template <class M>
Eigen::MatrixXd coordinate_rate_matrix(const ParamsOf<M>& p, const QVec<M>& q, double t = 0.0) {
  static_assert(has_generalized_speeds_v<M>,
                "gencoord: coordinate_rate_matrix() is for models with speeds");
  Eigen::MatrixXd G(M::nq, nv_of_v<M>);
  VVec<M> e = VVec<M>::Zero();
  for (int j = 0; j < nv_of_v<M>; ++j) {
    e[j] = 1.0;
    G.col(j) = M::coordinate_rates(q, e, t, p);
    e[j] = 0.0;
  }
  return G;
}

namespace detail {

// unit quaternions back on the sphere (a step on q, or a Gauss-Newton step, leaves them off it)
template <class M>
void normalize_quaternions(QVec<M>* q) {
  if constexpr (has_generalized_speeds_v<M>) {
    for (const int start : M::quaternion_starts) {
      auto quaternion = q->segment(start, 4);
      quaternion /= quaternion.norm();
    }
  }
}

// G(q)^T, row j the rates of unit speed j, in the model's own nv x nq type (a HeapMatrix past
// Eigen's stack limit), so that the systems' Newton Jacobians allocate nothing
template <class M>
VQMat<M> rate_matrix_transposed(const ParamsOf<M>& p, const QVec<M>& q, double t) {
  VQMat<M> rates_of;
  VVec<M> e = VVec<M>::Zero();
  for (int j = 0; j < nv_of_v<M>; ++j) {
    e[j] = 1.0;
    rates_of.row(j) = M::coordinate_rates(q, e, t, p).transpose();
    e[j] = 0.0;
  }
  return rates_of;
}

using Quaternion = std::array<double, 4>;  // (w, x, y, z)

inline Quaternion quaternion_product(const Quaternion& a, const Quaternion& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
          a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
          a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}

// exp(d) of a rotation vector d: the unit quaternion of the turn |d| about d
inline Quaternion quaternion_exp(double x, double y, double z) {
  const double angle = std::sqrt(x * x + y * y + z * z);
  // sin(a/2)/a, its series below where the quotient loses digits
  const double s = angle < 1e-4 ? 0.5 - angle * angle / 48.0 : std::sin(angle / 2) / angle;
  return {std::cos(angle / 2), s * x, s * y, s * z};
}

// log of a unit quaternion (the shorter turn of q and -q): a rotation vector
inline std::array<double, 3> quaternion_log(Quaternion r) {
  if (r[0] < 0)
    for (double& c : r) c = -c;
  const double s = std::sqrt(r[1] * r[1] + r[2] * r[2] + r[3] * r[3]);
  const double angle = 2 * std::atan2(s, r[0]);
  // angle / s, its series where s is small (the turn's sine, a = 2 s + s^3 / 3 + ...)
  const double f = s < 1e-8 ? 2.0 / r[0] : angle / s;
  return {f * r[1], f * r[2], f * r[3]};
}

// Which coordinates lie in a quaternion, and the speed index of each quaternion's first
// angular speed: speeds follow the coordinates in order, a quaternion's 4 taking 3 speeds.
template <class M>
struct SpeedLayout {
  std::array<bool, M::nq> in_quaternion{};
  std::array<bool, nv_of_v<M>> quaternion_speed{};
  std::vector<int> others_q, others_v;  // N and S of the file comment, paired in order

  SpeedLayout() {
    for (int k = 0; k < M::num_quaternions; ++k) {
      for (int i = 0; i < 4; ++i) in_quaternion[M::quaternion_starts[k] + i] = true;
      for (int i = 0; i < 3; ++i) quaternion_speed[omega_start(k) + i] = true;
    }
    for (int i = 0; i < M::nq; ++i)
      if (!in_quaternion[i]) others_q.push_back(i);
    for (int j = 0; j < nv_of_v<M>; ++j)
      if (!quaternion_speed[j]) others_v.push_back(j);
  }
  static int omega_start(int k) { return M::quaternion_starts[k] - k; }
};

// G_NS: G's rows N and columns S, the square block of the coordinates outside quaternions
template <class M>
Eigen::MatrixXd others_block(const SpeedLayout<M>& layout, const Eigen::MatrixXd& G) {
  const auto n = static_cast<Eigen::Index>(layout.others_q.size());
  Eigen::MatrixXd block(n, n);
  for (Eigen::Index r = 0; r < n; ++r)
    for (Eigen::Index c = 0; c < n; ++c) block(r, c) = G(layout.others_q[r], layout.others_v[c]);
  return block;
}

}  // namespace detail

/// q0 moved by the local coordinates delta (dim nv): see the file comment. Only for models
/// with generalized speeds; q0's quaternions should be unit, and so are the result's.
template <class M>
QVec<M> retract(const ParamsOf<M>& p, const QVec<M>& q0, const VVec<M>& delta, double t = 0.0) {
  static_assert(has_generalized_speeds_v<M>, "gencoord: retract() is for models with speeds");
  const detail::SpeedLayout<M> layout;
  const QVec<M> moved = M::coordinate_rates(q0, delta, t, p);  // G(q0) delta
  QVec<M> q = q0;
  for (int i : layout.others_q) q[i] += moved[i];
  for (int k = 0; k < M::num_quaternions; ++k) {
    const int s = M::quaternion_starts[k], w = layout.omega_start(k);
    const detail::Quaternion turned =
        detail::quaternion_product({q0[s], q0[s + 1], q0[s + 2], q0[s + 3]},
                                   detail::quaternion_exp(delta[w], delta[w + 1], delta[w + 2]));
    for (int i = 0; i < 4; ++i) q[s + i] = turned[i];
  }
  return q;
}

/// The local coordinates delta of q about q0, the inverse of retract() (the shorter turn
/// for each quaternion; q's quaternions are normalized first).
template <class M>
VVec<M> local_coordinates(const ParamsOf<M>& p, const QVec<M>& q0, const QVec<M>& q,
                          double t = 0.0) {
  static_assert(has_generalized_speeds_v<M>,
                "gencoord: local_coordinates() is for models with speeds");
  const detail::SpeedLayout<M> layout;
  VVec<M> delta = VVec<M>::Zero();
  for (int k = 0; k < M::num_quaternions; ++k) {
    const int s = M::quaternion_starts[k], w = layout.omega_start(k);
    const double norm =
        std::sqrt(q[s] * q[s] + q[s + 1] * q[s + 1] + q[s + 2] * q[s + 2] + q[s + 3] * q[s + 3]);
    const detail::Quaternion relative = detail::quaternion_product(
        {q0[s], -q0[s + 1], -q0[s + 2], -q0[s + 3]},
        {q[s] / norm, q[s + 1] / norm, q[s + 2] / norm, q[s + 3] / norm});
    const std::array<double, 3> turn = detail::quaternion_log(relative);
    for (int i = 0; i < 3; ++i) delta[w + i] = turn[i];
  }
  // q_N - q0_N = G_N(q0) delta, solved for delta_S with the quaternions' part known
  const Eigen::MatrixXd G = coordinate_rate_matrix<M>(p, q0, t);
  const auto n = static_cast<Eigen::Index>(layout.others_q.size());
  Eigen::VectorXd rest(n);
  const Eigen::VectorXd known = G * Eigen::VectorXd(delta);
  for (Eigen::Index r = 0; r < n; ++r) {
    const int i = layout.others_q[r];
    rest[r] = q[i] - q0[i] - known[i];
  }
  if (n == 0) return delta;  // quaternions only (ball joints)
  const Eigen::VectorXd others = detail::others_block<M>(layout, G).partialPivLu().solve(rest);
  for (Eigen::Index r = 0; r < n; ++r) delta[layout.others_v[r]] = others[r];
  return delta;
}

/// d(G(q) v)/dq at (q, v) (nq x nq), by a central difference that is exact for the degree-2
/// polynomial G(q) v (the file comment).
template <class M>
Eigen::MatrixXd coordinate_rates_jacobian(const ParamsOf<M>& p, const QVec<M>& q, const VVec<M>& v,
                                          double t = 0.0) {
  static_assert(has_generalized_speeds_v<M>,
                "gencoord: coordinate_rates_jacobian() is for models with speeds");
  Eigen::MatrixXd rates_D_q(M::nq, M::nq);
  for (int j = 0; j < M::nq; ++j) {
    QVec<M> qp = q, qm = q;
    qp[j] += 0.5;
    qm[j] -= 0.5;
    rates_D_q.col(j) =
        (M::coordinate_rates(qp, v, t, p) - M::coordinate_rates(qm, v, t, p)) / (qp[j] - qm[j]);
  }
  return rates_D_q;
}

/// G(q0) and the derivatives of delta' at delta = 0, speeds v0 (the file comment).
template <class M>
TangentRates tangent_rates(const ParamsOf<M>& p, const QVec<M>& q0, const VVec<M>& v0,
                           double t = 0.0) {
  static_assert(has_generalized_speeds_v<M>, "gencoord: tangent_rates() is for models with speeds");
  constexpr int nv = nv_of_v<M>;
  const detail::SpeedLayout<M> layout;
  TangentRates out;
  out.G = coordinate_rate_matrix<M>(p, q0, t);
  const Eigen::MatrixXd rates_D_q = coordinate_rates_jacobian<M>(p, q0, v0, t);
  const auto n = static_cast<Eigen::Index>(layout.others_q.size());
  Eigen::MatrixXd chained(n, nv), rows(n, nv);  // rows N of d(G v0)/dq G and of G
  const Eigen::MatrixXd full = rates_D_q * out.G;
  for (Eigen::Index r = 0; r < n; ++r) {
    chained.row(r) = full.row(layout.others_q[r]);
    rows.row(r) = out.G.row(layout.others_q[r]);
  }
  out.rate_D_delta = Eigen::MatrixXd::Zero(nv, nv);
  out.rate_D_v = Eigen::MatrixXd::Zero(nv, nv);
  Eigen::MatrixXd others_D_delta, others_D_v;
  if (n > 0) {  // none with quaternions only (ball joints)
    const auto lu = detail::others_block<M>(layout, out.G).partialPivLu();
    others_D_delta = lu.solve(chained);
    others_D_v = lu.solve(rows);
  }
  for (Eigen::Index r = 0; r < n; ++r) {
    out.rate_D_delta.row(layout.others_v[r]) = others_D_delta.row(r);
    out.rate_D_v.row(layout.others_v[r]) = others_D_v.row(r);
  }
  for (int k = 0; k < M::num_quaternions; ++k) {
    const int w = layout.omega_start(k);
    const double x = v0[w], y = v0[w + 1], z = v0[w + 2];
    Eigen::Matrix3d cross;  // [omega]x
    cross << 0, -z, y, z, 0, -x, -y, x, 0;
    out.rate_D_delta.block(w, w, 3, 3) = -0.5 * cross;
    out.rate_D_v.block(w, w, 3, 3).setIdentity();
  }
  return out;
}

}  // namespace gencoord
