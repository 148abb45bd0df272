// SPDX-License-Identifier: BSD-3-Clause
// Mass-spring object from a simplex mesh: lumped masses, k = c^2 m / L, then calibrated to
// the material (lattice_elasticity.hpp), with area or volume terms for a Poisson's ratio
// above the network's (volume_terms.hpp).
#include "gencoord/deformable/mesh_to_springs.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>
#include <vector>

#include "gencoord/deformable/continuum_elements.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/lattice_elasticity.hpp"
#include "gencoord/deformable/validate.hpp"
#include "gencoord/deformable/volume_terms.hpp"

namespace gencoord::deformable {

template <int Dim>
MassSpringSystem<Dim> make_mass_spring(const SimplexMesh<Dim>& mesh, const Material& material) {
  validate_mesh(mesh);
  validate_material(material);
  const bool continuum = material.elasticity == Elasticity::kCorotated;
  // the springs carry mu (all of it) and as much lambda; the terms add lambda - mu
  const LameSplit split = continuum ? LameSplit{} : lame_split<Dim>(material);
  const std::array<double, 2> lame =
      continuum ? continuum_lame<Dim>(material) : std::array<double, 2>{};
  constexpr int kNodesPerElement = Dim + 1;
  constexpr int kEdgesPerElement = (Dim + 1) * Dim / 2;
  const int count = static_cast<int>(mesh.nodes.cols());
  const double rho = material.density;
  const double c = material.wave_speed();

  MassSpringSystem<Dim> s;
  s.x = mesh.nodes;
  s.v = Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, count);
  s.mass = Eigen::VectorXd::Zero(count);
  s.pinned.assign(count, 0);
  s.wave_speed = c;

  // each element shares its mass equally among its nodes and among its edges
  std::vector<std::tuple<int, int, double>> edge_mass;
  edge_mass.reserve(mesh.elements.size() * kEdgesPerElement);
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) {
    const auto& el = mesh.elements[e];
    const double m = rho * element_measure(mesh, e);
    for (int a = 0; a < kNodesPerElement; ++a) {
      s.mass(el[a]) += m / kNodesPerElement;
      for (int b = a + 1; b < kNodesPerElement; ++b) {
        edge_mass.emplace_back(std::min(el[a], el[b]), std::max(el[a], el[b]),
                               m / kEdgesPerElement);
      }
    }
  }
  std::sort(edge_mass.begin(), edge_mass.end());

  // one spring per unique edge, with the mass summed over the elements sharing it
  for (size_t a = 0; a < edge_mass.size();) {
    const int i = std::get<0>(edge_mass[a]), j = std::get<1>(edge_mass[a]);
    double m = 0.0;
    for (; a < edge_mass.size() && std::get<0>(edge_mass[a]) == i && std::get<1>(edge_mass[a]) == j;
         ++a) {
      m += std::get<2>(edge_mass[a]);
    }
    Spring sp;
    sp.i = i;
    sp.j = j;
    sp.params.rest_length = (mesh.nodes.col(j) - mesh.nodes.col(i)).norm();
    sp.params.stiffness = c * c * m / sp.params.rest_length;
    sp.params.damping = material.damping * m / (rho * sp.params.rest_length);
    s.springs.push_back(sp);
  }
  if (continuum) {
    // the edges stay as springs without stiffness: rest lengths for the CFL limit, fracture
    // and contact; the elements carry the material
    for (Spring& sp : s.springs) sp.params.stiffness = sp.params.damping = 0.0;
    add_continuum_elements(s, mesh.elements, mesh.nodes, lame[0], lame[1],
                           material.damping / material.youngs_modulus);
    s.wave_speed = 0.5 * min_rest_length(s) * continuum_highest_frequency(s);
    return s;
  }
  // the network's own modulus is rho c^2 / 3 (2D) or / 6 (3D); lattice_elasticity.hpp
  double measure = 0.0;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e)
    measure += element_measure(mesh, e);
  const double largest = calibrate_springs(s, mesh.nodes, measure, split.network_youngs);
  s.wave_speed = c * std::sqrt(largest);  // the fastest spring's sqrt(k L / m), for the CFL limit
  if (split.volume_stiffness > 0.0)
    add_volume_terms(s, mesh.elements, mesh.nodes, split.volume_stiffness);
  return s;
}

