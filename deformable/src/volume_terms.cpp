// SPDX-License-Identifier: BSD-3-Clause
// Area and volume terms of simplex elements (volume_terms.hpp).
#include "gencoord/deformable/volume_terms.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <tuple>

#include "element_edges.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/mass_spring_system.hpp"
#include "message.hpp"

namespace gencoord::deformable {

namespace {

template <int Dim>
using Mat = Eigen::Matrix<double, Dim, Dim>;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// d^2 V / dx_a dx_b of the signed measure, a, b in the element's node order. V depends on
// x_0 only through e_k = x_k - x_0, so the row and column of node 0 are minus the sums of
// the others.
template <int Dim>
VolumeTermJacobian<Dim> measure_hessian(const Corners<Dim>& x) {
  VolumeTermJacobian<Dim> h;
  if constexpr (Dim == 2) {
    Mat<2> r;  // d (e1 x e2) / 2 / de1 = R e2 / 2, with R e = (e_y, -e_x)
    r << 0.0, 1.0, -1.0, 0.0;
    h[1][1] = h[2][2] = Mat<2>::Zero();
    h[1][2] = 0.5 * r;
    h[2][1] = -0.5 * r;
  } else {
    // dV/de_a = (e_b x e_c) / 6 for (a, b, c) cyclic; d (e_b x e_c) / de_c = [e_b]_x
    const Eigen::Vector3d e1 = x[1] - x[0], e2 = x[2] - x[0], e3 = x[3] - x[0];
    h[1][1] = h[2][2] = h[3][3] = Mat<3>::Zero();
    h[1][2] = -skew(e3) / 6.0;
    h[1][3] = skew(e2) / 6.0;
    h[2][3] = -skew(e1) / 6.0;
    h[2][1] = h[1][2].transpose();
    h[3][1] = h[1][3].transpose();
    h[3][2] = h[2][3].transpose();
  }
  h[0][0] = Mat<Dim>::Zero();
  for (int a = 1; a <= Dim; ++a) {
    h[a][0] = Mat<Dim>::Zero();
    for (int b = 1; b <= Dim; ++b) h[a][0] -= h[a][b];
    h[0][a] = h[a][0].transpose();
    h[0][0] -= h[a][0];
  }
  return h;
}

using detail::message;

// Speed c_v whose CFL limit L_min / c_v keeps the terms' stiffest mode stable on its own:
// symplectic Euler needs omega dt <= 2, and omega^2 <= max over nodes a of the Gershgorin row
// sum (1 / m_a) sum_{e at a} (kappa_e / V0_e) |g_a| sum_b |g_b| of M^-1 K (K's Gauss-Newton
// part at rest), so c_v = (L_min / 2) sqrt(that maximum).
template <int Dim>
double volume_terms_speed(const MassSpringSystem<Dim>& s,
                          const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest) {
  Eigen::VectorXd row = Eigen::VectorXd::Zero(s.num_nodes());
  for (const VolumeTerm<Dim>& term : s.volume_terms) {
    const Corners<Dim> g = signed_measure_gradient<Dim>(corners_of(term, rest));
    double sum = 0.0;
    for (int b = 0; b <= Dim; ++b) sum += g[b].norm();
    for (int a = 0; a <= Dim; ++a)
      row(term.nodes[a]) += term.stiffness / term.rest_measure * g[a].norm() * sum;
  }
  double largest = 0.0;
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (s.mass(n) > 0.0) largest = std::max(largest, row(n) / s.mass(n));
  }
  return 0.5 * min_rest_length(s) * std::sqrt(largest);
}

}  // namespace

template <int Dim>
double signed_measure(const Corners<Dim>& x) {
  if constexpr (Dim == 2) {
    const Eigen::Vector2d e1 = x[1] - x[0], e2 = x[2] - x[0];
    return 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
  } else {
    return (x[1] - x[0]).dot((x[2] - x[0]).cross(x[3] - x[0])) / 6.0;
  }
}

