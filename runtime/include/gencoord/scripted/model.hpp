// SPDX-License-Identifier: BSD-3-Clause
// Dynamics with scripted (prescribed) coordinates, chosen at runtime without regenerating.
//
// Split v = (v_f, v_s): the script gives a scripted coordinate's q_s(t), its rate v_s(t) and
// a_s(t); the free part obeys
//   Mt_ff a_f = (Ft + Fi)_f - Mt_fs a_s
// i.e. the free rows of the residual r(q, v, a) = Mt a - Ft - Fi vanish, and the scripted rows
//   tau_s = r_s(q, v, a)
// are the generalized forces that drive the scripted coordinates along the script.
// The free acceleration's Jacobians follow from r_f(q, v, a(q, v)) = 0 as in the unscripted
// case, restricted to the free-free blocks: da_f/dq_f = -Mt_ff^-1 (dr/dq)_ff and
// da_f/dv_f = -Mt_ff^-1 (dr/dv)_ff (the scripted q_s, v_s do not vary within a step).
//
// In a model with generalized speeds (free and ball joints, q' = G(q) v) the split is over
// the speeds: a scripted coordinate must be one whose rate is a speed of its own
// (M::coordinate_speeds; a revolute or prismatic joint's), not a free or ball joint's. The
// free part is integrated on q' = G(q) v with unit quaternions (coordinate_rate, normalize),
// and dq_f above is the derivative along the free speeds, (dr/dq) G: a free speed's direction
// G e_j moves no scripted coordinate, whose rate is its own speed alone.
#pragma once

#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "gencoord/errors.hpp"
#include "gencoord/integrate/system.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/heap_matrix.hpp"
#include "gencoord/model/inverse_dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/model/state.hpp"
#include "gencoord/model/tangent_space.hpp"
#include "gencoord/numerics/dense_solve.hpp"
#include "gencoord/scripted/script.hpp"

namespace gencoord {

/// Model M with the coordinates of a Script prescribed, a system for the integrators
/// (integrate/system.hpp): the free speeds are integrated, the scripted coordinates and their
/// speeds are set from the script at every stage time (impose()); Newton runs over the free
/// speeds. Holds the parameters, the script and the free/scripted index lists; every function
/// is const and thread-compatible.
template <class M>
class ScriptedModel {
  static constexpr int nv = nv_of_v<M>;

 public:
  /// Vectors and matrices over the free speeds (dim n_f <= nv): fixed capacity, no heap
  /// allocation, except for a matrix whose capacity would pass Eigen's stack limit.
  using FreeVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, nv, 1>;
  static constexpr int kMatrixCapacity =
      std::is_same_v<SizedMatrix<double, nv, nv>, Eigen::Matrix<double, nv, nv>> ? nv
                                                                                 : Eigen::Dynamic;
  using FreeMatrix =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMatrixCapacity, kMatrixCapacity>;
  using State = gencoord::State<M>;
  using Unknowns = FreeVector;
  using Matrix = FreeMatrix;
  static constexpr bool unit_mass = true;

  /// \param[in] p       The model parameters.
  /// \param[in] script  The prescribed motion; its coordinates index M's coordinates.
  /// \throws std::invalid_argument if a scripted index is not in [0, M::nq), or names a
  ///         coordinate of a free or ball joint.
  ScriptedModel(ParamsOf<M> p, Script script) : p_(std::move(p)), script_(std::move(script)) {
    static_assert(assert_model_v<M>);
    std::vector<bool> is_scripted(nv, false);
    for (const int i : script_.coordinates()) {
      if (i < 0 || i >= M::nq)
        throw std::invalid_argument("gencoord: scripted coordinate index " + std::to_string(i) +
                                    " is out of range for model '" + M::name +
                                    "' (nq = " + std::to_string(M::nq) + ")");
      const int speed = speed_of(i);
      if (speed < 0)
        throw std::invalid_argument(
            std::string("gencoord: coordinate '") + M::coordinate_names[i] + "' of model '" +
            M::name + "' belongs to a free or ball joint and cannot be scripted: its rate is " +
            "no speed of its own; script revolute and prismatic joints' coordinates");
      scripted_speeds_.push_back(speed);
      is_scripted[static_cast<std::size_t>(speed)] = true;
    }
    for (int j = 0; j < nv; ++j)
      if (!is_scripted[static_cast<std::size_t>(j)]) free_.push_back(j);
  }

