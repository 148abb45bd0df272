// SPDX-License-Identifier: BSD-3-Clause
// The linearization of a model with kinematic constraints (closed loops, rolling) about a
// state on its constraints, in a minimal set of coordinates and speeds: what stability
// studies read (a bicycle's weave and capsize modes, a rolling disk's).
//
// The caller splits the coordinates into independent ones (the linearization's), dependent
// ones (one per holonomic constraint, solved from C(q, t) = 0 by Newton steps) and held ones
// (kept at the reference: ignorable coordinates such as a vehicle's position and heading),
// and the speeds likewise (one dependent speed per constraint, from A v + b = 0). The
// reduced state z = (q_i, v_i) then moves by
//
//   z' = f(z, u) = (q'_i, v'_i),   q' = G(q) v,   v' the constrained acceleration,
//
// and A = df/dz, B = df/du come from central differences with one Richardson extrapolation
// (error O(h^4) + O(eps / h), about 1e-11 relative at the default step).
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <stdexcept>
#include <string>
#include <vector>

#include "gencoord/control/inputs.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord {

/// Which coordinates and speeds a constrained linearization keeps (independent), solves
/// from the constraints (dependent) and holds at the reference (the rest). Indices into q
/// and v.
struct CoordinateSplit {
  std::vector<int> independent_q, dependent_q;  // dependent_q: num_holonomic_constraints
  std::vector<int> independent_v, dependent_v;  // dependent_v: num_constraints
};

/// z' ~ f(z0) + A (z - z0) + B (u - u0), z = (q_i, v_i) in the split's order.
struct ConstrainedLinearization {
  Eigen::VectorXd zdot;  // f(z0, u0)
  Eigen::MatrixXd A;     // df/dz
  Eigen::MatrixXd B;     // df/du (num_inputs columns)
};

namespace detail {

template <class M>
void check_split(const CoordinateSplit& split) {
  int holonomic = 0;
  if constexpr (has_holonomic_constraints_v<M>) holonomic = M::num_holonomic_constraints;
  auto valid = [](const std::vector<int>& indices, int size) {
    for (const int i : indices)
      if (i < 0 || i >= size) return false;
    return true;
  };
  if (static_cast<int>(split.dependent_q.size()) != holonomic ||
      static_cast<int>(split.dependent_v.size()) != M::num_constraints ||
      !valid(split.independent_q, M::nq) || !valid(split.dependent_q, M::nq) ||
      !valid(split.independent_v, nv_of_v<M>) || !valid(split.dependent_v, nv_of_v<M>))
    throw std::invalid_argument(std::string("gencoord: linearize_constrained of model '") +
                                M::name + "' needs " + std::to_string(holonomic) +
                                " dependent coordinates and " + std::to_string(M::num_constraints) +
                                " dependent speeds, and indices within q and v");
}

// The full state of the reduced state z: dependent coordinates by Newton steps from the
// reference, dependent speeds from A v + b = 0.
template <class M>
State<M> full_state(const ParamsOf<M>& p, const State<M>& reference, const CoordinateSplit& split,
                    const Eigen::VectorXd& z) {
  State<M> s = reference;
  const int nqi = static_cast<int>(split.independent_q.size());
  for (int k = 0; k < nqi; ++k) s.q[split.independent_q[k]] = z[k];
  if constexpr (has_holonomic_constraints_v<M>) {
    const int nh = M::num_holonomic_constraints;
    for (int step = 0; step < 50; ++step) {
      const auto C = M::holonomic_constraints(s.q, s.t, p);
      const auto C_q = M::holonomic_jacobian(s.q, s.t, p);
      Eigen::MatrixXd square(nh, nh);
      for (int j = 0; j < nh; ++j) square.col(j) = C_q.col(split.dependent_q[j]);
      const Eigen::VectorXd dq = -square.partialPivLu().solve(Eigen::VectorXd(C));
      for (int j = 0; j < nh; ++j) s.q[split.dependent_q[j]] += dq[j];
      normalize_quaternions<M>(&s.q);
      if (dq.lpNorm<Eigen::Infinity>() <= 1e-15 * (1 + s.q.template lpNorm<Eigen::Infinity>()))
        break;
    }
  }
  for (int k = 0; k < static_cast<int>(split.independent_v.size()); ++k)
    s.v[split.independent_v[k]] = z[nqi + k];
  const int nc = M::num_constraints;
  for (const int j : split.dependent_v) s.v[j] = 0.0;
  const auto A = M::constraint_jacobian(s.q, s.t, p);
  Eigen::MatrixXd square(nc, nc);
  for (int j = 0; j < nc; ++j) square.col(j) = A.col(split.dependent_v[j]);
  const Eigen::VectorXd rest = M::constraint_velocities(s.q, s.v, s.t, p);
  const Eigen::VectorXd dependent = -square.partialPivLu().solve(rest);
  for (int j = 0; j < nc; ++j) s.v[split.dependent_v[j]] = dependent[j];
  return s;
}

// f(z, u): the independent coordinates' rates and speeds' accelerations
template <class M>
Eigen::VectorXd reduced_rate(const ParamsOf<M>& p, const State<M>& reference,
                             const CoordinateSplit& split, const Eigen::VectorXd& z) {
  const State<M> s = full_state<M>(p, reference, split, z);
  QVec<M> rates;
  if constexpr (has_generalized_speeds_v<M>) {
    rates = M::coordinate_rates(s.q, s.v, s.t, p);
  } else {
    rates = s.v;
  }
  const VVec<M> a = acceleration<M>(p, s.q, s.v, s.t);
  const int nqi = static_cast<int>(split.independent_q.size());
  Eigen::VectorXd f(z.size());
  for (int k = 0; k < nqi; ++k) f[k] = rates[split.independent_q[k]];
  for (int k = 0; k < static_cast<int>(split.independent_v.size()); ++k)
    f[nqi + k] = a[split.independent_v[k]];
  return f;
}

// d f / d x_k by central differences at steps h and h/2, Richardson-extrapolated
template <class F>
Eigen::VectorXd extrapolated_derivative(const F& f, double x, double h) {
  const Eigen::VectorXd coarse = (f(x + h) - f(x - h)) / (2 * h);
  const Eigen::VectorXd fine = (f(x + h / 2) - f(x - h / 2)) / h;
  return (4 * fine - coarse) / 3;
}

}  // namespace detail

