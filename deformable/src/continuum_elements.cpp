// SPDX-License-Identifier: BSD-3-Clause
// Co-rotated linear triangles and tetrahedra: energy, forces, exact and projected stiffness,
// strain-rate damping (continuum_elements.hpp).
#include "gencoord/deformable/continuum_elements.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>

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

// Smallest sum of two principal stretches used in the twist eigenvalues 2 / (s_i + s_j): the
// sum vanishes only for an element inverted so far that two stretches cancel, where R jumps.
constexpr double kMinStretchSum = 1e-6;

// F = R S with R a proper rotation and S symmetric, in the principal frame: F = U diag(s) V^T
// with U, V proper rotations, so that R = U V^T; an inverted F has its smallest stretch
// negative. One twist per pair of principal axes (i, j): T = U (e_i e_j^T - e_j e_i^T) V^T /
// sqrt(2), a unit vector of dP/dF's eigenbasis, with dR/dF's eigenvalue 2 / (s_i + s_j).
template <int Dim>
struct Polar {
  static constexpr int kTwists = Dim == 2 ? 1 : 3;
  Mat<Dim> rotation;
  double trace_s = 0.0;  // tr S = sum of the signed stretches
  std::array<Mat<Dim>, kTwists> twists;
  std::array<double, kTwists> stretch_sums{};  // s_i + s_j of each twist's pair
};

Polar<2> polar(const Mat<2>& f) {
  // the rotation nearest to F: angle atan2(F10 - F01, F00 + F11), and tr S the length of
  // that vector, which is s_0 + s_1 (the one twist's pair)
  Polar<2> out;
  const double a = f(0, 0) + f(1, 1), b = f(1, 0) - f(0, 1);
  const double r = std::hypot(a, b);
  const double c = r > 0.0 ? a / r : 1.0, s = r > 0.0 ? b / r : 0.0;
  out.rotation << c, -s, s, c;
  out.trace_s = r;
  Mat<2> turn;
  turn << 0.0, -1.0, 1.0, 0.0;
  out.twists[0] = turn * out.rotation / std::sqrt(2.0);
  out.stretch_sums[0] = r;
  return out;
}

// V by cyclic Jacobi rotations on F^T F (accurate eigenvectors, a few sweeps for 3 x 3), then
// U from the columns of B = F V, which are orthogonal: Gram-Schmidt on the two longest and
// u_2 = u_0 x u_1, so that U is proper and the smallest stretch u_2 . b_2 is negative for an
// inverted F. An element's whole force costs less than Eigen's JacobiSVD of its F alone
// (bench/element_force_bench.cc).
Polar<3> polar(const Mat<3>& f) {
  Mat<3> a = f.transpose() * f;
  Mat<3> v = Mat<3>::Identity();
  constexpr int pairs[3][3] = {{0, 1, 2}, {0, 2, 1}, {1, 2, 0}};  // p, q and the third axis
  for (int sweep = 0; sweep < 10; ++sweep) {
    const double off = a(0, 1) * a(0, 1) + a(0, 2) * a(0, 2) + a(1, 2) * a(1, 2);
    if (!(off > 1e-33 * a.diagonal().squaredNorm())) break;  // also on NaN
    for (const auto& pair : pairs) {
      const int p = pair[0], q = pair[1], r = pair[2];
      const double apq = a(p, q);
      if (apq == 0.0) continue;
      // the rotation J (c, s in (p, q), -s in (q, p)) that zeroes (p, q) of J^T A J (Golub
      // and Van Loan, the symmetric Schur decomposition), applied entry by entry
      const double tau = (a(q, q) - a(p, p)) / (2.0 * apq);
      const double t = std::abs(tau) > 1e150
                           ? 0.5 / tau
                           : std::copysign(1.0, tau) / (std::abs(tau) + std::sqrt(1.0 + tau * tau));
      const double c = 1.0 / std::sqrt(1.0 + t * t), sn = t * c;
      a(p, p) -= t * apq;
      a(q, q) += t * apq;
      a(p, q) = a(q, p) = 0.0;
      const double arp = a(r, p), arq = a(r, q);
      a(r, p) = a(p, r) = c * arp - sn * arq;
      a(r, q) = a(q, r) = sn * arp + c * arq;
      for (int k = 0; k < 3; ++k) {
        const double vkp = v(k, p), vkq = v(k, q);
        v(k, p) = c * vkp - sn * vkq;
        v(k, q) = sn * vkp + c * vkq;
      }
    }
  }
  Mat<3> b = f * v;
  // columns by decreasing length; a swap negates one column to keep V proper
  auto order = [&](int i, int k) {
    if (b.col(i).squaredNorm() >= b.col(k).squaredNorm()) return;
    b.col(i).swap(b.col(k));
    v.col(i).swap(v.col(k));
    b.col(k) *= -1.0;
    v.col(k) *= -1.0;
  };
  order(0, 1);
  order(0, 2);
  order(1, 2);
  Mat<3> u;
  const double n0 = b.col(0).norm();
  u.col(0) = n0 > 0.0 ? Vec<3>(b.col(0) / n0) : Vec<3>::UnitX();
  Vec<3> u1 = b.col(1) - u.col(0).dot(b.col(1)) * u.col(0);
  const double n1 = u1.norm();
  u.col(1) = n1 > 0.0 ? Vec<3>(u1 / n1) : Vec<3>(u.col(0).unitOrthogonal());
  u.col(2) = u.col(0).cross(u.col(1));
  const Vec<3> stretch(n0, u.col(1).dot(b.col(1)), u.col(2).dot(b.col(2)));
  Polar<3> out;
  out.rotation = u * v.transpose();
  out.trace_s = stretch.sum();
  constexpr int twist_pairs[3][2] = {{0, 1}, {1, 2}, {0, 2}};
  for (int t = 0; t < 3; ++t) {
    const int i = twist_pairs[t][0], j = twist_pairs[t][1];
    Mat<3> turn = Mat<3>::Zero();
    turn(i, j) = -1.0;
    turn(j, i) = 1.0;
    out.twists[t] = u * turn * v.transpose() / std::sqrt(2.0);
    out.stretch_sums[t] = stretch(i) + stretch(j);
  }
  return out;
}

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
  const Mat<Dim> f = deformation_gradient(element, x);
  const Polar<Dim> p = polar(f);
  const double volumetric = p.trace_s - Dim;
  return element.rest_measure * (element.mu * (f - p.rotation).squaredNorm() +
                                 0.5 * element.lambda * volumetric * volumetric);
}