  const ParamsOf<M>& params() const { return p_; }
  const Script& script() const { return script_; }
  /// Indices of the free speeds (n_f, increasing); in a model whose v is q', the free
  /// coordinates.
  const std::vector<int>& free_coordinates() const { return free_; }
  /// Indices of the scripted coordinates (k, in the script's order).
  const std::vector<int>& scripted_coordinates() const { return script_.coordinates(); }
  /// Indices of their speeds (k, in the script's order); in a model whose v is q', the same.
  const std::vector<int>& scripted_speeds() const { return scripted_speeds_; }
  int num_free() const { return static_cast<int>(free_.size()); }

  /// The script at time t. \throws as Script::operator().
  ScriptSample sample(double t) const { return script_(t); }

  /// Overwrites the scripted entries of q and v with the script's values in `at`.
  void impose(const ScriptSample& at, QVec<M>* q, VVec<M>* v) const {
    const std::vector<int>& s = scripted_coordinates();
    for (std::size_t j = 0; j < s.size(); ++j) {
      const auto jj = static_cast<Eigen::Index>(j);
      if (q) (*q)[s[j]] = at.q[jj];
      if (v) (*v)[scripted_speeds_[j]] = at.v[jj];
    }
  }

  /// The state s with its scripted q and v set from the script at s.t.
  /// \throws as Script::operator().
  State imposed(State s) const {
    impose(&s);
    return s;
  }

  /// Sets the scripted q and v of *s from the script at s->t. \throws as Script::operator().
  void impose(State* s) const { impose(sample(s->t), &s->q, &s->v); }

  const char* name() const { return M::name; }
  void check(const State&, double) const {}

  /// q' = G(q) v (M::coordinate_rates); only for models with generalized speeds.
  template <class Model = M, class = std::enable_if_t<has_generalized_speeds_v<Model>>>
  QVec<M> coordinate_rate(const State& s) const {
    return M::coordinate_rates(s.q, s.v, s.t, p_);
  }
  /// Divides each unit quaternion of q by its norm; only for models with generalized speeds.
  template <class Model = M, class = std::enable_if_t<has_generalized_speeds_v<Model>>>
  void normalize(State* s) const {
    detail::normalize_quaternions<M>(&s->q);
  }

  /// acceleration(s.q, s.v, s.t): the scripted entries are the script's a_s.
  VVec<M> acceleration(const State& s) const { return acceleration(s.q, s.v, s.t); }

  /// The free acceleration and its free-free Jacobians at s (acceleration_and_jacobians()).
  void linearize(const State& s, JacobianSource source, Linearization<ScriptedModel>* out) const {
    VVec<M> a;
    acceleration_and_jacobians(s.q, s.v, s.t, sample(s.t), source, &a, &out->force_D_q,
                               &out->force_D_v);
    out->force = free_part(a);
  }

  /// A singular A gives a non-finite x.
  bool solve(const FreeMatrix& A, const FreeVector& b, FreeVector* x) const {
    return detail::dense_lu_solve(A, b, x);
  }

  /// The full acceleration a (dim nv): a_s = the script's a_s(t), a_f solved from
  /// Mt_ff a_f = (Ft + Fi)_f - Mt_fs a_s. q and v are used as given (their scripted entries
  /// should be the script's; see imposed()).
  /// \param[in] q   The generalized coordinates (dim M::nq).
  /// \param[in] v   The generalized velocities or speeds (dim nv).
  /// \param[in] t   The time.
  /// \param[in] at  The script at t (sample(t)).
  /// \throws DynamicsError if Mt_ff is not positive definite or something is not finite.
  VVec<M> acceleration(const QVec<M>& q, const VVec<M>& v, double t, const ScriptSample& at) const {
    FreeMatrix factor;
    return solve_acceleration(q, v, t, at, &factor);
  }

  /// acceleration(q, v, t, sample(t)). \throws as acceleration() and Script::operator().
  VVec<M> acceleration(const QVec<M>& q, const VVec<M>& v, double t) const {
    return acceleration(q, v, t, sample(t));
  }

