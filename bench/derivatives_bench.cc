// SPDX-License-Identifier: BSD-3-Clause
// The derivatives of the forward dynamics of the URDF robots, side by side in one process
// pinned to one core, over the same 256 random states: gencoord's dynamics_derivatives (a,
// da/dq, da/dv and da/dtau = Mt^-1 from residual_jacobians, the derivative of the recursive
// Newton-Euler residual, in closed form for the arms and by forward mode for the quadrupeds,
// and one Cholesky factor), the same from central differences
// of gencoord's own acceleration, and MuJoCo's finite-difference linearization mjd_transitionFD
// (forward differences, its faster mode; it differences mj_step, one step of its Euler
// integrator per column); for scale, qddot and residual_jacobians alone (the generated part of
// the derivatives). Each round times every contender; the table gives the minimum and the
// median over the rounds of the time per call, and the ratios.
//   build/bench/bench_derivatives [rounds]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <vector>

#include "gencoord/gencoord.hpp"
#include "gencoord/model/dynamics_derivatives.hpp"
#include "generated/floating_quadruped.hpp"
#include "generated/iiwa14.hpp"
#include "generated/quadruped.hpp"
#include "generated/ur5e.hpp"
#include "robots/mujoco_model.hpp"
#include "robots/quaternion_base.hpp"

#include "interleaved.hpp"

namespace {

using gencoord::JacobianSource;
using gencoord::State;
using gencoord::robot_testing::MujocoReference;
using gencoord::robot_testing::QuaternionBaseReference;

constexpr int kStates = 256;
volatile double sink = 0.0;  // keeps the results alive

double time_per_call(const std::function<void(int)>& call) {
  return gencoord::bench::ns_per_call(kStates, call);
}

using gencoord::bench::kept;
using gencoord::bench::summarize;
using gencoord::bench::Summary;

template <class M, class Reference = MujocoReference<M>>
void compare(const char* robot, const char* urdf, int rounds) {
  Reference mujoco(urdf);
  mjModel* m = mujoco.model();
  mjData* d = mujoco.data();
  m->opt.integrator = mjINT_EULER;
  const typename M::Params p;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), rate(-2.0, 2.0);
  std::vector<State<M>> states(kStates);
  for (auto& s : states) {
    for (int i = 0; i < M::nq; ++i) s.q[i] = angle(rng);
    for (int i = 0; i < gencoord::nv_of_v<M>; ++i) s.v[i] = rate(rng);
    if constexpr (gencoord::has_generalized_speeds_v<M>) s.q.template segment<4>(3).normalize();
  }
  // the accelerations at which dynamics_derivatives evaluates the residual's Jacobians
  std::vector<gencoord::VVec<M>> accelerations;
  for (const auto& s : states) accelerations.push_back(gencoord::acceleration<M>(p, s.q, s.v, 0.0));
  const int n = 2 * m->nv + m->na;
  std::vector<mjtNum> A(static_cast<std::size_t>(n) * n);

  struct Contender {
    const char* name;
    std::function<void(int)> call;
    std::vector<double> ns;
  };
  const auto derivatives = [&](int k, JacobianSource source) {
    const auto out = gencoord::dynamics_derivatives<M>(p, states[k].q, states[k].v, 0.0, source);
    sink = sink + kept(out.a_D_q)(0, 0) + kept(out.a_D_v)(0, 0) + kept(out.a_D_tau)(0, 0);
  };
  std::vector<Contender> contenders = {
      {"dynamics_derivatives (generated)",
       [&](int k) { derivatives(k, JacobianSource::Generated); },
       {}},
      {"central differences of gencoord's acceleration",
       [&](int k) { derivatives(k, JacobianSource::FiniteDifference); },
       {}},
      {"mjd_transitionFD (forward differences)",
       [&](int k) {
         mujoco.set(states[k].q, states[k].v);
         mjd_transitionFD(m, d, 1e-6, 0, A.data(), nullptr, nullptr, nullptr);
         sink = sink + A[0];
       },
       {}},
      {"qddot (one call, for scale)",
       [&](int k) { sink = sink + kept(M::qddot(states[k].q, states[k].v, 0.0, p))[0]; },
       {}},
      {"residual_jacobians (one call, its share)",
       [&](int k) {
         gencoord::VQMat<M> r_D_q;
         gencoord::VMat<M> r_D_v;
         M::residual_jacobians(states[k].q, states[k].v, accelerations[k], 0.0, p, &r_D_q, &r_D_v);
         sink = sink + kept(r_D_q)(0, 0) + kept(r_D_v)(0, 0);
       },
       {}},
  };
  for (int round = 0; round < rounds; ++round)
    for (auto& c : contenders) c.ns.push_back(time_per_call(c.call));
  std::printf("\n%s (nq = %d, nv = %d), ns per call over %d rounds of %d states\n", robot, M::nq,
              gencoord::nv_of_v<M>, rounds, kStates);
  std::printf("%-48s %10s %10s\n", "contender", "min", "median");
  std::vector<Summary> summaries;
  for (auto& c : contenders) {
    summaries.push_back(summarize(c.ns));
    std::printf("%-48s %10.1f %10.1f\n", c.name, summaries.back().min, summaries.back().median);
  }
  const auto ratio = [&](int other, const char* what) {
    std::printf("%-48s %10.2f %10.2f\n", what, summaries[other].min / summaries[0].min,
                summaries[other].median / summaries[0].median);
  };
  ratio(1, "ratio central differences / generated");
  ratio(2, "ratio mjd_transitionFD / generated");
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 51;
  gencoord::bench::pin_to_one_core("bench_derivatives");
  compare<gencoord::models::Iiwa14>("iiwa14", GENCOORD_ROOT "/models/iiwa14.urdf", rounds);
  compare<gencoord::models::Ur5e>("ur5e", GENCOORD_ROOT "/models/ur5e.urdf", rounds);
  compare<gencoord::models::Quadruped>("quadruped", GENCOORD_ROOT "/models/quadruped.urdf", rounds);
  using Floating = gencoord::models::FloatingQuadruped;
  compare<Floating, QuaternionBaseReference<Floating>>(
      "floating_quadruped", GENCOORD_ROOT "/models/floating_quadruped.urdf", rounds);
}
