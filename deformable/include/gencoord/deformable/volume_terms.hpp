// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file volume_terms.hpp
/// Area (2D) and volume (3D) terms: per simplex element, an energy that resists a change of
/// its signed measure, which gives a spring network the Lame constant lambda it lacks.
///
/// An element with rest measure V0 (m^2 or m^3) and stiffness kappa at current signed measure
/// V stores
///
///     W = (kappa / 2) V0 (J - 1)^2,   J = V / V0,
///
/// and pushes node a with f_a = -kappa (J - 1) dV/dx_a. Under a small strain eps, J - 1 =
/// tr(eps) to first order, so W = (kappa / 2) tr(eps)^2 V0: exactly the lambda part of the
/// isotropic energy density (lambda / 2) tr(eps)^2 + mu eps : eps with lambda = kappa. The
/// quadratic form in J (rather than ln J or a barrier) keeps the force finite and linear in V
/// for any shape, inverted ones included, so that an explicit step never meets a singular
/// force, and its Gauss-Newton part is constant in the strain. Its units are those of E (N/m
/// in 2D, Pa in 3D).
///
/// Every node pair of an element is one of the object's springs; an element with a broken one
/// (fracture) exerts nothing from then on. The terms have no damping: the material's damping
/// acts through the springs.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "gencoord/deformable/material.hpp"

