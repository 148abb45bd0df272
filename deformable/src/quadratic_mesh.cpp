// SPDX-License-Identifier: BSD-3-Clause
// Quadratic meshes: midpoint nodes on every edge, and the linear simplices that tile each
// quadratic element (quadratic_mesh.hpp).
#include "gencoord/deformable/quadratic_mesh.hpp"

#include <algorithm>
#include <utility>

#include "gencoord/deformable/validate.hpp"
#include "gencoord/deformable/volume_terms.hpp"

namespace gencoord::deformable {

namespace {

// the simplex with its last two nodes exchanged when its rest measure is negative
template <int Dim>
std::array<int, Dim + 1> oriented(std::array<int, Dim + 1> simplex,
                                  const Eigen::Matrix<double, Dim, Eigen::Dynamic>& nodes) {
  Corners<Dim> corners;
  for (int a = 0; a <= Dim; ++a) corners[a] = nodes.col(simplex[a]);
  if (signed_measure<Dim>(corners) < 0.0) std::swap(simplex[Dim - 1], simplex[Dim]);
  return simplex;
}

}  // namespace

template <int Dim>
QuadraticMesh<Dim> quadratic_mesh(const SimplexMesh<Dim>& mesh) {
  validate_mesh(mesh);
  const std::vector<std::pair<int, int>> edges = mesh_edges(mesh);
  const int corners = static_cast<int>(mesh.nodes.cols());
  QuadraticMesh<Dim> out;
  out.nodes.resize(Dim, corners + static_cast<int>(edges.size()));
  out.nodes.leftCols(corners) = mesh.nodes;
  for (int k = 0; k < static_cast<int>(edges.size()); ++k)
    out.nodes.col(corners + k) =
        0.5 * (mesh.nodes.col(edges[k].first) + mesh.nodes.col(edges[k].second));
  auto midpoint = [&](int i, int j) {
    const auto it = std::lower_bound(edges.begin(), edges.end(),
                                     std::make_pair(std::min(i, j), std::max(i, j)));
    return corners + static_cast<int>(it - edges.begin());
  };
  out.elements.reserve(mesh.elements.size());
  for (const auto& el : mesh.elements) {
    std::array<int, QuadraticMesh<Dim>::kNodes> q;
    int m = 0;
    for (int a = 0; a <= Dim; ++a) q[m++] = el[a];
    for (int a = 0; a <= Dim; ++a)
      for (int b = a + 1; b <= Dim; ++b) q[m++] = midpoint(el[a], el[b]);
    out.elements.push_back(q);
  }
  return out;
}

SimplexMesh<2> subdivided_mesh(const QuadraticMesh<2>& mesh) {
  SimplexMesh<2> out;
  out.nodes = mesh.nodes;
  for (const auto& q : mesh.elements) {
    // corners 0, 1, 2; midpoints 3 = (0, 1), 4 = (0, 2), 5 = (1, 2)
    const int n0 = q[0], n1 = q[1], n2 = q[2], m01 = q[3], m02 = q[4], m12 = q[5];
    for (const std::array<int, 3>& t :
         {std::array<int, 3>{n0, m01, m02}, {n1, m12, m01}, {n2, m02, m12}, {m01, m12, m02}})
      out.elements.push_back(oriented<2>(t, mesh.nodes));
  }
  return out;
}

SimplexMesh<3> subdivided_mesh(const QuadraticMesh<3>& mesh) {
  SimplexMesh<3> out;
  out.nodes = mesh.nodes;
  for (const auto& q : mesh.elements) {
    // corners 0..3; midpoints 4 = (0, 1), 5 = (0, 2), 6 = (0, 3), 7 = (1, 2), 8 = (1, 3),
    // 9 = (2, 3)
    const int m01 = q[4], m02 = q[5], m03 = q[6], m12 = q[7], m13 = q[8], m23 = q[9];
    for (const std::array<int, 4>& t : {std::array<int, 4>{q[0], m01, m02, m03},
                                        {q[1], m01, m12, m13},
                                        {q[2], m02, m12, m23},
                                        {q[3], m03, m13, m23}})
      out.elements.push_back(oriented<3>(t, mesh.nodes));
    // the inner octahedron: three diagonals join opposite midpoints (of edges sharing no
    // corner); the shortest makes the best-shaped four tetrahedra
    const std::array<std::array<int, 2>, 3> diagonals{{{m01, m23}, {m02, m13}, {m03, m12}}};
    int axis = 0;
    for (int d = 1; d < 3; ++d) {
      const auto length = [&](int k) {
        return (mesh.nodes.col(diagonals[k][0]) - mesh.nodes.col(diagonals[k][1])).squaredNorm();
      };
      if (length(d) < length(axis)) axis = d;
    }
    // around the axis, the other two diagonals' ends alternate: a, b, a', b'
    const auto& a = diagonals[(axis + 1) % 3];
    const auto& b = diagonals[(axis + 2) % 3];
    const std::array<int, 4> ring{a[0], b[0], a[1], b[1]};
    for (int k = 0; k < 4; ++k)
      out.elements.push_back(oriented<3>(
          {diagonals[axis][0], diagonals[axis][1], ring[k], ring[(k + 1) % 4]}, mesh.nodes));
  }
  return out;
}

template QuadraticMesh<2> quadratic_mesh<2>(const SimplexMesh<2>&);
template QuadraticMesh<3> quadratic_mesh<3>(const SimplexMesh<3>&);

}  // namespace gencoord::deformable
