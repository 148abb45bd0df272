// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file continuum_elements.hpp
/// Continuum elements: linear triangles (2D, plane stress) and tetrahedra (3D) of a co-rotated
/// linear elastic material, the finite-element alternative to the springs.
///
/// An element with rest corners X_0..X_Dim has the rest edge matrix Dm = [X_1 - X_0, ...,
/// X_Dim - X_0] and, at current corners x, the deformation gradient F = Ds Dm^-1 (Ds the same
/// matrix of x), constant over the element. With F = R S its polar decomposition (R a proper
/// rotation, S symmetric; when the element is inverted, S has one negative eigenvalue, the
/// smallest in magnitude, so that R stays the rotation nearest to F) the energy density is
///
///     psi(F) = mu |F - R|^2 + (lambda / 2) (tr S - Dim)^2,
///
/// which is the linear isotropic energy mu eps : eps + (lambda / 2) tr(eps)^2 of the strain
/// eps = S - I, measured in the element's own rotated frame: exact for small strains, free of
/// the spurious stiffening of a rotated linear element, and defined for every F, inverted
/// shapes included, so an inverted element pushes back to the right orientation. The element
/// stores W = V0 psi (V0 its rest area or volume) and pushes node a with f_a = -V0 P g_a,
/// where P = dpsi/dF = 2 mu (F - R) + lambda (tr S - Dim) R and g_a are the gradients of the
/// linear shape functions (the rows of Dm^-1 for a = 1..Dim, minus their sum for a = 0).
///
/// Damping acts on the strain rate E' = sym(F^T F'), so a rigid rotation is not damped: the
/// first Piola stress F beta (2 mu E' + lambda tr(E') I), beta = D / E (the material's damping
/// over its Young's modulus), i.e. the elastic stress law applied to the strain rate, exactly
/// as a spring's damping D multiplies its strain rate. It is linear in the velocities.
///
/// The stiffness d f / d x is the exact Hessian of W, written in the eigenvectors of
/// dP/dF: 2 mu on every mode but the twists (the infinitesimal rotations about each pair of
/// principal axes) and R itself; for the implicit steps it is projected to negative
/// semi-definite by clamping the twist eigenvalues at zero, so that the step matrix stays
/// symmetric positive definite whatever the shape.
///
/// Every node pair of an element is one of the object's springs (which, for an object of
/// continuum elements, have zero stiffness and damping and carry only the rest lengths that
/// the CFL limit, fracture and contact use); an element with a broken one exerts nothing from
/// then on, as a volume term.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "gencoord/deformable/material.hpp"
#include "gencoord/deformable/quadratic_elements.hpp"
#include "gencoord/deformable/volume_terms.hpp"

