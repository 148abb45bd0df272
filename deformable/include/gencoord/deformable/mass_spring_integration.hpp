// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// \file mass_spring_integration.hpp
/// A mass-spring object as a system for the runtime's integrators
/// (gencoord/integrate/system.hpp): q and v are the node positions and velocities (Dim x n),
/// pinned nodes move with their own velocity (prescribed by impose(), no Newton unknowns),
/// and backward Euler's linear systems are sparse (free-DOF blocks, definite spring
/// Jacobians) and solved by conjugate gradients or a sparse Cholesky factorization
/// (ImplicitOptions).

#include <Eigen/SparseCore>
#include <vector>

#include "gencoord/deformable/mass_spring_system.hpp"
#include "gencoord/deformable/time_step.hpp"
#include "gencoord/integrate/newton.hpp"
#include "gencoord/integrate/system.hpp"

namespace gencoord::deformable {

template <int Dim>
class MassSpringIntegration {
 public:
  using Points = typename MassSpringSystem<Dim>::Points;
  using State = Phase<Points>;
  using Unknowns = Eigen::VectorXd;
  using Matrix = Eigen::SparseMatrix<double>;
  static constexpr bool unit_mass = false;

  /// Refers to `s` (which must outlive this) for everything but x, v and t.
  MassSpringIntegration(const MassSpringSystem<Dim>& s, const ImplicitOptions& options = {});

  /// The system's current state (t, x, v).
  State state() const { return {s_.t, s_.x, s_.v}; }

  const char* name() const { return "mass-spring system"; }
  /// f / m at the unpinned nodes, 0 at the pinned ones.
  Points acceleration(const State& y) const;
  /// Sets each pinned node's position and velocity at y->t: x + (t - s.t) v and v, from the
  /// object's x, v and t, so that a pinned node moves at constant velocity.
  void impose(State* y) const;
  void check(const State&, double) const {}

  const Unknowns& masses() const { return free_masses_; }
  Unknowns free_part(const Points& x) const;
  void add_to_free(const Unknowns& dx, Points* x) const;
  /// The free forces and their Jacobians K = df/dx, D = df/dv (definite spring and volume
  /// term blocks, the hinges' Gauss-Newton blocks, the ground penalty while it pushes, and for
  /// the contacts diagonal blocks that bound them from above: collision.hpp).
  void linearize(const State& y, JacobianSource, Linearization<MassSpringIntegration>* out) const;
  /// Conjugate gradients stop by ImplicitOptions::tolerance's rule, its velocity floor being
  /// the velocities of the last linearize() call's state.
  /// \throws LinearSolveError (errors.hpp) if conjugate gradients do not converge or the
  ///         factorization fails, with the residual and what to change.
  bool solve(const Matrix& A, const Unknowns& b, Unknowns* x) const;

  /// What the last solve() did.
  const ImplicitStats& last_solve() const { return stats_; }

 private:
  const MassSpringSystem<Dim>& s_;
  ImplicitOptions options_;
  std::vector<int> dof_;  // first free DOF of each node, -1 if pinned
  Unknowns free_masses_;
  mutable ImplicitStats stats_;
  mutable Unknowns linearized_velocities_;  // the CG stopping rule's floor (solve())
};

/// Ends a step of dt of `s` at `end` (what an integrator of the runtime returned for
/// MassSpringIntegration(*s)): checks it is finite (validate_step_result), takes its x and v,
/// advances t and the step count, then applies fracture and plasticity.
/// \throws ObjectError (validate.hpp) if `end` is not finite.
template <int Dim>
void finish_step(typename MassSpringIntegration<Dim>::State end, double dt,
                 MassSpringSystem<Dim>* s);

}  // namespace gencoord::deformable
