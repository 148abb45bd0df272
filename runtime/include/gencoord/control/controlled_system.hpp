// SPDX-License-Identifier: BSD-3-Clause
// A model driven by a control law u = law(t, q, v), as a system for the integrators
// (integrate/system.hpp): every acceleration the integrators ask for is taken with the inputs
// the law gives at that stage's time and state.
//
// The implicit methods' Jacobians include the law's: with u = u(t, q, v),
//   da/dq = -Mt^-1 dr/dq + Mt^-1 B du/dq,   da/dv = -Mt^-1 dr/dv + Mt^-1 B du/dv,
// where the law's du/dq, du/dv come from central differences (the law is the caller's code)
// unless it says it reads t only. A model with generalized speeds steps q' = G(q) v and keeps
// its quaternions unit, as ReducedSystem does; its da/dq is taken along G (nv x nv).
#pragma once

#include <Eigen/Core>

#include <functional>
#include <utility>

#include "gencoord/control/inputs.hpp"
#include "gencoord/control/linearize.hpp"
#include "gencoord/integrate/system.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/joint_limits.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"
#include "gencoord/model/tangent_space.hpp"

namespace gencoord {

/// The control inputs at time t and state (q, v) (dim num_inputs_v<M>).
template <class M>
using ControlLaw = std::function<InputVec<M>(double t, const QVec<M>& q, const VVec<M>& v)>;

/// Whether a control law reads the state (feedback) or only the time (an input script).
enum class LawKind { Feedback, OpenLoop };

template <class M>
class ControlledSystem {
 public:
  using State = gencoord::State<M>;
  using Unknowns = VVec<M>;
  using Matrix = VMat<M>;
  static constexpr bool unit_mass = true;

  /// \param[in] p     The model parameters (their input fields are overwritten by the law).
  /// \param[in] law   The control law; it must return num_inputs_v<M> values.
  /// \param[in] kind  OpenLoop when the law reads t only: the implicit methods then skip its
  ///                  Jacobian.
  ControlledSystem(ParamsOf<M> p, ControlLaw<M> law, LawKind kind = LawKind::Feedback)
      : p_(std::move(p)), law_(std::move(law)), kind_(kind) {
    static_assert(assert_model_v<M>);
    static_assert(has_inputs_v<M>, "ControlledSystem: the model declares no inputs");
  }

  const char* name() const { return M::name; }
  /// The inputs the law gives at s.
  InputVec<M> inputs(const State& s) const { return law_(s.t, s.q, s.v); }
  /// The parameters with the law's inputs at s.
  ParamsOf<M> params(const State& s) const { return with_inputs<M>(p_, inputs(s)); }

  /// \throws DynamicsError as gencoord::acceleration(); what the law throws.
  VVec<M> acceleration(const State& s) const { return gencoord::acceleration<M>(params(s), s); }
  void impose(State*) const {}
  void check(const State&, double) const {}

  const VVec<M>& free_part(const VVec<M>& x) const { return x; }
  void add_to_free(const VVec<M>& dx, VVec<M>* x) const { *x += dx; }

  /// The acceleration and its total Jacobians, the law's included (see the file comment).
  void linearize(const State& s, JacobianSource source,
                 Linearization<ControlledSystem>* out) const {
    const InputVec<M> u = inputs(s);
    VQMat<M> a_D_q;
    if (kind_ == LawKind::OpenLoop) {
      acceleration_and_input_jacobians<M>(p_, s.q, s.v, u, s.t, source, &out->force, &a_D_q,
                                          &out->force_D_v, nullptr);
    } else {
      InputJacobian<M> a_D_u;
      acceleration_and_input_jacobians<M>(p_, s.q, s.v, u, s.t, source, &out->force, &a_D_q,
                                          &out->force_D_v, &a_D_u);
      // the law's du/dq and du/dv, by central differences
      using detail::central_difference_step;
      for (int j = 0; j < M::nq; ++j) {
        State sp = s, sm = s;
        sp.q[j] += central_difference_step(s.q[j]);
        sm.q[j] -= central_difference_step(s.q[j]);
        a_D_q.col(j) += a_D_u * ((inputs(sp) - inputs(sm)) / (sp.q[j] - sm.q[j]));
      }
      for (int j = 0; j < nv_of_v<M>; ++j) {
        State sp = s, sm = s;
        sp.v[j] += central_difference_step(s.v[j]);
        sm.v[j] -= central_difference_step(s.v[j]);
        out->force_D_v.col(j) += a_D_u * ((inputs(sp) - inputs(sm)) / (sp.v[j] - sm.v[j]));
      }
    }
    if constexpr (has_generalized_speeds_v<M>) {  // along q1 = q0 + h G v1, G frozen at s
      out->force_D_q = Eigen::MatrixXd(a_D_q) * coordinate_rate_matrix<M>(p_, s.q, s.t);
    } else {
      out->force_D_q = a_D_q;
    }
  }

  /// A singular A gives a non-finite x.
  bool solve(const VMat<M>& A, const VVec<M>& b, VVec<M>* x) const {
    return detail::dense_lu_solve(A, b, x);
  }

  /// Whether normalize() enforces the model's joint limits (on by default), as
  /// ReducedSystem::set_joint_limits().
  ControlledSystem& set_joint_limits(bool enforce) {
    static_assert(has_joint_limits_v<M>, "gencoord: this model has no joint limits");
    enforce_limits_ = enforce;
    return *this;
  }
  /// q' = G(q) v (M::coordinate_rates); only for models with generalized speeds. The
  /// kinematics read no input, so the law is not called for it.
  template <class Model = M, class = std::enable_if_t<has_generalized_speeds_v<Model>>>
  QVec<M> coordinate_rate(const State& s) const {
    return M::coordinate_rates(s.q, s.v, s.t, p_);
  }
  /// Divides each unit quaternion by its norm and enforces the joint limits on each step's
  /// end state (enforce_joint_limits(); the inputs are forces, so the impulse does not depend
  /// on them); only for models with generalized speeds or joint limits.
  template <class Model = M,
            class = std::enable_if_t<has_generalized_speeds_v<Model> || has_joint_limits_v<Model>>>
  void normalize(State* s) const {
    detail::normalize_quaternions<M>(&s->q);
    if constexpr (has_joint_limits_v<M>) {
      if (enforce_limits_) enforce_joint_limits<M>(p_, s);
    }
  }

 private:
  ParamsOf<M> p_;
  ControlLaw<M> law_;
  LawKind kind_;
  bool enforce_limits_ = true;
};

}  // namespace gencoord