namespace gencoord::deformable {

template <int Dim>
struct MassSpringSystem;

/// One triangle (2D) or tetrahedron (3D) of co-rotated linear material.
template <int Dim>
struct ContinuumElement {
  static constexpr int kNodes = Dim + 1;
  static constexpr int kEdges = Dim * (Dim + 1) / 2;
  /// Node indices, in the order whose signed measure is positive at rest.
  std::array<int, kNodes> nodes{};
  /// Index into MassSpringSystem::springs of the spring along each edge, in the order of
  /// VolumeTerm::springs.
  std::array<int, kEdges> springs{};
  Eigen::Matrix<double, Dim, Dim> rest_inverse =
      Eigen::Matrix<double, Dim, Dim>::Identity();  ///< Dm^-1 (1/m)
  double rest_measure = 1.0;                        ///< V0 (m^2 in 2D, m^3 in 3D), > 0
  double mu = 0.0;                                  ///< shear modulus (N/m in 2D, Pa in 3D), >= 0
  double lambda = 0.0;        ///< Lame's first constant (2D: plane stress), >= 0
  double damping_time = 0.0;  ///< beta = D / E (s), >= 0
};

/// d f_a / d x_b of one element (N/m), or d f_a / d v_b (N s/m), a, b in its node order.
template <int Dim>
using ElementJacobian = VolumeTermJacobian<Dim>;

/// The Lame constants (mu, lambda) of `material` for continuum elements in Dim = 2 (plane
/// stress: lambda = E nu / (1 - nu^2)) or 3 dimensions; a NaN Poisson's ratio is the spring
/// network's own, 1/3 (2D) or 1/4 (3D).
/// \throws MaterialError for a Poisson's ratio outside [0, 1) (2D) or [0, 1/2) (3D).
template <int Dim>
std::array<double, 2> continuum_lame(const Material& material);

/// The element's deformation gradient F = Ds Dm^-1 at node positions x.
template <int Dim>
Eigen::Matrix<double, Dim, Dim> deformation_gradient(const ContinuumElement<Dim>& element,
                                                     const Corners<Dim>& x);

/// The element's elastic energy W = V0 psi(F) (J).
template <int Dim>
double continuum_element_energy(const ContinuumElement<Dim>& element, const Corners<Dim>& x);

/// The elastic and damping forces on its nodes (N) at positions x and velocities v.
template <int Dim>
Corners<Dim> continuum_element_forces(const ContinuumElement<Dim>& element, const Corners<Dim>& x,
                                      const Corners<Dim>& v);

/// d f_a / d x_b of the elastic forces (exact: the Hessian of -W).
/// \param definite  clamp the twist modes' eigenvalues so the blocks are negative
///                  semi-definite (see the file comment).
template <int Dim>
ElementJacobian<Dim> continuum_element_stiffness(const ContinuumElement<Dim>& element,
                                                 const Corners<Dim>& x, bool definite);

/// d f_a / d v_b of the damping forces (exact, as they are linear in v; negative
/// semi-definite). Their dependence on the positions is left out, as the springs' is.
template <int Dim>
ElementJacobian<Dim> continuum_element_damping(const ContinuumElement<Dim>& element,
                                               const Corners<Dim>& x);

/// Whether the element still acts: none of its edge springs is broken.
template <int Dim>
bool continuum_element_active(const MassSpringSystem<Dim>& s, const ContinuumElement<Dim>& element);

/// The nodes' positions of `element` among the columns of x (Dim x n).
template <int Dim>
Corners<Dim> corners_of(const ContinuumElement<Dim>& element,
                        const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x);

/// Adds the forces of every active element of `s`, linear and quadratic, at positions x and
/// velocities v to f (N). Nothing in 1D.
template <int Dim>
void accumulate_continuum_forces(const MassSpringSystem<Dim>& s,
                                 const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x,
                                 const Eigen::Matrix<double, Dim, Eigen::Dynamic>& v,
                                 Eigen::Matrix<double, Dim, Eigen::Dynamic>& f);

/// Elastic energy of every active element of `s`, linear and quadratic, at its positions s.x
/// (J). 0 in 1D.
template <int Dim>
double continuum_energy(const MassSpringSystem<Dim>& s);

/// Calls visit(a, b, stiffness, damping) with the blocks d f_a / d x_b (definite) and
/// d f_a / d v_b of every active element of `s`, linear and quadratic, at positions x, a and b
/// node indices of `s`, for all ordered pairs of its nodes. Nothing in 1D.
template <int Dim, class Visit>
void for_each_continuum_block(const MassSpringSystem<Dim>& s,
                              const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x, Visit&& visit);

/// An estimate from above of the highest angular frequency (1/s) of the elements of `s`
/// about positions s.x, over its free nodes: sqrt of the largest eigenvalue of M^-1 K (K their
/// definite stiffness, M the lumped masses) by Lanczos iterations, raised by a 5% margin that
/// covers what the iterations have not converged (continuum_elements.cpp). Symplectic Euler is
/// stable for dt <= 2 / omega_max; pinning more nodes only lowers it. 0 without elements.
template <int Dim>
double continuum_highest_frequency(const MassSpringSystem<Dim>& s);

/// Adds a continuum element of constants (mu, lambda) and damping time beta for every element
/// of a mesh whose edges are springs of `s` (make_mass_spring() does this for a Material with
/// Elasticity::kCorotated), with rest shapes from rest positions `rest` (Dim x n).
/// \throws ObjectError if an element's edge is not a spring of `s`, or its rest measure is
///         not positive.
template <int Dim>
void add_continuum_elements(MassSpringSystem<Dim>& s,
                            const std::vector<std::array<int, Dim + 1>>& elements,
                            const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest, double mu,
                            double lambda, double damping_time);

template <int Dim, class Visit>
void for_each_continuum_block(const MassSpringSystem<Dim>& s,
                              const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x, Visit&& visit) {
  if constexpr (Dim >= 2) {
    for (const ContinuumElement<Dim>& element : s.elements) {
      if (!continuum_element_active(s, element)) continue;
      const Corners<Dim> corners = corners_of(element, x);
      const ElementJacobian<Dim> k = continuum_element_stiffness(element, corners, true);
      const ElementJacobian<Dim> d = continuum_element_damping(element, corners);
      for (int a = 0; a <= Dim; ++a)
        for (int b = 0; b <= Dim; ++b) visit(element.nodes[a], element.nodes[b], k[a][b], d[a][b]);
    }
    for (const QuadraticElement<Dim>& element : s.quadratic_elements) {
      if (!quadratic_element_active(s, element)) continue;
      const QuadraticNodes<Dim> nodes = nodes_of(element, x);
      const QuadraticJacobian<Dim> k = quadratic_element_stiffness(element, nodes, true);
      const QuadraticJacobian<Dim> d = quadratic_element_damping(element, nodes);
      constexpr int kNodes = QuadraticElement<Dim>::kNodes;
      for (int a = 0; a < kNodes; ++a)
        for (int b = 0; b < kNodes; ++b)
          visit(element.nodes[a], element.nodes[b], k[a][b], d[a][b]);
    }
  }
}

}  // namespace gencoord::deformable
