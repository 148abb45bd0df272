// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file stretch_modulus.hpp
/// The Young's modulus a spring network shows in a static stretch, with every node free to
/// relax: the calibration of lattice_elasticity.hpp is the affine estimate, which the nodes
/// near free surfaces do not follow, so a thin strip or bar of few cells is softer than it
/// (its waves a few percent slow). Measuring the network as it is and scaling its springs to
/// the measurement removes that at any resolution, for the direction measured.

#include <Eigen/Core>

#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/mesh.hpp"

namespace gencoord::deformable {

/// Young's modulus of `s` (its unbroken springs, active volume terms and continuum elements) as
/// a bar along
/// `axis`: the nodes within 5%
/// of the length from either end (rest coordinates `rest` along the axis) are moved along it
/// by a small uniform strain eps, everything else relaxes to equilibrium (the springs
/// linearized at rest), and E = (force / cross-section) / eps, the force being what holds
/// the high end zone and the cross-section `measure` (area in 2D, volume in 3D) over the
/// length. For a prismatic body this is uniaxial stress: the
/// sides and the ends are free laterally.
/// \throws ObjectError if nothing carries the stretch from one end to the other, or `rest`
///         has not one column per node of `s`.
template <int Dim>
double stretch_modulus(const MassSpringSystem<Dim>& s,
                       const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest, double measure,
                       int axis);

/// What a relaxed static stretch shows (stretch_response()).
struct StretchResponse {
  double youngs_modulus = 0.0;  ///< as stretch_modulus()
  /// minus the lateral strain over the axial strain, from the least-squares slope of each
  /// lateral displacement across the body over the middle half of its length (averaged over
  /// the lateral axes in 3D)
  double poisson_ratio = 0.0;
};

/// The Young's modulus and Poisson's ratio of `s` in the stretch of stretch_modulus().
/// \throws ObjectError as stretch_modulus().
template <int Dim>
StretchResponse stretch_response(const MassSpringSystem<Dim>& s,
                                 const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest,
                                 double measure, int axis);

/// Scales the stiffness and damping of every spring of `s`, made from `mesh`
/// (make_mass_spring()), and the stiffness of its volume terms, by one factor so that its
/// stretch_modulus() along `axis` is `youngs_modulus`, and its wave speed with them; returns the
/// factor. Meant for slender bodies (strips, bars, beams) stretched along `axis`, their length: it
/// keeps the calibration's isotropy and Poisson's ratio, and makes waves and static stretch along
/// the length those of the material at any resolution (deformable/docs/deformables.md has the
/// figures). \throws ObjectError as stretch_modulus(); MaterialError unless youngs_modulus is
/// positive and finite.
template <int Dim>
double calibrate_to_stretch(MassSpringSystem<Dim>& s, const SimplexMesh<Dim>& mesh,
                            double youngs_modulus, int axis);

}  // namespace gencoord::deformable