namespace gencoord::deformable {

template <int Dim>
struct MassSpringSystem;

/// One element's area or volume term (not used in 1D).
template <int Dim>
struct VolumeTerm {
  static constexpr int kNodes = Dim + 1;
  static constexpr int kEdges = Dim * (Dim + 1) / 2;
  /// Node indices, in the order whose signed measure is positive at rest.
  std::array<int, kNodes> nodes{};
  /// Index into MassSpringSystem::springs of the spring along each edge, in the order
  /// (0, 1), (0, 2), ..., (0, Dim), (1, 2), ..., (Dim - 1, Dim) of `nodes`.
  std::array<int, kEdges> springs{};
  double rest_measure = 1.0;  ///< V0 (m^2 in 2D, m^3 in 3D), > 0
  double stiffness = 0.0;     ///< kappa (N/m in 2D, Pa in 3D), >= 0
};

/// Positions of one element's nodes (m).
template <int Dim>
using Corners = std::array<Eigen::Matrix<double, Dim, 1>, Dim + 1>;

/// d f_a / d x_b of one element (N/m), a, b in its node order.
template <int Dim>
using VolumeTermJacobian =
    std::array<std::array<Eigen::Matrix<double, Dim, Dim>, Dim + 1>, Dim + 1>;

/// Signed area (2D: (x1 - x0) x (x2 - x0) / 2) or volume (3D: (x1 - x0) . (x2 - x0) x (x3 - x0)
/// / 6) of a simplex (m^2 or m^3); positive when counter-clockwise (2D) or right-handed (3D).
template <int Dim>
double signed_measure(const Corners<Dim>& x);

/// dV / dx_a of the signed measure, for each node a (m or m^2); they sum to zero.
template <int Dim>
Corners<Dim> signed_measure_gradient(const Corners<Dim>& x);

/// The element's energy W (J) at node positions x.
template <int Dim>
double volume_term_energy(const VolumeTerm<Dim>& term, const Corners<Dim>& x);

/// The forces f_a = -dW/dx_a on its nodes (N).
template <int Dim>
Corners<Dim> volume_term_forces(const VolumeTerm<Dim>& term, const Corners<Dim>& x);

/// d f_a / d x_b = -(kappa / V0) (g_a g_b^T + (V - V0) d^2V / dx_a dx_b), g = dV/dx.
/// \param definite  keep only the Gauss-Newton part -(kappa / V0) g_a g_b^T, negative
///                  semi-definite whatever the shape, so that backward Euler's matrix stays
///                  symmetric positive definite (the dropped part vanishes at V = V0).
template <int Dim>
VolumeTermJacobian<Dim> volume_term_jacobian(const VolumeTerm<Dim>& term, const Corners<Dim>& x,
                                             bool definite);

/// Whether the element still acts: none of its edge springs is broken.
template <int Dim>
bool volume_term_active(const MassSpringSystem<Dim>& s, const VolumeTerm<Dim>& term);

/// The nodes' positions of `term` among the columns of x (Dim x n).
template <int Dim>
Corners<Dim> corners_of(const VolumeTerm<Dim>& term,
                        const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x);

/// Adds the forces of every active term of `s` at positions x to f (N), Dim x n each.
/// Nothing in 1D.
template <int Dim>
void accumulate_volume_term_forces(const MassSpringSystem<Dim>& s,
                                   const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x,
                                   Eigen::Matrix<double, Dim, Eigen::Dynamic>& f);

/// Energy of every active term of `s` at its positions s.x (J). 0 in 1D.
template <int Dim>
double volume_terms_energy(const MassSpringSystem<Dim>& s);

/// Calls visit(a, b, block) with block = d f_a / d x_b (definite as volume_term_jacobian())
/// of every active term of `s` at positions x, a and b node indices of `s`, for all
/// (Dim + 1)^2 ordered pairs of its nodes. Nothing in 1D.
template <int Dim, class Visit>
void for_each_volume_term_block(const MassSpringSystem<Dim>& s,
                                const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x, bool definite,
                                Visit&& visit) {
  if constexpr (Dim >= 2) {
    for (const VolumeTerm<Dim>& term : s.volume_terms) {
      if (!volume_term_active(s, term)) continue;
      const VolumeTermJacobian<Dim> jac = volume_term_jacobian(term, corners_of(term, x), definite);
      for (int a = 0; a <= Dim; ++a)
        for (int b = 0; b <= Dim; ++b) visit(term.nodes[a], term.nodes[b], jac[a][b]);
    }
  }
}

/// A material's Lame constants and how an object made of it splits them: springs that carry
/// all of mu (and so, as every central-spring network does, lambda_springs = mu) and volume
/// terms that add lambda - mu.
struct LameSplit {
  double mu = 0.0;                ///< shear modulus (N/m in 2D, Pa in 3D)
  double lambda = 0.0;            ///< lambda (2D: the plane-stress sheet's E nu / (1 - nu^2))
  double network_youngs = 0.0;    ///< E of the spring network with Lame constants mu, mu
  double volume_stiffness = 0.0;  ///< kappa = lambda - mu, 0 for the network's own ratio
  /// P-wave speed sqrt((lambda + 2 mu) / rho) (m/s)
  double p_wave_speed = 0.0;
};

/// The split of `material` in Dim = 2 or 3 dimensions. Without a Poisson's ratio (NaN) it is
/// the network's own (1/3 in 2D, 1/4 in 3D) and kappa = 0.
/// \throws MaterialError for a Poisson's ratio that is not NaN and outside [1/3, 1) (2D) or
///         [1/4, 1/2) (3D): below, the term would need a negative stiffness (unstable), and
///         1 (2D) or 1/2 (3D) is an incompressible material, which has no finite lambda.
template <int Dim>
LameSplit lame_split(const Material& material);

/// Adds the area (2D) or volume (3D) term of stiffness `stiffness` of every element of a mesh
/// whose edges are springs of `s` (make_mass_spring() does this for a Material with a
/// Poisson's ratio), with rest measures from rest positions `rest` (Dim x n), and raises
/// s.wave_speed to sqrt(c_s^2 + c_v^2): c_s its value for the springs, c_v the speed that
/// gives the terms' stiffest mode the same CFL limit L_min / c_v, from a Gershgorin bound of
/// their stiffness at rest. Elements are given as their node indices.
/// \throws ObjectError if an element's edge is not a spring of `s`, or its rest measure is
///         not positive.
template <int Dim>
void add_volume_terms(MassSpringSystem<Dim>& s,
                      const std::vector<std::array<int, Dim + 1>>& elements,
                      const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest, double stiffness);

}  // namespace gencoord::deformable
