// SPDX-License-Identifier: BSD-3-Clause
// Closed-loop dynamics against MuJoCo, side by side in one process pinned to one core: the
// Delta robot's constrained acceleration (models/delta_robot.py: the tree's Mt and forces,
// the loops' A and gamma, a range-space KKT solve) against mj_forward on the same mechanism
// with rods on ball joints and three `connect` equalities (tests/constrained/mujoco_delta.hpp;
// 15 degrees of freedom and 9 constraint rows there, 6 coordinates and 3 constraints here).
// Each round times every contender over the same 256 states, interleaved; the table gives
// the minimum and the median over the rounds of the time per call, and their ratios. The
// tree's own qddot (the loops left open) is listed to show what the constraints cost.
//   build/bench/bench_constrained [rounds]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <vector>

#include "constrained/mujoco_delta.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/state.hpp"

#include "interleaved.hpp"

namespace {

using gencoord::State;
using gencoord::constrained_testing::MujocoDelta;
using Delta = gencoord::models::DeltaRobot;

constexpr int kStates = 256;
volatile double sink = 0.0;  // keeps the results alive

double time_per_call(const std::function<void(int)>& call) {
  return gencoord::bench::ns_per_call(kStates, call);
}

using gencoord::bench::kept;
using gencoord::bench::summarize;
using gencoord::bench::Summary;

void compare_delta(int rounds) {
  Delta::Params p;
  p.set_inputs({{0.5, -0.2, 0.8}});
  MujocoDelta::Vec reference;
  for (int i = 0; i < Delta::nq; ++i) reference[i] = Delta::initial_q[i];
  MujocoDelta mujoco(p, reference);
  mjModel* m = mujoco.model();
  mjData* d = mujoco.data();
  // the states on the loops, and MuJoCo's copy of each (set up before any timing)
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> offset(-0.1, 0.1), rate(-1.5, 1.5);
  std::vector<State<Delta>> states(kStates);
  std::vector<std::vector<mjtNum>> qpos(kStates), qvel(kStates);
  for (int k = 0; k < kStates; ++k) {
    State<Delta>& s = states[k];
    s.q = reference;
    for (int i = 3; i < 6; ++i) s.q[i] += offset(rng);
    for (int i = 0; i < 6; ++i) s.v[i] = rate(rng);
    gencoord::project_onto_constraints<Delta>(p, &s);
    mujoco.set(s.q, s.v, p.inputs());
    qpos[k].assign(d->qpos, d->qpos + m->nq);
    qvel[k].assign(d->qvel, d->qvel + m->nv);
  }

  struct Contender {
    const char* name;
    std::function<void(int)> call;
    std::vector<double> ns;
  };
  std::vector<Contender> contenders = {
      {"constrained_acceleration",
       [&](int k) {
         const State<Delta>& s = states[k];
         sink = sink + kept(gencoord::constrained_acceleration<Delta>(p, s.q, s.v, s.t))[0];
       },
       {}},
      {"mj_forward",
       [&](int k) {
         std::copy(qpos[k].begin(), qpos[k].end(), d->qpos);
         std::copy(qvel[k].begin(), qvel[k].end(), d->qvel);
         mj_forward(m, d);
         sink = sink + d->qacc[0];
       },
       {}},
      {"qddot (the tree, loops open)",
       [&](int k) { sink = sink + kept(Delta::qddot(states[k].q, states[k].v, 0.0, p))[0]; },
       {}},
  };
  for (int round = 0; round < rounds; ++round) {
    for (auto& c : contenders) c.ns.push_back(time_per_call(c.call));
  }
  std::printf(
      "\ndelta_robot (nq = %d, %d constraints; MuJoCo nv = %d, %d constraint rows), "
      "ns per call over %d rounds of %d states\n",
      Delta::nq, Delta::num_constraints, m->nv, d->nefc, rounds, kStates);
  std::printf("%-40s %10s %10s\n", "contender", "min", "median");
  std::vector<Summary> summaries;
  for (auto& c : contenders) {
    summaries.push_back(summarize(c.ns));
    std::printf("%-40s %10.1f %10.1f\n", c.name, summaries.back().min, summaries.back().median);
  }
  std::printf("%-40s %10.2f %10.2f\n", "ratio mj_forward / constrained_acceleration",
              summaries[1].min / summaries[0].min, summaries[1].median / summaries[0].median);
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 51;
  gencoord::bench::pin_to_one_core("bench_constrained");
  compare_delta(rounds);
}
