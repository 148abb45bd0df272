// SPDX-License-Identifier: BSD-3-Clause
// gencoord vs its peers on the planar n-link chain, side by side in one run:
//   qddot/{ours,sympy}/n       one generalized acceleration (generated Mt, Ft + Fi, fixed LLT)
//   rk4_step/{ours,sympy}/n    one RK4 step (ours: gencoord::step; SymPy: the same formula)
//   mj_forward/n               MuJoCo's mj_forward (everything before integration, qacc too)
//   batch_{qddot,rk4}/ours/n/threads:T   gencoord/parallel/batch.hpp over 4096 states, T threads
// Before any timing, the peers are checked against ours at random states and parameters
// (SymPy to 1e-9 relative, MuJoCo to 1e-6: its point masses carry a tiny inertia); a mismatch
// aborts the run. Sizes: GENCOORD_PEER_CHAIN_SIZES. Run: scripts/bench_peers.sh.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include <benchmark/benchmark.h>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/model/state.hpp"
#include "gencoord/parallel/batch.hpp"
#include "peer_chains.hpp"  // generated: the headers of each size, GENCOORD_PEER_CHAINS(X)
#ifdef GENCOORD_HAVE_MUJOCO
#include "peers/mujoco_chain.hpp"
#endif

namespace {

constexpr double kPi = 3.14159265358979323846;

// The chain's parameter names in the peers' order: g, l1, m1, l2, m2, ...
std::vector<std::string> peer_parameter_names(int n) {
  std::vector<std::string> names{"g"};
  for (int k = 1; k <= n; ++k) {
    names.push_back("l" + std::to_string(k));
    names.push_back("m" + std::to_string(k));
  }
  return names;
}

// Our Params from the peers' array, by name, so a parameter-order mix-up cannot go unseen.
template <class M>
typename M::Params our_params(const std::vector<double>& peer) {
  typename M::Params p;
  const auto names = peer_parameter_names(M::nq);
  for (std::size_t i = 0; i < names.size(); ++i) {
    double* field = p.find(names[i]);
    if (!field) {
      std::fprintf(stderr, "%s has no parameter %s\n", M::name, names[i].c_str());
      std::abort();
    }
    *field = peer[i];
  }
  return p;
}

// The peers' parameter array of our defaults.
template <class M>
std::vector<double> default_peer_params() {
  typename M::Params p;
  std::vector<double> out;
  for (const auto& name : peer_parameter_names(M::nq)) out.push_back(*p.find(name));
  return out;
}

std::vector<double> random_peer_params(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> g(5.0, 15.0), length(0.5, 1.5), mass(0.5, 2.0);
  std::vector<double> out{g(rng)};
  for (int k = 0; k < n; ++k) {
    out.push_back(length(rng));
    out.push_back(mass(rng));
  }
  return out;
}

template <class M>
gencoord::State<M> random_state(std::mt19937& rng, double angle_range) {
  std::uniform_real_distribution<double> angle(-angle_range, angle_range), rate(-2.0, 2.0);
  gencoord::State<M> s;
  for (int i = 0; i < M::nq; ++i) {
    s.q[i] = angle(rng);
    s.v[i] = rate(rng);
  }
  return s;
}

// The benchmark state: the same for every peer.
template <class M>
gencoord::State<M> bench_state() {
  std::mt19937 rng(7);
  return random_state<M>(rng, 1.3);
}

// |a - b|_inf / |b|_inf
template <class V>
double relative_difference(const V& a, const V& b) {
  return (a - b).template lpNorm<Eigen::Infinity>() /
         std::max(b.template lpNorm<Eigen::Infinity>(), 1e-300);
}

// ---- cross-checks, before any timing ----

template <class Ours, class Peer>
void check_sympy_peer() {
  std::mt19937 rng(2024);
  double worst = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    const auto peer_p = random_peer_params(Ours::nq, rng);
    const auto s = random_state<Ours>(rng, kPi);
    const gencoord::QVec<Ours> ours = Ours::qddot(s.q, s.v, 0.0, our_params<Ours>(peer_p));
    gencoord::QVec<Ours> theirs;
    Peer::qddot(s.q.data(), s.v.data(), peer_p.data(), theirs.data());
    worst = std::max(worst, relative_difference(theirs, ours));
  }
  std::fprintf(stderr, "check sympy n=%d: max relative difference %.3g over 200 states\n", Ours::nq,
               worst);
  if (!(worst <= 1e-9)) {
    std::fprintf(stderr, "SymPy peer disagrees with %s beyond 1e-9\n", Ours::name);
    std::abort();
  }
}

