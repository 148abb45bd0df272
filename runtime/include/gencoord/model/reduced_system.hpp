// SPDX-License-Identifier: BSD-3-Clause
// A generated model with its parameters as a system for the integrators
// (integrate/system.hpp): a = Mt^-1 (Ft + Fi), unit mass, dense Jacobians.
#pragma once

#include <utility>

#include "gencoord/integrate/system.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord {

template <class M>
class ReducedSystem {
 public:
  using State = gencoord::State<M>;
  using Unknowns = QVec<M>;
  using Matrix = QMat<M>;
  static constexpr bool unit_mass = true;

  explicit ReducedSystem(ParamsOf<M> p) : p_(std::move(p)) { static_assert(assert_model_v<M>); }

  const ParamsOf<M>& params() const { return p_; }
  const char* name() const { return M::name; }
  /// \throws DynamicsError as gencoord::acceleration().
  QVec<M> acceleration(const State& s) const { return gencoord::acceleration<M>(p_, s); }
  void impose(State*) const {}
  void check(const State&, double) const {}

  const QVec<M>& free_part(const QVec<M>& x) const { return x; }
  void add_to_free(const QVec<M>& dx, QVec<M>* x) const { *x += dx; }
  /// The acceleration and its Jacobians (acceleration_and_jacobians()).
  void linearize(const State& s, JacobianSource source, Linearization<ReducedSystem>* out) const {
    acceleration_and_jacobians<M>(p_, s.q, s.v, s.t, source, &out->force, &out->force_D_q,
                                  &out->force_D_v);
  }
  /// A singular A gives a non-finite x.
  bool solve(const QMat<M>& A, const QVec<M>& b, QVec<M>* x) const {
    return detail::dense_lu_solve(A, b, x);
  }

 private:
  ParamsOf<M> p_;
};

}  // namespace gencoord