template <int Dim>
Corners<Dim> signed_measure_gradient(const Corners<Dim>& x) {
  Corners<Dim> g;
  if constexpr (Dim == 2) {
    const Eigen::Vector2d e1 = x[1] - x[0], e2 = x[2] - x[0];
    g[1] = 0.5 * Eigen::Vector2d(e2.y(), -e2.x());
    g[2] = 0.5 * Eigen::Vector2d(-e1.y(), e1.x());
  } else {
    const Eigen::Vector3d e1 = x[1] - x[0], e2 = x[2] - x[0], e3 = x[3] - x[0];
    g[1] = e2.cross(e3) / 6.0;
    g[2] = e3.cross(e1) / 6.0;
    g[3] = e1.cross(e2) / 6.0;
  }
  g[0] = -g[1];
  for (int a = 2; a <= Dim; ++a) g[0] -= g[a];
  return g;
}

template <int Dim>
double volume_term_energy(const VolumeTerm<Dim>& term, const Corners<Dim>& x) {
  const double strain = signed_measure<Dim>(x) / term.rest_measure - 1.0;
  return 0.5 * term.stiffness * term.rest_measure * strain * strain;
}

template <int Dim>
Corners<Dim> volume_term_forces(const VolumeTerm<Dim>& term, const Corners<Dim>& x) {
  const double pressure = term.stiffness * (signed_measure<Dim>(x) / term.rest_measure - 1.0);
  Corners<Dim> f = signed_measure_gradient<Dim>(x);
  for (auto& fa : f) fa *= -pressure;
  return f;
}

template <int Dim>
VolumeTermJacobian<Dim> volume_term_jacobian(const VolumeTerm<Dim>& term, const Corners<Dim>& x,
                                             bool definite) {
  const Corners<Dim> g = signed_measure_gradient<Dim>(x);
  const double scale = term.stiffness / term.rest_measure;
  VolumeTermJacobian<Dim> jac;
  for (int a = 0; a <= Dim; ++a)
    for (int b = 0; b <= Dim; ++b) jac[a][b] = -scale * g[a] * g[b].transpose();
  if (!definite) {
    const double excess = signed_measure<Dim>(x) - term.rest_measure;
    const VolumeTermJacobian<Dim> h = measure_hessian<Dim>(x);
    for (int a = 0; a <= Dim; ++a)
      for (int b = 0; b <= Dim; ++b) jac[a][b] -= scale * excess * h[a][b];
  }
  return jac;
}

template <int Dim>
bool volume_term_active(const MassSpringSystem<Dim>& s, const VolumeTerm<Dim>& term) {
  return detail::no_spring_broken(s, term);
}

template <int Dim>
Corners<Dim> corners_of(const VolumeTerm<Dim>& term,
                        const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x) {
  return detail::gather<Dim>(term.nodes, x);
}

template <int Dim>
void accumulate_volume_term_forces(const MassSpringSystem<Dim>& s,
                                   const Eigen::Matrix<double, Dim, Eigen::Dynamic>& x,
                                   Eigen::Matrix<double, Dim, Eigen::Dynamic>& f) {
  if constexpr (Dim >= 2) {
    for (const VolumeTerm<Dim>& term : s.volume_terms) {
      if (!volume_term_active(s, term)) continue;
      const Corners<Dim> fe = volume_term_forces(term, corners_of(term, x));
      for (int a = 0; a <= Dim; ++a) f.col(term.nodes[a]) += fe[a];
    }
  }
}

template <int Dim>
double volume_terms_energy(const MassSpringSystem<Dim>& s) {
  double e = 0.0;
  if constexpr (Dim >= 2) {
    for (const VolumeTerm<Dim>& term : s.volume_terms) {
      if (volume_term_active(s, term)) e += volume_term_energy(term, corners_of(term, s.x));
    }
  }
  return e;
}

