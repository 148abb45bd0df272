// SPDX-License-Identifier: BSD-3-Clause
// The maximal penalty model converges to the reduced model as kappa grows, for point masses,
// rigid bodies and models with generalized speeds (quaternions) alike: over kappa in 1e3..1e7
// the largest particle-position error falls with a fitted log-log slope of -0.8 or steeper
// and the largest constraint violation like 1/kappa (slope -1 +- 0.2). A model without
// declared constraints and nv = nx (spring_pendulum) has nothing for kappa to act on: its
// error sits at the integration floor for every kappa.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gencoord/maximal/crosscheck.hpp"
#include "generated/compound_pendulum.hpp"
#include "generated/floating_arm.hpp"
#include "generated/furuta_pendulum.hpp"
#include "generated/heavy_top.hpp"
#include "test_models.hpp"

namespace gencoord {
namespace {

// short runs keep the explicit maximal runs cheap (the suite's CI budget)
CrosscheckOptions short_run() {
  CrosscheckOptions o;
  o.duration = 2.0;
  o.points = 40;
  o.reference_dt = 1e-4;
  o.max_dt = 1e-4;
  return o;
}

struct Sweep {
  std::vector<double> kappa, error, violation;
  LogLogFit error_fit, violation_fit;
};

// the model's own initial state
template <class M>
State<M> initial_state() {
  State<M> s0;
  s0.q = initial_q_of<M>();
  s0.v = initial_v_of<M>();
  return s0;
}

template <class M>
Sweep sweep(const ParamsOf<M>& p, double lo, double hi, int count,
            const CrosscheckOptions& o = short_run(), const State<M>& s0 = initial_state<M>()) {
  const ReducedReference<M> ref = reduced_reference<M>(p, s0, o);
  Sweep out;
  for (double kappa : log_spaced(lo, hi, count)) {
    // RK4 alone (the options' integrator): the others would add to the compile time
    const CrosscheckRow row = crosscheck_at<M, IntegratorSet<Integrator::RK4>>(p, ref, kappa, o);
    std::printf("  %-22s kappa %8.1e  dt %8.2e  error %10.3e  violation %10.3e  drift %9.2e\n",
                M::name, kappa, row.dt, row.max_position_error, row.max_constraint_violation,
                row.energy_drift);
    out.kappa.push_back(kappa);
    out.error.push_back(row.max_position_error);
    out.violation.push_back(row.max_constraint_violation);
  }
  out.error_fit = fit_loglog(out.kappa, out.error);
  out.violation_fit = fit_loglog(out.kappa, out.violation);
  return out;
}

template <class M>
void expect_convergence(const ParamsOf<M>& p, const std::string& label, double lo = 1e3,
                        double hi = 1e7, const State<M>& s0 = initial_state<M>(),
                        const CrosscheckOptions& o = short_run()) {
  const Sweep s = sweep<M>(p, lo, hi, 5, o, s0);
  std::printf("  %-22s slopes: error %.3f, violation %.3f\n", M::name, s.error_fit.slope,
              s.violation_fit.slope);
  ::testing::Test::RecordProperty(label + "_error_slope", std::to_string(s.error_fit.slope));
  ::testing::Test::RecordProperty(label + "_violation_slope",
                                  std::to_string(s.violation_fit.slope));
  EXPECT_LE(s.error_fit.slope, -0.8) << M::name << ": position error falls too slowly";
  EXPECT_NEAR(s.violation_fit.slope, -1.0, 0.2) << M::name << ": violation is not ~ 1/kappa";
  for (std::size_t i = 1; i < s.error.size(); ++i)
    EXPECT_LT(s.error[i], s.error[i - 1]) << M::name << ": error grew at kappa " << s.kappa[i];
}

TEST(CrosscheckConvergence, Pendulum) { expect_convergence<models::Pendulum>({}, "pendulum"); }

TEST(CrosscheckConvergence, Pendulum3d) {
  expect_convergence<models::Pendulum3d>({}, "pendulum_3d");
}

TEST(CrosscheckConvergence, DoublePendulum) {
  expect_convergence<models::DoublePendulum>({}, "double_pendulum");
}

TEST(CrosscheckConvergence, CartPole) { expect_convergence<models::CartPole>({}, "cart_pole"); }

// a nonzero generalized force on the cart: mapped to x-space as M J Mt^-1 Q through the
// inverse map, it must not spoil the convergence
TEST(CrosscheckConvergence, CartPoleWithCartForce) {
  models::CartPole::Params p;
  p.u = 1.5;
  expect_convergence<models::CartPole>(p, "cart_pole_u");
}

// rigid bodies: each body's point masses (its mass, centre and inertia tensor) held rigid by
// rods and joined to the world or to each other by pins, against the body equations. The
// top and the Furuta pendulum spin fast on short rods: below kappa = 1e5 their penalty models
// stray by 0.1 to 0.6 m within the run, before the 1/kappa regime, so their sweeps start there
TEST(CrosscheckConvergence, CompoundPendulum) {
  expect_convergence<models::CompoundPendulum>({}, "compound_pendulum");
}

TEST(CrosscheckConvergence, FurutaPendulum) {
  expect_convergence<models::FurutaPendulum>({}, "furuta_pendulum", 1e5, 1e8);
}

TEST(CrosscheckConvergence, HeavyTop) {
  expect_convergence<models::HeavyTop>({}, "heavy_top", 1e5, 1e8);
}

// generalized speeds: a free trunk spinning about a tilted axis, a ball-jointed arm and a
// motorized hand (unit quaternions in q, nv < nq); the motor's torque goes through the inverse
// map, which steps along the speeds
TEST(CrosscheckConvergence, FloatingArmOnItsSpeeds) {
  using M = models::FloatingArm;
  static_assert(has_generalized_speeds_v<M>);
  State<M> s0 = initial_state<M>();
  s0.v << 0.2, -0.1, 0.5, 1.0, 2.0, 3.0, 0.5, -1.0, 0.3, 2.0;  // trunk twist, arm spin, hand
  M::Params p;
  p.u = 0.05;
  // 1 s: each force of its penalty model runs the inverse map (the motor torque), the
  // costliest model of this suite
  CrosscheckOptions o = short_run();
  o.duration = 1.0;
  expect_convergence<M>(p, "floating_arm", 1e3, 1e7, s0, o);
}

// no declared constraint: the runtime's manifold spring holds the bead on its wire
TEST(CrosscheckConvergence, BeadOnParabolaManifoldSpring) {
  static_assert(uses_manifold_spring_v<models::BeadOnParabola>);
  expect_convergence<models::BeadOnParabola>({}, "bead_on_parabola");
}

TEST(CrosscheckConvergence, SpringPendulumSitsAtTheIntegrationFloor) {
  static_assert(kappa_independent_v<models::SpringPendulum>);
  const Sweep s = sweep<models::SpringPendulum>({}, 1e3, 1e7, 5);
  const double lo = *std::min_element(s.error.begin(), s.error.end());
  const double hi = *std::max_element(s.error.begin(), s.error.end());
  ::testing::Test::RecordProperty("spring_pendulum_error_floor", std::to_string(hi));
  // the same maximal run for every kappa (nothing depends on it), at RK4's floor for dt = 1e-4
  EXPECT_LE(hi, 1e-10);
  EXPECT_LE(hi - lo, 1e-3 * hi + 1e-15);
  for (double v : s.violation) EXPECT_EQ(v, 0.0);
}

}  // namespace
}  // namespace gencoord
