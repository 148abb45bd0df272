// SPDX-License-Identifier: BSD-3-Clause
// Backward Euler of a mass-spring object with the step matrix and its factorization kept
// between steps (implicit_stepper.hpp).
#include "gencoord/deformable/implicit_stepper.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <vector>

#include "contact_forces.hpp"
#include "gencoord/deformable/mass_spring_integration.hpp"
#include "gencoord/deformable/validate.hpp"
#include "spd_solve.hpp"
#include "step_matrix.hpp"

namespace gencoord::deformable {

template <int Dim>
struct BackwardEulerStepper<Dim>::Kept {
  ImplicitOptions options;
  detail::StepMatrix<Dim> matrix;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> cholesky;
  bool built = false;
  int pattern_analyses = 0;
  Eigen::VectorXd last_dv;  // the previous step's velocity change, CG's warm start
};

template <int Dim>
BackwardEulerStepper<Dim>::BackwardEulerStepper(const ImplicitOptions& options)
    : kept_(std::make_unique<Kept>()) {
  kept_->options = options;
}

template <int Dim>
BackwardEulerStepper<Dim>::~BackwardEulerStepper() = default;
template <int Dim>
BackwardEulerStepper<Dim>::BackwardEulerStepper(BackwardEulerStepper&&) noexcept = default;
template <int Dim>
BackwardEulerStepper<Dim>& BackwardEulerStepper<Dim>::operator=(BackwardEulerStepper&&) noexcept =
    default;

template <int Dim>
const ImplicitOptions& BackwardEulerStepper<Dim>::options() const {
  return kept_->options;
}

namespace {

template <int Dim>
using Points = typename MassSpringSystem<Dim>::Points;

// detail::contact_set() at (q, v)
template <int Dim>
std::vector<int> contacts_at(const MassSpringSystem<Dim>& s, const Points<Dim>& q,
                             const Points<Dim>& v) {
  std::vector<detail::ContactJacobian<Dim>> blocks;
  if constexpr (Dim > 1) {
    if (s.collisions) blocks = detail::contact_jacobians<Dim>(s, q, v);
  }
  return detail::contact_set<Dim>(s, q, blocks);
}

// |y|_{M^-1} over the free unknowns
double inverse_mass_norm(const Eigen::VectorXd& y, const Eigen::VectorXd& masses) {
  return std::sqrt((y.array().square() / masses.array()).sum());
}

}  // namespace

template <int Dim>
ImplicitStats BackwardEulerStepper<Dim>::step(MassSpringSystem<Dim>& s, double dt) {
  validate_time_step(dt);
  validate_object(s);
  Kept& k = *kept_;
  const bool cholesky = k.options.solver == LinearSolver::kSparseCholesky;
  if (!k.built || !k.matrix.matches(s)) {
    k.built = false;
    k.matrix.build(s);
    if (cholesky) k.cholesky.analyzePattern(k.matrix.matrix());
    k.built = true;
    ++k.pattern_analyses;
    k.last_dv.resize(0);
  }
  const int count = s.num_nodes();
  const int unknowns = k.matrix.unknowns();
  ImplicitStats stats;
  stats.unknowns = unknowns;
  Eigen::VectorXd masses, k_v;
  int iterations = 0;  // CG's, over all solves of the step
  // solves A x = b with the matrix as assembled last, from the start x
  auto solve = [&](const Eigen::VectorXd& b, const Eigen::VectorXd& v_free, Eigen::VectorXd* x) {
    if (cholesky) {
      k.cholesky.factorize(k.matrix.matrix());
      if (k.cholesky.info() == Eigen::Success) *x = k.cholesky.solve(b);
      if (k.cholesky.info() != Eigen::Success || !x->allFinite())
        detail::throw_cholesky_failure(&stats);
    } else {
      detail::solve_by_conjugate_gradient(k.matrix.matrix(), b, masses, v_free, k.options, x,
                                          &stats);
      iterations += stats.iterations;
    }
  };
  // linearized about the start of the step with the pinned nodes at their end positions
  // (the runtime's linearly implicit Euler, gencoord/integrate/backward_euler.hpp):
  // (M - dt D - dt^2 K) dv = dt (f + dt K v) over the free nodes
  Points<Dim> q = s.x;
  for (int n = 0; n < count; ++n) {
    if (s.pinned[n]) q.col(n) += dt * s.v.col(n);
  }
  Points<Dim> f = Points<Dim>::Zero(Dim, count);
  accumulate_forces(s, q, s.v, f);
  k.matrix.assemble(s, q, s.v, dt, &masses, &k_v);
  Eigen::VectorXd b(unknowns), v_free(unknowns);
  for (int n = 0; n < count; ++n) {
    const int d = k.matrix.dof(n);
    if (d < 0) continue;
    b.template segment<Dim>(d) = dt * (f.col(n) + dt * k_v.template segment<Dim>(d));
    v_free.template segment<Dim>(d) = s.v.col(n);
  }
  Eigen::VectorXd dv;
  if (!cholesky && k.options.warm_start) dv = k.last_dv;
  solve(b, v_free, &dv);

  typename MassSpringIntegration<Dim>::State end{s.t + dt, s.x, s.v};
  auto set_end = [&] {
    end.v = s.v;
    for (int n = 0; n < count; ++n) {
      const int d = k.matrix.dof(n);
      if (d >= 0) end.v.col(n) += dv.template segment<Dim>(d);
    }
    end.q = s.x + dt * end.v;  // a pinned node moves with its own velocity
  };
  set_end();
  // A contact that begins or ends during the step is not in the matrix it was solved with,
  // and a penalty that starts unseen returns more energy than the step stored: then Newton's
  // method on the nonlinear backward Euler equation g(v1) = M (v1 - v) - dt f(x + dt v1, v1)
  // = 0, each iteration linearized at the end of the last, until the residual is small (it is
  // the residual at the end's own contacts, whichever they are).
  for (int iteration = 0; iteration < k.options.max_contact_iterations; ++iteration) {
    if (iteration == 0 && contacts_at<Dim>(s, end.q, end.v) == k.matrix.contacts())
      break;  // the linearized step saw every contact
    f.setZero();
    accumulate_forces(s, end.q, end.v, f);
    Eigen::VectorXd residual(unknowns), impulse(unknowns);
    for (int n = 0; n < count; ++n) {
      const int d = k.matrix.dof(n);
      if (d < 0) continue;
      impulse.template segment<Dim>(d) = dt * f.col(n);
      residual.template segment<Dim>(d) = dt * f.col(n) - s.mass(n) * (end.v.col(n) - s.v.col(n));
    }
    if (inverse_mass_norm(residual, masses) <=
        k.options.contact_tolerance * inverse_mass_norm(impulse, masses))
      break;
    k.matrix.assemble(s, end.q, end.v, dt, &masses, &k_v);
    for (int n = 0; n < count; ++n) {
      const int d = k.matrix.dof(n);
      if (d >= 0) v_free.template segment<Dim>(d) = end.v.col(n);
    }
    Eigen::VectorXd correction;
    solve(residual, v_free, &correction);
    dv += correction;
    set_end();
    ++stats.contact_iterations;
  }
  stats.iterations = iterations;
  stats.pattern_analyses = k.pattern_analyses;
  finish_step<Dim>(std::move(end), dt, &s);
  k.last_dv = std::move(dv);
  return stats;
}

template class BackwardEulerStepper<1>;
template class BackwardEulerStepper<2>;
template class BackwardEulerStepper<3>;

}  // namespace gencoord::deformable
