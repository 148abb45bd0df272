// The planar n-link chain's forward and inverse dynamics three ways, side by side in one
// process pinned to one core: the O(n) recursions (articulated-body qddot, Newton-Euler
// inverse_dynamics), the dense form (Mt, Ft + Fi and an LDL^T solve; Mt qdd - Ft - Fi) and
// MuJoCo (mj_forward; mj_rne after its position and velocity stages), plus one RK4 step of
// each. Each round times every contender over the same 64 random states, interleaved; the
// table gives the minimum and the median over the rounds of the ns per call, and the ratios.
// Before timing, the recursive kernels are checked against the dense ones and MuJoCo's qacc
// against both; a mismatch stops the run.
//   scripts/bench_recursion.sh [rounds]
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "gencoord/integrate/explicit_rk.hpp"
#include "gencoord/reduced_system.hpp"
#include "gencoord/state.hpp"
#include "peers/mujoco_chain.hpp"
#include "recursion_chains.hpp"  // generated: GENCOORD_RECURSION_CHAINS(X), X(n, Dense, Recursive)

namespace {

constexpr int kStates = 64;
constexpr double kStep = 1e-4;
volatile double sink = 0.0;  // keeps the results alive

double time_per_call(const std::function<void(int)>& call) {
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < kStates; ++k) call(k);
  const auto stop = std::chrono::steady_clock::now();
  return std::chrono::duration<double, std::nano>(stop - start).count() / kStates;
}

struct Contender {
  Contender(std::string label, std::function<void(int)> function)
      : name(std::move(label)), call(std::move(function)) {}
  std::string name;
  std::function<void(int)> call;
  std::vector<double> ns;
  double min() const { return *std::min_element(ns.begin(), ns.end()); }
  double median() const {
    std::vector<double> sorted = ns;
    std::sort(sorted.begin(), sorted.end());
    return sorted[sorted.size() / 2];
  }
};

/// Largest |a - b| relative to max(1, |b|) over the entries.
template <class A, class B>
double relative_difference(const A& a, const B& b, int n) {
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
    worst = std::max(worst, std::abs(a[i] - b[i]) / std::max(1.0, std::abs(b[i])));
  return worst;
}

