// SPDX-License-Identifier: BSD-3-Clause
// A generated model's kernels behind dynamic-size Eigen types. A check written against
// ModelView is a plain function, compiled once, where a check written against the model type
// is compiled again for every model of the type list: GCC spent most of the model tests'
// compile time instantiating those check bodies, not the kernels.
#pragma once

#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "gencoord/maximal/traits.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/inverse_dynamics.hpp"
#include "gencoord/model/model_traits.hpp"
#include "random_states.hpp"

namespace gencoord::testing {

/// The kernels of one model with q' = v, bound to one parameter set (the model's defaults
/// until sample_params() draws others). Empty functions: the model has no such kernel.
struct ModelView {
  using Vec = Eigen::VectorXd;
  using Mat = Eigen::MatrixXd;
  struct Point {
    Vec q, v;
    double t = 0;
  };

  std::string name;
  int nq = 0, nx = 0, dim = 0, num_particles = 0;
  std::vector<std::string> coordinate_names;
  bool forces_have_potential = false;

  std::function<Point(std::mt19937&)> random_state;  ///< random_states.hpp's random_state
  /// Replaces the parameters by sampled_params() of random_states.hpp.
  std::function<void(std::mt19937&)> sample_params;

  std::function<Mat(const Vec&q, double t)> mass_matrix, jacobian;
  std::function<Vec(const Vec& q, double t)> positions;
  std::function<double(const Vec& q, double t)> potential_energy;
  std::function<Vec(const Vec&q, const Vec&v, double t)> velocities, bias_acceleration, forces,
      applied_forces, inertial_forces, qddot, linear_momentum, angular_momentum;
  std::function<double(const Vec&q, const Vec&v, double t)> kinetic_energy, energy;
  std::function<void(const Vec& q, const Vec& v, double t, Mat* Mt, Vec* f)> dynamics;
  std::function<Vec()> particle_masses;
  std::function<bool(const Mat& A, const Vec& f, Vec* a)> solve;
  std::function<Vec(const Vec& q, const Vec& v, const Vec& a, double t)> inverse_dynamics;
  std::function<void(const Vec& q, const Vec& v, const Vec& a, double t, Mat* r_D_q, Mat* r_D_v)>
      residual_jacobians;
  /// The runtime's acceleration (dynamics.hpp), where the model has no kinematic constraints.
  std::function<Vec(const Vec& q, const Vec& v, double t)> runtime_acceleration;

  // kinematic constraints: the runtime's constrained acceleration and its multipliers
  std::function<Vec(const Vec& q, const Vec& v, double t, Vec* lambda)> constrained_acceleration;
  std::function<Mat(const Vec& q, double t)> constraint_jacobian;
  std::function<Vec(const Vec& q, const Vec& v, double t)> constraint_bias;