#ifdef GENCOORD_HAVE_MUJOCO
template <class Ours>
void check_mujoco_peer() {
  std::mt19937 rng(99);
  const auto peer_p = random_peer_params(Ours::nq, rng);
  const auto p = our_params<Ours>(peer_p);
  peers::MujocoChain chain(Ours::nq, peer_p);
  double worst = 0.0;
  for (int trial = 0; trial < 50; ++trial) {
    const auto s = random_state<Ours>(rng, kPi);
    chain.set_state(s.q.data(), s.v.data());
    chain.forward();
    gencoord::QVec<Ours> theirs;
    chain.absolute_qacc(theirs.data());
    worst = std::max(worst, relative_difference(theirs, Ours::qddot(s.q, s.v, 0.0, p)));
  }
  std::fprintf(stderr, "check mujoco n=%d: max relative difference %.3g over 50 states\n", Ours::nq,
               worst);
  if (!(worst <= 1e-6)) {
    std::fprintf(stderr, "MuJoCo peer disagrees with %s beyond 1e-6\n", Ours::name);
    std::abort();
  }
}
#endif

// ---- timings ----

template <class M>
void BM_ours_qddot(benchmark::State& state) {
  const typename M::Params p;
  auto s = bench_state<M>();
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.q.data());
    benchmark::DoNotOptimize(s.v.data());
    auto a = M::qddot(s.q, s.v, s.t, p);
    benchmark::DoNotOptimize(a.data());
  }
}

template <class M, class Peer>
void BM_sympy_qddot(benchmark::State& state) {
  const auto p = default_peer_params<M>();
  auto s = bench_state<M>();
  gencoord::QVec<M> a;
  for (auto _ : state) {
    benchmark::DoNotOptimize(s.q.data());
    benchmark::DoNotOptimize(s.v.data());
    Peer::qddot(s.q.data(), s.v.data(), p.data(), a.data());
    benchmark::DoNotOptimize(a.data());
  }
}

template <class M>
void BM_ours_rk4(benchmark::State& state) {
  const typename M::Params p;
  auto s = bench_state<M>();
  const auto start = s;
  for (auto _ : state) {
    // rk4_step itself: step() would instantiate the implicit integrators too, whose generated
    // Jacobian kernel dominates compile time for large chains
    s = gencoord::rk4_step(gencoord::ReducedSystem<M>(p), s, 1e-4);
    benchmark::DoNotOptimize(s.q.data());
    benchmark::ClobberMemory();
    if (s.t > 1.0) s = start;  // stay near the benchmark state
  }
}

