// SPDX-License-Identifier: BSD-3-Clause
// Inverse dynamics of a model with kinematic constraints: the control inputs u (and the
// constraint forces lambda) that give a prescribed acceleration of its independent speeds.
//
// On the constraints, A v' = -gamma fixes the dependent speeds' accelerations from the
// independent ones: A_d v'_d = -gamma - A_i v'_i. The whole v' then needs the generalized
// force Mt v' - f(u = 0) = B u + A^T lambda, with B = dFt/du the input matrix. That is nv
// equations in num_inputs + num_constraints unknowns: well posed when the model has one input
// per degree of freedom (num_inputs = nv - num_constraints), as a motor per crank of a four-bar
// or per arm of a Delta robot, and [B A^T] is invertible there (the motors can move the
// mechanism in every direction it can go).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "gencoord/control/inputs.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"

namespace gencoord {

/// What constrained_inverse_dynamics() returns.
template <class M>
struct ConstrainedInverseDynamics {
  InputVec<M> inputs;    // u
  CVec<M> multipliers;   // lambda, the constraint forces (constrained_acceleration()'s)
  VVec<M> acceleration;  // the whole v', dependent speeds' accelerations included
};

/// The inputs that give the independent speeds v[independent] the accelerations `prescribed`
/// at the state s (on the constraints), with the constraint forces and the whole acceleration.
/// Forward dynamics with those inputs (constrained_acceleration()) gives back the same v'.
/// \param[in] p            The model parameters (their own inputs are ignored).
/// \param[in] s            The state, on the constraints.
/// \param[in] independent  Indices into v of the independent speeds: nv - num_constraints.
/// \param[in] prescribed   Their accelerations, in the same order.
/// \throws std::invalid_argument for a wrong number of indices or values, or an index out of
///         range; DynamicsError (kDependentConstraints) where the dependent speeds are not
///         determined by the independent ones, or the inputs cannot produce the motion
///         ([B A^T] singular).
template <class M>
ConstrainedInverseDynamics<M> constrained_inverse_dynamics(const ParamsOf<M>& p, const State<M>& s,
                                                           const std::vector<int>& independent,
                                                           const Eigen::VectorXd& prescribed) {
  static_assert(has_kinematic_constraints_v<M> && has_inputs_v<M>,
                "gencoord: constrained_inverse_dynamics is for models with kinematic constraints "
                "and control inputs");
  constexpr int nv = nv_of_v<M>, nc = M::num_constraints, nu = num_inputs_v<M>;
  static_assert(nu + nc == nv,
                "gencoord: constrained_inverse_dynamics needs one control input per degree of "
                "freedom (num_inputs = nv - num_constraints)");
  std::vector<bool> is_independent(nv, false);
  for (const int i : independent) {
    if (i < 0 || i >= nv || is_independent[i])
      throw std::invalid_argument(std::string("gencoord: constrained_inverse_dynamics of '") +
                                  M::name + "': independent speed index " + std::to_string(i) +
                                  " is out of range or repeated");
    is_independent[i] = true;
  }
  if (static_cast<int>(independent.size()) != nu || prescribed.size() != nu)
    throw std::invalid_argument(std::string("gencoord: constrained_inverse_dynamics of '") +
                                M::name + "' needs " + std::to_string(nu) +
                                " independent speeds and as many accelerations");
  const auto fail = [&] {
    detail::throw_dynamics_error(M::name, DynamicsError::Reason::kDependentConstraints, s.t,
                                 s.q.data(), s.v.data(), M::nq, nv);
  };
  // the dependent speeds' accelerations from A v' = -gamma
  const CJac<M> A = M::constraint_jacobian(s.q, s.t, p);
  const CVec<M> gamma = M::constraint_bias(s.q, s.v, s.t, p);
  Eigen::Matrix<double, nc, nc> A_dependent;
  CVec<M> rhs = -gamma;
  VVec<M> acceleration = VVec<M>::Zero();
  for (int k = 0, column = 0; k < nv; ++k) {
    if (is_independent[k]) continue;
    A_dependent.col(column++) = A.col(k);
  }
  for (int k = 0; k < nu; ++k) {
    acceleration[independent[k]] = prescribed[k];
    rhs -= A.col(independent[k]) * prescribed[k];
  }
  const Eigen::FullPivLU<Eigen::Matrix<double, nc, nc>> dependent(A_dependent);
  if (!dependent.isInvertible()) fail();
  const CVec<M> dependent_acceleration = dependent.solve(rhs);
  for (int k = 0, row = 0; k < nv; ++k)
    if (!is_independent[k]) acceleration[k] = dependent_acceleration[row++];
  // the generalized force it takes, from the inputs and the constraints
  VMat<M> Mt;
  VVec<M> f;
  const ParamsOf<M> unforced = with_inputs<M>(p, InputVec<M>::Zero());
  M::dynamics(s.q, s.v, s.t, unforced, &Mt, &f);
  Eigen::Matrix<double, nv, nv> forces_of;
  forces_of << M::input_matrix(s.q, s.v, s.t, unforced), A.transpose();
  const Eigen::FullPivLU<Eigen::Matrix<double, nv, nv>> actuation(forces_of);
  if (!actuation.isInvertible()) fail();
  const VVec<M> unknowns = actuation.solve(VVec<M>(Mt * acceleration - f));
  ConstrainedInverseDynamics<M> out;
  out.inputs = unknowns.template head<nu>();
  out.multipliers = unknowns.template tail<nc>();
  out.acceleration = acceleration;
  return out;
}

}  // namespace gencoord
