// Backward Euler for the maximal model, with Newton's method on a sparse linear system
// assembled from the generated sparse force Jacobians: unconditionally stable, for large kappa.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "gencoord/errors.hpp"
#include "gencoord/implicit_steps.hpp"
#include "gencoord/maximal_model.hpp"
#include "gencoord/maximal_state.hpp"
#include "gencoord/newton.hpp"

namespace gencoord {

/// Backward Euler: x1 = x0 + h xdot1, M (xdot1 - xdot0) = h F(x1, xdot1, t0 + h). First order,
/// L-stable (damps the stiff penalty modes). Newton on the end velocity from xdot1 = xdot0,
/// each update solving (M - h K_v - h^2 K_x) dv = -g with K_x = dF/dx, K_v = dF/dxdot from
/// the generated sparse Jacobians (MaximalModel::force_jacobian_triplets()) by Eigen's SparseLU.
/// \param[in] model    The maximal model (penalty stiffness, damping, parameters).
/// \param[in] s        The state at the start of the step.
/// \param[in] h        The step size, positive.
/// \param[in] options  Newton settings: converged when |dv|_inf <= tolerance (1 + |xdot1|_inf).
/// \param[in,out] stats  Work counters (newton_solves, newton_iterations); may be null.
/// \return The state at s.t + h.
/// \throws NewtonError (model name "<name> (maximal)") if Newton does not converge in
///         options.max_iterations updates or the matrix is singular; InverseMapError as
///         MaximalModel::force(); std::invalid_argument for bad options.
template <class M>
MaximalState<M> maximal_backward_euler_step(const MaximalModel<M>& model,
                                            const MaximalState<M>& s, double h,
                                            const NewtonOptions& options = {},
                                            StepStats* stats = nullptr) {
  constexpr int nx = M::nx;
  const double t1 = s.t + h;
  const XVec<M>& m = model.masses();
  XVec<M> v1 = s.xdot;
  std::vector<Eigen::Triplet<double>> K_x, K_v, triplets;
  Eigen::SparseMatrix<double> A(nx, nx);
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  bool pattern_analysed = false;
  detail::newton_iterate(std::string(M::name) + " (maximal)", s.t, h, options, stats, false,
                         [&] {
    // residual g(v1) = M (v1 - v0) - h F(x0 + h v1, v1, t1) and its Jacobian
    const XVec<M> x1 = s.x + h * v1;
    const XVec<M> g = m.cwiseProduct(v1 - s.xdot) - h * model.force(x1, v1, t1);
    K_x.clear();
    K_v.clear();
    model.force_jacobian_triplets(x1, v1, t1, &K_x, &K_v);
    triplets.clear();
    for (int i = 0; i < nx; ++i) triplets.emplace_back(i, i, m(i));
    for (const auto& e : K_v) triplets.emplace_back(e.row(), e.col(), -h * e.value());
    for (const auto& e : K_x) triplets.emplace_back(e.row(), e.col(), -h * h * e.value());
    A.setFromTriplets(triplets.begin(), triplets.end());
    if (!pattern_analysed) lu.analyzePattern(A);  // the same pattern at every iterate
    pattern_analysed = true;
    lu.factorize(A);
    NewtonUpdate norms{g.template lpNorm<Eigen::Infinity>(),
                       std::numeric_limits<double>::quiet_NaN(), 0.0};
    if (lu.info() != Eigen::Success) return norms;  // singular: a non-finite update
    const XVec<M> dv = -lu.solve(g);
    norms.update_norm = dv.template lpNorm<Eigen::Infinity>();
    if (dv.allFinite()) v1 += dv;
    norms.velocity_norm = v1.template lpNorm<Eigen::Infinity>();
    return norms;
  });
  MaximalState<M> out;
  out.t = t1;
  out.x = s.x + h * v1;
  out.xdot = v1;
  return out;
}

}  // namespace gencoord
