// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file rod.hpp
/// The 1D elastic rod of lumped masses and strain springs (deformable/docs/deformables.md).
///
/// Rest parameter p in [0, 1] (more generally [p_0, p_n]) with nodes p_0 < p_1 < ... < p_n
/// spaced arbitrarily; the rod starts at rest with x_i = p_i.
///  - lumped masses m_i = rho (p_{i+1} - p_{i-1}) / 2, and at the ends
///    m_0 = rho (p_1 - p_0) / 2, m_n = rho (p_n - p_{n-1}) / 2;
///  - spring i+1/2 between nodes i and i+1 with rest length L = p_{i+1} - p_i, stiffness k = E
///    (force f = E (x_{i+1} - x_i - L) / L) and damping d = D (force D (v_{i+1} - v_i) / L).

#include <cstdint>
#include <vector>

#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/material.hpp"

namespace gencoord::deformable {

/// Builds the rod on the strictly increasing nodes p (size n + 1 >= 2). rho is a linear
/// density (kg/m), E a force (N), D a force times seconds (N s). Nothing is pinned.
MassSpringSystem<1> make_rod(const std::vector<double>& p, const Material& material);

/// n + 1 uniformly spaced nodes on [0, length].
std::vector<double> uniform_rod_nodes(int n, double length = 1.0);

/// n + 1 nodes on [0, length] whose spacings are drawn uniformly from
/// [1 - jitter, 1 + jitter] times the mean (then rescaled to the length); jitter in [0, 1).
std::vector<double> jittered_rod_nodes(int n, double jitter, std::uint64_t seed,
                                       double length = 1.0);

/// n + 1 nodes on [0, length] whose spacings grow geometrically by `ratio` from one interval
/// to the next (ratio > 1: fine at p = 0, coarse at p = length).
std::vector<double> graded_rod_nodes(int n, double ratio, double length = 1.0);

}  // namespace gencoord::deformable
