// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file bending.hpp
/// Bending of a sheet in 3D: one hinge per interior edge (MassSpringSystem::hinges), with the
/// discrete-shells energy (Grinspun et al. 2003, Bridson et al. 2003)
///
///     E_h = kb (theta - theta0)^2,
///
/// theta the dihedral angle across the edge, 0 where the two triangles are coplanar. Its
/// stiffness at the flat state is linear: a small out-of-plane displacement w changes theta to
/// first order. (A "bending spring" between the two opposite nodes is not: their distance
/// changes only quadratically with theta, so it gives no stiffness at the flat state.)
///
/// Geometry. With x0, x1 the edge's nodes, x2, x3 the wings, e = x1 - x0, l = |e|, the
/// triangles' normals nA = e x (x2 - x0) and nB = (x0 - x1) x (x3 - x1) (both the same side of
/// a flat hinge, whatever the triangles' stored orientation), theta is the angle from nA to nB
/// about e: theta = atan2((nA x nB) . e / l, nA . nB), in [-pi, pi]. Its gradient (Bridson et
/// al.'s bending modes) is, with the wings' heights hA = |nA| / l, hB = |nB| / l and their
/// positions along the edge sA = (x2 - x0) . e / l^2, sB = (x3 - x0) . e / l^2,
///
///     d theta / d x2 = -l nA / |nA|^2        (= -unit normal / hA)
///     d theta / d x3 = -l nB / |nB|^2
///     d theta / d x0 = -(1 - sA) d theta / d x2 - (1 - sB) d theta / d x3
///     d theta / d x1 = -sA d theta / d x2 - sB d theta / d x3
///
/// which sum to zero and exert no torque (a rigid motion does not change theta). The force on
/// node k is -2 kb (theta - theta0) d theta / d x_k, the angle difference wrapped into
/// [-pi, pi]. A hinge exerts nothing while its edge's spring is broken, or while one of its
/// triangles has collapsed (zero area or edge length), where theta is not defined.
///
/// Jacobian. d f_a / d x_b = -2 kb (g_a g_b^T + (theta - theta0) d^2 theta / d x_a d x_b)
/// with g = grad theta; the implicit steps keep the first (Gauss-Newton) term,
/// -2 kb g_a g_b^T, which is negative semi-definite, so the step matrix stays symmetric
/// positive definite. It is exact at the rest angle (the flat state of a flat sheet), and
/// what it leaves out is proportional to theta - theta0.
///
/// Time step. The hinges raise the highest frequency. Over the free nodes (masses m_k),
/// omega_b^2 <= max_k sum over hinges h at k of 2 kb_h |g_hk| / sqrt(m_k) sum_j |g_hj| / sqrt(m_j)
/// (block Gershgorin on M^-1/2 K_b M^-1/2), and the squared frequencies of springs and hinges
/// add at most, so the explicit step's limit with both is
/// dt <= 2 / sqrt(omega_s^2 + omega_b^2), omega_s = 2 c_s / L_min the springs'. make_sheet()
/// folds this into MassSpringSystem::wave_speed:
///     wave_speed = sqrt(c_s^2 + (omega_b L_min / 2)^2),
/// so cfl_limit() = L_min / wave_speed is that limit. Computed at the rest shape: recompute it
/// (bending_frequency_bound()) after changing the hinges' stiffness or the masses.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "gencoord/deformable/mass_spring_system.hpp"

namespace gencoord::deformable {

/// The dihedral angle of a hinge at given positions, and its gradient.
struct HingeAngle {
  double angle = 0.0;                       ///< theta (rad), in [-pi, pi]
  std::array<Eigen::Vector3d, 4> gradient;  ///< d theta / d x_k (1/m), k as in Hinge::nodes
  bool degenerate = false;  ///< a triangle or the edge has collapsed: angle 0, gradient 0
};

/// theta and its gradient for edge nodes x0, x1 and wings x2, x3 (see the file comment).
HingeAngle hinge_angle(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                       const Eigen::Vector3d& x2, const Eigen::Vector3d& x3);

/// theta - theta0 wrapped into [-pi, pi] (rad).
double angle_change(double angle, double rest_angle);

/// Whether hinge h of s acts: its edge's spring (if any) is not broken.
template <int Dim>
bool hinge_active(const MassSpringSystem<Dim>& s, const Hinge& h);

/// Energy kb (theta - theta0)^2 of one hinge at positions x (3 x n) (J); 0 if degenerate.
double hinge_energy(const Hinge& h, const Eigen::Matrix3Xd& x);

/// Forces on the hinge's four nodes (N), in the order of Hinge::nodes.
std::array<Eigen::Vector3d, 4> hinge_forces(const Hinge& h, const Eigen::Matrix3Xd& x);

/// The hinge's Jacobian blocks d f_a / d x_b (N/m), a, b in the order of Hinge::nodes: the
/// Gauss-Newton term -2 kb g_a g_b^T (the file comment says why).
std::array<std::array<Eigen::Matrix3d, 4>, 4> hinge_jacobian(const Hinge& h,
                                                             const Eigen::Matrix3Xd& x);

/// Adds the active hinges' forces at positions x to f (N, Dim x n). Does nothing in 1D and
/// 2D (validate_object() refuses hinges there).
template <int Dim>
void accumulate_bending_forces(const MassSpringSystem<Dim>& s,
                               const typename MassSpringSystem<Dim>::Points& x,
                               typename MassSpringSystem<Dim>::Points& f);

/// Energy of the active hinges at positions x (J); 0 in 1D and 2D.
template <int Dim>
double bending_energy(const MassSpringSystem<Dim>& s,
                      const typename MassSpringSystem<Dim>::Points& x);

/// Appends the active hinges' Jacobian blocks (hinge_jacobian()) at positions x to a free-DOF
/// matrix's triplets: dof[n] is node n's first unknown, -1 for a pinned node (left out).
template <int Dim>
void add_bending_jacobian(const MassSpringSystem<Dim>& s,
                          const typename MassSpringSystem<Dim>::Points& x,
                          const std::vector<int>& dof,
                          std::vector<Eigen::Triplet<double>>* triplets);

/// Bound on the hinges' highest angular frequency over the free nodes at s.x (rad/s), the
/// block Gershgorin bound of the file comment; 0 without active hinges.
double bending_frequency_bound(const MassSpringSystem<3>& s);

}  // namespace gencoord::deformable
