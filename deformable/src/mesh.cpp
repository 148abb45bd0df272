// SPDX-License-Identifier: BSD-3-Clause
// Procedural rectangle, disk and box meshes.
#include "gencoord/deformable/mesh.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include "pi.hpp"

namespace gencoord::deformable {

namespace {
using detail::kPi;
}  // namespace

SimplexMesh<2> rectangle_mesh(double width, double height, int nx, int ny, DiagonalPattern pattern,
                              double x0, double y0) {
  if (nx < 1 || ny < 1) throw std::invalid_argument("rectangle_mesh: need nx, ny >= 1");
  SimplexMesh<2> mesh;
  mesh.nodes.resize(2, (nx + 1) * (ny + 1));
  auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      mesh.nodes.col(id(i, j)) << x0 + width * i / nx, y0 + height * j / ny;
    }
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      const bool rising = pattern == DiagonalPattern::kUniform || (i + j) % 2 == 0;
      if (rising) {  // diagonal a-c
        mesh.elements.push_back({a, b, c});
        mesh.elements.push_back({a, c, d});
      } else {  // diagonal b-d
        mesh.elements.push_back({a, b, d});
        mesh.elements.push_back({b, c, d});
      }
    }
  }
  return mesh;
}

SimplexMesh<2> disk_mesh(double radius, int rings, const Eigen::Vector2d& center) {
  if (rings < 1) throw std::invalid_argument("disk_mesh: need rings >= 1");
  SimplexMesh<2> mesh;
  const int count = 1 + 3 * rings * (rings + 1);  // 1 + sum of 6 k
  mesh.nodes.resize(2, count);
  mesh.nodes.col(0) = center;
  std::vector<int> first(rings + 1, 0);  // index of the first node of each ring
  int next = 1;
  for (int k = 1; k <= rings; ++k) {
    first[k] = next;
    const double r = radius * k / rings;
    for (int j = 0; j < 6 * k; ++j) {
      const double theta = 2.0 * kPi * j / (6 * k);
      mesh.nodes.col(next++) = center + r * Eigen::Vector2d(std::cos(theta), std::sin(theta));
    }
  }
  // stitch ring k - 1 (m nodes, m = 1 for the centre) to ring k (M nodes) by walking both
  // in angle and always advancing the one whose next node comes first
  for (int k = 1; k <= rings; ++k) {
    const int m = k == 1 ? 1 : 6 * (k - 1), big_m = 6 * k;
    auto inner = [&](int a) { return k == 1 ? 0 : first[k - 1] + a % m; };
    auto outer = [&](int b) { return first[k] + b % big_m; };
    int a = 0, b = 0;
    while (a < (k == 1 ? 0 : m) || b < big_m) {
      const bool advance_inner =
          k > 1 && a < m &&
          (b >= big_m || static_cast<double>(a + 1) / m < static_cast<double>(b + 1) / big_m);
      if (advance_inner) {
        mesh.elements.push_back({inner(a), inner(a + 1), outer(b)});
        ++a;
      } else {
        mesh.elements.push_back({inner(a), outer(b), outer(b + 1)});
        ++b;
      }
    }
  }
  return mesh;
}

SimplexMesh<3> box_mesh(double lx, double ly, double lz, int nx, int ny, int nz,
                        const Eigen::Vector3d& origin) {
  if (nx < 1 || ny < 1 || nz < 1) throw std::invalid_argument("box_mesh: need n >= 1");
  SimplexMesh<3> mesh;
  mesh.nodes.resize(3, (nx + 1) * (ny + 1) * (nz + 1));
  auto id = [nx, ny](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  for (int k = 0; k <= nz; ++k) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) {
        mesh.nodes.col(id(i, j, k)) =
            origin + Eigen::Vector3d(lx * i / nx, ly * j / ny, lz * k / nz);
      }
    }
  }
  // Kuhn split: one tetrahedron per order of the three axes, along the diagonal 000 -> 111 of
  // the cell, mirrored along every axis whose cell index is odd. Neighbouring cells are mirror
  // images across their shared face, so the faces' diagonals match (the mesh conforms), and
  // the edges run along all 13 directions of the cubic lattice rather than 7: calibrated
  // springs can then be isotropic (lattice_elasticity.hpp).
  const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const int cell[3] = {i, j, k};
        auto node = [&](const int(&local)[3]) {
          int at[3];
          for (int a = 0; a < 3; ++a) at[a] = cell[a] + (cell[a] % 2 ? 1 - local[a] : local[a]);
          return id(at[0], at[1], at[2]);
        };
        for (const auto& order : orders) {
          int corner[3] = {0, 0, 0};
          std::array<int, 4> tet;
          tet[0] = node(corner);
          for (int step = 0; step < 3; ++step) {
            corner[order[step]] = 1;
            tet[step + 1] = node(corner);
          }
          mesh.elements.push_back(tet);
        }
      }
    }
  }
  return mesh;
}

template <int Dim>
double element_measure(const SimplexMesh<Dim>& mesh, int e) {
  const auto& el = mesh.elements[e];
  Eigen::Matrix<double, Dim, Dim> edges;
  for (int c = 0; c < Dim; ++c) edges.col(c) = mesh.nodes.col(el[c + 1]) - mesh.nodes.col(el[0]);
  const double factorial = Dim == 2 ? 2.0 : (Dim == 3 ? 6.0 : 1.0);
  return std::abs(edges.determinant()) / factorial;
}

template <int Dim>
std::vector<std::pair<int, int>> mesh_edges(const SimplexMesh<Dim>& mesh) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(mesh.elements.size() * (Dim + 1) * Dim / 2);
  for (const auto& el : mesh.elements) {
    for (int a = 0; a <= Dim; ++a) {
      for (int b = a + 1; b <= Dim; ++b) {
        edges.emplace_back(std::min(el[a], el[b]), std::max(el[a], el[b]));
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

template double element_measure<2>(const SimplexMesh<2>&, int);
template double element_measure<3>(const SimplexMesh<3>&, int);
template std::vector<std::pair<int, int>> mesh_edges<2>(const SimplexMesh<2>&);
template std::vector<std::pair<int, int>> mesh_edges<3>(const SimplexMesh<3>&);

}  // namespace gencoord::deformable
