// SPDX-License-Identifier: BSD-3-Clause
// Dynamics with scripted (prescribed) coordinates, chosen at runtime without regenerating.
//
// Split q = (q_f, q_s): the script gives q_s(t), v_s(t), a_s(t); the free part obeys
//   Mt_ff a_f = (Ft + Fi)_f - Mt_fs a_s
// i.e. the free rows of the residual r(q, v, a) = Mt a - Ft - Fi vanish, and the scripted rows
//   tau_s = r_s(q, v, a)
// are the generalized forces that drive the scripted coordinates along the script.
// The free acceleration's Jacobians follow from r_f(q, v, a(q, v)) = 0 as in the unscripted
// case, restricted to the free-free blocks: da_f/dq_f = -Mt_ff^-1 (dr/dq)_ff and
// da_f/dv_f = -Mt_ff^-1 (dr/dv)_ff (the scripted q_s, v_s do not vary within a step).
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
#include "gencoord/numerics/dense_solve.hpp"
#include "gencoord/scripted/script.hpp"

namespace gencoord {

/// Model M with the coordinates of a Script prescribed, a system for the integrators
/// (integrate/system.hpp): the free coordinates are integrated, the scripted ones are set
/// from the script at every stage time (impose()); Newton runs over the free velocities.
/// Holds the parameters, the script and the free/scripted index lists; every function is
/// const and thread-compatible.
template <class M>
class ScriptedModel {
  static_assert(!has_generalized_speeds_v<M>,
                "gencoord: scripted coordinates does not support models with generalized speeds "
                "(free or ball "
                "joints) yet");

 public:
  /// Vectors and matrices over the free coordinates (dim n_f <= M::nq): fixed capacity, no
  /// heap allocation, except for a matrix whose capacity would pass Eigen's stack limit.
  using FreeVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, M::nq, 1>;
  static constexpr int kMatrixCapacity =
      std::is_same_v<SizedMatrix<double, M::nq, M::nq>, Eigen::Matrix<double, M::nq, M::nq>>
          ? M::nq
          : Eigen::Dynamic;
  using FreeMatrix =
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMatrixCapacity, kMatrixCapacity>;
  using State = gencoord::State<M>;
  using Unknowns = FreeVector;
  using Matrix = FreeMatrix;
  static constexpr bool unit_mass = true;

  /// \param[in] p       The model parameters.
  /// \param[in] script  The prescribed motion; its coordinates index M's coordinates.
  /// \throws std::invalid_argument if a scripted index is not in [0, M::nq).
  ScriptedModel(ParamsOf<M> p, Script script) : p_(std::move(p)), script_(std::move(script)) {
    static_assert(assert_model_v<M>);
    std::vector<bool> is_scripted(M::nq, false);
    for (const int i : script_.coordinates()) {
      if (i < 0 || i >= M::nq)
        throw std::invalid_argument("gencoord: scripted coordinate index " + std::to_string(i) +
                                    " is out of range for model '" + M::name +
                                    "' (nq = " + std::to_string(M::nq) + ")");
      is_scripted[static_cast<std::size_t>(i)] = true;
    }
    for (int i = 0; i < M::nq; ++i)
      if (!is_scripted[static_cast<std::size_t>(i)]) free_.push_back(i);
  }

  const ParamsOf<M>& params() const { return p_; }
  const Script& script() const { return script_; }
  /// Indices of the free coordinates (n_f, increasing).
  const std::vector<int>& free_coordinates() const { return free_; }
  /// Indices of the scripted coordinates (k, in the script's order).
  const std::vector<int>& scripted_coordinates() const { return script_.coordinates(); }
  int num_free() const { return static_cast<int>(free_.size()); }

  /// The script at time t. \throws as Script::operator().
  ScriptSample sample(double t) const { return script_(t); }

