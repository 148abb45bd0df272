// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file quadratic_elements.hpp
/// Quadratic continuum elements: 6-node triangles (2D, plane stress) and 10-node tetrahedra
/// (3D) of the co-rotated linear material of continuum_elements.hpp.
///
/// A linear element's strain is constant, so it cannot bend without shearing and a beam
/// meshed with a few of them through its depth is far too stiff. A quadratic element's
/// displacement is quadratic, its strain linear, which represents bending: the shape
/// functions in the barycentric coordinates l_a of the straight-sided element are
/// l_a (2 l_a - 1) at corner a and 4 l_a l_b at the midpoint of edge (a, b).
///
/// The energy is the co-rotated density psi(F) integrated by the symmetric degree-2 rule, Dim +
/// 1 points of weight V0 / (Dim + 1) (barycentric (2/3, 1/6, 1/6) and its permutations in
/// 2D; (a, b, b, b), a = (5 + 3 sqrt 5) / 20, b = (5 - sqrt 5) / 20 in 3D), each with its own
/// F = sum_a x_a grad N_a and its own polar decomposition: exact for the stiffness at rest, whose
/// integrand is quadratic, and with no spurious zero-energy mode. Forces, exact and projected
/// stiffness and the strain-rate damping are those of continuum_elements.hpp summed over the
/// points.
///
/// Every node pair of an element is one of the object's springs, without stiffness (rest
/// lengths for the CFL limit, fracture and the step matrix's pattern); an element with a broken
/// one exerts nothing from then on, as a linear element.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "gencoord/deformable/quadratic_mesh.hpp"

namespace gencoord::deformable {

template <int Dim>
struct MassSpringSystem;

/// One 6-node triangle (2D) or 10-node tetrahedron (3D) of co-rotated linear material.
template <int Dim>
struct QuadraticElement {
  static constexpr int kNodes = QuadraticMesh<Dim>::kNodes;
  static constexpr int kPoints = Dim + 1;  ///< quadrature points
  static constexpr int kPairs = kNodes * (kNodes - 1) / 2;
  using Vec = Eigen::Matrix<double, Dim, 1>;
  /// Node indices: the corners, in the order whose signed measure is positive at rest, then the
  /// edges' midpoints in the order of QuadraticMesh.
  std::array<int, kNodes> nodes{};
  /// Index into MassSpringSystem::springs of the spring joining each pair (a, b), a < b, of
  /// `nodes`, in the order (0, 1), (0, 2), ..., (kNodes - 2, kNodes - 1).
  std::array<int, kPairs> springs{};
  /// grad N_a of each node's shape function at each quadrature point, at rest (1/m).
  std::array<std::array<Vec, kNodes>, kPoints> gradients{};
  double rest_measure = 1.0;  ///< V0 (m^2 in 2D, m^3 in 3D), > 0
  double mu = 0.0;            ///< shear modulus (N/m in 2D, Pa in 3D), >= 0
  double lambda = 0.0;        ///< Lame's first constant (2D: plane stress), >= 0
  double damping_time = 0.0;  ///< beta = D / E (s), >= 0
};

/// Positions or velocities of one quadratic element's nodes.
template <int Dim>
using QuadraticNodes = std::array<Eigen::Matrix<double, Dim, 1>, QuadraticElement<Dim>::kNodes>;

/// d f_a / d x_b (N/m) or d f_a / d v_b (N s/m) of one quadratic element, a, b in its node order.
template <int Dim>
using QuadraticJacobian =
    std::array<std::array<Eigen::Matrix<double, Dim, Dim>, QuadraticElement<Dim>::kNodes>,
               QuadraticElement<Dim>::kNodes>;

/// The element's elastic energy W = sum_q w_q psi(F_q) (J) at node positions x.
template <int Dim>
double quadratic_element_energy(const QuadraticElement<Dim>& element, const QuadraticNodes<Dim>& x);

/// The elastic and damping forces on its nodes (N) at positions x and velocities v.
template <int Dim>
QuadraticNodes<Dim> quadratic_element_forces(const QuadraticElement<Dim>& element,
                                             const QuadraticNodes<Dim>& x,
                                             const QuadraticNodes<Dim>& v);

/// d f_a / d x_b of the elastic forces (exact: the Hessian of -W), or with each point's twist
/// modes clamped so that the blocks are negative semi-definite (`definite`).
template <int Dim>
QuadraticJacobian<Dim> quadratic_element_stiffness(const QuadraticElement<Dim>& element,
                                                   const QuadraticNodes<Dim>& x, bool definite);

/// d f_a / d v_b of the damping forces (exact; negative semi-definite).
template <int Dim>
QuadraticJacobian<Dim> quadratic_element_damping(const QuadraticElement<Dim>& element,
                                                 const QuadraticNodes<Dim>& x);

/// Whether the element still acts: none of its springs is broken.
template <int Dim>
bool quadratic_element_active(const MassSpringSystem<Dim>& s, const QuadraticElement<Dim>& element);

/// The nodes' positions of `element` among the columns of x (Dim x n).
template <int Dim>
QuadraticNodes<Dim> nodes_of(const QuadraticElement<Dim>& element,
                             const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x);

/// Adds a quadratic element of constants (mu, lambda) and damping time beta for every element
/// of a quadratic mesh whose node pairs are springs of `s` (make_mass_spring() of a
/// QuadraticMesh does this), with rest shapes from rest positions `rest` (Dim x n).
/// \throws ObjectError if a node pair is not a spring of `s`, the corners' rest measure is
///         not positive, or a midpoint node is not at the middle of its edge at rest (curved
///         elements are not supported).
template <int Dim>
void add_quadratic_elements(
    MassSpringSystem<Dim>& s,
    const std::vector<std::array<int, QuadraticMesh<Dim>::kNodes>>& elements,
    const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest, double mu, double lambda,
    double damping_time);

}  // namespace gencoord::deformable
