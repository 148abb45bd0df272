// SPDX-License-Identifier: BSD-3-Clause
// The maximal-coordinate (penalty) model of a generated model M: every particle free in
// x (nx = dim * num_particles), the same external forces, each declared constraint a stiff
// spring of stiffness kappa (generated `M::Maximal` kernels), plus two terms the runtime adds:
//  - generalized forces Q(q, v) (acting on q in the reduced model) mapped to x-space as
//    F = M J Mt^-1 Q at (q, v) from the inverse map, so that J^T F = Q;
//  - for a model without declared constraints but with nv < nx, a zero-length spring kappa
//    from every particle to its closest point X(q*(x)) on the parameterized manifold.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/QR>
#include <Eigen/SparseCore>

#include "gencoord/integrate/system.hpp"
#include "gencoord/maximal/errors.hpp"
#include "gencoord/maximal/inverse_map.hpp"
#include "gencoord/maximal/state.hpp"
#include "gencoord/maximal/traits.hpp"
#include "gencoord/model/acceleration_jacobians.hpp"
#include "gencoord/model/heap_matrix.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord/numerics/sparse_lu.hpp"

namespace gencoord {

/// The maximal (penalty) model of M at one penalty stiffness, a system for the integrators
/// (integrate/system.hpp): mass-weighted Newton residual, sparse Jacobians solved by SparseLU.
/// Evaluating forces may run the inverse map, warm-started from the previous solution (a
/// mutable cache): one instance must not be used from several threads at once.
template <class M>
class MaximalModel {
 public:
  using Max = MaximalOf<M>;
  static constexpr int nx = M::nx;
  static constexpr int num_constraints = Max::num_constraints;
  /// Whether the manifold spring replaces declared constraints (none declared, nv < nx).
  static constexpr bool manifold_spring = uses_manifold_spring_v<M>;
  /// Whether forces need the inverse map (generalized forces, or the manifold spring).
  static constexpr bool needs_inverse_map = needs_inverse_map_v<M>;
  using State = MaximalState<M>;
  using Unknowns = XVec<M>;
  using Matrix = Eigen::SparseMatrix<double>;
  static constexpr bool unit_mass = false;

  /// \param[in] p                The model parameters (copied).
  /// \param[in] kappa            Penalty stiffness, >= 0 (rods: force per unit strain, N;
  ///                             pins, planes and the manifold spring: N/m).
  /// \param[in] penalty_damping  Penalty damping coefficient, >= 0.
  /// \param[in] q_guess          First warm start of the inverse map (nq); M::initial_q if omitted.
  /// \throws std::invalid_argument if kappa or penalty_damping is negative or not finite, or a
  ///         particle mass is not positive (the maximal model divides by every mass).
  explicit MaximalModel(const ParamsOf<M>& p, double kappa, double penalty_damping = 0.0,
                        const QVec<M>& q_guess = initial_q_of<M>())
      : p_(p),
        kappa_(kappa),
        damping_(penalty_damping),
        masses_(coordinate_masses<M>(p)),
        q_guess_(q_guess),
        name_(std::string(M::name) + " (maximal)") {
    static_assert(assert_model_v<M>);
    static_assert(has_maximal_v<M>, "gencoord: the model has no generated Maximal struct");
    if (!(kappa >= 0.0) || !std::isfinite(kappa) || !(penalty_damping >= 0.0) ||
        !std::isfinite(penalty_damping))
      throw std::invalid_argument("gencoord: MaximalModel needs kappa >= 0 and damping >= 0");
    if (!(masses_.minCoeff() > 0.0))
      throw std::invalid_argument(std::string("gencoord: the maximal model of '") + M::name +
                                  "' needs every particle mass to be positive");
    inverse_options_.max_residual = std::numeric_limits<double>::infinity();
    inverse_options_.max_iterations = 100;
  }

  const ParamsOf<M>& params() const { return p_; }
  double kappa() const { return kappa_; }
  double penalty_damping() const { return damping_; }
  /// The diagonal of the mass matrix: each particle's mass, dim times (nx).
  const XVec<M>& masses() const { return masses_; }
  /// The inverse map's current warm start (nq): the last closest-point coordinates.
  const QVec<M>& warm_start() const { return q_guess_; }
  /// Sets the inverse map's warm start (nq), e.g. after a jump in the state.
  void set_warm_start(const QVec<M>& q) const { q_guess_ = q; }