template <int Dim>
Corners<Dim> continuum_element_forces(const ContinuumElement<Dim>& element, const Corners<Dim>& x,
                                      const Corners<Dim>& v) {
  const Mat<Dim> f = deformation_gradient(element, x);
  const Polar<Dim> p = polar(f);
  Mat<Dim> stress = 2.0 * element.mu * (f - p.rotation) +
                    element.lambda * (p.trace_s - Dim) * p.rotation;  // P (first Piola)
  if (element.damping_time > 0.0) {
    const Mat<Dim> f_rate = deformation_gradient(element, v);  // F' = Vs Dm^-1
    const Mat<Dim> e_rate = 0.5 * (f.transpose() * f_rate + f_rate.transpose() * f);
    stress += element.damping_time * f *
              (2.0 * element.mu * e_rate + element.lambda * e_rate.trace() * Mat<Dim>::Identity());
  }
  const Corners<Dim> g = shape_gradients(element);
  Corners<Dim> out;
  for (int a = 0; a <= Dim; ++a) out[a] = -element.rest_measure * stress * g[a];
  return out;
}

template <int Dim>
ElementJacobian<Dim> continuum_element_stiffness(const ContinuumElement<Dim>& element,
                                                 const Corners<Dim>& x, bool definite) {
  // dP/dF = 2 mu I + lambda r r^T + sum_t c_t t t^T (r = vec R, t the twists), with
  // c_t = (lambda (tr S - Dim) - 2 mu) 2 / (s_i + s_j) from dR/dF; the twists' eigenvalues
  // are 2 mu + c_t, the others 2 mu and 2 mu + Dim lambda. K_ab = -V0 (dP/dF contracted with
  // g_a and g_b).
  const Polar<Dim> p = polar(deformation_gradient(element, x));
  const Corners<Dim> g = shape_gradients(element);
  const double mu = element.mu, lambda = element.lambda;
  std::array<double, Polar<Dim>::kTwists> weight{};
  for (int t = 0; t < Polar<Dim>::kTwists; ++t) {
    weight[t] =
        (lambda * (p.trace_s - Dim) - 2.0 * mu) * 2.0 / std::max(p.stretch_sums[t], kMinStretchSum);
    if (definite) weight[t] = std::max(weight[t], -2.0 * mu);
  }
  Corners<Dim> rg;
  std::array<Corners<Dim>, Polar<Dim>::kTwists> tg;
  for (int a = 0; a <= Dim; ++a) {
    rg[a] = p.rotation * g[a];
    for (int t = 0; t < Polar<Dim>::kTwists; ++t) tg[t][a] = p.twists[t] * g[a];
  }
  ElementJacobian<Dim> out;
  for (int a = 0; a <= Dim; ++a) {
    for (int b = 0; b <= Dim; ++b) {
      Mat<Dim> h =
          (2.0 * mu * g[a].dot(g[b])) * Mat<Dim>::Identity() + lambda * rg[a] * rg[b].transpose();
      for (int t = 0; t < Polar<Dim>::kTwists; ++t)
        h += weight[t] * tg[t][a] * tg[t][b].transpose();
      out[a][b] = -element.rest_measure * h;
    }
  }
  return out;
}

template <int Dim>
ElementJacobian<Dim> continuum_element_damping(const ContinuumElement<Dim>& element,
                                               const Corners<Dim>& x) {
  // f_a = -V0 F beta (2 mu E' + lambda tr(E') I) g_a with E' = sym(F^T F'), F' = sum v_b g_b^T:
  // d f_a / d v_b = -V0 beta (mu (g_a . g_b) F F^T + mu F g_b (F g_a)^T + lambda F g_a (F g_b)^T)
  ElementJacobian<Dim> out;
  const double beta = element.damping_time;
  const Mat<Dim> f = deformation_gradient(element, x);
  const Corners<Dim> g = shape_gradients(element);
  const Mat<Dim> ff = f * f.transpose();
  Corners<Dim> fg;
  for (int a = 0; a <= Dim; ++a) fg[a] = f * g[a];
  for (int a = 0; a <= Dim; ++a) {
    for (int b = 0; b <= Dim; ++b) {
      out[a][b] = -element.rest_measure * beta *
                  (element.mu * g[a].dot(g[b]) * ff + element.mu * fg[b] * fg[a].transpose() +
                   element.lambda * fg[a] * fg[b].transpose());
    }
  }
  return out;
}

template <int Dim>
bool continuum_element_active(const MassSpringSystem<Dim>& s,
                              const ContinuumElement<Dim>& element) {
  return std::none_of(element.springs.begin(), element.springs.end(),
                      [&](int k) { return s.springs[k].broken; });
}

template <int Dim>
Corners<Dim> corners_of(const ContinuumElement<Dim>& element,
                        const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x) {
  Corners<Dim> out;
  for (int a = 0; a <= Dim; ++a) out[a] = x.col(element.nodes[a]);
  return out;
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