  // the Maximal model's declared constraints
  int num_maximal_constraints = 0, num_declared_constraints = 0;
  std::vector<std::string> maximal_constraint_names;
  std::function<Vec(const Vec& x, double t)> constraint_violations;
};

namespace view_detail {

/// A fixed-size matrix as a dynamic one, copied through a Map: GCC 12 reports a false
/// -Warray-bounds when Eigen copies a 1 x 1 fixed matrix into a dynamic one directly.
template <class Fixed>
ModelView::Mat dynamic(const Fixed& m) {
  return Eigen::Map<const ModelView::Mat>(m.data(), m.rows(), m.cols());
}

template <class M>
void bind_residual_jacobians(const std::shared_ptr<ParamsOf<M>>& params, ModelView* m) {
  using Vec = ModelView::Vec;
  using Mat = ModelView::Mat;
  m->residual_jacobians = [params](const Vec& q, const Vec& v, const Vec& a, double t, Mat* r_D_q,
                                   Mat* r_D_v) {
    QMat<M> dq = QMat<M>::Zero(), dv = QMat<M>::Zero();  // the kernel writes them
    M::residual_jacobians(QVec<M>(q), QVec<M>(v), QVec<M>(a), t, *params, &dq, &dv);
    *r_D_q = dynamic(dq);
    *r_D_v = dynamic(dv);
  };
}

template <class M>
void bind_kinematic_constraints(const std::shared_ptr<ParamsOf<M>>& params, ModelView* m) {
  using Vec = ModelView::Vec;
  using Mat = ModelView::Mat;
  m->constrained_acceleration = [params](const Vec& q, const Vec& v, double t, Vec* lambda) -> Vec {
    typename M::template CVector<double> multipliers = M::template CVector<double>::Zero();
    const QVec<M> a = constrained_acceleration<M>(*params, QVec<M>(q), QVec<M>(v), t, &multipliers);
    *lambda = multipliers;
    return a;
  };
  m->constraint_jacobian = [params](const Vec& q, double t) -> Mat {
    return dynamic(M::constraint_jacobian(QVec<M>(q), t, *params));
  };
  m->constraint_bias = [params](const Vec& q, const Vec& v, double t) -> Vec {
    return M::constraint_bias(QVec<M>(q), QVec<M>(v), t, *params);
  };
}

template <class M>
void bind_runtime_acceleration(const std::shared_ptr<ParamsOf<M>>& params, ModelView* m) {
  using Vec = ModelView::Vec;
  m->runtime_acceleration = [params](const Vec& q, const Vec& v, double t) -> Vec {
    return acceleration<M>(*params, QVec<M>(q), QVec<M>(v), t);
  };
}

template <class M>
void bind_maximal(const std::shared_ptr<ParamsOf<M>>& params, ModelView* m) {
  using X = typename M::Maximal;
  using Vec = ModelView::Vec;
  m->num_maximal_constraints = X::num_constraints;
  m->num_declared_constraints = X::num_declared_constraints;
  for (const char* c : X::constraint_names) m->maximal_constraint_names.emplace_back(c);
  m->constraint_violations = [params](const Vec& x, double t) -> Vec {
    return X::constraint_violations(XVec<M>(x), t, *params);
  };
}

}  // namespace view_detail

template <class M>
ModelView view_of() {
  using Vec = ModelView::Vec;
  using Mat = ModelView::Mat;
  using Params = ParamsOf<M>;
  auto params = std::make_shared<Params>();
  ModelView m;
  m.name = M::name;
  m.nq = M::nq;
  m.nx = M::nx;
  m.dim = M::dim;
  m.num_particles = M::num_particles;
  for (const char* c : M::coordinate_names) m.coordinate_names.emplace_back(c);
  m.forces_have_potential = M::forces_have_potential;

  m.random_state = [](std::mt19937& rng) {
    const State<M> s = random_state<M>(rng);
    return ModelView::Point{s.q, s.v, s.t};
  };
  m.sample_params = [params](std::mt19937& rng) { *params = sampled_params<M>(rng); };

  m.mass_matrix = [params](const Vec& q, double t) -> Mat {
    return view_detail::dynamic(M::mass_matrix(QVec<M>(q), t, *params));
  };
  m.jacobian = [params](const Vec& q, double t) -> Mat {
    return view_detail::dynamic(M::jacobian(QVec<M>(q), t, *params));
  };
  m.positions = [params](const Vec& q, double t) -> Vec {
    return M::positions(QVec<M>(q), t, *params);
  };
  m.potential_energy = [params](const Vec& q, double t) {
    return M::potential_energy(QVec<M>(q), t, *params);
  };
#define GENCOORD_VIEW_OF_QVT(kernel)                                 \
  m.kernel = [params](const Vec& q, const Vec& v, double t) -> Vec { \
    return M::kernel(QVec<M>(q), QVec<M>(v), t, *params);            \
  }
  GENCOORD_VIEW_OF_QVT(velocities);
  GENCOORD_VIEW_OF_QVT(bias_acceleration);
  GENCOORD_VIEW_OF_QVT(forces);
  GENCOORD_VIEW_OF_QVT(applied_forces);
  GENCOORD_VIEW_OF_QVT(inertial_forces);
  GENCOORD_VIEW_OF_QVT(qddot);
  GENCOORD_VIEW_OF_QVT(linear_momentum);
  GENCOORD_VIEW_OF_QVT(angular_momentum);
#undef GENCOORD_VIEW_OF_QVT
  m.kinetic_energy = [params](const Vec& q, const Vec& v, double t) {
    return M::kinetic_energy(QVec<M>(q), QVec<M>(v), t, *params);
  };
  m.energy = [params](const Vec& q, const Vec& v, double t) {
    return M::energy(QVec<M>(q), QVec<M>(v), t, *params);
  };
  m.dynamics = [params](const Vec& q, const Vec& v, double t, Mat* Mt, Vec* f) {
    QMat<M> mass = QMat<M>::Zero();
    QVec<M> force = QVec<M>::Zero();
    M::dynamics(QVec<M>(q), QVec<M>(v), t, *params, &mass, &force);
    *Mt = view_detail::dynamic(mass);
    *f = force;
  };
  m.particle_masses = [params]() -> Vec {
    const auto masses = M::template particle_masses<double>(*params);
    return Eigen::Map<const Vec>(masses.data(), static_cast<Eigen::Index>(masses.size()));
  };
  m.solve = [](const Mat& A, const Vec& f, Vec* a) {
    QVec<M> solution = QVec<M>::Zero();  // left alone where solve() refuses
    const bool solved = M::solve(QMat<M>(A), QVec<M>(f), &solution);
    *a = solution;
    return solved;
  };
  m.inverse_dynamics = [params](const Vec& q, const Vec& v, const Vec& a, double t) -> Vec {
    return M::inverse_dynamics(QVec<M>(q), QVec<M>(v), QVec<M>(a), t, *params);
  };
  // the optional kernels, each bound by a function template of its own
  if constexpr (has_residual_jacobians_v<M>) view_detail::bind_residual_jacobians<M>(params, &m);
  if constexpr (has_kinematic_constraints_v<M>) {
    view_detail::bind_kinematic_constraints<M>(params, &m);
  } else {
    view_detail::bind_runtime_acceleration<M>(params, &m);
  }
  if constexpr (has_maximal_v<M>) view_detail::bind_maximal<M>(params, &m);
  return m;
}

}  // namespace gencoord::testing
