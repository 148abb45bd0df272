// The gantry crane of gantry_crane.py, simulated with RK4 and backward Euler, and its
// inverse dynamics. Prints each checked figure with its limit; exits with status 1 if any
// check fails.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gencoord/gencoord.hpp"
#include "generated/gantry_crane.hpp"

namespace {

using Crane = gencoord::models::GantryCrane;
using State = gencoord::State<Crane>;

int failures = 0;

void check(bool ok, const char* what) {
  std::printf("  %s\n", ok ? "ok" : "FAILED");
  if (!ok) {
    std::printf("check failed: %s\n", what);
    ++failures;
  }
}

State initial_state() {
  State s;
  // the model file's initial values (std::array) as Eigen vectors
  s.q = Eigen::Map<const gencoord::QVec<Crane>>(Crane::initial_q.data());
  s.v = Eigen::Map<const gencoord::QVec<Crane>>(Crane::initial_v.data());
  return s;
}

double energy(const Crane::Params& p, const State& s) { return Crane::energy(s.q, s.v, s.t, p); }

// Integrates from the model's initial state and returns the largest |E - E0| on the way.
double max_energy_error(const Crane::Params& p, gencoord::Integrator integrator, double dt,
                        double duration, State* end) {
  const State start = initial_state();
  const double e0 = energy(p, start);
  double worst = 0.0;
  *end = gencoord::simulate(
      gencoord::ReducedSystem<Crane>(p), start, {integrator, dt, duration},
      [&](const State& s) { worst = std::max(worst, std::abs(energy(p, s) - e0)); });
  return worst;
}

// Largest coordinate difference from `reference` after `duration` with step dt.
double position_error(const Crane::Params& p, gencoord::Integrator integrator, double dt,
                      double duration, const State& reference) {
  const State end = gencoord::simulate(gencoord::ReducedSystem<Crane>(p), initial_state(),
                                       {integrator, dt, duration}, [](const State&) {});
  return (end.q - reference.q).cwiseAbs().maxCoeff();
}

}  // namespace

int main() {
  Crane::Params p;  // the model file's defaults; u = 0: no drive force, energy is conserved
  const double scale = p.m_load * p.g * p.l;  // energy scale of the swinging load (J)
  std::printf("%s: nq = %d, %d particles, E0 = %.9f J\n", Crane::name, Crane::nq,
              Crane::num_particles, energy(p, initial_state()));

  // RK4 conserves the energy up to its truncation error, O(dt^4).
  State rk4_end;
  const double rk4_drift = max_energy_error(p, gencoord::Integrator::RK4, 1e-3, 10.0, &rk4_end);
  std::printf("rk4, dt = 0.001, 10 s: max |E - E0| / (m_load g l) = %.3e (limit 1e-10)",
              rk4_drift / scale);
  check(rk4_drift / scale < 1e-10, "RK4 energy drift");

  // Backward Euler damps the swing numerically: the energy falls, by much more than RK4's
  // error, and never rises above E0.
  State be_end;
  gencoord::StepStats stats;
  const double e0 = energy(p, initial_state());
  double be_max_gain = 0.0;
  be_end = gencoord::simulate(
      gencoord::ReducedSystem<Crane>(p), initial_state(),
      {gencoord::Integrator::BackwardEuler, 1e-2, 10.0, {}, &stats},
      [&](const State& s) { be_max_gain = std::max(be_max_gain, energy(p, s) - e0); });
  const double be_loss = e0 - energy(p, be_end);
  std::printf(
      "backward_euler, dt = 0.01, 10 s: E0 - E(end) = %.4f J, max E - E0 = %.1e J, "
      "%.2f Newton iterations per step (loss > 0.01 m_load g l, no gain)",
      be_loss, be_max_gain, double(stats.newton_iterations) / double(stats.steps));
  check(be_loss > 0.01 * scale && be_max_gain <= 1e-12 * scale, "backward Euler dissipation");

  // Backward Euler is first order: halving dt halves the error at t = 1 s.
  State reference;
  max_energy_error(p, gencoord::Integrator::RK4, 1e-4, 1.0, &reference);
  const double coarse =
      position_error(p, gencoord::Integrator::BackwardEuler, 4e-3, 1.0, reference);
  const double fine = position_error(p, gencoord::Integrator::BackwardEuler, 2e-3, 1.0, reference);
  const double order = std::log2(coarse / fine);
  std::printf(
      "backward_euler order at t = 1 s: errors %.3e, %.3e at dt = 4e-3, 2e-3: "
      "order %.3f (expected 0.9 to 1.1)",
      coarse, fine, order);
  check(order > 0.9 && order < 1.1, "backward Euler order of accuracy");

  // Inverse dynamics: accelerate under a drive force u, then ask which generalized force
  // produces that acceleration in the undriven model. It is u on s and nothing on theta.
  Crane::Params driven = p;
  driven.u = 3.5;
  const auto qdd = gencoord::acceleration<Crane>(driven, rk4_end.q, rk4_end.v, rk4_end.t);
  const auto tau = gencoord::inverse_dynamics<Crane>(p, rk4_end.q, rk4_end.v, qdd, rk4_end.t);
  const double tau_error = std::max(std::abs(tau[0] - driven.u), std::abs(tau[1]));
  std::printf(
      "inverse dynamics at t = 10 s: tau = (%.12f, %.3e), max |tau - (u, 0)| = %.3e "
      "(limit 1e-9)",
      tau[0], tau[1], tau_error);
  check(tau_error < 1e-9, "inverse dynamics reproduces the drive force");

  if (failures == 0) std::printf("all checks passed\n");
  return failures == 0 ? 0 : 1;
}
