// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file mesh.hpp
/// Procedural simplex meshes: triangles in 2D, tetrahedra in 3D. Their edges form a
/// triangulated (chordal) spring graph, so the mass-spring object does not shear freely.

#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

namespace gencoord::deformable {

/// Nodes and simplices (Dim + 1 node indices each).
template <int Dim>
struct SimplexMesh {
  Eigen::Matrix<double, Dim, Eigen::Dynamic> nodes;  ///< rest positions (m), Dim x n
  std::vector<std::array<int, Dim + 1>> elements;
};

/// Triangles in 3D: a sheet (cloth, a membrane) or the boundary of a solid. Each triangle's
/// nodes run counter-clockwise seen from the side its normal points to.
struct TriangleSurface {
  Eigen::Matrix3Xd nodes;  ///< rest positions (m), 3 x n
  std::vector<std::array<int, 3>> triangles;
};

/// How each grid cell of a rectangle is cut into two triangles.
enum class DiagonalPattern {
  kUniform,      ///< every cell cut along the same diagonal (strongly anisotropic)
  kAlternating,  ///< diagonals alternate in a checkerboard (less anisotropic)
};

/// Rectangle [x0, x0 + width] x [y0, y0 + height] cut into nx x ny cells, two triangles each.
SimplexMesh<2> rectangle_mesh(double width, double height, int nx, int ny,
                              DiagonalPattern pattern = DiagonalPattern::kAlternating,
                              double x0 = 0.0, double y0 = 0.0);

/// Disk of `radius` around `center`: a centre node and `rings` concentric rings, ring k
/// holding 6 k nodes, so triangles have roughly equal size (edge about radius / rings).
SimplexMesh<2> disk_mesh(double radius, int rings, const Eigen::Vector2d& center);

/// Box [0, lx] x [0, ly] x [0, lz] + origin cut into nx x ny x nz cubes, each split into the
/// six Kuhn tetrahedra around its main diagonal, each cell the mirror image of its neighbours
/// (conforming across cells; the edges run along all 13 directions of the cubic lattice).
SimplexMesh<3> box_mesh(double lx, double ly, double lz, int nx, int ny, int nz,
                        const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());

/// Area (2D) or volume (3D) of element e of the mesh, positive (m^2 or m^3).
template <int Dim>
double element_measure(const SimplexMesh<Dim>& mesh, int e);

/// Unique edges (i < j) of the mesh, sorted.
template <int Dim>
std::vector<std::pair<int, int>> mesh_edges(const SimplexMesh<Dim>& mesh);

}  // namespace gencoord::deformable