template <int Dim>
MassSpringSystem<Dim> make_mass_spring(const QuadraticMesh<Dim>& mesh, const Material& material) {
  validate_mesh(mesh);
  validate_material(material);
  if (material.elasticity != Elasticity::kCorotated)
    throw MaterialError(
        "material: a quadratic mesh carries quadratic continuum elements; set the material's "
        "elasticity to Elasticity::kCorotated (springs need the linear mesh)");
  const std::array<double, 2> lame = continuum_lame<Dim>(material);
  // HRZ lumping: the consistent mass matrix's diagonal, int N_a^2, is V/30 (corner) and 8 V/45
  // (midpoint) for a triangle, V/70 and 8 V/105 for a tetrahedron, scaled to sum to the mass
  const double corner_share = Dim == 2 ? 1.0 / 19.0 : 1.0 / 36.0;
  const double midpoint_share = Dim == 2 ? 16.0 / 57.0 : 4.0 / 27.0;
  const int count = static_cast<int>(mesh.nodes.cols());
  MassSpringSystem<Dim> s;
  s.x = mesh.nodes;
  s.v = Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, count);
  s.mass = Eigen::VectorXd::Zero(count);
  s.pinned.assign(count, 0);
  std::vector<std::pair<int, int>> pairs;
  constexpr int kNodes = QuadraticMesh<Dim>::kNodes;
  for (const auto& el : mesh.elements) {
    Corners<Dim> corners;
    for (int a = 0; a <= Dim; ++a) corners[a] = mesh.nodes.col(el[a]);
    const double m = material.density * std::abs(signed_measure<Dim>(corners));
    for (int a = 0; a < kNodes; ++a) {
      s.mass(el[a]) += m * (a <= Dim ? corner_share : midpoint_share);
      for (int b = a + 1; b < kNodes; ++b)
        pairs.emplace_back(std::min(el[a], el[b]), std::max(el[a], el[b]));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  for (const auto& [i, j] : pairs) {
    Spring sp;
    sp.i = i;
    sp.j = j;
    sp.params.rest_length = (mesh.nodes.col(j) - mesh.nodes.col(i)).norm();
    sp.params.stiffness = sp.params.damping = 0.0;
    s.springs.push_back(sp);
  }
  add_quadratic_elements(s, mesh.elements, mesh.nodes, lame[0], lame[1],
                         material.damping / material.youngs_modulus);
  s.wave_speed = 0.5 * min_rest_length(s) * continuum_highest_frequency(s);
  return s;
}

template <int Dim>
int pin_nodes_where(MassSpringSystem<Dim>& s, int axis, double value, double tolerance) {
  int pinned = 0;
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (std::abs(s.x(axis, n) - value) <= tolerance) {
      s.pinned[n] = 1;
      ++pinned;
    }
  }
  return pinned;
}

template MassSpringSystem<2> make_mass_spring<2>(const SimplexMesh<2>&, const Material&);
template MassSpringSystem<3> make_mass_spring<3>(const SimplexMesh<3>&, const Material&);
template MassSpringSystem<2> make_mass_spring<2>(const QuadraticMesh<2>&, const Material&);
template MassSpringSystem<3> make_mass_spring<3>(const QuadraticMesh<3>&, const Material&);
template int pin_nodes_where<1>(MassSpringSystem<1>&, int, double, double);
template int pin_nodes_where<2>(MassSpringSystem<2>&, int, double, double);
template int pin_nodes_where<3>(MassSpringSystem<3>&, int, double, double);

}  // namespace gencoord::deformable