  /// The full acceleration and the free-free Jacobians of the free acceleration,
  /// da_f/dq_f and da_f/dv_f (each dim n_f x n_f; with generalized speeds dq_f is along the
  /// free speeds), from `source`: generated (one Cholesky factor of Mt_ff, one
  /// residual_jacobians() call) or central finite differences over the free speeds
  /// (4 n_f + 1 accelerations).
  /// \param[out] a        Full acceleration (dim nv); must not be null.
  /// \param[out] af_D_qf  da_f/dq_f; must not be null.
  /// \param[out] af_D_vf  da_f/dv_f; must not be null.
  /// \throws DynamicsError as acceleration(); std::invalid_argument if source is Generated
  ///         and M has no residual_jacobians().
  void acceleration_and_jacobians(const QVec<M>& q, const VVec<M>& v, double t,
                                  const ScriptSample& at, JacobianSource source, VVec<M>* a,
                                  FreeMatrix* af_D_qf, FreeMatrix* af_D_vf) const {
    const int nf = num_free();
    af_D_qf->resize(nf, nf);
    af_D_vf->resize(nf, nf);
    if (resolve_jacobian_source<M>(source) == JacobianSource::FiniteDifference) {
      *a = acceleration(q, v, t, at);
      fd_jacobians(q, v, t, at, af_D_qf, af_D_vf);
      return;
    }
    if constexpr (has_residual_jacobians_v<M>) {
      FreeMatrix factor;
      *a = solve_acceleration(q, v, t, at, &factor);
      if (nf == 0) return;  // everything scripted: no unknowns
      VQMat<M> r_D_q;
      VMat<M> r_D_v;
      M::residual_jacobians(q, v, *a, t, p_, &r_D_q, &r_D_v);
      if constexpr (has_generalized_speeds_v<M>) {
        const VMat<M> r_D_speeds = r_D_q * detail::rate_matrix_transposed<M>(p_, q, t).transpose();
        *af_D_qf = -free_block(r_D_speeds);
      } else {
        *af_D_qf = -free_block(r_D_q);
      }
      *af_D_vf = -free_block(r_D_v);
      cholesky_solve(factor, *af_D_qf);
      cholesky_solve(factor, *af_D_vf);
    } else {
      detail::throw_no_generated_jacobians(M::name);
    }
  }

  /// The generalized forces that drive the scripted coordinates: tau_s = r_s(q, v, a), the
  /// scripted speeds' rows of the inverse-dynamics residual at the full acceleration a =
  /// acceleration(q, v, t) (dim k, in the script's order). For a scripted joint angle it is
  /// the joint torque the actuator must supply.
  /// \throws as acceleration() and Script::operator().
  Eigen::VectorXd driving_force(const QVec<M>& q, const VVec<M>& v, double t) const {
    const VVec<M> a = acceleration(q, v, t);
    const VVec<M> r = inverse_dynamics<M>(p_, q, v, a, t);
    Eigen::VectorXd tau(static_cast<Eigen::Index>(scripted_speeds_.size()));
    for (std::size_t j = 0; j < scripted_speeds_.size(); ++j)
      tau[static_cast<Eigen::Index>(j)] = r[scripted_speeds_[j]];
    return tau;
  }

  /// driving_force(s.q, s.v, s.t) at a state whose scripted entries follow the script.
  Eigen::VectorXd driving_force(const State& s) const { return driving_force(s.q, s.v, s.t); }

  /// The free entries of x (dim n_f).
  FreeVector free_part(const VVec<M>& x) const {
    FreeVector out(num_free());
    for (int i = 0; i < num_free(); ++i) out[i] = x[free_[static_cast<std::size_t>(i)]];
    return out;
  }

  /// Adds dx (dim n_f) to the free entries of x.
  void add_to_free(const FreeVector& dx, VVec<M>* x) const {
    for (int i = 0; i < num_free(); ++i) (*x)[free_[static_cast<std::size_t>(i)]] += dx[i];
  }

 private:
  // the speed whose value is coordinate i's rate, -1 for a free or ball joint's coordinate
  static int speed_of(int i) {
    if constexpr (has_generalized_speeds_v<M>) {
      return M::coordinate_speeds[static_cast<std::size_t>(i)];
    } else {
      return i;
    }
  }

