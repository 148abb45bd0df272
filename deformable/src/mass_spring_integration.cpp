// SPDX-License-Identifier: BSD-3-Clause
// The mass-spring object's side of the integrators' system interface.
#include "gencoord/deformable/mass_spring_integration.hpp"

#include <Eigen/SparseCholesky>
#include <utility>

#include "contact_forces.hpp"
#include "gencoord/deformable/bending.hpp"
#include "gencoord/deformable/errors.hpp"
#include "gencoord/deformable/inelastic.hpp"
#include "gencoord/deformable/validate.hpp"
#include "spd_solve.hpp"

namespace gencoord::deformable {

namespace {

// Adds the (i, j) block to the free-DOF matrix (skips pinned nodes).
template <int Dim>
void add_block(std::vector<Eigen::Triplet<double>>& triplets, const std::vector<int>& dof, int i,
               int j, const Eigen::Matrix<double, Dim, Dim>& block) {
  if (dof[i] < 0 || dof[j] < 0) return;
  for (int r = 0; r < Dim; ++r) {
    for (int c = 0; c < Dim; ++c) triplets.emplace_back(dof[i] + r, dof[j] + c, block(r, c));
  }
}

}  // namespace

template <int Dim>
MassSpringIntegration<Dim>::MassSpringIntegration(const MassSpringSystem<Dim>& s,
                                                  const ImplicitOptions& options)
    : s_(s), options_(options), dof_(s.num_nodes(), -1) {
  int unknowns = 0;
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (!s.pinned[n]) {
      dof_[n] = unknowns;
      unknowns += Dim;
    }
  }
  free_masses_.resize(unknowns);
  for (int n = 0; n < s.num_nodes(); ++n) {
    if (dof_[n] >= 0) free_masses_.segment<Dim>(dof_[n]).setConstant(s.mass(n));
  }
}

template <int Dim>
typename MassSpringIntegration<Dim>::Points MassSpringIntegration<Dim>::acceleration(
    const State& y) const {
  Points f = Points::Zero(Dim, s_.num_nodes());
  accumulate_forces(s_, y.q, y.v, f);
  for (int n = 0; n < s_.num_nodes(); ++n) {
    if (s_.pinned[n]) {
      f.col(n).setZero();
    } else {
      f.col(n) /= s_.mass(n);
    }
  }
  return f;
}

template <int Dim>
void MassSpringIntegration<Dim>::impose(State* y) const {
  const double elapsed = y->t - s_.t;
  for (int n = 0; n < s_.num_nodes(); ++n) {
    if (dof_[n] >= 0) continue;
    y->q.col(n) = s_.x.col(n) + elapsed * s_.v.col(n);
    y->v.col(n) = s_.v.col(n);
  }
}

template <int Dim>
Eigen::VectorXd MassSpringIntegration<Dim>::free_part(const Points& x) const {
  Unknowns out(free_masses_.size());
  for (int n = 0; n < s_.num_nodes(); ++n) {
    if (dof_[n] >= 0) out.segment<Dim>(dof_[n]) = x.col(n);
  }
  return out;
}

template <int Dim>
void MassSpringIntegration<Dim>::add_to_free(const Unknowns& dx, Points* x) const {
  for (int n = 0; n < s_.num_nodes(); ++n) {
    if (dof_[n] >= 0) x->col(n) += dx.segment<Dim>(dof_[n]);
  }
}