/// `reference` put on the constraints as the split says: its independent and held
/// coordinates and speeds kept, the dependent ones solved (a steady motion from its
/// nonzero independent values, or a push on it).
/// \throws std::invalid_argument for a split of the wrong sizes.
template <class M>
State<M> state_on_constraints(const ParamsOf<M>& p, const State<M>& reference,
                              const CoordinateSplit& split) {
  detail::check_split<M>(split);
  const int nqi = static_cast<int>(split.independent_q.size());
  Eigen::VectorXd z(nqi + split.independent_v.size());
  for (int k = 0; k < nqi; ++k) z[k] = reference.q[split.independent_q[k]];
  for (int k = nqi; k < z.size(); ++k) z[k] = reference.v[split.independent_v[k - nqi]];
  return detail::full_state<M>(p, reference, split, z);
}

/// The linearization of a constrained model about `reference` (a state on its
/// constraints, for instance a steady motion) in the reduced state z = (q_i, v_i).
/// \param[in] p          The model parameters (their inputs are u0).
/// \param[in] reference  The operating point; its held coordinates and speeds stay fixed.
/// \param[in] split      Independent, dependent and (the rest) held coordinates and speeds.
/// \param[in] step       The relative difference step (h = step * (1 + |z_k|)).
/// \throws std::invalid_argument for a split of the wrong sizes; DynamicsError where the
///         dynamics fail near the reference.
template <class M>
ConstrainedLinearization linearize_constrained(const ParamsOf<M>& p, const State<M>& reference,
                                               const CoordinateSplit& split, double step = 1e-3) {
  static_assert(has_kinematic_constraints_v<M>,
                "gencoord: linearize_constrained is for models with kinematic constraints; "
                "others use linearize()");
  detail::check_split<M>(split);
  const int nqi = static_cast<int>(split.independent_q.size());
  const int n = nqi + static_cast<int>(split.independent_v.size());
  Eigen::VectorXd z0(n);
  for (int k = 0; k < nqi; ++k) z0[k] = reference.q[split.independent_q[k]];
  for (int k = nqi; k < n; ++k) z0[k] = reference.v[split.independent_v[k - nqi]];
  ConstrainedLinearization out;
  out.zdot = detail::reduced_rate<M>(p, reference, split, z0);
  out.A.resize(n, n);
  for (int k = 0; k < n; ++k) {
    const auto along = [&](double x) {
      Eigen::VectorXd z = z0;
      z[k] = x;
      return detail::reduced_rate<M>(p, reference, split, z);
    };
    out.A.col(k) = detail::extrapolated_derivative(along, z0[k], step * (1 + std::abs(z0[k])));
  }
  out.B.resize(n, num_inputs_v<M>);
  if constexpr (has_inputs_v<M>) {
    const InputVec<M> u0 = inputs_of<M>(p);
    for (int k = 0; k < M::num_inputs; ++k) {
      const auto along = [&](double x) {
        InputVec<M> u = u0;
        u[k] = x;
        return detail::reduced_rate<M>(with_inputs<M>(p, u), reference, split, z0);
      };
      out.B.col(k) = detail::extrapolated_derivative(along, u0[k], step * (1 + std::abs(u0[k])));
    }
  }
  return out;
}

}  // namespace gencoord
