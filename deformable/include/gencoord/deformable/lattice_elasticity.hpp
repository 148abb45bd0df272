// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file lattice_elasticity.hpp
/// The elastic moduli of a spring network, and springs calibrated to a requested material.
///
/// Under a small uniform strain eps, a spring along the unit vector n with rest length L and
/// stiffness k (force per unit strain) stretches by the strain n . eps n and stores
/// k L (n . eps n)^2 / 2. Summed over the springs of a body of measure V (area or volume), the
/// network's stiffness tensor (the Cauchy-Born, affine estimate) is
///     C_ijkl = (1 / V) sum_s k_s L_s n_i n_j n_k n_l,
/// a fully symmetric tensor: central springs satisfy the Cauchy relations. Its isotropic
/// part is alpha (d_ij d_kl + d_ik d_jl + d_il d_jk) with alpha = sum_s k_s L_s / (V D (D + 2)),
/// i.e. Lame constants lambda = mu = alpha, so that
///     2D:  E = 8 alpha / 3,  Poisson's ratio 1/3      3D:  E = 5 alpha / 2,  Poisson's ratio 1/4
/// whatever the mesh: a spring network by itself cannot offer another Poisson's ratio (area
/// or volume terms add the missing lambda: Material::poisson_ratio, volume_terms.hpp). With
/// k = c^2 m / L (m the mass around the spring), sum_s k_s L_s = c^2 rho V, so the plain rule
/// gives E_network = rho c^2 / 3 in 2D and rho c^2 / 6 in 3D: waves at 0.58 c and 0.41 c.
///
/// calibrate_springs() therefore scales every spring by a factor that is a quartic form of its
/// direction, g(n) = 1 + z . phi(n) (phi: the monomials n_x^a n_y^b n_z^c, a + b + c = 4),
/// the smallest change of the k_s L_s (in their own weights) that makes the network's tensor
/// that of the isotropic material with the requested E. On an irregular mesh g is about 3
/// (2D) or 6 (3D) everywhere; on a structured mesh it also removes the lattice's anisotropy
/// where its spring directions allow (a square grid with alternating diagonals, box_mesh()'s
/// mirrored cells, irregular meshes: exactly; a grid whose diagonals all run one way: not,
/// and LatticeElasticity::anisotropy says how much is left).

#include <Eigen/Core>

#include "gencoord/deformable/mass_spring_system.hpp"

namespace gencoord::deformable {

/// A spring network's stiffness (affine estimate) and its isotropic part.
template <int Dim>
struct LatticeElasticity {
  static constexpr int kVoigt = Dim == 2 ? 3 : 6;
  /// C in Voigt notation (2D: xx, yy, xy; 3D: xx, yy, zz, yz, xz, xy), N/m (2D) or Pa (3D)
  Eigen::Matrix<double, kVoigt, kVoigt> voigt;
  double youngs_modulus = 0.0;  ///< of the isotropic part
  double poisson_ratio = 0.0;   ///< of the isotropic part: 1/3 (2D) or 1/4 (3D)
  /// |C - C_iso| / |C_iso| over the full tensors' components: 0 for an isotropic network
  double anisotropy = 0.0;

  /// Young's modulus for uniaxial stress along unit vector `d`: 1 / (d d : C^-1 : d d).
  double youngs_modulus_along(const Eigen::Matrix<double, Dim, 1>& d) const;
};

/// The stiffness of the unbroken springs of `s` over a body of area (2D) or volume (3D)
/// `measure`, at their rest lengths and rest directions `rest` (Dim x n node positions).
template <int Dim>
LatticeElasticity<Dim> lattice_elasticity(const MassSpringSystem<Dim>& s,
                                          const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest,
                                          double measure);

/// Scales the stiffness and damping of every spring of `s` (at rest positions `rest`, body
/// measure `measure`) by g(n), so that the network is the isotropic material of Young's
/// modulus `youngs_modulus` as far as its spring directions allow. Where that would take a
/// factor below a fifth of the uniform one (springs in too few directions, or nearly those of
/// such a lattice), every spring gets the uniform factor instead, which gives the isotropic
/// part its modulus and keeps the mesh's anisotropy (lattice_elasticity() measures it).
/// Returns the largest factor. \throws MaterialError if the stiffness would not be finite.
template <int Dim>
double calibrate_springs(MassSpringSystem<Dim>& s,
                         const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest, double measure,
                         double youngs_modulus);

}  // namespace gencoord::deformable
