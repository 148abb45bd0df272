// SPDX-License-Identifier: BSD-3-Clause
// Co-rotated linear triangles and tetrahedra: energy, forces, exact and projected stiffness,
// strain-rate damping (continuum_elements.hpp).
#include "gencoord/deformable/continuum_elements.hpp"

#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

#include "corotated_point.hpp"
#include "element_edges.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mass_spring_system.hpp"
#include "largest_eigenvalue.hpp"
#include "message.hpp"

namespace gencoord::deformable {

using detail::message;

namespace {

template <int Dim>
using Mat = Eigen::Matrix<double, Dim, Dim>;
template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;

// g_a: the gradients of the element's linear shape functions (1/m)
template <int Dim>
Corners<Dim> shape_gradients(const ContinuumElement<Dim>& element) {
  Corners<Dim> g;
  g[0] = Vec<Dim>::Zero();
  for (int a = 1; a <= Dim; ++a) {
    g[a] = element.rest_inverse.row(a - 1).transpose();
    g[0] -= g[a];
  }
  return g;
}

template <int Dim>
detail::CorotatedConstants constants(const ContinuumElement<Dim>& element) {
  return {element.mu, element.lambda, element.damping_time};
}

}  // namespace

template <int Dim>
std::array<double, 2> continuum_lame(const Material& material) {
  const double nu =
      std::isnan(material.poisson_ratio) ? (Dim == 2 ? 1.0 / 3.0 : 0.25) : material.poisson_ratio;
  const double top = Dim == 2 ? 1.0 : 0.5;
  if (!(nu >= 0.0 && nu < top))
    throw MaterialError(message(
        "material: Poisson's ratio ", nu, " is outside [0, ", Dim == 2 ? "1" : "1/2",
        ") for continuum elements of a ", Dim == 2 ? "2D sheet (plane stress)" : "3D solid", ": ",
        Dim == 2 ? "1" : "1/2",
        " is incompressible (no finite lambda) and a negative ratio is not supported; choose nu "
        "in that range"));
  const double youngs = material.youngs_modulus;
  const double mu = youngs / (2.0 * (1.0 + nu));
  const double lambda =
      Dim == 2 ? youngs * nu / (1.0 - nu * nu) : youngs * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  return {mu, lambda};
}

template <int Dim>
Mat<Dim> deformation_gradient(const ContinuumElement<Dim>& element, const Corners<Dim>& x) {
  Mat<Dim> ds;
  for (int a = 1; a <= Dim; ++a) ds.col(a - 1) = x[a] - x[0];
  return ds * element.rest_inverse;
}

template <int Dim>
double continuum_element_energy(const ContinuumElement<Dim>& element, const Corners<Dim>& x) {
  return element.rest_measure *
         detail::energy_density<Dim>(deformation_gradient(element, x), constants(element));
}

template <int Dim>
Corners<Dim> continuum_element_forces(const ContinuumElement<Dim>& element, const Corners<Dim>& x,
                                      const Corners<Dim>& v) {
  const Mat<Dim> f = deformation_gradient(element, x);
  Mat<Dim> stress = detail::elastic_stress<Dim>(f, constants(element));  // P
  if (element.damping_time > 0.0)                                        // F' = Vs Dm^-1
    stress += detail::damping_stress<Dim>(f, deformation_gradient(element, v), constants(element));
  const Corners<Dim> g = shape_gradients(element);
  Corners<Dim> out;
  for (int a = 0; a <= Dim; ++a) out[a] = -element.rest_measure * stress * g[a];
  return out;
}

template <int Dim>
ElementJacobian<Dim> continuum_element_stiffness(const ContinuumElement<Dim>& element,
                                                 const Corners<Dim>& x, bool definite) {
  ElementJacobian<Dim> out = detail::zero_blocks<Dim, Dim + 1>();
  detail::add_stiffness<Dim, Dim + 1>(deformation_gradient(element, x), constants(element),
                                      element.rest_measure, shape_gradients(element), definite,
                                      out);
  return out;
}

template <int Dim>
ElementJacobian<Dim> continuum_element_damping(const ContinuumElement<Dim>& element,
                                               const Corners<Dim>& x) {
  ElementJacobian<Dim> out = detail::zero_blocks<Dim, Dim + 1>();
  detail::add_damping<Dim, Dim + 1>(deformation_gradient(element, x), constants(element),
                                    element.rest_measure, shape_gradients(element), out);
  return out;
}

template <int Dim>
bool continuum_element_active(const MassSpringSystem<Dim>& s,
                              const ContinuumElement<Dim>& element) {
  return detail::no_spring_broken(s, element);
}

template <int Dim>
Corners<Dim> corners_of(const ContinuumElement<Dim>& element,
                        const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x) {
  return detail::gather<Dim>(element.nodes, x);
}

template <int Dim>
void accumulate_continuum_forces(const MassSpringSystem<Dim>& s,
                                 const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x,
                                 const Eigen::Matrix<double, Dim, Eigen::Dynamic>& v,
                                 Eigen::Matrix<double, Dim, Eigen::Dynamic>& f) {
  if constexpr (Dim >= 2) {
    for (const ContinuumElement<Dim>& element : s.elements) {
      if (!continuum_element_active(s, element)) continue;
      const Corners<Dim> forces =
          continuum_element_forces(element, corners_of(element, x), corners_of(element, v));
      for (int a = 0; a <= Dim; ++a) f.col(element.nodes[a]) += forces[a];
    }
    for (const QuadraticElement<Dim>& element : s.quadratic_elements) {
      if (!quadratic_element_active(s, element)) continue;
      const QuadraticNodes<Dim> forces =
          quadratic_element_forces(element, nodes_of(element, x), nodes_of(element, v));
      for (int a = 0; a < QuadraticElement<Dim>::kNodes; ++a) f.col(element.nodes[a]) += forces[a];
    }
  }
}

template <int Dim>
double continuum_energy(const MassSpringSystem<Dim>& s) {
  double e = 0.0;
  if constexpr (Dim >= 2) {
    for (const ContinuumElement<Dim>& element : s.elements) {
      if (continuum_element_active(s, element))
        e += continuum_element_energy(element, corners_of(element, s.x));
    }
    for (const QuadraticElement<Dim>& element : s.quadratic_elements) {
      if (quadratic_element_active(s, element))
        e += quadratic_element_energy(element, nodes_of(element, s.x));
    }
  }
  return e;
}

template <int Dim>
double continuum_highest_frequency(const MassSpringSystem<Dim>& s) {
  // Lanczos on M^-1/2 K M^-1/2: its Ritz value approaches the largest eigenvalue from below;
  // the margin covers what is left
  constexpr double kMargin = 1.05;
  const int n = Dim * s.num_nodes();
  std::vector<Eigen::Triplet<double>> entries;
  for_each_continuum_block(s, s.x, [&](int a, int b, const Mat<Dim>& k, const Mat<Dim>&) {
    if (s.pinned[a] || s.pinned[b]) return;
    const double scale = std::sqrt(s.mass(a) * s.mass(b));
    for (int r = 0; r < Dim; ++r) {
      for (int c = 0; c < Dim; ++c) {
        entries.emplace_back(Dim * a + r, Dim * b + c, -k(r, c) / scale);
      }
    }
  });
  if (entries.empty()) return 0.0;
  Eigen::SparseMatrix<double> k(n, n);
  k.setFromTriplets(entries.begin(), entries.end());
  return kMargin * std::sqrt(std::max(0.0, detail::largest_eigenvalue(k)));
}

template <int Dim>
void add_continuum_elements(MassSpringSystem<Dim>& s,
                            const std::vector<std::array<int, Dim + 1>>& elements,
                            const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest, double mu,
                            double lambda, double damping_time) {
  const detail::SpringsByPair springs(s.springs);
  for (int e = 0; e < static_cast<int>(elements.size()); ++e) {
    ContinuumElement<Dim> element;
    element.mu = mu;
    element.lambda = lambda;
    element.damping_time = damping_time;
    element.rest_measure =
        detail::place_element<Dim>(springs, elements[e], rest, "continuum elements", e, &element);
    const Corners<Dim> corners = corners_of(element, rest);
    Mat<Dim> dm;
    for (int a = 1; a <= Dim; ++a) dm.col(a - 1) = corners[a] - corners[0];
    element.rest_inverse = dm.inverse();
    s.elements.push_back(element);
  }
}

#define GENCOORD_INSTANTIATE(D)                                                                  \
  template std::array<double, 2> continuum_lame<D>(const Material&);                             \
  template Mat<D> deformation_gradient<D>(const ContinuumElement<D>&, const Corners<D>&);        \
  template double continuum_element_energy<D>(const ContinuumElement<D>&, const Corners<D>&);    \
  template Corners<D> continuum_element_forces<D>(const ContinuumElement<D>&, const Corners<D>&, \
                                                  const Corners<D>&);                            \
  template ElementJacobian<D> continuum_element_stiffness<D>(const ContinuumElement<D>&,         \
                                                             const Corners<D>&, bool);           \
  template ElementJacobian<D> continuum_element_damping<D>(const ContinuumElement<D>&,           \
                                                           const Corners<D>&);                   \
  template double continuum_highest_frequency<D>(const MassSpringSystem<D>&);                    \
  template bool continuum_element_active<D>(const MassSpringSystem<D>&,                          \
                                            const ContinuumElement<D>&);                         \
  template Corners<D> corners_of<D>(const ContinuumElement<D>&,                                  \
                                    const Eigen::Matrix<double, D, Eigen::Dynamic>&);            \
  template void add_continuum_elements<D>(                                                       \
      MassSpringSystem<D>&, const std::vector<std::array<int, D + 1>>&,                          \
      const Eigen::Matrix<double, D, Eigen::Dynamic>&, double, double, double);
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

#define GENCOORD_INSTANTIATE(D)                                                                    \
  template void accumulate_continuum_forces<D>(                                                    \
      const MassSpringSystem<D>&, const Eigen::Matrix<double, D, Eigen::Dynamic>&,                 \
      const Eigen::Matrix<double, D, Eigen::Dynamic>&, Eigen::Matrix<double, D, Eigen::Dynamic>&); \
  template double continuum_energy<D>(const MassSpringSystem<D>&);
GENCOORD_INSTANTIATE(1)
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

}  // namespace gencoord::deformable
