// SPDX-License-Identifier: BSD-3-Clause
// Moving a state from one chart of an atlas to another through the particles.
//
// Both charts describe the same particles, so the state (q, v) of chart From gives positions
// x = X_From(q, t) and velocities xdot; chart To's state is the inverse map of (x, xdot):
// Gauss-Newton on X_To(q') = x with the generated J, then Mt' v' = J'^T M (xdot - X'_t). On
// the manifold both are exact (to the Gauss-Newton tolerance), so no energy is lost.
//
// Gauss-Newton needs a first guess in chart To's branch of the solution. The guesses are
// tried in order: chart To's last state (when it was used before), its suggested initial
// state, then a deterministic spread of points around it (a Kronecker sequence, angles
// +-pi), enough for the few coordinates of a chart.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include <Eigen/Cholesky>

#include "gencoord/maximal/inverse_map.hpp"
#include "gencoord/maximal/traits.hpp"
#include "gencoord/model/conditioning.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord {

/// First guesses for the inverse map into chart M: `last` (if any), M's initial state, then
/// `spread` points of a Kronecker sequence within +-pi of the initial state in every entry.
template <class M>
std::vector<QVec<M>> chart_guesses(const std::optional<QVec<M>>& last, int spread) {
  std::vector<QVec<M>> guesses;
  if (last) guesses.push_back(*last);
  const QVec<M> initial = initial_q_of<M>();
  guesses.push_back(initial);
  constexpr double kPi = 3.14159265358979323846;
  // fractional parts of square roots of distinct primes: well spread in every entry
  constexpr int primes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53};
  static_assert(M::nq <= 16, "chart_guesses spreads guesses over at most 16 coordinates");
  QVec<M> alpha;
  for (int i = 0; i < M::nq; ++i) {
    const double root = std::sqrt(static_cast<double>(primes[i]));
    alpha(i) = root - std::floor(root);
  }
  for (int k = 1; k <= spread; ++k) {
    QVec<M> q;
    for (int i = 0; i < M::nq; ++i) {
      const double u = k * alpha(i) - std::floor(k * alpha(i));  // in [0, 1)
      q(i) = initial(i) + kPi * (2.0 * u - 1.0);
    }
    guesses.push_back(q);
  }
  return guesses;
}

/// The condition estimate of chart M's mass matrix at q (see condition_estimate()).
template <class M>
double chart_condition(const ParamsOf<M>& p, const QVec<M>& q, double t) {
  return condition_estimate(Eigen::LLT<PlainOf<QMat<M>>>(M::mass_matrix(q, t, p)));
}

/// The state of chart To at the configuration and velocity of `s` (a state of chart From),
/// or nothing when no guess converges onto the same particle positions.
/// \param[in] p        The parameters (every chart of an atlas shares them).
/// \param[in] s        The state in chart From.
/// \param[in] guesses  First guesses of To's coordinates, tried in order (chart_guesses()).
/// \param[in] options  Gauss-Newton settings; max_residual is the accepted mismatch of x.
template <class From, class To>
std::optional<State<To>> transfer_state(const ParamsOf<From>& p, const State<From>& s,
                                        const std::vector<QVec<To>>& guesses,
                                        const InverseMapOptions& options = {}) {
  static_assert(From::nx == To::nx, "charts of an atlas move the same particles");
  static_assert(!has_generalized_speeds_v<From>,
                "gencoord: the atlas's chart transfer does not support models with generalized "
                "speeds (free or ball "
                "joints) yet");
  static_assert(!has_generalized_speeds_v<To>,
                "gencoord: the atlas's chart transfer does not support models with generalized "
                "speeds (free or ball "
                "joints) yet");
  const XVec<From> x = From::positions(s.q, s.t, p);
  const XVec<From> xdot = From::velocities(s.q, s.v, s.t, p);
  for (const QVec<To>& guess : guesses) {
    try {
      return inverse_map<To>(p, x, xdot, s.t, guess, options);
    } catch (const InverseMapError&) {
      // another local minimum or a singular point of To: try the next guess
    }
  }
  return std::nullopt;
}

}  // namespace gencoord