  /// Total force on the particles: external + penalty (+ mapped generalized forces, + manifold
  /// spring), at positions x and velocities xdot (nx each), time t. Returns nx entries.
  /// \throws InverseMapError if the inverse map is needed and fails (singular J, NaN state).
  XVec<M> force(const XVec<M>& x, const XVec<M>& xdot, double t) const {
    XVec<M> f = Max::external_forces(x, xdot, t, p_) +
                Max::penalty_forces(x, xdot, t, kappa_, damping_, p_);
    if constexpr (needs_inverse_map) {
      const QVec<M> q = closest_point(x, t);
      const VVec<M> v = inverse_map_velocities<M>(p_, q, xdot, t);
      if constexpr (Max::has_generalized_forces) f += mapped_generalized_forces(q, v, t);
      if constexpr (manifold_spring)
        f -= kappa_ * (x - M::positions(q, t, p_)) + damping_ * (xdot - M::velocities(q, v, t, p_));
    }
    return f;
  }

  /// Particle accelerations M^-1 F (nx). \throws InverseMapError as force().
  XVec<M> acceleration(const XVec<M>& x, const XVec<M>& xdot, double t) const {
    return force(x, xdot, t).cwiseQuotient(masses_);
  }

  /// "<name> (maximal)", for error messages.
  const char* name() const { return name_.c_str(); }
  /// acceleration(s.q, s.v, s.t). \throws as force().
  XVec<M> acceleration(const State& s) const { return acceleration(s.q, s.v, s.t); }
  void impose(State*) const {}
  /// \throws MaximalDivergedError if the state is not finite.
  void check(const State& s, double dt) const {
    if (!s.q.allFinite() || !s.v.allFinite()) throw MaximalDivergedError(M::name, s.t, dt, kappa_);
  }
  const XVec<M>& free_part(const XVec<M>& x) const { return x; }
  void add_to_free(const XVec<M>& dx, XVec<M>* x) const { *x += dx; }
  /// The force and its sparse Jacobians (force_jacobian_triplets()).
  /// \throws as force().
  void linearize(const State& s, JacobianSource, Linearization<MaximalModel>* out) const {
    out->force = force(s.q, s.v, s.t);
    std::vector<Eigen::Triplet<double>> K_x, K_v;
    K_x.reserve(jacobian_triplet_count(Max::jacobian_x_nonzeros));
    K_v.reserve(jacobian_triplet_count(Max::jacobian_xdot_nonzeros));
    force_jacobian_triplets(s.q, s.v, s.t, &K_x, &K_v);
    out->force_D_q.resize(nx, nx);
    out->force_D_q.setFromTriplets(K_x.begin(), K_x.end());
    out->force_D_v.resize(nx, nx);
    out->force_D_v.setFromTriplets(K_v.begin(), K_v.end());
  }
  /// Sparse LU; false if A is singular. The ordering is computed on the first call and kept:
  /// every A the integrators pass has the same pattern (that of m - h (h K_x + K_v), K_x and
  /// K_v from the fixed triplet lists of force_jacobian_triplets(), whose zero values are
  /// stored entries too, as setFromTriplets() and sparse sums keep them).
  bool solve(const Matrix& A, const XVec<M>& b, XVec<M>* x) const { return lu_.solve(A, b, *x); }

  /// Kinetic energy 1/2 xdot^T M xdot.
  double kinetic_energy(const MaximalState<M>& s) const {
    return 0.5 * s.v.dot(masses_.cwiseProduct(s.v));
  }

  /// Total energy T + V_x + V_penalty (+ the manifold spring's energy, + the generalized
  /// potential at q(x) when the model has generalized forces).
  /// \throws InverseMapError if the inverse map is needed and fails.
  double energy(const MaximalState<M>& s) const {
    double e = kinetic_energy(s) + Max::potential_energy(s.q, s.t, p_) +
               Max::penalty_energy(s.q, s.t, kappa_, p_);
    if constexpr (needs_inverse_map) {
      const QVec<M> q = closest_point(s.q, s.t);
      if constexpr (Max::has_generalized_forces) e += M::generalized_potential_energy(q, s.t, p_);
      if constexpr (manifold_spring)
        e += 0.5 * kappa_ * (s.q - M::positions(q, s.t, p_)).squaredNorm();
    }
    return e;
  }

  /// Largest constraint violation at x: max |C_i(x, t)| over the declared constraints
  /// (rod |d| - L, pin distance, plane distance); with the manifold spring, the distance
  /// |x - X(q*)|_2 to the manifold; 0 for a model with neither.
  /// \throws InverseMapError with the manifold spring if the inverse map fails.
  double max_constraint_violation(const XVec<M>& x, double t) const {
    if constexpr (num_constraints > 0) {
      return Max::constraint_violations(x, t, p_).cwiseAbs().maxCoeff();
    } else if constexpr (manifold_spring) {
      return (x - M::positions(closest_point(x, t), t, p_)).norm();
    } else {
      (void)x;
      (void)t;
      return 0.0;
    }
  }

