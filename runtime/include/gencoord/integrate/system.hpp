// SPDX-License-Identifier: BSD-3-Clause
// What the integrators (explicit_rk.hpp, backward_euler.hpp, step.hpp, simulate.hpp) require
// of a system: every method is written once over this interface, and each kind of system
// (reduced model, scripted coordinates, maximal penalty model, deformable mass-spring object)
// implements it in a thin adapter. Calls are resolved at compile time (templates, no virtual
// functions), so a fixed-size system allocates nothing per step.
//
// A system S provides
//   using State = ...;    double t and vectors q, v (the coordinates and their velocities);
//   const char* name() const;                      for error messages;
//   auto acceleration(const State& s) const;       a(t, q, v), a vector like s.q;
//   void impose(State* s) const;                   sets prescribed entries (scripted
//                                                  coordinates) at s->t; may do nothing;
//   void check(const State& s, double dt) const;   called by step() on an end state that is
//                                                  not finite, to throw the system's own
//                                                  error for it; may do nothing;
// and, for the implicit methods, Newton on the end velocity of backward Euler over the free
// entries of v (all of them unless some are prescribed):
//   using Unknowns = ...;  using Matrix = ...;    free vector, free-free matrix (dense or
//                                                  Eigen::SparseMatrix);
//   static constexpr bool unit_mass;               the residual is v-based (mass 1), or
//   const Unknowns& masses() const;                its diagonal mass (used when !unit_mass);
//   Unknowns free_part(const Vector& x) const;     the free entries of x;
//   void add_to_free(const Unknowns& dx, Vector* x) const;
//   void linearize(const State& s, JacobianSource source, Linearization<S>* out) const;
//                                                  the free force (mass times acceleration)
//                                                  and its free-free Jacobians dF/dq, dF/dv;
//   bool solve(const Matrix& A, const Unknowns& b, Unknowns* x) const;   A x = b.
//
// Two members are optional (detected at compile time, so systems whose v is q' need neither):
//   auto coordinate_rate(const State& s) const;    q' = G(q) v at s, linear in v, for systems
//                                                  whose v are generalized speeds (v may be
//                                                  shorter than q); default s.v;
//   void normalize(State* s) const;                puts q back on its manifold (unit
//                                                  quaternions); default nothing.
// The methods then integrate q' = coordinate_rate(s): the explicit stages take it at each
// stage state, symplectic Euler at (t0, q0, v1), and backward Euler solves q1 = q0 + h G(q1) v1
// with its v1 (so that the trapezoidal rule and implicit midpoint built from its half steps keep
// order 2); its Newton Jacobian takes dF/dq as the derivative along the speeds, dF/dq G (nv x
// nv). step() calls normalize() once on each step's end state, never on stages or half steps.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "gencoord/numerics/dense_solve.hpp"

namespace gencoord {

/// A state of the generic form: time, coordinates and velocities.
template <class Vector>
struct Phase {
  double t = 0.0;  // time (s)
  Vector q;        // coordinates
  Vector v;        // velocities
};

/// The force of a system at a state and its Jacobians, over the free entries.
template <class S>
struct Linearization {
  typename S::Unknowns force;    // F (mass times acceleration; the acceleration if unit_mass)
  typename S::Matrix force_D_q;  // dF/dq
  typename S::Matrix force_D_v;  // dF/dv
};

namespace detail {

template <class S, class = void>
struct has_coordinate_rate : std::false_type {};
template <class S>
struct has_coordinate_rate<S, std::void_t<decltype(std::declval<const S&>().coordinate_rate(
                                  std::declval<const typename S::State&>()))>> : std::true_type {};
template <class S, class = void>
struct has_normalize : std::false_type {};
template <class S>
struct has_normalize<S, std::void_t<decltype(std::declval<const S&>().normalize(
                            std::declval<typename S::State*>()))>> : std::true_type {};

}  // namespace detail

/// True when system S has generalized speeds: q' = S::coordinate_rate(s) instead of v.
template <class S>
inline constexpr bool has_coordinate_rate_v = detail::has_coordinate_rate<S>::value;

/// q' at s: the system's coordinate_rate(s) where it has one, else s.v itself (a reference:
/// the stages of a system whose v is q' copy nothing more than before).
template <class S>
decltype(auto) coordinate_rate(const S& system, const typename S::State& s) {
  if constexpr (has_coordinate_rate_v<S>) {
    return system.coordinate_rate(s);
  } else {
    (void)system;
    return (s.v);
  }
}

/// Puts s's coordinates back on their manifold where the system has a normalize(); else nothing.
template <class S>
void normalize(const S& system, typename S::State* s) {
  if constexpr (detail::has_normalize<S>::value) {
    system.normalize(s);
  } else {
    (void)system;
    (void)s;
  }
}

namespace detail {

// |x|_inf by a plain loop, inf if an entry is NaN or inf (Eigen's vectorized reduction over a
// fixed-capacity dynamic vector trips a false -Warray-bounds in GCC 12)
template <class Dense>
double max_abs(const Dense& x) {
  double m = 0.0;
  const double* data = x.data();
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!std::isfinite(data[i])) return std::numeric_limits<double>::infinity();
    m = std::max(m, std::abs(data[i]));
  }
  return m;
}

// x = A^-1 b by LU with partial pivoting (dense systems' solve(), through the library's
// lu_solve()); a singular A gives a non-finite x, so it always returns true
template <class Matrix, class Vector>
bool dense_lu_solve(const Matrix& A, const Vector& b, Vector* x) {
  x->resize(b.size());
  return lu_solve(A, b, *x);
}

}  // namespace detail
}  // namespace gencoord
