// SPDX-License-Identifier: BSD-3-Clause
// Objects by material model, jittered meshes, the relaxed stretch, the cantilever's tip and a
// pulse's speed (figures.hpp).
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "figures.hpp"
#include "gencoord/deformable/continuum_elements.hpp"
#include "gencoord/deformable/mesh_to_springs.hpp"
#include "gencoord/deformable/quadratic_mesh.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "test_helpers.hpp"

namespace gencoord::deformable::validation {

const char* model_name(Model model) {
  switch (model) {
    case Model::kSprings:
      return "springs";
    case Model::kLinear:
      return "linear elements";
    case Model::kQuadratic:
      return "quadratic elements";
  }
  return "?";
}

template <int Dim>
MassSpringSystem<Dim> make_object(const SimplexMesh<Dim>& mesh, Material material, Model model) {
  material.elasticity = model == Model::kSprings ? Elasticity::kSprings : Elasticity::kCorotated;
  return model == Model::kQuadratic ? make_mass_spring(quadratic_mesh(mesh), material)
                                    : make_mass_spring(mesh, material);
}

template <int Dim>
SimplexMesh<Dim> jittered(SimplexMesh<Dim> mesh, double h, double fraction, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> offset(-fraction * h, fraction * h);
  const Eigen::Matrix<double, Dim, 1> low = mesh.nodes.rowwise().minCoeff();
  const Eigen::Matrix<double, Dim, 1> high = mesh.nodes.rowwise().maxCoeff();
  for (int n = 0; n < mesh.nodes.cols(); ++n) {
    for (int axis = 0; axis < Dim; ++axis) {
      const double move = offset(random), p = mesh.nodes(axis, n);
      if (p > low(axis) + 1e-12 && p < high(axis) - 1e-12) mesh.nodes(axis, n) += move;
    }
  }
  return mesh;
}

template <int Dim>
StretchResponse stretch(const SimplexMesh<Dim>& mesh, double youngs, double nu, Model model) {
  Material material{youngs, 1000.0, 0.0};
  material.poisson_ratio = nu;
  const MassSpringSystem<Dim> s = make_object(mesh, material, model);
  double measure = 0.0;
  for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e)
    measure += element_measure(mesh, e);
  return stretch_response(s, s.x, measure, 0);
}

template <int Dim>
double cantilever_tip_ratio(int across, Model model) {
  const double youngs = 1e5, nu = 0.3, length = 1.0, depth = 0.1, load = 1e-3;
  SimplexMesh<Dim> mesh;
  if constexpr (Dim == 2) {
    mesh = rectangle_mesh(length, depth, 10 * across, across);
  } else {
    mesh = box_mesh(length, depth, depth, 10 * across, across, across);
  }
  Material material{youngs, 1000.0, 0.0};
  material.poisson_ratio = nu;
  const MassSpringSystem<Dim> s = make_object(mesh, material, model);
  // unknowns: every coordinate of every node off the clamped end
  std::vector<int> index(Dim * s.num_nodes(), -1), tip;
  int unknowns = 0;
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (s.x(0, n) > 1e-9)
      for (int d = 0; d < Dim; ++d) index[Dim * n + d] = unknowns++;
    if (s.x(0, n) > length - 1e-9) tip.push_back(n);
  }
  std::vector<Eigen::Triplet<double>> entries;
  for_each_continuum_block(s, s.x, [&](int a, int b, const auto& k, const auto&) {
    for (int r = 0; r < Dim; ++r)
      for (int c = 0; c < Dim; ++c) {
        const int i = index[Dim * a + r], j = index[Dim * b + c];
        if (i >= 0 && j >= 0) entries.emplace_back(i, j, -k(r, c));
      }
  });
  Eigen::SparseMatrix<double> stiffness(unknowns, unknowns);
  stiffness.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd force = Eigen::VectorXd::Zero(unknowns);
  for (int n : tip) force(index[Dim * n + Dim - 1]) = -load / tip.size();
  const Eigen::VectorXd u =
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>(stiffness).solve(force);
  double deflection = 0.0;
  for (int n : tip) deflection -= u(index[Dim * n + Dim - 1]) / tip.size();
  const double area = Dim == 2 ? depth : depth * depth;
  const double inertia = area * depth * depth / 12.0, shear = youngs / (2.0 * (1.0 + nu));
  const double timoshenko = load * std::pow(length, 3) / (3.0 * youngs * inertia) +
                            load * length / (5.0 / 6.0 * shear * area);
  return deflection / timoshenko;
}

template <int Dim>
double pulse_speed(const SimplexMesh<Dim>& mesh, double h, const Material& material, Model model,
                   double width, bool stretched) {
  MassSpringSystem<Dim> s = make_object(mesh, material, model);
  if (stretched) calibrate_to_stretch(s, mesh, material.youngs_modulus, 0);
  const double c = material.wave_speed();
  const testing::GaussianPulse pulse{1e-3, 0.6, width, c};
  const double probe_a = 1.2, probe_b = 2.0;
  const Eigen::Matrix<double, Dim, Eigen::Dynamic> rest = s.x;
  std::vector<int> column_a, column_b;
  for (int n = 0; n < s.num_nodes(); ++n) {
    const double px = rest(0, n);
    s.x(0, n) += pulse.displacement(px);
    s.v(0, n) = pulse.velocity(px);
    if (std::abs(px - probe_a) < 0.5 * h) column_a.push_back(n);
    if (std::abs(px - probe_b) < 0.5 * h) column_b.push_back(n);
  }
  if (column_a.empty() || column_b.empty()) return std::numeric_limits<double>::quiet_NaN();
  auto mean_ux = [&](const std::vector<int>& column) {
    double sum = 0.0;
    for (int n : column) sum += s.x(0, n) - rest(0, n);
    return sum / column.size();
  };
  const double dt = 0.5 * cfl_limit(s);
  // up to 1.5 times the time the pulse needs to reach probe b, before the reflection from
  // the far end (which arrives after 3.4 / c) can
  const int steps = static_cast<int>(2.2 / c / dt);
  std::vector<double> at_a, at_b;
  for (int k = 0; k < steps; ++k) {
    symplectic_euler_step(s, dt);
    at_a.push_back(mean_ux(column_a));
    at_b.push_back(mean_ux(column_b));
  }
  return (probe_b - probe_a) / (testing::peak_time(at_b, dt) - testing::peak_time(at_a, dt));
}

#define GENCOORD_INSTANTIATE(D)                                                                 \
  template MassSpringSystem<D> make_object<D>(const SimplexMesh<D>&, Material, Model);          \
  template SimplexMesh<D> jittered<D>(SimplexMesh<D>, double, double, unsigned);                \
  template StretchResponse stretch<D>(const SimplexMesh<D>&, double, double, Model);            \
  template double cantilever_tip_ratio<D>(int, Model);                                          \
  template double pulse_speed<D>(const SimplexMesh<D>&, double, const Material&, Model, double, \
                                 bool);
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

}  // namespace gencoord::deformable::validation
