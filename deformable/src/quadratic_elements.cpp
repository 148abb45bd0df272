// SPDX-License-Identifier: BSD-3-Clause
// Quadratic co-rotated triangles and tetrahedra: shape-function gradients at the quadrature
// points, energy, forces, stiffness and damping summed over them (quadratic_elements.hpp).
#include "gencoord/deformable/quadratic_elements.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <utility>

#include "corotated_point.hpp"
#include "element_edges.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/validate.hpp"
#include "message.hpp"

namespace gencoord::deformable {

using detail::message;

namespace {

template <int Dim>
using Mat = Eigen::Matrix<double, Dim, Dim>;
template <int Dim>
using Vec = Eigen::Matrix<double, Dim, 1>;

template <int Dim>
constexpr int kNodes = QuadraticElement<Dim>::kNodes;
template <int Dim>
constexpr int kPoints = QuadraticElement<Dim>::kPoints;

// The corners (a, b), a < b, of each edge, in the order of the midpoints.
template <int Dim>
constexpr std::array<std::pair<int, int>, Dim*(Dim + 1) / 2> edge_corners() {
  std::array<std::pair<int, int>, Dim*(Dim + 1) / 2> out{};
  int k = 0;
  for (int a = 0; a <= Dim; ++a)
    for (int b = a + 1; b <= Dim; ++b) out[k++] = {a, b};
  return out;
}

// Barycentric coordinates of the degree-2 rule's points (equal weights 1 / (Dim + 1)).
template <int Dim>
std::array<double, Dim + 1> quadrature_point(int q) {
  const double high = Dim == 2 ? 2.0 / 3.0 : (5.0 + 3.0 * std::sqrt(5.0)) / 20.0;
  const double low = (1.0 - high) / Dim;
  std::array<double, Dim + 1> l;
  l.fill(low);
  l[q] = high;
  return l;
}

// grad N_a at barycentric point l, from the gradients of the barycentric coordinates:
// corner a: (4 l_a - 1) grad l_a; midpoint of (a, b): 4 (l_a grad l_b + l_b grad l_a).
template <int Dim>
std::array<Vec<Dim>, kNodes<Dim>> shape_gradients(const std::array<double, Dim + 1>& l,
                                                  const std::array<Vec<Dim>, Dim + 1>& grad_l) {
  std::array<Vec<Dim>, kNodes<Dim>> g;
  for (int a = 0; a <= Dim; ++a) g[a] = (4.0 * l[a] - 1.0) * grad_l[a];
  int m = Dim + 1;
  for (const auto& [a, b] : edge_corners<Dim>())
    g[m++] = 4.0 * (l[a] * grad_l[b] + l[b] * grad_l[a]);
  return g;
}

template <int Dim>
detail::CorotatedConstants constants(const QuadraticElement<Dim>& element) {
  return {element.mu, element.lambda, element.damping_time};
}

// the nodes with corners Dim - 1 and Dim exchanged, the midpoints following their edges
template <int Dim>
std::array<int, kNodes<Dim>> mirrored(const std::array<int, kNodes<Dim>>& nodes) {
  std::array<int, Dim + 1> corner;
  for (int a = 0; a <= Dim; ++a) corner[a] = a;
  std::swap(corner[Dim - 1], corner[Dim]);
  const auto edges = edge_corners<Dim>();
  auto midpoint = [&](int a, int b) {
    for (int k = 0; k < static_cast<int>(edges.size()); ++k)
      if (edges[k] == std::make_pair(std::min(a, b), std::max(a, b))) return nodes[Dim + 1 + k];
    return -1;
  };
  std::array<int, kNodes<Dim>> out;
  for (int a = 0; a <= Dim; ++a) out[a] = nodes[corner[a]];
  for (int k = 0; k < static_cast<int>(edges.size()); ++k)
    out[Dim + 1 + k] = midpoint(corner[edges[k].first], corner[edges[k].second]);
  return out;
}

}  // namespace

template <int Dim>
double quadratic_element_energy(const QuadraticElement<Dim>& element,
                                const QuadraticNodes<Dim>& x) {
  double w = 0.0;
  for (int q = 0; q < kPoints<Dim>; ++q)
    w += detail::energy_density<Dim>(detail::gradient_at<Dim, kNodes<Dim>>(x, element.gradients[q]),
                                     constants(element));
  return element.rest_measure / kPoints<Dim> * w;
}

template <int Dim>
QuadraticNodes<Dim> quadratic_element_forces(const QuadraticElement<Dim>& element,
                                             const QuadraticNodes<Dim>& x,
                                             const QuadraticNodes<Dim>& v) {
  QuadraticNodes<Dim> out;
  for (auto& f : out) f.setZero();
  const double weight = element.rest_measure / kPoints<Dim>;
  for (int q = 0; q < kPoints<Dim>; ++q) {
    const auto& g = element.gradients[q];
    const Mat<Dim> f = detail::gradient_at<Dim, kNodes<Dim>>(x, g);
    Mat<Dim> stress = detail::elastic_stress<Dim>(f, constants(element));
    if (element.damping_time > 0.0)
      stress += detail::damping_stress<Dim>(f, detail::gradient_at<Dim, kNodes<Dim>>(v, g),
                                            constants(element));
    for (int a = 0; a < kNodes<Dim>; ++a) out[a].noalias() -= weight * stress * g[a];
  }
  return out;
}

template <int Dim>
QuadraticJacobian<Dim> quadratic_element_stiffness(const QuadraticElement<Dim>& element,
                                                   const QuadraticNodes<Dim>& x, bool definite) {
  QuadraticJacobian<Dim> out = detail::zero_blocks<Dim, kNodes<Dim>>();
  for (int q = 0; q < kPoints<Dim>; ++q) {
    const auto& g = element.gradients[q];
    detail::add_stiffness<Dim, kNodes<Dim>>(detail::gradient_at<Dim, kNodes<Dim>>(x, g),
                                            constants(element), element.rest_measure / kPoints<Dim>,
                                            g, definite, out);
  }
  return out;
}

template <int Dim>
QuadraticJacobian<Dim> quadratic_element_damping(const QuadraticElement<Dim>& element,
                                                 const QuadraticNodes<Dim>& x) {
  QuadraticJacobian<Dim> out = detail::zero_blocks<Dim, kNodes<Dim>>();
  if (element.damping_time == 0.0) return out;
  for (int q = 0; q < kPoints<Dim>; ++q) {
    const auto& g = element.gradients[q];
    detail::add_damping<Dim, kNodes<Dim>>(detail::gradient_at<Dim, kNodes<Dim>>(x, g),
                                          constants(element), element.rest_measure / kPoints<Dim>,
                                          g, out);
  }
  return out;
}

template <int Dim>
bool quadratic_element_active(const MassSpringSystem<Dim>& s,
                              const QuadraticElement<Dim>& element) {
  return detail::no_spring_broken(s, element);
}

template <int Dim>
QuadraticNodes<Dim> nodes_of(const QuadraticElement<Dim>& element,
                             const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x) {
  return detail::gather<Dim>(element.nodes, x);
}

template <int Dim>
void add_quadratic_elements(
    MassSpringSystem<Dim>& s,
    const std::vector<std::array<int, QuadraticMesh<Dim>::kNodes>>& elements,
    const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest, double mu, double lambda,
    double damping_time) {
  const detail::SpringsByPair springs(s.springs);
  const auto edges = edge_corners<Dim>();
  for (int e = 0; e < static_cast<int>(elements.size()); ++e) {
    QuadraticElement<Dim> element;
    element.mu = mu;
    element.lambda = lambda;
    element.damping_time = damping_time;
    element.nodes = elements[e];
    Corners<Dim> corners;
    for (int a = 0; a <= Dim; ++a) corners[a] = rest.col(element.nodes[a]);
    double measure = signed_measure<Dim>(corners);
    if (measure < 0.0) {
      element.nodes = mirrored<Dim>(element.nodes);
      std::swap(corners[Dim - 1], corners[Dim]);
      measure = -measure;
    }
    if (!(measure > 0.0 && std::isfinite(measure)))
      throw ObjectError(message("quadratic elements: element ", e, " has rest measure ", measure,
                                "; need a positive, finite area or volume"),
                        element.nodes[0], -1);
    element.rest_measure = measure;
    for (int k = 0; k < static_cast<int>(edges.size()); ++k) {
      const auto [a, b] = edges[k];
      const int m = element.nodes[Dim + 1 + k];
      const Vec<Dim> middle = 0.5 * (corners[a] + corners[b]);
      if (!((rest.col(m) - middle).norm() <=
            kMaxRelativeMidpointOffset * (corners[b] - corners[a]).norm()))
        throw ObjectError(
            message("quadratic elements: element ", e, "'s node ", m,
                    " is not at the middle of its edge (", element.nodes[a], ", ", element.nodes[b],
                    "); curved elements are not supported: place it at the middle"),
            m, -1);
    }
    int pair = 0;
    for (int a = 0; a < kNodes<Dim>; ++a) {
      for (int b = a + 1; b < kNodes<Dim>; ++b, ++pair) {
        const int i = element.nodes[a], j = element.nodes[b];
        element.springs[pair] = springs.find(i, j);
        if (element.springs[pair] < 0)
          throw ObjectError(message("quadratic elements: element ", e, "'s nodes ", std::min(i, j),
                                    " and ", std::max(i, j),
                                    " are not joined by a spring of the object; every pair "
                                    "needs one"),
                            std::min(i, j), -1);
      }
    }
    // grad l_a: the rows of Dm^-1 for a = 1..Dim, minus their sum for a = 0
    Mat<Dim> dm;
    for (int a = 1; a <= Dim; ++a) dm.col(a - 1) = corners[a] - corners[0];
    const Mat<Dim> inverse = dm.inverse();
    std::array<Vec<Dim>, Dim + 1> grad_l;
    grad_l[0] = Vec<Dim>::Zero();
    for (int a = 1; a <= Dim; ++a) {
      grad_l[a] = inverse.row(a - 1).transpose();
      grad_l[0] -= grad_l[a];
    }
    for (int q = 0; q < kPoints<Dim>; ++q)
      element.gradients[q] = shape_gradients<Dim>(quadrature_point<Dim>(q), grad_l);
    s.quadratic_elements.push_back(element);
  }
}

#define GENCOORD_INSTANTIATE(D)                                                                 \
  template double quadratic_element_energy<D>(const QuadraticElement<D>&,                       \
                                              const QuadraticNodes<D>&);                        \
  template QuadraticNodes<D> quadratic_element_forces<D>(                                       \
      const QuadraticElement<D>&, const QuadraticNodes<D>&, const QuadraticNodes<D>&);          \
  template QuadraticJacobian<D> quadratic_element_stiffness<D>(const QuadraticElement<D>&,      \
                                                               const QuadraticNodes<D>&, bool); \
  template QuadraticJacobian<D> quadratic_element_damping<D>(const QuadraticElement<D>&,        \
                                                             const QuadraticNodes<D>&);         \
  template bool quadratic_element_active<D>(const MassSpringSystem<D>&,                         \
                                            const QuadraticElement<D>&);                        \
  template QuadraticNodes<D> nodes_of<D>(const QuadraticElement<D>&,                            \
                                         const Eigen::Matrix<double, D, Eigen::Dynamic>&);      \
  template void add_quadratic_elements<D>(                                                      \
      MassSpringSystem<D>&, const std::vector<std::array<int, QuadraticMesh<D>::kNodes>>&,      \
      const Eigen::Matrix<double, D, Eigen::Dynamic>&, double, double, double);
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

}  // namespace gencoord::deformable