template <class Dense, class Recursive>
void compare(int n, int rounds) {
  static_assert(Dense::nq == Recursive::nq);
  static_assert(!Dense::recursive_qddot && Recursive::recursive_qddot);
  const typename Dense::Params dense_params;
  const typename Recursive::Params recursive_params;
  typename Dense::Params by_name;  // the defaults, in MuJoCo's order g, l1, m1, l2, ...
  std::vector<double> mujoco_params{by_name.g};
  for (int k = 1; k <= n; ++k) {
    mujoco_params.push_back(*by_name.find("l" + std::to_string(k)));
    mujoco_params.push_back(*by_name.find("m" + std::to_string(k)));
  }
  std::unique_ptr<peers::MujocoChain> mujoco;
  try {
    mujoco = std::make_unique<peers::MujocoChain>(n, mujoco_params);
  } catch (const std::exception& error) {
    std::printf("\nn = %d: MuJoCo left out (%s)\n", n, error.what());
  }

  using Q = gencoord::QVec<Dense>;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), rate(-2.0, 2.0);
  std::vector<Q> q(kStates), v(kStates), qdd(kStates), relative_qdd(kStates);
  for (int k = 0; k < kStates; ++k) {
    for (int i = 0; i < n; ++i) q[k][i] = angle(rng), v[k][i] = rate(rng);
    qdd[k] = Dense::qddot(q[k], v[k], 0.0, dense_params);
    for (int i = 0; i < n; ++i) relative_qdd[k][i] = qdd[k][i] - (i ? qdd[k][i - 1] : 0.0);
  }

  // the contenders must agree before they are timed
  double worst_qddot = 0.0, worst_inverse = 0.0, worst_mujoco = 0.0;
  for (int k = 0; k < kStates; ++k) {
    const Q recursive = Recursive::qddot(q[k], v[k], 0.0, recursive_params);
    worst_qddot = std::max(worst_qddot, relative_difference(recursive, qdd[k], n));
    const Q r = Recursive::inverse_dynamics(q[k], v[k], qdd[k], 0.0, recursive_params);
    const Q r_dense = Dense::inverse_dynamics(q[k], v[k], qdd[k], 0.0, dense_params);
    worst_inverse = std::max(worst_inverse, relative_difference(r, r_dense, n));
    if (mujoco) {
      std::vector<double> qacc(n);
      mujoco->set_state(q[k].data(), v[k].data());
      mujoco->forward();
      mujoco->absolute_qacc(qacc.data());
      worst_mujoco = std::max(worst_mujoco, relative_difference(qacc, qdd[k], n));
    }
  }
  std::printf(
      "\nn = %d: recursive vs dense qddot %.1e, inverse_dynamics %.1e; MuJoCo qacc %.1e"
      " (relative)\n",
      n, worst_qddot, worst_inverse, worst_mujoco);
  if (worst_qddot > 1e-9 || worst_inverse > 1e-9 || worst_mujoco > 1e-5) {
    std::fprintf(stderr, "bench_recursion: the contenders disagree at n = %d\n", n);
    std::exit(1);
  }

  std::vector<double> torque(n);
  auto dense_state = gencoord::State<Dense>{};
  auto recursive_state = gencoord::State<Recursive>{};
  std::vector<Contender> contenders = {
      {"qddot recursive",
       [&](int k) { sink = sink + Recursive::qddot(q[k], v[k], 0.0, recursive_params)[0]; }},
      {"qddot dense", [&](int k) { sink = sink + Dense::qddot(q[k], v[k], 0.0, dense_params)[0]; }},
      {"inverse_dynamics recursive",
       [&](int k) {
         sink = sink + Recursive::inverse_dynamics(q[k], v[k], qdd[k], 0.0, recursive_params)[0];
       }},
      {"inverse_dynamics dense",
       [&](int k) {
         sink = sink + Dense::inverse_dynamics(q[k], v[k], qdd[k], 0.0, dense_params)[0];
       }},
      {"rk4 step recursive",
       [&](int k) {
         recursive_state.q = q[k], recursive_state.v = v[k];
         recursive_state = gencoord::rk4_step(gencoord::ReducedSystem<Recursive>(recursive_params),
                                              recursive_state, kStep);
         sink = sink + recursive_state.q[0];
       }},
      {"rk4 step dense",
       [&](int k) {
         dense_state.q = q[k], dense_state.v = v[k];
         dense_state =
             gencoord::rk4_step(gencoord::ReducedSystem<Dense>(dense_params), dense_state, kStep);
         sink = sink + dense_state.q[0];
       }},
  };
  if (mujoco) {
    contenders.push_back({"mj_forward", [&](int k) {
                            mujoco->set_state(q[k].data(), v[k].data());
                            mujoco->forward();
                            sink = sink + mujoco->data()->qacc[0];
                          }});
    contenders.push_back({"mj_rne with its stages", [&](int k) {
                            mujoco->set_state(q[k].data(), v[k].data());
                            mujoco->inverse_dynamics(relative_qdd[k].data(), torque.data());
                            sink = sink + torque[0];
                          }});
    contenders.push_back({"mj_step rk4", [&](int k) {
                            mujoco->set_state(q[k].data(), v[k].data());
                            mujoco->rk4_step(kStep);
                            sink = sink + mujoco->data()->qpos[0];
                          }});
  }
  for (int round = 0; round < rounds; ++round)
    for (auto& c : contenders) c.ns.push_back(time_per_call(c.call));

  std::printf("%-30s %10s %10s\n", "contender (ns per call)", "min", "median");
  for (const auto& c : contenders)
    std::printf("%-30s %10.1f %10.1f\n", c.name.c_str(), c.min(), c.median());
  const auto ratio = [&](std::size_t slower, std::size_t faster, const char* what) {
    if (slower >= contenders.size()) return;
    std::printf("%-30s %10.2f %10.2f\n", what, contenders[slower].min() / contenders[faster].min(),
                contenders[slower].median() / contenders[faster].median());
  };
  ratio(1, 0, "dense / recursive qddot");
  ratio(3, 2, "dense / recursive inverse");
  ratio(5, 4, "dense / recursive rk4");
  ratio(6, 0, "mj_forward / recursive qddot");
  ratio(7, 2, "mj_rne / recursive inverse");
  ratio(8, 4, "mj_step / recursive rk4");
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 21;
  cpu_set_t one_core;
  CPU_ZERO(&one_core);
  CPU_SET(0, &one_core);
  if (sched_setaffinity(0, sizeof one_core, &one_core) != 0)
    std::fprintf(stderr, "bench_recursion: could not pin to core 0; figures may be noisier\n");
#define GENCOORD_COMPARE(n, Dense, Recursive) compare<Dense, Recursive>(n, rounds);
  GENCOORD_RECURSION_CHAINS(GENCOORD_COMPARE)
#undef GENCOORD_COMPARE
}
