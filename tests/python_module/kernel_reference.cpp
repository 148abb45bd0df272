// SPDX-License-Identifier: BSD-3-Clause
// Every kernel of one model at the states read from standard input, printed exactly (%a), for
// test_model_module.py to compare with the Python module's results bit for bit. The build
// defines GENCOORD_MODEL_HEADER and GENCOORD_MODEL_CLASS as for the module.
//   input:  one state per line: t, then q, v, qdd (nq each), as decimal or hex floats
//   output: per state, one line per kernel: its name and its entries in row-major order; a
//           model with inputs adds input_matrix and qddot_with_inputs at u_k = 0.5 + k
#include <array>
#include <cstddef>
#include <cstdio>
#include <iostream>
#include <string>

#include GENCOORD_MODEL_HEADER

namespace {

using M = GENCOORD_MODEL_CLASS;
using V = M::QVector<double>;

void print(const char* name, double value) { std::printf("%s %a\n", name, value); }

template <class Matrix>
void print(const char* name, const Matrix& m) {
  std::printf("%s", name);
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) std::printf(" %a", m(r, c));
  std::printf("\n");
}

V read_vector() {
  V x;
  for (int k = 0; k < M::nq; ++k) {
    std::string word;
    std::cin >> word;
    x(k) = std::stod(word);
  }
  return x;
}

// input_matrix and qddot at u_k = 0.5 + k, which test_model_module.py passes as u=
template <class Model>
void print_input_kernels(const V& q, const V& v, double t, const typename Model::Params& p) {
  if constexpr (Model::num_inputs > 0) {
    typename Model::Params driven = p;
    std::array<double, Model::num_inputs> u;
    for (int k = 0; k < Model::num_inputs; ++k) u[static_cast<std::size_t>(k)] = 0.5 + k;
    driven.set_inputs(u);
    print("input_matrix", Model::input_matrix(q, v, t, driven));
    print("qddot_with_inputs", Model::qddot(q, v, t, driven));
  }
}

}  // namespace

int main() {
  const M::Params p;
  std::string word;
  while (std::cin >> word) {
    const double t = std::stod(word);
    const V q = read_vector(), v = read_vector(), qdd = read_vector();
    print("mass_matrix", M::mass_matrix(q, t, p));
    print("applied_forces", M::applied_forces(q, v, t, p));
    print("generalized_forces", M::generalized_forces(q, v, t, p));
    print("inertial_forces", M::inertial_forces(q, v, t, p));
    print("forces", M::forces(q, v, t, p));
    M::QMatrix<double> Mt, r_D_q, r_D_v;
    V f;
    M::dynamics(q, v, t, p, &Mt, &f);
    print("dynamics.0", Mt);
    print("dynamics.1", f);
    print("qddot", M::qddot(q, v, t, p));
    print("inverse_dynamics", M::inverse_dynamics(q, v, qdd, t, p));
    M::residual_jacobians(q, v, qdd, t, p, &r_D_q, &r_D_v);
    print("residual_jacobians.0", r_D_q);
    print("residual_jacobians.1", r_D_v);
    print("kinetic_energy", M::kinetic_energy(q, v, t, p));
    print("potential_energy", M::potential_energy(q, t, p));
    print("generalized_potential_energy", M::generalized_potential_energy(q, t, p));
    print("energy", M::energy(q, v, t, p));
    print("positions", M::positions(q, t, p));
    print("velocities", M::velocities(q, v, t, p));
    print("jacobian", M::jacobian(q, t, p));
    print("bias_acceleration", M::bias_acceleration(q, v, t, p));
    print("linear_momentum", M::linear_momentum(q, v, t, p));
    print("angular_momentum", M::angular_momentum(q, v, t, p));
    print("fixed_point_positions", M::fixed_point_positions(t, p));
    print_input_kernels<M>(q, v, t, p);
  }
  return 0;
}
