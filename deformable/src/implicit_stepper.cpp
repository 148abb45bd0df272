// SPDX-License-Identifier: BSD-3-Clause
// Backward Euler of a mass-spring object with the step matrix and its factorization kept
// between steps (implicit_stepper.hpp).
#include "gencoord/deformable/implicit_stepper.hpp"

#include <Eigen/SparseCholesky>

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

template <int Dim>
ImplicitStats BackwardEulerStepper<Dim>::step(MassSpringSystem<Dim>& s, double dt) {
  using Points = typename MassSpringSystem<Dim>::Points;
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
  // linearized about the start of the step with the pinned nodes at their end positions
  // (the runtime's linearly implicit Euler, gencoord/integrate/backward_euler.hpp):
  // (M - dt D - dt^2 K) dv = dt (f + dt K v) over the free nodes
  Points q = s.x;
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (s.pinned[n]) q.col(n) += dt * s.v.col(n);
  }
  Points f = Points::Zero(Dim, s.num_nodes());
  accumulate_forces(s, q, s.v, f);
  Eigen::VectorXd masses, k_v;
  k.matrix.assemble(s, q, s.v, dt, &masses, &k_v);
  const int unknowns = k.matrix.unknowns();
  Eigen::VectorXd b(unknowns), v_free(unknowns);
  for (int n = 0; n < s.num_nodes(); ++n) {
    const int d = k.matrix.dof(n);
    if (d < 0) continue;
    b.template segment<Dim>(d) = dt * (f.col(n) + dt * k_v.template segment<Dim>(d));
    v_free.template segment<Dim>(d) = s.v.col(n);
  }

  ImplicitStats stats;
  stats.unknowns = unknowns;
  Eigen::VectorXd dv;
  if (cholesky) {
    k.cholesky.factorize(k.matrix.matrix());
    if (k.cholesky.info() == Eigen::Success) dv = k.cholesky.solve(b);
    if (k.cholesky.info() != Eigen::Success || !dv.allFinite())
      detail::throw_cholesky_failure(&stats);
  } else {
    if (k.options.warm_start) dv = k.last_dv;
    detail::solve_by_conjugate_gradient(k.matrix.matrix(), b, masses, v_free, k.options, &dv,
                                        &stats);
  }
  stats.pattern_analyses = k.pattern_analyses;

  typename MassSpringIntegration<Dim>::State end{s.t + dt, s.v, s.v};
  for (int n = 0; n < s.num_nodes(); ++n) {
    const int d = k.matrix.dof(n);
    if (d >= 0) end.v.col(n) += dv.template segment<Dim>(d);
  }
  end.q = s.x + dt * end.v;  // a pinned node moves with its own velocity
  finish_step<Dim>(std::move(end), dt, &s);
  k.last_dv = std::move(dv);
  return stats;
}

template class BackwardEulerStepper<1>;
template class BackwardEulerStepper<2>;
template class BackwardEulerStepper<3>;

}  // namespace gencoord::deformable