  // rows and columns of the free speeds
  FreeMatrix free_block(const VMat<M>& A) const {
    const int nf = num_free();
    FreeMatrix out(nf, nf);
    for (int i = 0; i < nf; ++i)
      for (int j = 0; j < nf; ++j)
        out(i, j) = A(free_[static_cast<std::size_t>(i)], free_[static_cast<std::size_t>(j)]);
    return out;
  }

  VVec<M> solve_acceleration(const QVec<M>& q, const VVec<M>& v, double t, const ScriptSample& at,
                             FreeMatrix* factor) const {
    using Reason = DynamicsError::Reason;
    VMat<M> Mt;
    VVec<M> f;
    M::dynamics(q, v, t, p_, &Mt, &f);
    if (!Mt.allFinite())
      detail::throw_dynamics_error(M::name, Reason::kNonFiniteMassMatrix, t, q.data(), v.data(),
                                   M::nq, nv);
    if (!f.allFinite())
      detail::throw_dynamics_error(M::name, Reason::kNonFiniteForces, t, q.data(), v.data(), M::nq,
                                   nv);
    // a_s from the script; right-hand side (Ft + Fi)_f - Mt_fs a_s
    VVec<M> a = VVec<M>::Zero();
    for (std::size_t j = 0; j < scripted_speeds_.size(); ++j)
      a[scripted_speeds_[j]] = at.a[static_cast<Eigen::Index>(j)];
    const int nf = num_free();
    if (nf == 0) return a;
    const VVec<M> rhs_full = f - Mt * a;  // free rows: (Ft + Fi)_f - Mt_fs a_s
    *factor = free_block(Mt);
    if (!cholesky_factor(*factor))
      detail::throw_dynamics_error(M::name, Reason::kNotPositiveDefinite, t, q.data(), v.data(),
                                   M::nq, nv);
    FreeVector af = free_part(rhs_full);
    cholesky_solve(*factor, af);
    if (!af.allFinite())
      detail::throw_dynamics_error(M::name, Reason::kNonFiniteAcceleration, t, q.data(), v.data(),
                                   M::nq, nv);
    for (int i = 0; i < nf; ++i) a[free_[static_cast<std::size_t>(i)]] = af[i];
    return a;
  }

  // q moved by h along free speed j: q + h e_j, or retract(q, h e_j) with generalized speeds
  QVec<M> moved(const QVec<M>& q, int j, double h, double t) const {
    if constexpr (has_generalized_speeds_v<M>) {
      VVec<M> delta = VVec<M>::Zero();
      delta[j] = h;
      return retract<M>(p_, q, delta, t);
    } else {
      (void)t;
      QVec<M> out = q;
      out[j] += h;
      return out;
    }
  }

  // central differences of a_f over the free q (along the free speeds) and v, as
  // acceleration_jacobians_fd()
  void fd_jacobians(const QVec<M>& q, const VVec<M>& v, double t, const ScriptSample& at,
                    FreeMatrix* af_D_qf, FreeMatrix* af_D_vf) const {
    using detail::central_difference_step;
    for (int j = 0; j < num_free(); ++j) {
      const int c = free_[static_cast<std::size_t>(j)];
      // a speed's direction has no coordinate of its own to scale the step by
      const double hq = central_difference_step(has_generalized_speeds_v<M> ? 0.0 : q[c]);
      af_D_qf->col(j) = (free_part(acceleration(moved(q, c, hq, t), v, t, at)) -
                         free_part(acceleration(moved(q, c, -hq, t), v, t, at))) /
                        (2 * hq);
      VVec<M> vp = v, vm = v;
      vp[c] += central_difference_step(v[c]);
      vm[c] -= central_difference_step(v[c]);
      af_D_vf->col(j) =
          (free_part(acceleration(q, vp, t, at)) - free_part(acceleration(q, vm, t, at))) /
          (vp[c] - vm[c]);
    }
  }

  ParamsOf<M> p_;
  Script script_;
  std::vector<int> scripted_speeds_;
  std::vector<int> free_;
};

}  // namespace gencoord
