// SPDX-License-Identifier: BSD-3-Clause
// Explicit stability of the maximal model: the stable step computed from the stiffest mode
// (omega_max^2 = largest eigenvalue of M^-1 K) keeps symplectic Euler and RK4 stable, 1.5
// times it blows up; backward Euler (sparse Newton) stays stable at 10x the explicit limit.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/maximal/crosscheck.hpp"
#include "gencoord/maximal/stability.hpp"
#include "test_models.hpp"

namespace gencoord {
namespace {

constexpr double kKappa = 1e6;  // stiff: omega_max ~ 1e3 rad/s

struct Run {
  bool diverged = false;
  double max_energy_change = 0;  // max |E - E(0)|
  double max_energy_gain = 0;    // max E - E(0)
  double max_violation = 0;
};

// integrates for `duration` at step h (rounded down to divide it), watching energy
template <class M>
Run run(Integrator integrator, double h, double duration, const ParamsOf<M>& p = {}) {
  const MaximalModel<M> model(p, kKappa);
  State<M> s0;
  s0.q = initial_q_of<M>();
  const MaximalState<M> x0 = to_maximal<M>(p, s0);
  const double e0 = model.energy(x0);
  Run r;
  const double dt = divisor_step(duration, h);
  try {
    simulate(model, x0, {integrator, dt, duration}, [&](const MaximalState<M>& s) {
      const double e = model.energy(s);
      if (!std::isfinite(e) || std::abs(e - e0) > 1e6)
        throw MaximalDivergedError(M::name, s.t, dt, kKappa);
      r.max_energy_change = std::max(r.max_energy_change, std::abs(e - e0));
      r.max_energy_gain = std::max(r.max_energy_gain, e - e0);
      r.max_violation = std::max(r.max_violation, model.max_constraint_violation(s.q, s.t));
    });
  } catch (const MaximalDivergedError&) {
    r.diverged = true;
  }
  return r;
}

// the stiffest mode along the reduced motion, as the cross-check computes it
template <class M>
double omega_along(double duration, const ParamsOf<M>& p = {}) {
  State<M> s0;
  s0.q = initial_q_of<M>();
  CrosscheckOptions o;
  o.duration = duration;
  o.points = 50;
  return omega_max_along(MaximalModel<M>(p, kKappa), reduced_reference<M>(p, s0, o));
}

TEST(MaximalStability, PendulumOmegaMaxIsTheRodsAxialFrequency) {
  using M = models::Pendulum;
  const ParamsOf<M> p;
  State<M> s;
  s.q = initial_q_of<M>();
  // at rest length the rod is a spring of stiffness kappa / l on the bob
  const double omega = omega_max(MaximalModel<M>(p, kKappa), to_maximal<M>(p, s));
  EXPECT_NEAR(omega, std::sqrt(kKappa / (p.l * p.m)), 1e-9 * omega);
}

template <class M>
void expect_explicit_limit(Integrator integrator) {
  const double duration = 1.0;
  const double omega = omega_along<M>(duration);
  const double h = stable_step(integrator, omega);
  const Run stable = run<M>(integrator, h, duration);
  const Run unstable = run<M>(integrator, 1.5 * h, duration);
  std::printf("  %-16s %-16s omega_max %.1f, stable step %.3e: energy change %.2e; 1.5x: %s\n",
              M::name, to_string(integrator), omega, h, stable.max_energy_change,
              unstable.diverged ? "diverged" : "did not diverge");
  EXPECT_FALSE(stable.diverged) << M::name << " " << to_string(integrator) << " at h = " << h;
  EXPECT_LT(stable.max_energy_change, 0.1) << M::name;  // energies are O(10 J)
  EXPECT_LT(stable.max_violation, 1e-3) << M::name;
  EXPECT_TRUE(unstable.diverged) << M::name << " " << to_string(integrator)
                                 << " at 1.5 h = " << 1.5 * h << " did not blow up";
}

TEST(MaximalStability, SymplecticEulerPendulum) {
  expect_explicit_limit<models::Pendulum>(Integrator::SymplecticEuler);
}
TEST(MaximalStability, SymplecticEulerDoublePendulum) {
  expect_explicit_limit<models::DoublePendulum>(Integrator::SymplecticEuler);
}
TEST(MaximalStability, SymplecticEulerPendulum3d) {
  expect_explicit_limit<models::Pendulum3d>(Integrator::SymplecticEuler);
}
TEST(MaximalStability, Rk4Pendulum) { expect_explicit_limit<models::Pendulum>(Integrator::RK4); }
TEST(MaximalStability, Rk4DoublePendulum) {
  expect_explicit_limit<models::DoublePendulum>(Integrator::RK4);
}

template <class M>
void expect_backward_euler_stable_at_10x() {
  const double duration = 1.0;
  const double h = 10.0 * stable_step(Integrator::SymplecticEuler, omega_along<M>(duration));
  const Run r = run<M>(Integrator::BackwardEuler, h, duration);
  std::printf(
      "  %-16s backward Euler at 10x the explicit limit (h = %.3e): energy lost %.2e, "
      "gained %.2e, violation %.2e\n",
      M::name, h, r.max_energy_change, r.max_energy_gain, r.max_violation);
  EXPECT_FALSE(r.diverged) << M::name;
  EXPECT_LT(r.max_energy_gain, 1e-6) << M::name;  // dissipates, never gains
  EXPECT_LT(r.max_violation, 1e-3) << M::name;
}

TEST(MaximalStability, BackwardEulerPendulumAt10xTheExplicitLimit) {
  expect_backward_euler_stable_at_10x<models::Pendulum>();
}
TEST(MaximalStability, BackwardEulerDoublePendulumAt10xTheExplicitLimit) {
  expect_backward_euler_stable_at_10x<models::DoublePendulum>();
}
TEST(MaximalStability, BackwardEulerPendulum3dAt10xTheExplicitLimit) {
  expect_backward_euler_stable_at_10x<models::Pendulum3d>();
}
TEST(MaximalStability, BackwardEulerCartPoleAt10xTheExplicitLimit) {
  expect_backward_euler_stable_at_10x<models::CartPole>();
}

// backward Euler never gains energy: E(t) <= E(0) (up to Newton's tolerance)
TEST(MaximalStability, BackwardEulerDissipates) {
  using M = models::DoublePendulum;
  const ParamsOf<M> p;
  const MaximalModel<M> model(p, kKappa);
  State<M> s0;
  s0.q = initial_q_of<M>();
  const MaximalState<M> x0 = to_maximal<M>(p, s0);
  const double e0 = model.energy(x0);
  double previous = e0;
  simulate(model, x0, {Integrator::BackwardEuler, 1e-2, 1.0}, [&](const MaximalState<M>& s) {
    const double e = model.energy(s);
    EXPECT_LE(e, previous + 1e-9) << "energy grew at t = " << s.t;
    previous = e;
  });
  EXPECT_LT(previous, e0);
}

}  // namespace
}  // namespace gencoord