// gencoord's RK4 step (integrate/explicit_rk.hpp) with the SymPy peer's qddot, minus its finiteness
// checks, which the peer does not have
template <class M, class Peer>
gencoord::State<M> sympy_rk4_step(const std::vector<double>& p, const gencoord::State<M>& s,
                                  double h) {
  using V = gencoord::QVec<M>;
  const auto a = [&](const V& q, const V& v) {
    V out;
    Peer::qddot(q.data(), v.data(), p.data(), out.data());
    return out;
  };
  const double half = 0.5 * h;
  const V& k1q = s.v;
  const V k1v = a(s.q, s.v);
  const V k2q = s.v + half * k1v;
  const V k2v = a(s.q + half * k1q, k2q);
  const V k3q = s.v + half * k2v;
  const V k3v = a(s.q + half * k2q, k3q);
  const V k4q = s.v + h * k3v;
  const V k4v = a(s.q + h * k3q, k4q);
  gencoord::State<M> out;
  out.t = s.t + h;
  out.q = s.q + (h / 6.0) * (k1q + 2.0 * k2q + 2.0 * k3q + k4q);
  out.v = s.v + (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
  return out;
}

template <class M, class Peer>
void BM_sympy_rk4(benchmark::State& state) {
  const auto p = default_peer_params<M>();
  auto s = bench_state<M>();
  const auto start = s;
  for (auto _ : state) {
    s = sympy_rk4_step<M, Peer>(p, s, 1e-4);
    benchmark::DoNotOptimize(s.q.data());
    benchmark::ClobberMemory();
    if (s.t > 1.0) s = start;
  }
}

#ifdef GENCOORD_HAVE_MUJOCO
template <class M>
void BM_mj_forward(benchmark::State& state) {
  peers::MujocoChain chain(M::nq, default_peer_params<M>());
  const auto s = bench_state<M>();
  chain.set_state(s.q.data(), s.v.data());
  for (auto _ : state) {
    chain.forward();
    benchmark::DoNotOptimize(chain.data()->qacc);
  }
}
#endif

// batches of 4096 random states, one parameter set; wall time, since threads do the work
constexpr int kBatch = 4096;

template <class M>
std::vector<gencoord::State<M>> batch_states() {
  std::mt19937 rng(5);
  std::vector<gencoord::State<M>> states;
  for (int i = 0; i < kBatch; ++i) states.push_back(random_state<M>(rng, 1.3));
  return states;
}

template <class M>
void BM_batch_qddot(benchmark::State& state) {
  const std::vector<typename M::Params> p(1);
  const auto states = batch_states<M>();
  std::vector<gencoord::QVec<M>> out;
  for (auto _ : state) {
    gencoord::batch_qddot<M>(states, p, &out, static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

template <class M>
void BM_batch_rk4(benchmark::State& state) {
  const std::vector<typename M::Params> p(1);
  const auto states = batch_states<M>();
  std::vector<gencoord::State<M>> out;
  for (auto _ : state) {
    gencoord::batch_step<M>(gencoord::Integrator::RK4, p, states, 1e-4, &out,
                            static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(state.iterations() * kBatch);
}

template <class M, class Peer>
void register_size() {
  const std::string n = std::to_string(M::nq);
  benchmark::RegisterBenchmark(("qddot/ours/" + n).c_str(), BM_ours_qddot<M>);
  benchmark::RegisterBenchmark(("rk4_step/ours/" + n).c_str(), BM_ours_rk4<M>);
  if constexpr (!std::is_void_v<Peer>) {  // no SymPy peer past GENCOORD_SYMPY_PEER_MAX_N
    check_sympy_peer<M, Peer>();
    benchmark::RegisterBenchmark(("qddot/sympy/" + n).c_str(), BM_sympy_qddot<M, Peer>);
    benchmark::RegisterBenchmark(("rk4_step/sympy/" + n).c_str(), BM_sympy_rk4<M, Peer>);
  }
#ifdef GENCOORD_HAVE_MUJOCO
  check_mujoco_peer<M>();
  benchmark::RegisterBenchmark(("mj_forward/" + n).c_str(), BM_mj_forward<M>);
#endif
  // batch_step() goes through step(), which instantiates every integrator: small chains only
  if constexpr (M::nq <= 20) {
    for (auto* b :
         {benchmark::RegisterBenchmark(("batch_qddot/ours/" + n).c_str(), BM_batch_qddot<M>),
          benchmark::RegisterBenchmark(("batch_rk4/ours/" + n).c_str(), BM_batch_rk4<M>)})
      b->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime();
  }
}

}  // namespace

int main(int argc, char** argv) {
#define GENCOORD_REGISTER_CHAIN(n, peer) register_size<gencoord::models::NLinkChain##n, peer>();
  GENCOORD_PEER_CHAINS(GENCOORD_REGISTER_CHAIN)
#undef GENCOORD_REGISTER_CHAIN
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
