// SPDX-License-Identifier: BSD-3-Clause
// Contact forces, their energy and their diagonal Jacobian blocks (collision.hpp). Private to
// the library: accumulate_forces() and potential_energy() add them, and the implicit steps
// take their Jacobians.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "gencoord/deformable/mass_spring_system.hpp"

namespace gencoord::deformable::detail {

/// One node in contact and the force Jacobian blocks on its own diagonal (N/m and N s/m).
template <int Dim>
struct ContactJacobian {
  int node = 0;
  Eigen::Matrix<double, Dim, Dim> d_position;  ///< d f_node / d x_node
  Eigen::Matrix<double, Dim, Dim> d_velocity;  ///< d f_node / d v_node
};

/// Adds the contact forces at positions x and velocities v (Dim x n) to f; nothing when
/// s.collisions is empty.
template <int Dim>
void add_contact_forces(const MassSpringSystem<Dim>& s,
                        const typename MassSpringSystem<Dim>::Points& x,
                        const typename MassSpringSystem<Dim>::Points& v,
                        typename MassSpringSystem<Dim>::Points& f);

/// The penalty potential m omega^2 depth^2 / 2 summed over the contacts at positions x (J).
template <int Dim>
double contact_energy(const MassSpringSystem<Dim>& s,
                      const typename MassSpringSystem<Dim>::Points& x);

/// Diagonal blocks that bound the contact forces' Jacobians at (x, v) from above, one entry per
/// node of each contact (a node may appear several times; the blocks add up). A contact between
/// a node and a surface point c = sum_a w_a x_a has the stiffness K (u u^T) (x) (n n^T), u =
/// (1, -w_0, ...), whose coupling blocks the step matrix's fixed pattern cannot hold; since
/// u u^T <= diag(|u_i| |u|_1) and |u|_1 = 2, the node gets 2 K and corner a gets 2 w_a K (an
/// obstacle's contact, with no corners, K), so the matrix is at least as stiff as the contact in
/// every direction. (The blocks u_i^2 K alone are softer in the node's motion against the
/// surface: with them an implicit drop of one object onto another gains up to 1% of its energy.)
template <int Dim>
std::vector<ContactJacobian<Dim>> contact_jacobians(
    const MassSpringSystem<Dim>& s, const typename MassSpringSystem<Dim>::Points& x,
    const typename MassSpringSystem<Dim>::Points& v);

}  // namespace gencoord::deformable::detail
