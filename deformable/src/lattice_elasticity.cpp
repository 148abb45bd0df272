// SPDX-License-Identifier: BSD-3-Clause
// A spring network's stiffness tensor and its calibration (lattice_elasticity.hpp). Fully
// symmetric rank-4 tensors are stored by their distinct components, one per monomial
// n_x^a n_y^b (n_z^c) of degree 4, each scaled by the square root of how many index orders
// give it, so that a plain Euclidean norm of the stored vector is the tensor's Frobenius norm.
#include "gencoord/deformable/lattice_elasticity.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "gencoord/deformable/errors.hpp"

namespace gencoord::deformable {
namespace {

template <int Dim>
using Exponents = std::array<int, Dim>;

// the degree-4 monomials: (4,0), (3,1), ... in 2D; (4,0,0), (3,1,0), ... in 3D
template <int Dim>
std::vector<Exponents<Dim>> quartic_monomials() {
  std::vector<Exponents<Dim>> out;
  for (int a = 4; a >= 0; --a) {
    if constexpr (Dim == 2) {
      out.push_back({a, 4 - a});
    } else {
      for (int b = 4 - a; b >= 0; --b) out.push_back({a, b, 4 - a - b});
    }
  }
  return out;
}

template <int Dim>
constexpr int kMonomials = Dim == 2 ? 5 : 15;

template <int Dim>
using Components = Eigen::Matrix<double, kMonomials<Dim>, 1>;

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// index orders (i, j, k, l) that give the monomial: 4! / (a! b! c!)
template <int Dim>
double orders(const Exponents<Dim>& e) {
  double count = factorial(4);
  for (int p : e) count /= factorial(p);
  return count;
}

// n (x) n (x) n (x) n, stored
template <int Dim>
Components<Dim> outer4(const Eigen::Matrix<double, Dim, 1>& n) {
  const auto monomials = quartic_monomials<Dim>();
  Components<Dim> out;
  for (int m = 0; m < kMonomials<Dim>; ++m) {
    double value = std::sqrt(orders<Dim>(monomials[m]));
    for (int axis = 0; axis < Dim; ++axis) value *= std::pow(n(axis), monomials[m][axis]);
    out(m) = value;
  }
  return out;
}

// alpha (d_ij d_kl + d_ik d_jl + d_il d_jk), stored: 3 alpha for n_x^4, alpha for n_x^2 n_y^2
template <int Dim>
Components<Dim> isotropic(double alpha) {
  const auto monomials = quartic_monomials<Dim>();
  Components<Dim> out;
  for (int m = 0; m < kMonomials<Dim>; ++m) {
    const auto& e = monomials[m];
    const bool even = std::all_of(e.begin(), e.end(), [](int p) { return p % 2 == 0; });
    const int fours = static_cast<int>(std::count(e.begin(), e.end(), 4));
    out(m) = even ? (fours ? 3.0 : 1.0) * alpha * std::sqrt(orders<Dim>(e)) : 0.0;
  }
  return out;
}

// C_ijkl of the stored tensor
template <int Dim>
double component(const Components<Dim>& t, int i, int j, int k, int l) {
  Exponents<Dim> e{};
  for (int index : {i, j, k, l}) ++e[index];
  const auto monomials = quartic_monomials<Dim>();
  const auto m = std::find(monomials.begin(), monomials.end(), e) - monomials.begin();
  return t(m) / std::sqrt(orders<Dim>(e));
}

// the Voigt pairs: 2D xx, yy, xy; 3D xx, yy, zz, yz, xz, xy
template <int Dim>
std::array<std::pair<int, int>, LatticeElasticity<Dim>::kVoigt> voigt_pairs() {
  if constexpr (Dim == 2) {
    return {{{0, 0}, {1, 1}, {0, 1}}};
  } else {
    return {{{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};
  }
}

// E of the isotropic part alpha: lambda = mu = alpha
template <int Dim>
double youngs_of(double alpha) {
  return Dim == 2 ? 8.0 * alpha / 3.0 : 5.0 * alpha / 2.0;
}

template <int Dim>
double alpha_of_youngs(double youngs) {
  return Dim == 2 ? 3.0 * youngs / 8.0 : 2.0 * youngs / 5.0;
}

template <int Dim>
Eigen::Matrix<double, Dim, 1> rest_direction(
    const Spring& sp, const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest) {
  return (rest.col(sp.j) - rest.col(sp.i)).normalized();
}

// calibrate_springs() accepts direction-dependent factors down to this fraction of the
// uniform one; the meshes tested need no less than about half
constexpr double kSmallestFactor = 0.2;

void check_measure(double measure) {
  if (!(std::isfinite(measure) && measure > 0.0))
    throw std::invalid_argument("lattice elasticity: the body's measure " +
                                std::to_string(measure) + " must be positive and finite");
}

}  // namespace

template <int Dim>
double LatticeElasticity<Dim>::youngs_modulus_along(const Eigen::Matrix<double, Dim, 1>& d) const {
  Eigen::Matrix<double, kVoigt, 1> stress;  // uniaxial unit stress d d, in Voigt order
  const auto pairs = voigt_pairs<Dim>();
  for (int I = 0; I < kVoigt; ++I) stress(I) = d(pairs[I].first) * d(pairs[I].second);
  return 1.0 / stress.dot(voigt.ldlt().solve(stress));
}

template <int Dim>
LatticeElasticity<Dim> lattice_elasticity(const MassSpringSystem<Dim>& s,
                                          const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest,
                                          double measure) {
  check_measure(measure);
  Components<Dim> tensor = Components<Dim>::Zero();
  double trace = 0.0;  // C_iijj = sum_s k_s L_s / V
  for (const Spring& sp : s.springs) {
    if (sp.broken) continue;
    const double weight = sp.params.stiffness * sp.params.rest_length / measure;
    tensor += weight * outer4<Dim>(rest_direction<Dim>(sp, rest));
    trace += weight;
  }
  const double alpha = trace / (Dim * (Dim + 2));
  LatticeElasticity<Dim> out;
  const auto pairs = voigt_pairs<Dim>();
  for (int I = 0; I < out.kVoigt; ++I)
    for (int J = 0; J < out.kVoigt; ++J)
      out.voigt(I, J) =
          component<Dim>(tensor, pairs[I].first, pairs[I].second, pairs[J].first, pairs[J].second);
  out.youngs_modulus = youngs_of<Dim>(alpha);
  out.poisson_ratio = Dim == 2 ? 1.0 / 3.0 : 1.0 / 4.0;
  const Components<Dim> iso = isotropic<Dim>(alpha);
  out.anisotropy = (tensor - iso).norm() / iso.norm();
  return out;
}

template <int Dim>
double calibrate_springs(MassSpringSystem<Dim>& s,
                         const Eigen::Matrix<double, Dim, Eigen::Dynamic>& rest, double measure,
                         double youngs_modulus) {
  check_measure(measure);
  // g_s = 1 + phi_s . z with the smallest sum_s w_s (g_s - 1)^2 (w_s = k_s L_s) such that
  // sum_s w_s g_s phi_s is the target tensor times V, or, where the springs' directions cannot
  // reach it, closest to it: z = G^+ (V target - sum_s w_s phi_s), G = sum_s w_s phi_s phi_s^T.
  // Every sum is taken relative to W = sum_s w_s, so that no extreme material overflows it.
  double total = 0.0;
  for (const Spring& sp : s.springs)
    if (!sp.broken) total += sp.params.stiffness * sp.params.rest_length;
  // the factor that gives the isotropic part alone its modulus: sum_s w_s g = V alpha D (D + 2)
  const double uniform = measure / total * alpha_of_youngs<Dim>(youngs_modulus) * Dim * (Dim + 2);
  if (!(std::isfinite(uniform) && uniform > 0.0))
    throw MaterialError("calibrate springs: Young's modulus " + std::to_string(youngs_modulus) +
                        " over springs of total k L " + std::to_string(total) + " and measure " +
                        std::to_string(measure) +
                        " gives no finite spring stiffness; choose E, rho and the mesh's size "
                        "so that E / rho and the springs' stiffness stay within double range");
  using Gram = Eigen::Matrix<double, kMonomials<Dim>, kMonomials<Dim>>;
  Gram gram = Gram::Zero();
  Components<Dim> now = Components<Dim>::Zero();
  std::vector<Components<Dim>> phi(s.springs.size());
  for (std::size_t k = 0; k < s.springs.size(); ++k) {
    const Spring& sp = s.springs[k];
    if (sp.broken) continue;
    phi[k] = outer4<Dim>(rest_direction<Dim>(sp, rest));
    const double weight = sp.params.stiffness * sp.params.rest_length / total;
    gram += weight * phi[k] * phi[k].transpose();
    now += weight * phi[k];
  }
  const Components<Dim> target = isotropic<Dim>(uniform / (Dim * (Dim + 2)));
  const Components<Dim> z = gram.completeOrthogonalDecomposition().solve(target - now);
  std::vector<double> factor(s.springs.size(), uniform);
  bool directional = true;
  for (std::size_t k = 0; k < s.springs.size() && directional; ++k) {
    if (s.springs[k].broken) continue;
    factor[k] = 1.0 + phi[k].dot(z);
    // directions too few, or too nearly those of a lattice with too few, ask for factors near
    // or below zero: then keep the mesh's anisotropy and set the isotropic part only
    directional = std::isfinite(factor[k]) && factor[k] >= kSmallestFactor * uniform;
  }
  if (!directional) std::fill(factor.begin(), factor.end(), uniform);
  double largest = 0.0;
  for (std::size_t k = 0; k < s.springs.size(); ++k) {
    Spring& sp = s.springs[k];
    if (sp.broken) continue;
    sp.params.stiffness *= factor[k];
    sp.params.damping *= factor[k];
    largest = std::max(largest, factor[k]);
  }
  return largest;
}

template struct LatticeElasticity<2>;
template struct LatticeElasticity<3>;
template LatticeElasticity<2> lattice_elasticity<2>(const MassSpringSystem<2>&,
                                                    const Eigen::Matrix<double, 2, Eigen::Dynamic>&,
                                                    double);
template LatticeElasticity<3> lattice_elasticity<3>(const MassSpringSystem<3>&,
                                                    const Eigen::Matrix<double, 3, Eigen::Dynamic>&,
                                                    double);
template double calibrate_springs<2>(MassSpringSystem<2>&,
                                     const Eigen::Matrix<double, 2, Eigen::Dynamic>&, double,
                                     double);
template double calibrate_springs<3>(MassSpringSystem<3>&,
                                     const Eigen::Matrix<double, 3, Eigen::Dynamic>&, double,
                                     double);

}  // namespace gencoord::deformable
