// SPDX-License-Identifier: BSD-3-Clause
// The co-rotated linear material at one point of an element (continuum_elements.hpp states
// the model): its energy density, first Piola stress with the strain-rate damping, and the
// node blocks of its exact or projected Hessian and of its damping, for any number N of nodes
// whose shape-function gradients g_a at that point are given. A linear element is one such
// point with weight V0; a quadratic element sums several (quadratic_elements.hpp). Private to
// the library.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>

#include "polar_decomposition.hpp"

namespace gencoord::deformable::detail {

template <int Dim, int N>
using NodeVectors = std::array<Eigen::Matrix<double, Dim, 1>, N>;
template <int Dim, int N>
using NodeBlocks = std::array<std::array<Eigen::Matrix<double, Dim, Dim>, N>, N>;

/// The constants of the material at a point.
struct CorotatedConstants {
  double mu = 0.0;            ///< shear modulus
  double lambda = 0.0;        ///< Lame's first constant
  double damping_time = 0.0;  ///< beta = D / E (s)
};

// Smallest sum of two principal stretches used in the twist eigenvalues 2 / (s_i + s_j): the
// sum vanishes only for an element inverted so far that two stretches cancel, where R jumps.
constexpr double kMinStretchSum = 1e-6;

/// F = sum_a x_a g_a^T.
template <int Dim, int N>
Eigen::Matrix<double, Dim, Dim> gradient_at(const NodeVectors<Dim, N>& x,
                                            const NodeVectors<Dim, N>& g) {
  Eigen::Matrix<double, Dim, Dim> f = Eigen::Matrix<double, Dim, Dim>::Zero();
  for (int a = 0; a < N; ++a) f.noalias() += x[a] * g[a].transpose();
  return f;
}

/// psi(F) = mu |F - R|^2 + (lambda / 2) (tr S - Dim)^2.
template <int Dim>
double energy_density(const Eigen::Matrix<double, Dim, Dim>& f, const CorotatedConstants& c) {
  const Polar<Dim> p = polar(f);
  const double volumetric = p.trace_s - Dim;
  return c.mu * (f - p.rotation).squaredNorm() + 0.5 * c.lambda * volumetric * volumetric;
}

/// P = 2 mu (F - R) + lambda (tr S - Dim) R.
template <int Dim>
Eigen::Matrix<double, Dim, Dim> elastic_stress(const Eigen::Matrix<double, Dim, Dim>& f,
                                               const CorotatedConstants& c) {
  const Polar<Dim> p = polar(f);
  return 2.0 * c.mu * (f - p.rotation) + c.lambda * (p.trace_s - Dim) * p.rotation;
}

/// The damping's first Piola stress F beta (2 mu E' + lambda tr(E') I), E' = sym(F^T F').
template <int Dim>
Eigen::Matrix<double, Dim, Dim> damping_stress(const Eigen::Matrix<double, Dim, Dim>& f,
                                               const Eigen::Matrix<double, Dim, Dim>& f_rate,
                                               const CorotatedConstants& c) {
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  const Mat e_rate = 0.5 * (f.transpose() * f_rate + f_rate.transpose() * f);
  return c.damping_time * f * (2.0 * c.mu * e_rate + c.lambda * e_rate.trace() * Mat::Identity());
}

/// Adds -weight (dP/dF contracted with g_a and g_b) to out[a][b]: the Hessian of -weight psi.
/// dP/dF = 2 mu I + lambda r r^T + sum_t c_t t t^T (r = vec R, t the twists), with
/// c_t = (lambda (tr S - Dim) - 2 mu) 2 / (s_i + s_j) from dR/dF; the twists' eigenvalues are
/// 2 mu + c_t, the others 2 mu and 2 mu + Dim lambda. `definite` clamps the twists' at zero.
template <int Dim, int N>
void add_stiffness(const Eigen::Matrix<double, Dim, Dim>& f, const CorotatedConstants& c,
                   double weight, const NodeVectors<Dim, N>& g, bool definite,
                   NodeBlocks<Dim, N>& out) {
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  const Polar<Dim> p = polar(f);
  constexpr int kTwists = Polar<Dim>::kTwists;
  std::array<double, kTwists> twist_weight{};
  for (int t = 0; t < kTwists; ++t) {
    twist_weight[t] = (c.lambda * (p.trace_s - Dim) - 2.0 * c.mu) * 2.0 /
                      std::max(p.stretch_sums[t], kMinStretchSum);
    if (definite) twist_weight[t] = std::max(twist_weight[t], -2.0 * c.mu);
  }
  NodeVectors<Dim, N> rg;
  std::array<NodeVectors<Dim, N>, kTwists> tg;
  for (int a = 0; a < N; ++a) {
    rg[a] = p.rotation * g[a];
    for (int t = 0; t < kTwists; ++t) tg[t][a] = p.twists[t] * g[a];
  }
  for (int a = 0; a < N; ++a) {
    for (int b = 0; b < N; ++b) {
      Mat h =
          (2.0 * c.mu * g[a].dot(g[b])) * Mat::Identity() + c.lambda * rg[a] * rg[b].transpose();
      for (int t = 0; t < kTwists; ++t) h += twist_weight[t] * tg[t][a] * tg[t][b].transpose();
      out[a][b] -= weight * h;
    }
  }
}

/// Adds d f_a / d v_b of the damping forces f_a = -weight F beta (2 mu E' + lambda tr(E') I)
/// g_a, E' = sym(F^T F'), F' = sum v_b g_b^T, to out[a][b]:
/// -weight beta (mu (g_a . g_b) F F^T + mu F g_b (F g_a)^T + lambda F g_a (F g_b)^T).
template <int Dim, int N>
void add_damping(const Eigen::Matrix<double, Dim, Dim>& f, const CorotatedConstants& c,
                 double weight, const NodeVectors<Dim, N>& g, NodeBlocks<Dim, N>& out) {
  const Eigen::Matrix<double, Dim, Dim> ff = f * f.transpose();
  NodeVectors<Dim, N> fg;
  for (int a = 0; a < N; ++a) fg[a] = f * g[a];
  const double scale = weight * c.damping_time;
  for (int a = 0; a < N; ++a) {
    for (int b = 0; b < N; ++b) {
      out[a][b] -= scale * (c.mu * g[a].dot(g[b]) * ff + c.mu * fg[b] * fg[a].transpose() +
                            c.lambda * fg[a] * fg[b].transpose());
    }
  }
}

/// Blocks of zeros.
template <int Dim, int N>
NodeBlocks<Dim, N> zero_blocks() {
  NodeBlocks<Dim, N> out;
  for (auto& row : out)
    for (auto& block : row) block.setZero();
  return out;
}

}  // namespace gencoord::deformable::detail
