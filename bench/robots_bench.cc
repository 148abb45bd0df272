// SPDX-License-Identifier: BSD-3-Clause
// The generated robot models against MuJoCo on the same URDF, side by side in one process
// pinned to one core: qddot against mj_forward, mass_matrix against mj_fullM after MuJoCo's
// position stage (mj_fwdPosition, which forms qM), inverse_dynamics against mj_rne. Each round
// times every contender over the same 256 random states, interleaved; the table gives the
// minimum and the median over the rounds of the time per call, and the ratios. The floating
// quadruped's base is a free joint (unit quaternion, body twist) on both sides.
//   build/bench/bench_robots [rounds]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "gencoord/gencoord.hpp"
#include "generated/floating_quadruped.hpp"
#include "generated/iiwa14.hpp"
#include "generated/quadruped.hpp"
#include "generated/ur5e.hpp"
#include "robots/mujoco_model.hpp"
#include "robots/quaternion_base.hpp"

#include "interleaved.hpp"

namespace {

using gencoord::State;
using gencoord::robot_testing::MujocoReference;
using gencoord::robot_testing::QuaternionBaseReference;

constexpr int kStates = 256;
volatile double sink = 0.0;  // keeps the results alive

/// Nanoseconds per call of `call(k)` over k = 0 .. kStates - 1.
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
  const typename M::Params p;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), rate(-2.0, 2.0);
  std::vector<State<M>> states(kStates);
  for (auto& s : states) {
    for (int i = 0; i < M::nq; ++i) s.q[i] = angle(rng);
    for (int i = 0; i < M::nv; ++i) s.v[i] = rate(rng);
    if constexpr (gencoord::has_generalized_speeds_v<M>) s.q.template segment<4>(3).normalize();
  }
  std::vector<gencoord::VVec<M>> qdd(kStates);
  for (int k = 0; k < kStates; ++k) qdd[k] = M::qddot(states[k].q, states[k].v, 0.0, p);
  std::vector<double> full(m->nv * m->nv);
  std::vector<mjtNum> rne(m->nv);

  struct Contender {
    const char* name;
    std::function<void(int)> call;
    std::vector<double> ns;
  };
  std::vector<Contender> contenders = {
      {"qddot",
       [&](int k) { sink = sink + kept(M::qddot(states[k].q, states[k].v, 0.0, p))[0]; },
       {}},
      {"mj_forward",
       [&](int k) {
         mujoco.set(states[k].q, states[k].v);
         mj_forward(m, d);
         sink = sink + d->qacc[0];
       },
       {}},
      {"mass_matrix",
       [&](int k) { sink = sink + kept(M::mass_matrix(states[k].q, 0.0, p))(0, 0); },
       {}},
      {"mj_fwdPosition+mj_fullM",
       [&](int k) {
         mujoco.set(states[k].q, states[k].v);
         mj_fwdPosition(m, d);
         mj_fullM(m, full.data(), d->qM);
         sink = sink + full[0];
       },
       {}},
      {"inverse_dynamics",
       [&](int k) {
         sink = sink + kept(M::inverse_dynamics(states[k].q, states[k].v, qdd[k], 0.0, p))[0];
       },
       {}},
      {"mj_rne (after mj_fwdPosition+mj_fwdVelocity)",
       [&](int k) {
         mujoco.set(states[k].q, states[k].v);
         mj_fwdPosition(m, d);
         mj_fwdVelocity(m, d);
         for (int i = 0; i < M::nv; ++i) d->qacc[i] = qdd[k][i];
         mj_rne(m, d, 1, rne.data());
         sink = sink + rne[0];
       },
       {}},
      {"mj_rne alone",
       [&](int k) {
         for (int i = 0; i < M::nv; ++i) d->qacc[i] = qdd[k][i];
         mj_rne(m, d, 1, rne.data());
         sink = sink + rne[0];
       },
       {}},
  };
  for (int round = 0; round < rounds; ++round) {
    for (auto& c : contenders) c.ns.push_back(time_per_call(c.call));
  }
  std::printf("\n%s (nq = %d, nv = %d), ns per call over %d rounds of %d states\n", robot, M::nq,
              gencoord::nv_of_v<M>, rounds, kStates);
  std::printf("%-48s %10s %10s\n", "contender", "min", "median");
  std::vector<Summary> summaries;
  for (auto& c : contenders) {
    summaries.push_back(summarize(c.ns));
    std::printf("%-48s %10.1f %10.1f\n", c.name, summaries.back().min, summaries.back().median);
  }
  const auto ratio = [&](int mujoco_index, int ours_index, const char* what) {
    std::printf("%-48s %10.2f %10.2f\n", what,
                summaries[mujoco_index].min / summaries[ours_index].min,
                summaries[mujoco_index].median / summaries[ours_index].median);
  };
  ratio(1, 0, "ratio mj_forward / qddot");
  ratio(3, 2, "ratio mj_fwdPosition+mj_fullM / mass_matrix");
  ratio(5, 4, "ratio mj_rne with its stages / inverse_dynamics");
  ratio(6, 4, "ratio mj_rne alone / inverse_dynamics");
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 51;
  gencoord::bench::pin_to_one_core("bench_robots");
  compare<gencoord::models::Iiwa14>("iiwa14", GENCOORD_ROOT "/models/iiwa14.urdf", rounds);
  compare<gencoord::models::Ur5e>("ur5e", GENCOORD_ROOT "/models/ur5e.urdf", rounds);
  compare<gencoord::models::Quadruped>("quadruped", GENCOORD_ROOT "/models/quadruped.urdf", rounds);
  using Floating = gencoord::models::FloatingQuadruped;
  compare<Floating, QuaternionBaseReference<Floating>>(
      "floating_quadruped", GENCOORD_ROOT "/models/floating_quadruped.urdf", rounds);
}
