// SPDX-License-Identifier: BSD-3-Clause
// The degeneracy check of a mesh element or surface triangle, shared by the mesh readers and
// validate.cpp. Private to the library.
#pragma once

#include <Eigen/Core>
#include <string>

namespace gencoord::deformable::detail {

/// A simplex's measure (length, area or volume) and its longest edge. `relative` is the
/// measure over the longest edge to the power Dim, computed from the edges divided by the
/// longest one, so that it does not depend on the scale: coordinates of 1e200 or 1e-200 give
/// the same ratio as coordinates of 1.
struct SimplexShape {
  double measure = 0.0;
  double longest = 0.0;
  double relative = 0.0;
  int dim = 0;
};

/// The shape of the simplex with corner 0 at the origin and the other corners at the columns
/// of `edges` (Dim x Dim).
template <int Dim>
SimplexShape simplex_shape(const Eigen::Matrix<double, Dim, Dim>& edges);

/// The shape of the triangle (0, e1, e2) in 3D (its area).
SimplexShape triangle_shape(const Eigen::Vector3d& e1, const Eigen::Vector3d& e2);

/// Empty when the shape is usable; otherwise what is wrong with it, to follow the element's
/// name: "is degenerate: its volume 0 is not above ... its nodes are (nearly) coplanar", or
/// that its measure is outside the range of a double at this scale. `corners` names its
/// corners in the message ("nodes", "vertices"); `remedy` follows a degenerate one's message.
std::string shape_problem(const SimplexShape& shape, const char* corners, const char* remedy = "");

}  // namespace gencoord::deformable::detail