  /// Appends the nonzeros of K_x = dF/dx and K_v = dF/dxdot (F as force(); the mapped
  /// generalized forces are left out, the manifold spring's Jacobian is its projection
  /// approximation -kappa (I - J J^+)) as (row, col, value) triplets; duplicates add up.
  /// Either output may be null. \throws InverseMapError as force().
  void force_jacobian_triplets(const XVec<M>& x, const XVec<M>& xdot, double t,
                               std::vector<Eigen::Triplet<double>>* K_x,
                               std::vector<Eigen::Triplet<double>>* K_v) const {
    if (K_x) {
      const auto values = Max::force_jacobian_x(x, xdot, t, kappa_, damping_, p_);
      for (int k = 0; k < Max::jacobian_x_nonzeros; ++k)
        K_x->emplace_back(Max::jacobian_x_rows[k], Max::jacobian_x_cols[k], values[k]);
    }
    if (K_v) {
      const auto values = Max::force_jacobian_xdot(x, xdot, t, kappa_, damping_, p_);
      for (int k = 0; k < Max::jacobian_xdot_nonzeros; ++k)
        K_v->emplace_back(Max::jacobian_xdot_rows[k], Max::jacobian_xdot_cols[k], values[k]);
    }
    if constexpr (manifold_spring) {
      // normal projector I - J (J^T J)^-1 J^T at the closest point
      const XJac<M> J = M::jacobian(closest_point(x, t), t, p_);
      const SizedMatrix<double, nx, nx> P = SizedMatrix<double, nx, nx>::Identity() -
                                            J * (J.transpose() * J).ldlt().solve(J.transpose());
      for (int c = 0; c < nx; ++c)
        for (int r = 0; r < nx; ++r) {
          if (K_x) K_x->emplace_back(r, c, -kappa_ * P(r, c));
          if (K_v) K_v->emplace_back(r, c, -damping_ * P(r, c));
        }
    }
  }

  /// Dense K_x = dF/dx (nx x nx), from force_jacobian_triplets().
  Eigen::MatrixXd force_jacobian_x_dense(const XVec<M>& x, const XVec<M>& xdot, double t) const {
    Eigen::MatrixXd K_x;
    force_jacobians_dense(x, xdot, t, &K_x, nullptr);
    return K_x;
  }

  /// Dense K_x = dF/dx and K_v = dF/dxdot (nx x nx each; either may be null), from one
  /// force_jacobian_triplets().
  void force_jacobians_dense(const XVec<M>& x, const XVec<M>& xdot, double t, Eigen::MatrixXd* K_x,
                             Eigen::MatrixXd* K_v) const {
    std::vector<Eigen::Triplet<double>> x_triplets, v_triplets;
    force_jacobian_triplets(x, xdot, t, K_x ? &x_triplets : nullptr, K_v ? &v_triplets : nullptr);
    for (auto [K, triplets] : {std::pair{K_x, &x_triplets}, std::pair{K_v, &v_triplets}}) {
      if (!K) continue;
      K->setZero(nx, nx);
      for (const auto& e : *triplets) (*K)(e.row(), e.col()) += e.value();
    }
  }

 private:
  // the number of triplets force_jacobian_triplets() appends to one list of `nonzeros`
  static constexpr std::size_t jacobian_triplet_count(int nonzeros) {
    return static_cast<std::size_t>(nonzeros) + (manifold_spring ? std::size_t{nx} * nx : 0);
  }

  // closest point on the manifold (any distance), warm-started and updating the warm start
  QVec<M> closest_point(const XVec<M>& x, double t) const {
    q_guess_ = inverse_map_positions<M>(p_, x, t, q_guess_, inverse_options_).q;
    return q_guess_;
  }

  // F = M J Mt^-1 Q: the x-space force whose J^T-projection is Q
  XVec<M> mapped_generalized_forces(const QVec<M>& q, const VVec<M>& v, double t) const {
    const VVec<M> Q = M::generalized_forces(q, v, t, p_);
    const XJac<M> J = M::jacobian(q, t, p_);
    const VMat<M> Mt = J.transpose() * masses_.asDiagonal() * J;
    return masses_.asDiagonal() * (J * Mt.llt().solve(Q));
  }

  ParamsOf<M> p_;
  double kappa_, damping_;
  XVec<M> masses_;
  InverseMapOptions inverse_options_;
  mutable QVec<M> q_guess_;
  mutable SparseLuSolver lu_;  // the step matrices of solve(), all of one pattern
  std::string name_;
};

}  // namespace gencoord
