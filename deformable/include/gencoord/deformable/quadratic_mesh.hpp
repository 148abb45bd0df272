// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file quadratic_mesh.hpp
/// Quadratic triangles (6 nodes) and tetrahedra (10 nodes): a simplex mesh with a node at the
/// middle of every edge, for the quadratic continuum elements (quadratic_elements.hpp).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "gencoord/deformable/mesh.hpp"

namespace gencoord::deformable {

/// A straight-sided quadratic simplex mesh. Each element lists its Dim + 1 corners, then the
/// midpoints of its edges in the order (0, 1), (0, 2), ..., (0, Dim), (1, 2), ..., (Dim - 1,
/// Dim) of its corners.
template <int Dim>
struct QuadraticMesh {
  static constexpr int kNodes = (Dim + 1) * (Dim + 2) / 2;
  Eigen::Matrix<double, Dim, Eigen::Dynamic> nodes;  ///< rest positions (m), Dim x n
  std::vector<std::array<int, kNodes>> elements;
};

/// The quadratic mesh of `mesh`: its nodes (same indices), then one node at the middle of each
/// of its edges, in the order of mesh_edges().
/// \throws MeshError for a mesh that validate_mesh() refuses.
template <int Dim>
QuadraticMesh<Dim> quadratic_mesh(const SimplexMesh<Dim>& mesh);

/// The linear simplices on the same nodes that tile each quadratic element: 4 triangles or 8
/// tetrahedra (the inner octahedron cut along its shortest diagonal), each positively
/// oriented at the rest positions. What draws the object, writes it to ParaView and finds its
/// boundary for contact (boundary_triangles(), boundary_segments()).
SimplexMesh<2> subdivided_mesh(const QuadraticMesh<2>& mesh);
SimplexMesh<3> subdivided_mesh(const QuadraticMesh<3>& mesh);

}  // namespace gencoord::deformable
