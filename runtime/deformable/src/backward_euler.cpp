// Implicit backward Euler step: one linearized sparse solve per step.
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <stdexcept>
#include <vector>

#include "gencoord/deformable/inelastic.hpp"
#include "gencoord/deformable/time_step.hpp"

namespace gencoord::deformable {

namespace {

// Adds coefficient * block to the (i, j) block of the free-DOF system (skips pinned nodes).
template <int Dim>
void add_block(std::vector<Eigen::Triplet<double>>& triplets, const std::vector<int>& dof,
               int i, int j, const Eigen::Matrix<double, Dim, Dim>& block) {
  if (dof[i] < 0 || dof[j] < 0) return;
  for (int r = 0; r < Dim; ++r) {
    for (int c = 0; c < Dim; ++c) triplets.emplace_back(dof[i] + r, dof[j] + c, block(r, c));
  }
}

}  // namespace

template <int Dim>
ImplicitStats step_backward_euler(MassSpringSystem<Dim>& s, double dt,
                                  const ImplicitOptions& options) {
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  const int count = s.num_nodes();

  // free degrees of freedom: Dim per unpinned node
  std::vector<int> dof(count, -1);
  int unknowns = 0;
  for (int n = 0; n < count; ++n) {
    if (!s.pinned[n]) {
      dof[n] = unknowns;
      unknowns += Dim;
    }
  }

  // f(x, v) and K v (K v also over pinned nodes, whose velocity is prescribed)
  Eigen::Matrix<double, Dim, Eigen::Dynamic> f =
      Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, count);
  accumulate_forces(s, f);
  Eigen::Matrix<double, Dim, Eigen::Dynamic> k_v =
      Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, count);

  // A = M - dt D - dt^2 K; spring blocks are (-J at ii and jj, +J at ij and ji)
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(s.springs.size() * 4 * Dim * Dim + count * Dim);
  for (const Spring& sp : s.springs) {
    if (sp.broken) continue;
    const SpringForce<Dim> sf = spring_force<Dim>(s.x.col(sp.i), s.x.col(sp.j), s.v.col(sp.i),
                                                  s.v.col(sp.j), sp.params);
    const SpringJacobian<Dim> jac = spring_jacobian<Dim>(sf, sp.params, /*definite=*/true);
    const Eigen::Matrix<double, Dim, 1> kv = jac.f_i_D_d * (s.v.col(sp.j) - s.v.col(sp.i));
    k_v.col(sp.i) += kv;
    k_v.col(sp.j) -= kv;
    const Mat block = dt * jac.f_i_D_dv + dt * dt * jac.f_i_D_d;  // -(A's ij block)
    add_block<Dim>(triplets, dof, sp.i, sp.i, block);
    add_block<Dim>(triplets, dof, sp.j, sp.j, block);
    add_block<Dim>(triplets, dof, sp.i, sp.j, -block);
    add_block<Dim>(triplets, dof, sp.j, sp.i, -block);
  }
  // mass and ground contact (a penalty spring along the up axis while penetrating)
  for (int n = 0; n < count; ++n) {
    if (dof[n] < 0) continue;
    for (int r = 0; r < Dim; ++r) triplets.emplace_back(dof[n] + r, dof[n] + r, s.mass(n));
    if (s.ground) {
      const GroundPlane& g = *s.ground;
      constexpr int up = Dim - 1;
      const double depth = g.height - s.x(up, n);
      const double push =
          g.omega * g.omega * depth - 2.0 * g.damping_ratio * g.omega * s.v(up, n);
      if (depth > 0.0 && push > 0.0) {
        const double k_ground = s.mass(n) * g.omega * g.omega;
        const double c_ground = s.mass(n) * 2.0 * g.damping_ratio * g.omega;
        triplets.emplace_back(dof[n] + up, dof[n] + up, dt * c_ground + dt * dt * k_ground);
        k_v(up, n) -= k_ground * s.v(up, n);
      }
    }
  }
  Eigen::SparseMatrix<double> a(unknowns, unknowns);
  a.setFromTriplets(triplets.begin(), triplets.end());

  // b = dt (f + dt K v) over the free nodes
  Eigen::VectorXd b(unknowns);
  for (int n = 0; n < count; ++n) {
    if (dof[n] >= 0) b.segment<Dim>(dof[n]) = dt * (f.col(n) + dt * k_v.col(n));
  }

  ImplicitStats stats;
  stats.unknowns = unknowns;
  Eigen::VectorXd dv;
  if (options.solver == LinearSolver::kConjugateGradient) {
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
    cg.setTolerance(options.tolerance);
    cg.setMaxIterations(options.max_iterations);
    cg.compute(a);
    dv = cg.solve(b);
    stats.iterations = static_cast<int>(cg.iterations());
    stats.residual = cg.error();
    if (cg.info() != Eigen::Success) {
      throw std::runtime_error("backward Euler: conjugate gradient did not converge");
    }
  } else {
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(a);
    if (ldlt.info() != Eigen::Success) {
      throw std::runtime_error("backward Euler: sparse Cholesky factorization failed");
    }
    dv = ldlt.solve(b);
  }

  // v += dv, then x += dt v (pinned nodes keep their prescribed velocity)
  for (int n = 0; n < count; ++n) {
    if (dof[n] >= 0) s.v.col(n) += dv.segment<Dim>(dof[n]);
  }
  s.x += dt * s.v;
  s.time += dt;
  ++s.steps;
  apply_fracture_and_plasticity(s);
  return stats;
}

template ImplicitStats step_backward_euler<1>(MassSpringSystem<1>&, double,
                                              const ImplicitOptions&);
template ImplicitStats step_backward_euler<2>(MassSpringSystem<2>&, double,
                                              const ImplicitOptions&);
template ImplicitStats step_backward_euler<3>(MassSpringSystem<3>&, double,
                                              const ImplicitOptions&);

}  // namespace gencoord::deformable
