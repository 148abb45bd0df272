// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file springs.hpp
/// One strain-form spring-damper between two nodes, with its analytic Jacobians.
///
/// This is the reusable piece: the deformable mass-spring systems use it for every spring,
/// and a maximal-coordinate penalty model can use it for its penalty springs.
///
/// With d = x_j - x_i, l = |d|, n = d / l, the force on node i is (node j gets the opposite)
///
///     f_i = k (l - L) / L n  +  c ((v_j - v_i) . n) / L n
///
/// where L is the rest length (m), k the stiffness (N: force per unit strain; for a 1D rod it
/// is Young's modulus E) and c the damping (N s: force per unit strain rate). Dividing by L
/// makes k and c independent of how finely the object is meshed (deformable/docs/deformables.md).
///
/// In 1D (Dim == 1) the direction is fixed to n = +1 (springs are oriented so that
/// x_j > x_i at rest), which gives exactly the linear rod spring
/// f = k (x_j - x_i - L) / L + c (v_j - v_i) / L, also for an inverted element.

#include <Eigen/Core>
#include <algorithm>

namespace gencoord::deformable {

/// Rest length, stiffness and damping of one spring.
struct SpringParams {
  double rest_length = 1.0;  ///< L (m), > 0
  double stiffness = 0.0;    ///< k (N): force per unit strain
  double damping = 0.0;      ///< c (N s): force per unit strain rate
};

/// Force of one spring on its first node, and the quantities it was computed from.
template <int Dim>
struct SpringForce {
  Eigen::Matrix<double, Dim, 1> f_i;        ///< force on node i (N); node j gets -f_i
  Eigen::Matrix<double, Dim, 1> direction;  ///< n, unit vector from i to j
  double length = 0.0;                      ///< l = |x_j - x_i| (m)
  double strain = 0.0;                      ///< (l - L) / L, signed (positive in tension)
};

/// Derivatives of f_i, each a Dim x Dim block. Since f_i depends on x and v only through
/// d = x_j - x_i and dv = v_j - v_i, the global blocks are: d f_i / d x_j = f_i_D_d,
/// d f_i / d x_i = -f_i_D_d, d f_j / d x_j = -f_i_D_d, d f_j / d x_i = f_i_D_d (same for v).
template <int Dim>
struct SpringJacobian {
  Eigen::Matrix<double, Dim, Dim> f_i_D_d;   ///< d f_i / d (x_j - x_i) (N/m)
  Eigen::Matrix<double, Dim, Dim> f_i_D_dv;  ///< d f_i / d (v_j - v_i) (N s/m)
};

/// Unit direction from i to j and the length; 1D is fixed to +1 (see the file comment).
template <int Dim>
inline void spring_direction(const Eigen::Matrix<double, Dim, 1>& d,
                             Eigen::Matrix<double, Dim, 1>* n, double* length) {
  if constexpr (Dim == 1) {
    *n = Eigen::Matrix<double, 1, 1>::Ones();
    *length = d(0);  // signed: the linear rod spring
  } else {
    *length = d.norm();
    // coincident nodes: any direction, the elastic force is still -k n
    *n = *length > 0.0 ? Eigen::Matrix<double, Dim, 1>(d / *length)
                       : Eigen::Matrix<double, Dim, 1>::UnitX();
  }
}

/// Force on node i of a spring between nodes i and j.
/// \param xi, xj  positions (m), \param vi, vj  velocities (m/s).
template <int Dim>
inline SpringForce<Dim> spring_force(const Eigen::Matrix<double, Dim, 1>& xi,
                                     const Eigen::Matrix<double, Dim, 1>& xj,
                                     const Eigen::Matrix<double, Dim, 1>& vi,
                                     const Eigen::Matrix<double, Dim, 1>& vj,
                                     const SpringParams& p) {
  SpringForce<Dim> out;
  spring_direction<Dim>(xj - xi, &out.direction, &out.length);
  out.strain = (out.length - p.rest_length) / p.rest_length;
  const double strain_rate = (vj - vi).dot(out.direction) / p.rest_length;
  out.f_i = (p.stiffness * out.strain + p.damping * strain_rate) * out.direction;
  return out;
}

/// Elastic energy of a spring at length l: k (l - L)^2 / (2 L) (J).
inline double spring_energy(double length, const SpringParams& p) {
  const double stretch = length - p.rest_length;
  return 0.5 * p.stiffness * stretch * stretch / p.rest_length;
}

/// Jacobian of f_i. The damping's dependence on position is neglected (it is second order in
/// the velocity), as is usual for implicit mass-spring steps.
/// \param definite  clamp the transverse term (1 - L / l) at zero so that the stiffness is
///                  negative semi-definite also in compression (keeps the implicit system SPD).
template <int Dim>
inline SpringJacobian<Dim> spring_jacobian(const SpringForce<Dim>& s, const SpringParams& p,
                                           bool definite) {
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  SpringJacobian<Dim> jac;
  const Mat nn = s.direction * s.direction.transpose();
  if constexpr (Dim == 1) {
    jac.f_i_D_d = Mat::Constant(p.stiffness / p.rest_length);
  } else {
    // d/dd of (k/L)(d - L d/|d|) = (k/L) [(1 - L/l) I + (L/l) n n^T]
    const double ratio = s.length > 0.0 ? p.rest_length / s.length : 1.0;
    double transverse = 1.0 - ratio;
    if (definite) transverse = std::max(0.0, transverse);
    jac.f_i_D_d = (p.stiffness / p.rest_length) * (transverse * Mat::Identity() + ratio * nn);
  }
  jac.f_i_D_dv = (p.damping / p.rest_length) * nn;
  return jac;
}

}  // namespace gencoord::deformable
