// SPDX-License-Identifier: BSD-3-Clause
// Surfaces of meshes and the contact settings of an object (collision.hpp).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "gencoord/deformable/collision.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mass_spring_system.hpp"

namespace gencoord::deformable {

namespace {

// the faces (Dim-node simplices) found in exactly one element, as oriented by `orient`
template <int Dim, class Orient>
std::vector<std::array<int, Dim>> faces_of_one_element(const SimplexMesh<Dim>& mesh,
                                                       Orient orient) {
  using Face = std::array<int, Dim>;
  std::vector<std::pair<Face, Face>> faces;  // (sorted corners, oriented face)
  faces.reserve(mesh.elements.size() * (Dim + 1));
  for (const auto& element : mesh.elements) {
    for (int opposite = 0; opposite <= Dim; ++opposite) {
      Face face;
      for (int a = 0, k = 0; a <= Dim; ++a) {
        if (a != opposite) face[k++] = element[a];
      }
      Face key = face;
      std::sort(key.begin(), key.end());
      faces.emplace_back(key, orient(face, element[opposite]));
    }
  }
  std::sort(faces.begin(), faces.end());
  std::vector<Face> out;
  for (std::size_t a = 0; a < faces.size();) {
    std::size_t b = a + 1;
    while (b < faces.size() && faces[b].first == faces[a].first) ++b;
    if (b == a + 1) out.push_back(faces[a].second);
    a = b;
  }
  return out;
}

}  // namespace

std::vector<std::array<int, 3>> boundary_triangles(const SimplexMesh<3>& mesh) {
  return faces_of_one_element<3>(mesh, [&](std::array<int, 3> face, int opposite) {
    const Eigen::Vector3d a = mesh.nodes.col(face[0]);
    const Eigen::Vector3d normal = (mesh.nodes.col(face[1]) - a).cross(mesh.nodes.col(face[2]) - a);
    if (normal.dot(mesh.nodes.col(opposite) - a) > 0.0) std::swap(face[1], face[2]);
    return face;
  });
}

std::vector<std::array<int, 2>> boundary_segments(const SimplexMesh<2>& mesh) {
  return faces_of_one_element<2>(mesh, [&](std::array<int, 2> face, int opposite) {
    const Eigen::Vector2d along = mesh.nodes.col(face[1]) - mesh.nodes.col(face[0]);
    const Eigen::Vector2d to_opposite = mesh.nodes.col(opposite) - mesh.nodes.col(face[0]);
    // counter-clockwise around the mesh: the element lies to the left
    if (along.x() * to_opposite.y() - along.y() * to_opposite.x() < 0.0)
      std::swap(face[0], face[1]);
    return face;
  });
}

template <int Dim>
Collisions<Dim>& enable_collisions(MassSpringSystem<Dim>& s,
                                   std::vector<std::array<int, Dim>> surface, double friction,
                                   double damping_ratio, Sides sides) {
  double shortest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < surface.size(); ++k) {
    for (int a = 0; a < Dim; ++a) {
      const int n = surface[k][a];
      if (n < 0 || n >= s.num_nodes()) {
        std::ostringstream message;
        message << "collisions: surface simplex " << k << " has node " << n << ", but the object "
                << "has " << s.num_nodes() << " nodes; give indices of the object's nodes";
        throw ObjectError(message.str(), n, -1);
      }
      for (int b = a + 1; b < Dim; ++b) {
        if (surface[k][b] == n) {
          std::ostringstream message;
          message << "collisions: surface simplex " << k << " repeats node " << n
                  << "; give each simplex distinct corners";
          throw ObjectError(message.str(), n, -1);
        }
      }
    }
    // every corner is in range now
    for (int a = 0; a < Dim; ++a) {
      for (int b = a + 1; b < Dim; ++b)
        shortest = std::min(shortest, (s.x.col(surface[k][b]) - s.x.col(surface[k][a])).norm());
    }
  }
  Collisions<Dim> c;
  c.params.omega = 0.5 * s.wave_speed / min_rest_length(s);
  c.params.damping_ratio = damping_ratio;
  c.params.friction = friction;
  c.params.thickness = surface.empty() ? 0.0 : 0.25 * shortest;
  if (sides == Sides::kBoth) c.two_sided.assign(surface.size(), 1);
  c.surface = std::move(surface);
  s.collisions = std::move(c);
  return *s.collisions;
}

template Collisions<2>& enable_collisions<2>(MassSpringSystem<2>&, std::vector<std::array<int, 2>>,
                                             double, double, Sides);
template Collisions<3>& enable_collisions<3>(MassSpringSystem<3>&, std::vector<std::array<int, 3>>,
                                             double, double, Sides);

}  // namespace gencoord::deformable
