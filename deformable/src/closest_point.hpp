// SPDX-License-Identifier: BSD-3-Clause
// The closest point of a segment or a triangle to a point, as barycentric weights of its
// corners. Private to the library (contact_forces.cpp).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>

namespace gencoord::deformable::detail {

/// Weights (w0, w1), w0 + w1 = 1, of the point of segment [a, b] closest to p.
template <int Dim>
std::array<double, 2> closest_on_segment(const Eigen::Matrix<double, Dim, 1>& p,
                                         const Eigen::Matrix<double, Dim, 1>& a,
                                         const Eigen::Matrix<double, Dim, 1>& b) {
  const Eigen::Matrix<double, Dim, 1> ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return {1.0 - t, t};
}

/// Weights (w0, w1, w2), summing to 1 and each >= 0, of the point of triangle (a, b, c)
/// closest to p: the projection when it falls inside, else the closest point of the nearest
/// edge or corner (the Voronoi regions of the corners and edges are tested in turn).
inline std::array<double, 3> closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                 const Eigen::Vector3d& b,
                                                 const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};  // corner a
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};  // corner b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {  // edge ab
    const double t = d1 / (d1 - d3);
    return {1.0 - t, t, 0.0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};  // corner c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {  // edge ac
    const double t = d2 / (d2 - d6);
    return {1.0 - t, 0.0, t};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {  // edge bc
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - t, t};
  }
  const double sum = va + vb + vc;           // inside: barycentric coordinates of the projection
  if (!(sum > 0.0)) return {1.0, 0.0, 0.0};  // a degenerate triangle: its first corner
  return {va / sum, vb / sum, vc / sum};
}

}  // namespace gencoord::deformable::detail
