// SPDX-License-Identifier: BSD-3-Clause
// Everything a generated model offers Python: metadata, Params, every kernel, the right-hand
// side and its Jacobian for scipy.integrate.solve_ivp, and the runtime's simulation loop.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <string>
#include <tuple>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/model/dissipated_work.hpp"
#include "gencoord/model/inverse_dynamics.hpp"
#include "gencoord/model/joint_limits.hpp"
#include "gencoord/model/model_traits.hpp"
#include "gencoord_python/arrays.hpp"
#include "gencoord_python/constraints.hpp"
#include "gencoord_python/control.hpp"
#include "gencoord_python/errors.hpp"
#include "gencoord_python/first_order.hpp"
#include "gencoord_python/kernels.hpp"
#include "gencoord_python/params.hpp"
#include "gencoord_python/qddot_lanes.hpp"
#include "gencoord_python/simulation.hpp"
#include "gencoord_python/speeds.hpp"

namespace gencoord::python {

namespace py = pybind11;

template <class Array>
py::tuple string_tuple(const Array& strings) {
  py::tuple tuple(strings.size());
  for (std::size_t k = 0; k < strings.size(); ++k) tuple[k] = py::str(strings[k]);
  return tuple;
}

template <class M>
void bind_metadata(py::module_& module) {
  module.attr("name") = M::name;
  module.attr("nq") = M::nq;
  module.attr("nv") = nv_of_v<M>;
  module.attr("dim") = M::dim;
  module.attr("num_particles") = M::num_particles;
  module.attr("nx") = M::nx;
  module.attr("num_fixed_points") = M::num_fixed_points;
  module.attr("coordinate_names") = string_tuple(M::coordinate_names);
  module.attr("coordinate_descriptions") = string_tuple(M::coordinate_descriptions);
  module.attr("parameter_names") = string_tuple(M::parameter_names);
  module.attr("parameter_descriptions") = string_tuple(M::parameter_descriptions);
  module.attr("num_inputs") = num_inputs_v<M>;
  if constexpr (has_inputs_v<M>) {
    module.attr("input_names") = string_tuple(M::input_names);
    module.attr("input_descriptions") = string_tuple(M::input_descriptions);
  } else {
    module.attr("input_names") = py::tuple();
    module.attr("input_descriptions") = py::tuple();
  }
  module.attr("particle_names") = string_tuple(M::particle_names);
  module.attr("fixed_point_names") = string_tuple(M::fixed_point_names);
  if constexpr (has_generalized_speeds_v<M>) {  // q' = G(q) v: speeds of their own
    module.attr("speed_names") = string_tuple(M::speed_names);
    py::tuple starts(M::num_quaternions);
    for (int k = 0; k < M::num_quaternions; ++k) starts[k] = M::quaternion_starts[k];
    module.attr("quaternion_starts") = starts;
  } else {
    module.attr("speed_names") = string_tuple(M::coordinate_names);
    module.attr("quaternion_starts") = py::tuple();
  }
  module.attr("initial_q") = read_only_array(M::initial_q);
  module.attr("initial_v") = read_only_array(M::initial_v);
  if constexpr (has_joint_limits_v<M>) {  // limited coordinates' indices, ends and ratings
    module.attr("limit_names") = string_tuple(M::limit_names);
    py::tuple coordinates(M::num_limits);
    for (int i = 0; i < M::num_limits; ++i) coordinates[i] = M::limited_coordinates[i];
    module.attr("limited_coordinates") = coordinates;
    module.attr("lower_limits") = read_only_array(M::lower_limits);
    module.attr("upper_limits") = read_only_array(M::upper_limits);
    module.attr("velocity_limits") = read_only_array(M::velocity_limits);
    module.attr("effort_limits") = read_only_array(M::effort_limits);
  } else {
    module.attr("limit_names") = py::tuple();
  }
  module.attr("forces_have_potential") = M::forces_have_potential;
  module.attr("dissipative") = is_dissipative_v<M>;
  module.attr("recursive_qddot") = M::recursive_qddot;
  // the names parse_integrator() accepts, in the runtime's order
  module.attr("integrators") = py::tuple(py::str(integrator_names()).attr("split")(", "));
}

namespace detail {

inline std::string kernel_doc(const char* summary, const char* returns) {
  return std::string(summary) + "\n\nReturns " + returns +
         "; with a batch of N states, one per state (leading dimension N).";
}

}  // namespace detail

/// The reduced-coordinate kernels of the generated header (docs/model_interface.md).
template <class M>
void bind_kernels(py::module_& m) {
  using P = ParamsOf<M>;
  using V = VVec<M>;  // forces and accelerations: one entry per speed
  using X = StateVectors<M>;
  using detail::kernel_doc;
  const std::array<const char*, 1> q{"q"};
  const std::array<const char*, 2> qv{"q", "v"};
  const std::array<const char*, 3> qva{"q", "v", "qdd"};
  def_kernel<M>(
      m, "mass_matrix", kernel_doc("Reduced mass matrix Mt = J^T M J.", "(nv, nv)"), q,
      [](const X& x, double t, const P& p) { return VMat<M>(M::mass_matrix(x.q, t, p)); });
  def_kernel<M>(
      m, "applied_forces",
      kernel_doc("Applied forces Ft = J^T F plus the generalized forces.", "(nv,)"), qv,
      [](const X& x, double t, const P& p) { return V(M::applied_forces(x.q, x.v, t, p)); });
  def_kernel<M>(
      m, "generalized_forces", kernel_doc("The part of Ft that acts on q directly.", "(nv,)"), qv,
      [](const X& x, double t, const P& p) { return V(M::generalized_forces(x.q, x.v, t, p)); });
  def_kernel<M>(
      m, "inertial_forces", kernel_doc("Inertial forces Fi = -J^T M gamma.", "(nv,)"), qv,
      [](const X& x, double t, const P& p) { return V(M::inertial_forces(x.q, x.v, t, p)); });
  def_kernel<M>(m, "forces", kernel_doc("Right-hand side Ft + Fi of Mt qddot = Ft + Fi.", "(nv,)"),
                qv, [](const X& x, double t, const P& p) { return V(M::forces(x.q, x.v, t, p)); });
  def_kernel<M>(m, "dynamics", kernel_doc("Mt and Ft + Fi in one pass.", "(Mt, f)"), qv,
                [](const X& x, double t, const P& p) {
                  VMat<M> Mt;
                  V f;
                  M::dynamics(x.q, x.v, t, p, &Mt, &f);
                  return std::make_tuple(Mt, f);
                });
  def_kernel<M>(m, "qddot",
                kernel_doc("Generalized accelerations Mt^-1 (Ft + Fi); NaN entries where Mt is "
                           "not positive definite.",
                           "(nv,)"),
                qv, [](const X& x, double t, const P& p) { return V(M::qddot(x.q, x.v, t, p)); });
  if constexpr (!has_kinematic_constraints_v<M>) {
    def_kernel<M>(
        m, "qddot_simd",
        kernel_doc("qddot, a batch evaluated 4 states per call across SIMD lanes: equal to qddot "
                   "to a few ulp (sin and cos from glibc's vector library), NaN where qddot is "
                   "NaN; one Params and one u for the whole batch.",
                   "(nv,)"),
        qv, [](const X& x, double t, const P& p) { return V(M::qddot(x.q, x.v, t, p)); },
        simd_qddot_lanes<M>);
  }
  def_kernel<M>(m, "inverse_dynamics",
                kernel_doc("Residual r = Mt qdd - Ft - Fi: the generalized force that gives "
                           "the acceleration qdd.",
                           "(nv,)"),
                qva, [](const X& x, double t, const P& p) {
                  return V(M::inverse_dynamics(x.q, x.v, x.qdd, t, p));
                });
  if constexpr (has_residual_jacobians_v<M>) {
    def_kernel<M>(m, "residual_jacobians",
                  kernel_doc("Jacobians dr/dq and dr/dv of the residual r(q, v, qdd).",
                             "(dr_dq, dr_dv), of shapes (nv, nq), (nv, nv)"),
                  qva, [](const X& x, double t, const P& p) {
                    VQMat<M> r_D_q;
                    VMat<M> r_D_v;
                    M::residual_jacobians(x.q, x.v, x.qdd, t, p, &r_D_q, &r_D_v);
                    return std::make_tuple(r_D_q, r_D_v);
                  });
  }
  if constexpr (has_inputs_v<M>) {
    def_kernel<M>(m, "input_matrix",
                  kernel_doc("Input matrix B = dFt/du: the generalized force per unit of each "
                             "control input.",
                             "(nv, num_inputs)"),
                  qv, [](const X& x, double t, const P& p) {
                    return AsMatrix<typename M::template InputMatrix<double>>{
                        M::input_matrix(x.q, x.v, t, p)};
                  });
  }
  def_kernel<M>(
      m, "kinetic_energy", kernel_doc("Kinetic energy T.", "a float"), qv,
      [](const X& x, double t, const P& p) { return double(M::kinetic_energy(x.q, x.v, t, p)); });
  def_kernel<M>(
      m, "potential_energy", kernel_doc("Potential energy V.", "a float"), q,
      [](const X& x, double t, const P& p) { return double(M::potential_energy(x.q, t, p)); });
  def_kernel<M>(m, "generalized_potential_energy",
                kernel_doc("The joint-spring part of V.", "a float"), q,
                [](const X& x, double t, const P& p) {
                  return double(M::generalized_potential_energy(x.q, t, p));
                });
  def_kernel<M>(m, "energy", kernel_doc("Total energy T + V.", "a float"), qv,
                [](const X& x, double t, const P& p) { return double(M::energy(x.q, x.v, t, p)); });
  def_kernel<M>(m, "positions",
                kernel_doc("Particle positions x, dim entries per particle.", "(nx,)"), q,
                [](const X& x, double t, const P& p) { return XVec<M>(M::positions(x.q, t, p)); });
  def_kernel<M>(
      m, "velocities", kernel_doc("Particle velocities J v + X_t.", "(nx,)"), qv,
      [](const X& x, double t, const P& p) { return XVec<M>(M::velocities(x.q, x.v, t, p)); });
  def_kernel<M>(m, "jacobian",
                kernel_doc("Jacobian J = dX/dq G of the positions (v = q', G = I, without speeds).",
                           "(nx, nv)"),
                q,
                [](const X& x, double t, const P& p) { return XJac<M>(M::jacobian(x.q, t, p)); });
  def_kernel<M>(
      m, "bias_acceleration",
      kernel_doc("Bias acceleration gamma: the particles' acceleration at qddot = 0.", "(nx,)"), qv,
      [](const X& x, double t, const P& p) {
        return XVec<M>(M::bias_acceleration(x.q, x.v, t, p));
      });
  def_kernel<M>(m, "linear_momentum", kernel_doc("Linear momentum p.", "(dim,)"), qv,
                [](const X& x, double t, const P& p) {
                  return
                      typename M::template SpaceVector<double>(M::linear_momentum(x.q, x.v, t, p));
                });
  def_kernel<M>(
      m, "angular_momentum",
      kernel_doc("Angular momentum L about the origin (its z component in 2D).", "(angular_dim,)"),
      qv, [](const X& x, double t, const P& p) {
        return typename M::template AngularVector<double>(M::angular_momentum(x.q, x.v, t, p));
      });
  def_kernel<M>(m, "fixed_point_positions",
                kernel_doc("Positions of the fixed points, stacked.", "(dim * num_fixed_points,)"),
                std::array<const char*, 0>{}, [](const X&, double t, const P& p) {
                  return
                      typename M::template FixedPointVector<double>(M::fixed_point_positions(t, p));
                });
  m.def(
      "particle_masses",
      [](py::object params) {
        using Masses = typename M::template ParticleVector<double>;
        const Masses masses(M::template particle_masses<double>(params_input<M>(params, -1).at(0)));
        py::array_t<double> array = output_array(-1, Result<Masses>::shape());
        Result<Masses>::copy(masses, array.mutable_data());
        return array;
      },
      "The particles' masses, (num_particles,).", py::arg("params") = py::none());
}

/// The model's module: metadata, Params, kernels, first-order form and simulation.
template <class M>
void bind_model(py::module_& module) {
  static_assert(assert_model_v<M>);
  static_assert(!(has_generalized_speeds_v<M> && has_kinematic_constraints_v<M>),
                "gencoord: the Python bindings do not take a model with both generalized speeds "
                "(free or ball joints) and kinematic constraints");
  module.doc() = std::string("gencoord model ") + M::name +
                 ": generated kernels, scipy.integrate right-hand side and simulation.";
  bind_metadata<M>(module);
  bind_errors(module);
  bind_params<M>(module);
  bind_kernels<M>(module);
  if constexpr (has_generalized_speeds_v<M>) bind_speeds<M>(module);
  bind_first_order<M>(module);
  if constexpr (has_kinematic_constraints_v<M>) {
    bind_constraints<M>(module);  // linearize_constrained in place of linearize
  } else {
    bind_control<M>(module);
  }
  bind_simulation<M>(module);
}

}  // namespace gencoord::python