template <int Dim>
void MassSpringIntegration<Dim>::linearize(const State& y, JacobianSource,
                                           Linearization<MassSpringIntegration>* out) const {
  const int count = s_.num_nodes();
  const auto unknowns = free_masses_.size();
  Points f = Points::Zero(Dim, count);
  accumulate_forces(s_, y.q, y.v, f);
  out->force = free_part(f);
  linearized_velocities_ = free_part(y.v);
  // spring blocks: +J at ii and jj, -J at ij and ji
  std::vector<Eigen::Triplet<double>> k_x, k_v;
  k_x.reserve(s_.springs.size() * 4 * Dim * Dim);
  k_v.reserve(s_.springs.size() * 4 * Dim * Dim);
  for (const Spring& sp : s_.springs) {
    if (sp.broken) continue;
    const SpringForce<Dim> sf =
        spring_force<Dim>(y.q.col(sp.i), y.q.col(sp.j), y.v.col(sp.i), y.v.col(sp.j), sp.params);
    const SpringJacobian<Dim> jac = spring_jacobian<Dim>(sf, sp.params, /*definite=*/true);
    // f_i depends on d = x_j - x_i: df_i/dx_i = -f_i_D_d, df_i/dx_j = f_i_D_d; f_j = -f_i
    for (auto* list : {&k_x, &k_v}) {
      const auto& J = list == &k_x ? jac.f_i_D_d : jac.f_i_D_dv;
      add_block<Dim>(*list, dof_, sp.i, sp.i, -J);
      add_block<Dim>(*list, dof_, sp.j, sp.j, -J);
      add_block<Dim>(*list, dof_, sp.i, sp.j, J);
      add_block<Dim>(*list, dof_, sp.j, sp.i, J);
    }
  }
  // area and volume terms: definite position blocks, no damping
  for_each_volume_term_block(s_, y.q, /*definite=*/true,
                             [&](int a, int b, const Eigen::Matrix<double, Dim, Dim>& block) {
                               add_block<Dim>(k_x, dof_, a, b, block);
                             });
  for_each_continuum_block(s_, y.q,
                           [&](int a, int b, const Eigen::Matrix<double, Dim, Dim>& stiffness,
                               const Eigen::Matrix<double, Dim, Dim>& damping) {
                             add_block<Dim>(k_x, dof_, a, b, stiffness);
                             add_block<Dim>(k_v, dof_, a, b, damping);
                           });
  add_bending_jacobian(s_, y.q, dof_, &k_x);  // hinges: Gauss-Newton blocks (bending.hpp)
  // ground contact: a penalty spring and damper along the up axis while it pushes
  if (s_.ground) {
    const GroundPlane& g = *s_.ground;
    constexpr int up = Dim - 1;
    for (int n = 0; n < count; ++n) {
      if (dof_[n] < 0) continue;
      const double depth = g.height - y.q(up, n);
      const double push = g.omega * g.omega * depth - 2.0 * g.damping_ratio * g.omega * y.v(up, n);
      if (depth > 0.0 && push > 0.0) {
        k_x.emplace_back(dof_[n] + up, dof_[n] + up, -s_.mass(n) * g.omega * g.omega);
        k_v.emplace_back(dof_[n] + up, dof_[n] + up, -s_.mass(n) * 2.0 * g.damping_ratio * g.omega);
      }
    }
  }
  // contacts: diagonal blocks that bound them from above (collision.hpp)
  if constexpr (Dim > 1) {
    for (const auto& block : detail::contact_jacobians<Dim>(s_, y.q, y.v)) {
      add_block<Dim>(k_x, dof_, block.node, block.node, block.d_position);
      add_block<Dim>(k_v, dof_, block.node, block.node, block.d_velocity);
    }
  }
  out->force_D_q.resize(unknowns, unknowns);
  out->force_D_q.setFromTriplets(k_x.begin(), k_x.end());
  out->force_D_v.resize(unknowns, unknowns);
  out->force_D_v.setFromTriplets(k_v.begin(), k_v.end());
}

template <int Dim>
bool MassSpringIntegration<Dim>::solve(const Matrix& A, const Unknowns& b, Unknowns* x) const {
  stats_ = ImplicitStats{};
  stats_.unknowns = static_cast<int>(b.size());
  if (options_.solver == LinearSolver::kConjugateGradient) {
    x->resize(0);  // no warm start: each solve is a new Newton update
    detail::solve_by_conjugate_gradient(A, b, free_masses_, linearized_velocities_, options_, x,
                                        &stats_);
  } else {
    Eigen::SimplicialLDLT<Matrix> ldlt(A);
    if (ldlt.info() == Eigen::Success) *x = ldlt.solve(b);
    if (ldlt.info() != Eigen::Success || !x->allFinite()) detail::throw_cholesky_failure(&stats_);
  }
  return true;
}

template <int Dim>
void finish_step(typename MassSpringIntegration<Dim>::State end, double dt,
                 MassSpringSystem<Dim>* s) {
  validate_step_result<Dim>(end.q, end.v, s->t, dt);
  s->x = std::move(end.q);
  s->v = std::move(end.v);
  s->t += dt;
  ++s->steps;
  apply_fracture_and_plasticity(*s);
}

template void finish_step<1>(MassSpringIntegration<1>::State, double, MassSpringSystem<1>*);
template void finish_step<2>(MassSpringIntegration<2>::State, double, MassSpringSystem<2>*);
template void finish_step<3>(MassSpringIntegration<3>::State, double, MassSpringSystem<3>*);
template class MassSpringIntegration<1>;
template class MassSpringIntegration<2>;
template class MassSpringIntegration<3>;

}  // namespace gencoord::deformable
