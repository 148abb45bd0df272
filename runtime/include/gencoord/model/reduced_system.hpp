// SPDX-License-Identifier: BSD-3-Clause
// A generated model with its parameters as a system for the integrators
// (integrate/system.hpp): a = Mt^-1 (Ft + Fi), unit mass, dense Jacobians. A model with
// generalized speeds also gives the system coordinate_rate (M::coordinate_rates) and
// normalize (its unit quaternions); one with kinematic constraints gets the constrained
// acceleration, and normalize projects each step's end state onto the constraints (or, as
// its ConstraintStabilization says, Baumgarte's feedback acts in the acceleration). A model
// with joint limits has them enforced on each step's end state unless set_joint_limits(false).
#pragma once

#include <utility>

#include <Eigen/Core>

#include "gencoord/integrate/system.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/joint_limits.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"
#include "gencoord/model/tangent_space.hpp"

namespace gencoord {

template <class M>
class ReducedSystem {
 public:
  using State = gencoord::State<M>;
  using Unknowns = VVec<M>;
  using Matrix = VMat<M>;
  static constexpr bool unit_mass = true;

  explicit ReducedSystem(ParamsOf<M> p) : p_(std::move(p)) { static_assert(assert_model_v<M>); }
  /// A model with kinematic constraints, kept on them as `stabilization` says.
  ReducedSystem(ParamsOf<M> p, ConstraintStabilization stabilization)
      : p_(std::move(p)), stabilization_(stabilization) {
    static_assert(has_kinematic_constraints_v<M>,
                  "gencoord: a ConstraintStabilization is for models with kinematic constraints");
  }

  const ParamsOf<M>& params() const { return p_; }
  /// Whether normalize() enforces the model's joint limits (enforce_joint_limits()); on by
  /// default for a model that has them.
  ReducedSystem& set_joint_limits(bool enforce) {
    static_assert(has_joint_limits_v<M>, "gencoord: this model has no joint limits");
    enforce_limits_ = enforce;
    return *this;
  }
  bool joint_limits_enforced() const { return has_joint_limits_v<M> && enforce_limits_; }
  const ConstraintStabilization& stabilization() const { return stabilization_; }
  const char* name() const { return M::name; }
  /// \throws DynamicsError as gencoord::acceleration().
  VVec<M> acceleration(const State& s) const {
    if constexpr (has_kinematic_constraints_v<M>) {
      return constrained_acceleration<M>(p_, s.q, s.v, s.t, nullptr, stabilization_.baumgarte);
    } else {
      return gencoord::acceleration<M>(p_, s);
    }
  }
  void impose(State*) const {}
  void check(const State&, double) const {}

  const VVec<M>& free_part(const VVec<M>& x) const { return x; }
  void add_to_free(const VVec<M>& dx, VVec<M>* x) const { *x += dx; }
  /// The acceleration and its Jacobians (acceleration_and_jacobians()). With generalized
  /// speeds force_D_q is (da/dq) G(q) at s (nv x nv): the derivative along q1 = q0 + h G v1
  /// that backward Euler's Newton needs, with G frozen at s (backward_euler.hpp).
  void linearize(const State& s, JacobianSource source, Linearization<ReducedSystem>* out) const {
    if constexpr (has_kinematic_constraints_v<M>) {
      if (stabilization_.baumgarte.active()) {  // the feedback is in the acceleration
        out->force = acceleration(s);
        VQMat<M> a_D_q;
        central_difference_jacobians<M>(
            [this](const QVec<M>& q, const VVec<M>& v, double t) {
              return constrained_acceleration<M>(p_, q, v, t, nullptr, stabilization_.baumgarte);
            },
            s.q, s.v, s.t, &a_D_q, &out->force_D_v);
        if constexpr (has_generalized_speeds_v<M>) {
          out->force_D_q = a_D_q * detail::rate_matrix_transposed<M>(p_, s.q, s.t).transpose();
        } else {
          out->force_D_q = a_D_q;
        }
        return;
      }
    }
    if constexpr (has_generalized_speeds_v<M>) {
      VQMat<M> a_D_q;
      acceleration_and_jacobians<M>(p_, s.q, s.v, s.t, source, &out->force, &a_D_q,
                                    &out->force_D_v);
      out->force_D_q = a_D_q * detail::rate_matrix_transposed<M>(p_, s.q, s.t).transpose();
    } else {
      acceleration_and_jacobians<M>(p_, s.q, s.v, s.t, source, &out->force, &out->force_D_q,
                                    &out->force_D_v);
    }
  }
  /// A singular A gives a non-finite x.
  bool solve(const VMat<M>& A, const VVec<M>& b, VVec<M>* x) const {
    return detail::dense_lu_solve(A, b, x);
  }

  /// q' = G(q) v (M::coordinate_rates); only for models with generalized speeds.
  template <class Model = M, class = std::enable_if_t<has_generalized_speeds_v<Model>>>
  QVec<M> coordinate_rate(const State& s) const {
    return M::coordinate_rates(s.q, s.v, s.t, p_);
  }
  /// Puts s back on its manifold: divides each unit quaternion of q by its norm, enforces the
  /// joint limits (enforce_joint_limits(), unless set_joint_limits(false)), and projects a
  /// constrained model's state onto its constraints (project_onto_constraints()); only for
  /// models with generalized speeds, joint limits or kinematic constraints.
  template <class Model = M,
            class = std::enable_if_t<has_generalized_speeds_v<Model> || has_joint_limits_v<Model> ||
                                     has_kinematic_constraints_v<Model>>>
  void normalize(State* s) const {
    detail::normalize_quaternions<M>(&s->q);
    if constexpr (has_joint_limits_v<M>) {
      if (enforce_limits_) enforce_joint_limits<M>(p_, s);
    }
    if constexpr (has_kinematic_constraints_v<M>) {
      if (stabilization_.project) project_onto_constraints<M>(p_, s);
    }
  }

 private:
  ParamsOf<M> p_;
  ConstraintStabilization stabilization_;
  bool enforce_limits_ = true;
};

}  // namespace gencoord
