// SPDX-License-Identifier: BSD-3-Clause
// The planar n-link chain's forward and inverse dynamics three ways, side by side in one
// process pinned to one core: the O(n) recursions (articulated-body qddot, Newton-Euler
// inverse_dynamics), the dense form (Mt, Ft + Fi and an LDL^T solve; Mt qdd - Ft - Fi) and
// MuJoCo (mj_forward; mj_rne after its position and velocity stages), plus one RK4 step of
// each. Each round times every contender over the same 64 random states, interleaved; the
// table gives the minimum and the median over the rounds of the ns per call, and the ratios.
// Before timing, the recursive kernels are checked against the dense ones and MuJoCo's qacc
// against both; a mismatch stops the run. Sizes above GENCOORD_RECURSION_DENSE_MAX (CMake) have
// no dense contender, and MuJoCo is checked against the recursion there.
//   scripts/bench_recursion.sh [rounds]
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
#include <type_traits>
#include <utility>
#include <vector>

#include "gencoord/integrate/explicit_rk.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/model/state.hpp"
#include "peers/mujoco_chain.hpp"
#include "recursion_chains.hpp"  // generated: GENCOORD_RECURSION_CHAINS(X), X(n, Dense, Recursive)

#include "interleaved.hpp"

namespace {

using gencoord::bench::kept;

constexpr int kStates = 64;
constexpr double kStep = 1e-4;
volatile double sink = 0.0;  // keeps the results alive

double time_per_call(const std::function<void(int)>& call) {
  return gencoord::bench::ns_per_call(kStates, call);
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

/// Times the chain of n links; Dense is void for a size given no dense contender
/// (GENCOORD_RECURSION_DENSE_MAX), and MuJoCo is then checked against the recursion.
template <class Dense, class Recursive>
void compare(int n, int rounds) {
  constexpr bool kDense = !std::is_void_v<Dense>;
  static_assert(Recursive::recursive_qddot);
  const typename Recursive::Params recursive_params;
  typename Recursive::Params by_name;  // the defaults, in MuJoCo's order g, l1, m1, l2, ...
  std::vector<double> mujoco_params{by_name.g};
  for (int k = 1; k <= n; ++k) {
    mujoco_params.push_back(*by_name.find("l" + std::to_string(k)));
    mujoco_params.push_back(*by_name.find("m" + std::to_string(k)));
  }
  if constexpr (!kDense) {
    std::printf(
        "\nn = %d: dense contender left out: n > GENCOORD_RECURSION_DENSE_MAX = %d (CMake), since"
        " the dense chain's generation and compile grow steeply with n (bench/CMakeLists.txt)\n",
        n, GENCOORD_RECURSION_DENSE_MAX);
  }
  std::unique_ptr<peers::MujocoChain> mujoco;
  try {
    mujoco = std::make_unique<peers::MujocoChain>(n, mujoco_params);
  } catch (const std::exception& error) {
    std::printf("\nn = %d: MuJoCo left out (%s)\n", n, error.what());
  }

  // the reference accelerations: the dense solve where there is one, else the recursion
  using Q = gencoord::QVec<Recursive>;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), rate(-2.0, 2.0);
  std::vector<Q> q(kStates), v(kStates), qdd(kStates), relative_qdd(kStates);
  for (int k = 0; k < kStates; ++k) {
    for (int i = 0; i < n; ++i) q[k][i] = angle(rng), v[k][i] = rate(rng);
    if constexpr (kDense) qdd[k] = Dense::qddot(q[k], v[k], 0.0, typename Dense::Params{});
    else qdd[k] = Recursive::qddot(q[k], v[k], 0.0, recursive_params);
    for (int i = 0; i < n; ++i) relative_qdd[k][i] = qdd[k][i] - (i ? qdd[k][i - 1] : 0.0);
  }

  // the contenders must agree before they are timed
  double worst_qddot = 0.0, worst_inverse = 0.0, worst_mujoco = 0.0;
  for (int k = 0; k < kStates; ++k) {
    if constexpr (kDense) {
      static_assert(Dense::nq == Recursive::nq && !Dense::recursive_qddot);
      const typename Dense::Params dense_params;
      const Q recursive = Recursive::qddot(q[k], v[k], 0.0, recursive_params);
      worst_qddot = std::max(worst_qddot, relative_difference(recursive, qdd[k], n));
      const Q r = Recursive::inverse_dynamics(q[k], v[k], qdd[k], 0.0, recursive_params);
      const Q r_dense = Dense::inverse_dynamics(q[k], v[k], qdd[k], 0.0, dense_params);
      worst_inverse = std::max(worst_inverse, relative_difference(r, r_dense, n));
    }
    if (mujoco) {
      std::vector<double> qacc(n);
      mujoco->set_state(q[k].data(), v[k].data());
      mujoco->forward();
      mujoco->absolute_qacc(qacc.data());
      worst_mujoco = std::max(worst_mujoco, relative_difference(qacc, qdd[k], n));
    }
  }
  if constexpr (kDense) {
    std::printf(
        "\nn = %d: recursive vs dense qddot %.1e, inverse_dynamics %.1e; MuJoCo qacc vs dense"
        " %.1e (relative)\n",
        n, worst_qddot, worst_inverse, worst_mujoco);
  } else {
    std::printf("\nn = %d: MuJoCo qacc vs recursive %.1e (relative)\n", n, worst_mujoco);
  }
  if (worst_qddot > 1e-9 || worst_inverse > 1e-9 || worst_mujoco > 1e-5) {
    std::fprintf(stderr, "bench_recursion: the contenders disagree at n = %d\n", n);
    std::exit(1);
  }

  // timed interleaved and tabled in this order: each dense kernel after its recursive one
  std::vector<double> torque(n);
  auto recursive_state = gencoord::State<Recursive>{};
  std::vector<Contender> contenders;
  contenders.emplace_back("qddot recursive", [&](int k) {
    sink = sink + kept(Recursive::qddot(q[k], v[k], 0.0, recursive_params))[0];
  });
  // the dense lambdas own their parameters and state: Dense names no type where it is void
  if constexpr (kDense) {
    contenders.emplace_back("qddot dense", [&, params = typename Dense::Params{}](int k) {
      sink = sink + kept(Dense::qddot(q[k], v[k], 0.0, params))[0];
    });
  }
  contenders.emplace_back("inverse_dynamics recursive", [&](int k) {
    sink = sink + kept(Recursive::inverse_dynamics(q[k], v[k], qdd[k], 0.0, recursive_params))[0];
  });
  if constexpr (kDense) {
    contenders.emplace_back(
        "inverse_dynamics dense", [&, params = typename Dense::Params{}](int k) {
          sink = sink + kept(Dense::inverse_dynamics(q[k], v[k], qdd[k], 0.0, params))[0];
        });
  }
  contenders.emplace_back("rk4 step recursive", [&](int k) {
    recursive_state.q = q[k], recursive_state.v = v[k];
    recursive_state = gencoord::rk4_step(gencoord::ReducedSystem<Recursive>(recursive_params),
                                         recursive_state, kStep);
    sink = sink + recursive_state.q[0];
  });
  if constexpr (kDense) {
    contenders.emplace_back("rk4 step dense", [&, params = typename Dense::Params{},
                                               state = gencoord::State<Dense>{}](int k) mutable {
      state.q = q[k], state.v = v[k];
      state = gencoord::rk4_step(gencoord::ReducedSystem<Dense>(params), state, kStep);
      sink = sink + state.q[0];
    });
  }
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
  const auto find = [&](const char* name) -> const Contender* {
    for (const auto& c : contenders)
      if (c.name == name) return &c;
    return nullptr;
  };
  // a ratio whose contenders are both present
  const auto ratio = [&](const char* slower_name, const char* faster_name, const char* what) {
    const Contender *slower = find(slower_name), *faster = find(faster_name);
    if (!slower || !faster) return;
    std::printf("%-30s %10.2f %10.2f\n", what, slower->min() / faster->min(),
                slower->median() / faster->median());
  };
  ratio("qddot dense", "qddot recursive", "dense / recursive qddot");
  ratio("inverse_dynamics dense", "inverse_dynamics recursive", "dense / recursive inverse");
  ratio("rk4 step dense", "rk4 step recursive", "dense / recursive rk4");
  ratio("mj_forward", "qddot recursive", "mj_forward / recursive qddot");
  ratio("mj_rne with its stages", "inverse_dynamics recursive", "mj_rne / recursive inverse");
  ratio("mj_step rk4", "rk4 step recursive", "mj_step / recursive rk4");
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 21;
  gencoord::bench::pin_to_one_core("bench_recursion");
#define GENCOORD_COMPARE(n, Dense, Recursive) compare<Dense, Recursive>(n, rounds);
  GENCOORD_RECURSION_CHAINS(GENCOORD_COMPARE)
#undef GENCOORD_COMPARE
}