  /// Overwrites the scripted entries of q and v with the script's values in `at`.
  void impose(const ScriptSample& at, QVec<M>* q, QVec<M>* v) const {
    const std::vector<int>& s = scripted_coordinates();
    for (std::size_t j = 0; j < s.size(); ++j) {
      const auto jj = static_cast<Eigen::Index>(j);
      if (q) (*q)[s[j]] = at.q[jj];
      if (v) (*v)[s[j]] = at.v[jj];
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

  /// acceleration(s.q, s.v, s.t): the scripted entries are the script's a_s.
  QVec<M> acceleration(const State& s) const { return acceleration(s.q, s.v, s.t); }

  /// The free acceleration and its free-free Jacobians at s (acceleration_and_jacobians()).
  void linearize(const State& s, JacobianSource source, Linearization<ScriptedModel>* out) const {
    QVec<M> a;
    acceleration_and_jacobians(s.q, s.v, s.t, sample(s.t), source, &a, &out->force_D_q,
                               &out->force_D_v);
    out->force = free_part(a);
  }

  /// A singular A gives a non-finite x.
  bool solve(const FreeMatrix& A, const FreeVector& b, FreeVector* x) const {
    return detail::dense_lu_solve(A, b, x);
  }

  /// The full acceleration a (dim M::nq): a_s = the script's a_s(t), a_f solved from
  /// Mt_ff a_f = (Ft + Fi)_f - Mt_fs a_s. q and v are used as given (their scripted entries
  /// should be the script's; see imposed()).
  /// \param[in] q   The generalized coordinates (dim M::nq).
  /// \param[in] v   The generalized velocities (dim M::nq).
  /// \param[in] t   The time.
  /// \param[in] at  The script at t (sample(t)).
  /// \throws DynamicsError if Mt_ff is not positive definite or something is not finite.
  QVec<M> acceleration(const QVec<M>& q, const QVec<M>& v, double t, const ScriptSample& at) const {
    FreeMatrix factor;
    return solve_acceleration(q, v, t, at, &factor);
  }

  /// acceleration(q, v, t, sample(t)). \throws as acceleration() and Script::operator().
  QVec<M> acceleration(const QVec<M>& q, const QVec<M>& v, double t) const {
    return acceleration(q, v, t, sample(t));
  }

  /// The full acceleration and the free-free Jacobians of the free acceleration,
  /// da_f/dq_f and da_f/dv_f (each dim n_f x n_f), from `source`: generated (one Cholesky
  /// factor of Mt_ff, one residual_jacobians() call) or central finite differences over the
  /// free coordinates (4 n_f + 1 accelerations).
  /// \param[out] a        Full acceleration (dim M::nq); must not be null.
  /// \param[out] af_D_qf  da_f/dq_f; must not be null.
  /// \param[out] af_D_vf  da_f/dv_f; must not be null.
  /// \throws DynamicsError as acceleration(); std::invalid_argument if source is Generated
  ///         and M has no residual_jacobians().
  void acceleration_and_jacobians(const QVec<M>& q, const QVec<M>& v, double t,
                                  const ScriptSample& at, JacobianSource source, QVec<M>* a,
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
      QMat<M> r_D_q, r_D_v;
      M::residual_jacobians(q, v, *a, t, p_, &r_D_q, &r_D_v);
      *af_D_qf = -free_block(r_D_q);
      *af_D_vf = -free_block(r_D_v);
      cholesky_solve(factor, *af_D_qf);
      cholesky_solve(factor, *af_D_vf);
    } else {
      detail::throw_no_generated_jacobians(M::name);
    }
  }

  /// The generalized forces that drive the scripted coordinates: tau_s = r_s(q, v, a), the
  /// scripted rows of the inverse-dynamics residual at the full acceleration a =
  /// acceleration(q, v, t) (dim k, in the script's order). For a scripted joint angle it is
  /// the joint torque the actuator must supply.
  /// \throws as acceleration() and Script::operator().
  Eigen::VectorXd driving_force(const QVec<M>& q, const QVec<M>& v, double t) const {
    const QVec<M> a = acceleration(q, v, t);
    const QVec<M> r = inverse_dynamics<M>(p_, q, v, a, t);
    const std::vector<int>& s = scripted_coordinates();
    Eigen::VectorXd tau(static_cast<Eigen::Index>(s.size()));
    for (std::size_t j = 0; j < s.size(); ++j) tau[static_cast<Eigen::Index>(j)] = r[s[j]];
    return tau;
  }

  /// driving_force(s.q, s.v, s.t) at a state whose scripted entries follow the script.
  Eigen::VectorXd driving_force(const State& s) const { return driving_force(s.q, s.v, s.t); }

  /// The free entries of x (dim n_f).
  FreeVector free_part(const QVec<M>& x) const {
    FreeVector out(num_free());
    for (int i = 0; i < num_free(); ++i) out[i] = x[free_[static_cast<std::size_t>(i)]];
    return out;
  }

  /// Adds dx (dim n_f) to the free entries of x.
  void add_to_free(const FreeVector& dx, QVec<M>* x) const {
    for (int i = 0; i < num_free(); ++i) (*x)[free_[static_cast<std::size_t>(i)]] += dx[i];
  }

 private:
  // rows and columns of the free coordinates
  FreeMatrix free_block(const QMat<M>& A) const {
    const int nf = num_free();
    FreeMatrix out(nf, nf);
    for (int i = 0; i < nf; ++i)
      for (int j = 0; j < nf; ++j)
        out(i, j) = A(free_[static_cast<std::size_t>(i)], free_[static_cast<std::size_t>(j)]);
    return out;
  }

  QVec<M> solve_acceleration(const QVec<M>& q, const QVec<M>& v, double t, const ScriptSample& at,
                             FreeMatrix* factor) const {
    using Reason = DynamicsError::Reason;
    QMat<M> Mt;
    QVec<M> f;
    M::dynamics(q, v, t, p_, &Mt, &f);
    if (!Mt.allFinite())
      detail::throw_dynamics_error(M::name, Reason::kNonFiniteMassMatrix, t, q.data(), v.data(),
                                   M::nq);
    if (!f.allFinite())
      detail::throw_dynamics_error(M::name, Reason::kNonFiniteForces, t, q.data(), v.data(), M::nq);
    // a_s from the script; right-hand side (Ft + Fi)_f - Mt_fs a_s
    QVec<M> a = QVec<M>::Zero();
    const std::vector<int>& s = scripted_coordinates();
    for (std::size_t j = 0; j < s.size(); ++j) a[s[j]] = at.a[static_cast<Eigen::Index>(j)];
    const int nf = num_free();
    if (nf == 0) return a;
    const QVec<M> rhs_full = f - Mt * a;  // free rows: (Ft + Fi)_f - Mt_fs a_s
    *factor = free_block(Mt);
    if (!cholesky_factor(*factor))
      detail::throw_dynamics_error(M::name, Reason::kNotPositiveDefinite, t, q.data(), v.data(),
                                   M::nq);
    FreeVector af = free_part(rhs_full);
    cholesky_solve(*factor, af);
    if (!af.allFinite())
      detail::throw_dynamics_error(M::name, Reason::kNonFiniteAcceleration, t, q.data(), v.data(),
                                   M::nq);
    for (int i = 0; i < nf; ++i) a[free_[static_cast<std::size_t>(i)]] = af[i];
    return a;
  }

  // central differences of a_f over the free q and v, as acceleration_jacobians_fd()
  void fd_jacobians(const QVec<M>& q, const QVec<M>& v, double t, const ScriptSample& at,
                    FreeMatrix* af_D_qf, FreeMatrix* af_D_vf) const {
    using detail::central_difference_step;
    for (int j = 0; j < num_free(); ++j) {
      const int c = free_[static_cast<std::size_t>(j)];
      QVec<M> qp = q, qm = q;
      qp[c] += central_difference_step(q[c]);
      qm[c] -= central_difference_step(q[c]);
      af_D_qf->col(j) =
          (free_part(acceleration(qp, v, t, at)) - free_part(acceleration(qm, v, t, at))) /
          (qp[c] - qm[c]);
      QVec<M> vp = v, vm = v;
      vp[c] += central_difference_step(v[c]);
      vm[c] -= central_difference_step(v[c]);
      af_D_vf->col(j) =
          (free_part(acceleration(q, vp, t, at)) - free_part(acceleration(q, vm, t, at))) /
          (vp[c] - vm[c]);
    }
  }

  ParamsOf<M> p_;
  Script script_;
  std::vector<int> free_;
};

}  // namespace gencoord