template <int Dim>
LameSplit lame_split(const Material& material) {
  static_assert(Dim == 2 || Dim == 3, "Poisson's ratio is that of a sheet or a solid");
  const double network_ratio = Dim == 2 ? 1.0 / 3.0 : 1.0 / 4.0;
  const double upper = Dim == 2 ? 1.0 : 0.5;
  const double nu = std::isnan(material.poisson_ratio) ? network_ratio : material.poisson_ratio;
  if (!(nu >= network_ratio && nu < upper))
    throw MaterialError(message(
        "material: Poisson's ratio nu = ", material.poisson_ratio, " is outside [",
        Dim == 2 ? "1/3, 1) for a 2D sheet" : "1/4, 1/2) for a 3D solid", ": a spring network has ",
        Dim == 2 ? "1/3" : "1/4",
        " by itself and area or volume terms can only raise it (a lower ratio would need a "
        "negative, unstable stiffness), and ",
        Dim == 2 ? "1" : "1/2",
        " is incompressible (no finite lambda); choose nu in that range, or leave it NaN for the "
        "network's own"));
  const double youngs = material.youngs_modulus;
  LameSplit out;
  out.mu = youngs / (2.0 * (1.0 + nu));
  out.lambda =
      Dim == 2 ? youngs * nu / (1.0 - nu * nu) : youngs * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  // the network's own ratio: exactly the springs' material, no term
  const bool own = nu == network_ratio;
  out.network_youngs = own ? youngs : (Dim == 2 ? 8.0 / 3.0 : 5.0 / 2.0) * out.mu;
  out.volume_stiffness = own ? 0.0 : std::max(0.0, out.lambda - out.mu);
  out.p_wave_speed = std::sqrt((out.lambda + 2.0 * out.mu) / material.density);
  return out;
}

template <int Dim>
void add_volume_terms(MassSpringSystem<Dim>& s,
                      const std::vector<std::array<int, Dim + 1>>& elements,
                      const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest, double stiffness) {
  const detail::SpringsByPair springs(s.springs);
  const double spring_speed = s.wave_speed;
  for (int e = 0; e < static_cast<int>(elements.size()); ++e) {
    VolumeTerm<Dim> term;
    term.stiffness = stiffness;
    term.rest_measure =
        detail::place_element<Dim>(springs, elements[e], rest, "volume terms", e, &term);
    s.volume_terms.push_back(term);
  }
  const double volume_speed = volume_terms_speed(s, rest);
  s.wave_speed = std::sqrt(spring_speed * spring_speed + volume_speed * volume_speed);
}

#define GENCOORD_INSTANTIATE(D)                                                                   \
  template double signed_measure<D>(const Corners<D>&);                                           \
  template Corners<D> signed_measure_gradient<D>(const Corners<D>&);                              \
  template double volume_term_energy<D>(const VolumeTerm<D>&, const Corners<D>&);                 \
  template Corners<D> volume_term_forces<D>(const VolumeTerm<D>&, const Corners<D>&);             \
  template VolumeTermJacobian<D> volume_term_jacobian<D>(const VolumeTerm<D>&, const Corners<D>&, \
                                                         bool);                                   \
  template bool volume_term_active<D>(const MassSpringSystem<D>&, const VolumeTerm<D>&);          \
  template Corners<D> corners_of<D>(const VolumeTerm<D>&,                                         \
                                    const Eigen::Matrix<double, D, Eigen::Dynamic>&);             \
  template LameSplit lame_split<D>(const Material&);                                              \
  template void add_volume_terms<D>(MassSpringSystem<D>&,                                         \
                                    const std::vector<std::array<int, D + 1>>&,                   \
                                    const Eigen::Matrix<double, D, Eigen::Dynamic>&, double);
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

#define GENCOORD_INSTANTIATE(D)                                                                   \
  template void accumulate_volume_term_forces<D>(const MassSpringSystem<D>&,                      \
                                                 const Eigen::Matrix<double, D, Eigen::Dynamic>&, \
                                                 Eigen::Matrix<double, D, Eigen::Dynamic>&);      \
  template double volume_terms_energy<D>(const MassSpringSystem<D>&);
GENCOORD_INSTANTIATE(1)
GENCOORD_INSTANTIATE(2)
GENCOORD_INSTANTIATE(3)
#undef GENCOORD_INSTANTIATE

}  // namespace gencoord::deformable
