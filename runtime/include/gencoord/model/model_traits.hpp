// SPDX-License-Identifier: BSD-3-Clause
// The Model concept: what the runtime requires of a generated model struct.
//
// The contract is docs/model_interface.md. This header is the only place where the runtime
// spells it out; everything else uses the aliases below. C++17, so the concept is a set of
// detection-idiom traits: is_model_v<M> says yes or no, and ModelCheck<M> names each missing
// member in a static_assert message (use `static_assert(assert_model_v<M>);`).
#pragma once

#include <array>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "gencoord/model/heap_matrix.hpp"

namespace gencoord {

// Shorthands for a model's double-precision types.
template <class M>
using ParamsOf = typename M::Params;
template <class M>
using QVec = typename M::template QVector<double>;  // (nq)
template <class M>
using QMat = typename M::template QMatrix<double>;  // (nq x nq)
template <class M>
using XVec = typename M::template XVector<double>;  // (nx = dim * num_particles)
template <class M>
using XJac = typename M::template XJacobian<double>;  // (nx x nq)
// The Eigen type a decomposition of one of the above takes (LLT<PlainOf<QMat<M>>>): the type
// itself when fixed-size, Eigen's dynamic-size Matrix for a HeapMatrix.
template <class T>
using PlainOf = typename T::PlainObject;

namespace detail {

// M's own VVector/VMatrix/VQMatrix<double> where declared: a model with generalized speeds
// (q' = G(q) v) declares them; any other model may not, and then v is q' (nv == nq)
template <class M>
using nv_member_op = std::enable_if_t<std::is_integral_v<std::remove_cv_t<decltype(M::nv)>>>;
template <class M>
using vvector_member_op = typename M::template VVector<double>;
template <class M>
using vmatrix_member_op = typename M::template VMatrix<double>;
template <class M>
using vqmatrix_member_op = typename M::template VQMatrix<double>;

template <class M, class = void>
struct SpeedCount : std::integral_constant<int, M::nq> {};
template <class M>
struct SpeedCount<M, nv_member_op<M>> : std::integral_constant<int, M::nv> {};
template <class M, template <class> class Member, class Default, class = void>
struct MemberOr {
  using type = Default;
};
template <class M, template <class> class Member, class Default>
struct MemberOr<M, Member, Default, std::void_t<Member<M>>> {
  using type = Member<M>;
};

}  // namespace detail

/// The number of generalized speeds of M: M::nv where declared, else M::nq (v = q').
template <class M>
inline constexpr int nv_of_v = detail::SpeedCount<M>::value;
template <class M>
using VVec = typename detail::MemberOr<M, detail::vvector_member_op, QVec<M>>::type;  // (nv)
template <class M>
using VMat = typename detail::MemberOr<M, detail::vmatrix_member_op, QMat<M>>::type;  // (nv x nv)
template <class M>
using VQMat = typename detail::MemberOr<M, detail::vqmatrix_member_op, QMat<M>>::type;  // (nv x nq)

namespace detail {

// detection idiom (std::experimental::is_detected, without the library TS)
template <class M, template <class> class Op, class = void>
struct detector : std::false_type {};
template <class M, template <class> class Op>
struct detector<M, Op, std::void_t<Op<M>>> : std::true_type {};
template <class M, template <class> class Op>
inline constexpr bool detected_v = detector<M, Op>::value;

// argument shorthands for unevaluated calls
template <class M>
const QVec<M>& q_arg();
template <class M>
const VVec<M>& v_arg();
template <class M>
const ParamsOf<M>& p_arg();
const double& t_arg();

template <class From, class To>
using require_convertible = std::enable_if_t<std::is_convertible_v<From, To>>;
template <class T>
using require_integral = std::enable_if_t<std::is_integral_v<std::remove_cv_t<T>>>;

// static data
template <class M>
using name_op = require_convertible<decltype(M::name), const char*>;
template <class M>
using sizes_op =
    std::enable_if_t<std::is_integral_v<std::remove_cv_t<decltype(M::nq)>> &&
                     std::is_integral_v<std::remove_cv_t<decltype(M::dim)>> &&
                     std::is_integral_v<std::remove_cv_t<decltype(M::num_particles)>> &&
                     std::is_integral_v<std::remove_cv_t<decltype(M::nx)>> &&
                     std::is_integral_v<std::remove_cv_t<decltype(M::angular_dim)>>>;
template <class M>
using sizes_valid_op =
    std::enable_if_t<(M::nq > 0) && (M::dim == 2 || M::dim == 3) && (M::num_particles > 0) &&
                     (M::nx == M::dim * M::num_particles) &&
                     (M::angular_dim == (M::dim == 3 ? 3 : 1)) && (nv_of_v<M> > 0) &&
                     (nv_of_v<M> <= M::nq)>;
template <class M>
using names_op = std::enable_if_t<
    std::is_same_v<std::remove_cv_t<decltype(M::coordinate_names)>,
                   std::array<const char*, static_cast<std::size_t>(M::nq)>> &&
    std::is_same_v<std::remove_cv_t<decltype(M::particle_names)>,
                   std::array<const char*, static_cast<std::size_t>(M::num_particles)>>>;

// types
template <class M>
using params_op = std::enable_if_t<std::is_default_constructible_v<ParamsOf<M>> &&
                                   std::is_copy_constructible_v<ParamsOf<M>>>;
// a rows x cols matrix: fixed-size Eigen, or HeapMatrix past Eigen's stack limit
template <class T, int Rows, int Cols>
constexpr bool is_sized_v = std::is_same_v<T, Eigen::Matrix<double, Rows, Cols>> ||
                            std::is_same_v<T, HeapMatrix<double, Rows, Cols>>;
template <class M>
using types_op =
    std::enable_if_t<is_sized_v<QVec<M>, M::nq, 1> && is_sized_v<QMat<M>, M::nq, M::nq> &&
                     is_sized_v<VVec<M>, nv_of_v<M>, 1> &&
                     is_sized_v<VMat<M>, nv_of_v<M>, nv_of_v<M>> &&
                     is_sized_v<VQMat<M>, nv_of_v<M>, M::nq> && is_sized_v<XVec<M>, M::nx, 1> &&
                     is_sized_v<XJac<M>, M::nx, nv_of_v<M>>>;

// functions, called with double arguments
template <class M>
using mass_matrix_op =
    require_convertible<decltype(M::mass_matrix(q_arg<M>(), t_arg(), p_arg<M>())), VMat<M>>;
template <class M>
using applied_forces_op =
    require_convertible<decltype(M::applied_forces(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())),
                        VVec<M>>;
template <class M>
using inertial_forces_op =
    require_convertible<decltype(M::inertial_forces(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())),
                        VVec<M>>;
template <class M>
using forces_op =
    require_convertible<decltype(M::forces(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())), VVec<M>>;
template <class M>
using dynamics_op = decltype(M::dynamics(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>(),
                                         std::declval<VMat<M>*>(), std::declval<VVec<M>*>()));
template <class M>
using qddot_op =
    require_convertible<decltype(M::qddot(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())), VVec<M>>;
template <class M>
using energies_op = std::enable_if_t<
    std::is_convertible_v<decltype(M::kinetic_energy(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())),
                          double> &&
    std::is_convertible_v<decltype(M::potential_energy(q_arg<M>(), t_arg(), p_arg<M>())), double> &&
    std::is_convertible_v<decltype(M::energy(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())),
                          double>>;
template <class M>
using kinematics_op = std::enable_if_t<
    std::is_convertible_v<decltype(M::positions(q_arg<M>(), t_arg(), p_arg<M>())), XVec<M>> &&
    std::is_convertible_v<decltype(M::velocities(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())),
                          XVec<M>> &&
    std::is_convertible_v<decltype(M::jacobian(q_arg<M>(), t_arg(), p_arg<M>())), XJac<M>> &&
    std::is_convertible_v<
        decltype(M::bias_acceleration(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())), XVec<M>>>;
template <class M>
using momenta_op = std::enable_if_t<
    std::is_convertible_v<decltype(M::linear_momentum(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())),
                          Eigen::Matrix<double, M::dim, 1>> &&
    std::is_convertible_v<decltype(M::angular_momentum(q_arg<M>(), v_arg<M>(), t_arg(),
                                                       p_arg<M>())),
                          Eigen::Matrix<double, M::angular_dim, 1>>>;
// particle_masses(p) has no argument to deduce Scalar from: accept a template called as
// particle_masses<double>(p), or a plain function
template <class M>
using particle_masses_template_op =
    require_convertible<decltype(M::template particle_masses<double>(p_arg<M>())),
                        Eigen::Matrix<double, M::num_particles, 1>>;
template <class M>
using particle_masses_plain_op = require_convertible<decltype(M::particle_masses(p_arg<M>())),
                                                     Eigen::Matrix<double, M::num_particles, 1>>;
template <class M>
inline constexpr bool has_particle_masses_v =
    detected_v<M, particle_masses_template_op> || detected_v<M, particle_masses_plain_op>;

// fixed points: optional, so hand-written models without anchors stay models
template <class M>
using fixed_points_op = std::enable_if_t<
    std::is_integral_v<std::remove_cv_t<decltype(M::num_fixed_points)>> &&
    std::is_same_v<std::remove_cv_t<decltype(M::fixed_point_names)>,
                   std::array<const char*, static_cast<std::size_t>(M::num_fixed_points)>> &&
    std::is_convertible_v<decltype(M::fixed_point_positions(t_arg(), p_arg<M>())),
                          Eigen::Matrix<double, M::dim * M::num_fixed_points, 1>>>;

// recursive_qddot: optional; generated models declare whether their qddot is O(nq)
template <class M>
using recursive_qddot_op = std::enable_if_t<M::recursive_qddot>;

// control inputs: optional; a model with inputs holds their values in Params (inputs(),
// set_inputs()) and has B = input_matrix(q, v, t, p)
template <class M>
using inputs_op = std::enable_if_t<
    (M::num_inputs > 0) &&
    std::is_same_v<std::remove_cv_t<decltype(M::input_names)>,
                   std::array<const char*, static_cast<std::size_t>(M::num_inputs)>> &&
    std::is_same_v<decltype(std::declval<const typename M::Params&>().inputs()),
                   std::array<double, static_cast<std::size_t>(M::num_inputs)>> &&
    std::is_void_v<decltype(std::declval<typename M::Params&>().set_inputs(
        std::declval<const std::array<double, static_cast<std::size_t>(M::num_inputs)>&>()))> &&
    std::is_convertible_v<decltype(M::input_matrix(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())),
                          Eigen::Matrix<double, nv_of_v<M>, M::num_inputs>>>;

// generalized speeds: q' = coordinate_rates(q, v, t, p), linear in v
template <class M>
using coordinate_rates_op =
    require_convertible<decltype(M::coordinate_rates(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())),
                        QVec<M>>;
// what a model with generalized speeds declares besides: speed names and its unit quaternions
// (scalar first, at quaternion_starts in q)
template <class M>
using speed_members_op = std::enable_if_t<
    std::is_same_v<std::remove_cv_t<decltype(M::speed_names)>,
                   std::array<const char*, static_cast<std::size_t>(nv_of_v<M>)>> &&
    std::is_integral_v<std::remove_cv_t<decltype(M::num_quaternions)>> &&
    std::is_same_v<std::remove_cv_t<decltype(M::quaternion_starts)>,
                   std::array<int, static_cast<std::size_t>(M::num_quaternions)>>>;

// kinematic constraints: A(q, t) v + b = 0 (all of them), C(q, t) = 0 (the holonomic ones)
template <class M>
using kinematic_constraints_op = std::enable_if_t<
    std::is_integral_v<std::remove_cv_t<decltype(M::num_constraints)>> &&
    std::is_convertible_v<decltype(M::constraint_jacobian(q_arg<M>(), t_arg(), p_arg<M>())),
                          typename M::template CJacobian<double>> &&
    std::is_convertible_v<decltype(M::constraint_velocities(q_arg<M>(), v_arg<M>(), t_arg(),
                                                            p_arg<M>())),
                          typename M::template CVector<double>> &&
    std::is_convertible_v<decltype(M::constraint_bias(q_arg<M>(), v_arg<M>(), t_arg(), p_arg<M>())),
                          typename M::template CVector<double>>>;
template <class M>
using holonomic_constraints_op = std::enable_if_t<
    std::is_convertible_v<decltype(M::holonomic_constraints(q_arg<M>(), t_arg(), p_arg<M>())),
                          typename M::template HVector<double>> &&
    std::is_convertible_v<decltype(M::holonomic_jacobian(q_arg<M>(), t_arg(), p_arg<M>())),
                          typename M::template HJacobian<double>>>;

}  // namespace detail

/// True when M has kinematic constraints that its coordinates do not satisfy by
/// construction (closed loops, rolling): A(q, t) v + b(q, t) = 0 with M::num_constraints
/// rows, M::constraint_jacobian, constraint_velocities and constraint_bias (gamma, with
/// A v' + gamma = 0). acceleration() then solves the constrained dynamics.
template <class M>
inline constexpr bool has_kinematic_constraints_v =
    detail::detected_v<M, detail::kinematic_constraints_op>;

/// True when some of M's kinematic constraints are holonomic, C(q, t) = 0:
/// M::holonomic_constraints and M::holonomic_jacobian (dC/dq).
template <class M>
inline constexpr bool has_holonomic_constraints_v =
    detail::detected_v<M, detail::holonomic_constraints_op>;

namespace detail {
template <class M>
constexpr bool has_velocity_rows() {
  if constexpr (has_holonomic_constraints_v<M>)
    return M::num_constraints > M::num_holonomic_constraints;
  else return has_kinematic_constraints_v<M>;
}
}  // namespace detail

/// True when some of M's kinematic constraints are velocity (nonholonomic) constraints,
/// A(q, t) v + b = 0 with no C(q, t) behind them: the rows after the holonomic ones.
template <class M>
inline constexpr bool has_velocity_constraints_v = detail::has_velocity_rows<M>();

/// True when M::qddot is a recursion that is cheaper than Mt, Ft + Fi and a factorization
/// (generated tree models that say `recursive_qddot = true`); acceleration() then calls it.
template <class M>
inline constexpr bool has_recursive_qddot_v = detail::detected_v<M, detail::recursive_qddot_op>;

/// True when M has generalized speeds: v of size nv <= nq and q' = M::coordinate_rates(q, v,
/// t, p) = G(q) v (free and ball joints, unit quaternions in q). Other models have v = q'.
template <class M>
inline constexpr bool has_generalized_speeds_v = detail::detected_v<M, detail::coordinate_rates_op>;

/// True when M has control inputs (docs/model_interface.md): num_inputs > 0, input_names,
/// Params::inputs() and set_inputs(), input_matrix(q, v, t, p).
template <class M>
inline constexpr bool has_inputs_v = detail::detected_v<M, detail::inputs_op>;

namespace detail {
template <class M, bool = has_inputs_v<M>>
struct InputCount : std::integral_constant<int, 0> {};
template <class M>
struct InputCount<M, true> : std::integral_constant<int, M::num_inputs> {};
}  // namespace detail

/// The number of control inputs of M (0 for a model without them).
template <class M>
inline constexpr int num_inputs_v = detail::InputCount<M>::value;

/// A vector of M's control inputs, in the order of M::input_names (dim num_inputs_v<M>).
template <class M>
using InputVec = Eigen::Matrix<double, num_inputs_v<M>, 1>;

/// True when M has the optional fixed-point members of docs/model_interface.md
/// (num_fixed_points, fixed_point_names, fixed_point_positions(t, p)).
template <class M>
inline constexpr bool has_fixed_points_v = detail::detected_v<M, detail::fixed_points_op>;

/// True when M satisfies the whole interface of docs/model_interface.md (with Scalar = double).
template <class M>
inline constexpr bool is_model_v = std::conjunction_v<
    detail::detector<M, detail::name_op>, detail::detector<M, detail::sizes_op>,
    detail::detector<M, detail::sizes_valid_op>, detail::detector<M, detail::names_op>,
    detail::detector<M, detail::params_op>, detail::detector<M, detail::types_op>,
    detail::detector<M, detail::mass_matrix_op>, detail::detector<M, detail::applied_forces_op>,
    detail::detector<M, detail::inertial_forces_op>, detail::detector<M, detail::forces_op>,
    detail::detector<M, detail::dynamics_op>, detail::detector<M, detail::qddot_op>,
    detail::detector<M, detail::energies_op>, detail::detector<M, detail::kinematics_op>,
    detail::detector<M, detail::momenta_op>, std::bool_constant<detail::has_particle_masses_v<M>>,
    std::bool_constant<!has_generalized_speeds_v<M> ||
                       detail::detected_v<M, detail::speed_members_op>>>;

/// Instantiating ModelCheck<M> fails with one readable message per missing or malformed member.
template <class M>
struct ModelCheck {
  static_assert(detail::detected_v<M, detail::name_op>,
                "gencoord model: missing `static constexpr const char* name`");
  static_assert(detail::detected_v<M, detail::sizes_op>,
                "gencoord model: missing an integral `static constexpr` size "
                "(nq, dim, num_particles, nx, angular_dim; nv where declared)");
  static_assert(detail::detected_v<M, detail::sizes_valid_op>,
                "gencoord model: inconsistent sizes (need nq > 0, dim in {2, 3}, "
                "nx == dim * num_particles, angular_dim == (dim == 3 ? 3 : 1), 0 < nv <= nq)");
  static_assert(detail::detected_v<M, detail::names_op>,
                "gencoord model: need `std::array<const char*, nq> coordinate_names` and "
                "`std::array<const char*, num_particles> particle_names`");
  static_assert(detail::detected_v<M, detail::params_op>,
                "gencoord model: missing a default-constructible, copyable `struct Params`");
  static_assert(detail::detected_v<M, detail::types_op>,
                "gencoord model: QVector/QMatrix/XVector/XJacobian<Scalar> (and VVector/VMatrix/"
                "VQMatrix where declared) must be fixed-size Eigen::Matrix (or "
                "gencoord::HeapMatrix) aliases of sizes (nq), (nq x nq), (nx), (nx x nv); (nv), "
                "(nv x nv), (nv x nq)");
  static_assert(
      detail::detected_v<M, detail::mass_matrix_op>,
      "gencoord model: missing `VMatrix<S> mass_matrix(q, t, p)` (QMatrix without speeds)");
  static_assert(detail::detected_v<M, detail::applied_forces_op>,
                "gencoord model: missing `VVector<S> applied_forces(q, v, t, p)` (v a VVector)");
  static_assert(detail::detected_v<M, detail::inertial_forces_op>,
                "gencoord model: missing `VVector<S> inertial_forces(q, v, t, p)` (v a VVector)");
  static_assert(detail::detected_v<M, detail::forces_op>,
                "gencoord model: missing `VVector<S> forces(q, v, t, p)` (v a VVector)");
  static_assert(detail::detected_v<M, detail::dynamics_op>,
                "gencoord model: missing `void dynamics(q, v, t, p, VMatrix<S>* Mt, "
                "VVector<S>* f)`");
  static_assert(detail::detected_v<M, detail::qddot_op>,
                "gencoord model: missing `VVector<S> qddot(q, v, t, p)` (v a VVector)");
  static_assert(detail::detected_v<M, detail::energies_op>,
                "gencoord model: missing kinetic_energy(q, v, t, p), potential_energy(q, t, p) "
                "or energy(q, v, t, p) returning a scalar");
  static_assert(detail::detected_v<M, detail::kinematics_op>,
                "gencoord model: missing positions(q, t, p), velocities(q, v, t, p), "
                "jacobian(q, t, p) or bias_acceleration(q, v, t, p)");
  static_assert(detail::detected_v<M, detail::momenta_op>,
                "gencoord model: missing linear_momentum(q, v, t, p) or "
                "angular_momentum(q, v, t, p)");
  static_assert(detail::has_particle_masses_v<M>,
                "gencoord model: missing `ParticleVector<S> particle_masses(p)`");
  static_assert(!has_generalized_speeds_v<M> || detail::detected_v<M, detail::speed_members_op>,
                "gencoord model: a model with coordinate_rates(q, v, t, p) needs "
                "`std::array<const char*, nv> speed_names`, `int num_quaternions` and "
                "`std::array<int, num_quaternions> quaternion_starts`");
  static constexpr bool value = true;
};

/// `static_assert(assert_model_v<M>);` at the top of a runtime template gives readable errors.
template <class M>
inline constexpr bool assert_model_v = ModelCheck<M>::value;

}  // namespace gencoord
