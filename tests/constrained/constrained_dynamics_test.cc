// SPDX-License-Identifier: BSD-3-Clause
// Kinematic constraints (closed loops, rolling) in the runtime: the constrained acceleration
// and multipliers against closed forms, the projection that keeps the constraints at
// round-off over long runs, and every integrator on a constrained model.
//  - The Cartesian pendulum (x, y and x^2 + y^2 = l^2) moves as models/pendulum.py does, and
//    its multiplier is the rod's tension.
//  - The four-bar (models/four_bar.py): the loop force is the force on the rocker's tip
//    (Newton-Euler for the rocker alone), energy is conserved and the motor's work is its
//    torque times the crank's turn.
//  - The rolling coin: energy, spin and turning rates constant, the centre on a circle.
//  - Without projection the four-bar's drift grows; Baumgarte's feedback holds it.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "figures.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/cartesian_pendulum.hpp"
#include "generated/four_bar.hpp"
#include "generated/pendulum.hpp"
#include "generated/rolling_coin.hpp"
#include "initial_state.hpp"

namespace gencoord::testing {
namespace {

using models::CartesianPendulum;
using models::FourBar;
using models::Pendulum;
using models::RollingCoin;

static_assert(has_kinematic_constraints_v<FourBar> && has_holonomic_constraints_v<FourBar>);
static_assert(has_kinematic_constraints_v<RollingCoin> &&
              !has_holonomic_constraints_v<RollingCoin>);
static_assert(!has_kinematic_constraints_v<Pendulum>);
static_assert(FourBar::num_constraints == 2 && RollingCoin::num_constraints == 2);

TEST(CartesianPendulum, MovesAsThePendulumAndItsMultiplierIsTheTension) {
  const ReducedSystem<CartesianPendulum> cartesian({});
  const ReducedSystem<Pendulum> angle({});
  State<Pendulum> s_angle;
  s_angle.q << 0.5;
  s_angle.v << 0.0;
  State<CartesianPendulum> s = initial_state<CartesianPendulum>();
  const double l = 1.0, m = 1.0, g = 9.81;
  double worst_position = 0, worst_tension = 0, worst_drift = 0;
  for (int k = 0; k < 5000; ++k) {
    const double theta = s_angle.q[0], omega = s_angle.v[0];
    const Eigen::Vector2d expected(l * std::sin(theta), -l * std::cos(theta));
    worst_position = std::max(worst_position, (s.q - expected).cwiseAbs().maxCoeff());
    const double tension = m * (l * omega * omega + g * std::cos(theta));
    const double lambda = constraint_forces<CartesianPendulum>(cartesian.params(), s)[0];
    worst_tension = std::max(worst_tension, std::abs(lambda + tension / (2 * l)) / tension);
    worst_drift =
        std::max(worst_drift, constraint_residual<CartesianPendulum>(cartesian.params(), s));
    s = step(cartesian, Integrator::RK4, s, 1e-3);
    s_angle = step(angle, Integrator::RK4, s_angle, 1e-3);
  }
  RecordProperty("worst_position", std::to_string(worst_position));
  EXPECT_LT(worst_position, 1e-11);
  EXPECT_LT(worst_tension, 1e-11);
  EXPECT_LT(worst_drift, 1e-14);
}

TEST(FourBar, TheLoopForceActsOnTheRockersTip) {
  // Newton-Euler for the rocker alone (a bar of mass m_c, length c about D): its angular
  // acceleration times its moment of inertia about D is the moment of gravity plus that of
  // the loop force lambda at its tip C
  const FourBar::Params p;
  State<FourBar> s = initial_state<FourBar>();
  s.v << 2.0, 0.0, 0.0;
  project_onto_constraints<FourBar>(p, &s);
  FourBar::CVector<double> lambda;
  const auto a = constrained_acceleration<FourBar>(p, s.q, s.v, s.t, &lambda);
  const double rocker = s.q[2], c = p.c;
  const double moment = -p.m_c * p.g * c / 2 * std::cos(rocker) +
                        c * (std::cos(rocker) * lambda[1] - std::sin(rocker) * lambda[0]);
  const double inertia = p.m_c * c * c / 3;
  EXPECT_NEAR(inertia * a[2], moment, 1e-12 * std::abs(moment));
  EXPECT_GT(lambda.norm(), 1.0);  // a real force, not a vanishing one
}

TEST(FourBar, StaysOnTheLoopAndConservesEnergyOver100Seconds) {
  const ReducedSystem<FourBar> system({});
  State<FourBar> s = initial_state<FourBar>();
  s.v << 3.0, 0.0, 0.0;
  normalize(system, &s);
  const double e0 = FourBar::energy(s.q, s.v, s.t, system.params());
  double worst_drift = 0, worst_energy = 0;
  for (int k = 0; k < 100000; ++k) {
    s = step(system, Integrator::RK4, s, 1e-3);
    worst_drift = std::max(worst_drift, constraint_residual<FourBar>(system.params(), s));
    if (k % 100 == 0)
      worst_energy = std::max(worst_energy,
                              std::abs(FourBar::energy(s.q, s.v, s.t, system.params()) - e0) / e0);
  }
  RecordProperty("worst_drift", std::to_string(worst_drift));
  RecordProperty("worst_energy", std::to_string(worst_energy));
  EXPECT_LT(worst_drift, 1e-10);
  // RK4's own error: 3.0e-8 at dt = 1e-3, below 1e-8 at dt = 5e-4
  EXPECT_LT(worst_energy, 1e-7);
  EXPECT_GT(std::abs(s.q[0]), 10.0);  // the crank turned round: the run went somewhere
}

TEST(FourBar, TheMotorsWorkIsItsTorqueTimesTheCranksTurn) {
  FourBar::Params p;
  p.u = 0.7;
  const ReducedSystem<FourBar> system(p);
  State<FourBar> s = initial_state<FourBar>();
  const double e0 = FourBar::energy(s.q, s.v, s.t, p), crank0 = s.q[0];
  for (int k = 0; k < 3000; ++k) s = step(system, Integrator::RK4, s, 1e-3);
  const double work = p.u * (s.q[0] - crank0);
  EXPECT_NEAR(FourBar::energy(s.q, s.v, s.t, p) - e0, work, 1e-9 * std::abs(work));
  EXPECT_GT(std::abs(work), 0.1);
}

TEST(FourBar, EveryIntegratorKeepsTheLoop) {
  const ReducedSystem<FourBar> system({});
  for (const Integrator integrator :
       {Integrator::ForwardEuler, Integrator::SymplecticEuler, Integrator::RK4,
        Integrator::BackwardEuler, Integrator::Trapezoidal, Integrator::ImplicitMidpoint}) {
    State<FourBar> s = initial_state<FourBar>();
    s.v << 2.0, 0.0, 0.0;
    normalize(system, &s);
    const double e0 = FourBar::energy(s.q, s.v, s.t, system.params());
    double worst_drift = 0;
    for (int k = 0; k < 1000; ++k) {
      s = step(system, integrator, s, 1e-3);
      worst_drift = std::max(worst_drift, constraint_residual<FourBar>(system.params(), s));
    }
    const double energy_change =
        std::abs(FourBar::energy(s.q, s.v, s.t, system.params()) - e0) / e0;
    EXPECT_LT(worst_drift, 1e-10) << to_string(integrator);
    EXPECT_LT(energy_change, 0.05) << to_string(integrator);
  }
}

// The largest constraint residual over `seconds` of `integrator` at dt = 1e-3 from the
// four-bar's initial state with the crank at 3 rad/s.
double four_bar_drift(const ReducedSystem<FourBar>& system, Integrator integrator, double seconds) {
  State<FourBar> s = initial_state<FourBar>();
  s.v << 3.0, 0.0, 0.0;
  project_onto_constraints<FourBar>(system.params(), &s);
  double worst = 0;
  for (int k = 0; k < static_cast<int>(seconds * 1000); ++k) {
    s = step(system, integrator, s, 1e-3);
    worst = std::max(worst, constraint_residual<FourBar>(system.params(), s));
  }
  return worst;
}

TEST(FourBar, BaumgarteHoldsTheDriftThatGrowsWithoutProjection) {
  const FourBar::Params p;
  const ReducedSystem<FourBar> free_running(p, {false, {}});
  const ReducedSystem<FourBar> baumgarte(p, {false, {20.0, 20.0}});
  const double unstabilized = four_bar_drift(free_running, Integrator::RK4, 20.0);
  const double stabilized = four_bar_drift(baumgarte, Integrator::RK4, 20.0);
  RecordProperty("drift_unstabilized", scientific(unstabilized));
  RecordProperty("drift_baumgarte", scientific(stabilized));
  EXPECT_GT(unstabilized, 100 * stabilized);
  EXPECT_LT(stabilized, 5e-8);
  // an implicit step, with the feedback in its Newton Jacobian: backward Euler's first-order
  // error moves the loop apart by 1e-4 in 0.4 s, the feedback holds it ten times closer
  const auto loop_gap = [&](const ReducedSystem<FourBar>& system) {
    State<FourBar> s = initial_state<FourBar>();
    s.v << 3.0, 0.0, 0.0;
    project_onto_constraints<FourBar>(p, &s);
    for (int k = 0; k < 400; ++k) s = step(system, Integrator::BackwardEuler, s, 1e-3);
    return FourBar::holonomic_constraints(s.q, s.t, p).norm();
  };
  const double implicit_free = loop_gap(free_running), implicit_stabilized = loop_gap(baumgarte);
  RecordProperty("loop_gap_backward_euler_unstabilized", scientific(implicit_free));
  RecordProperty("loop_gap_backward_euler_baumgarte", scientific(implicit_stabilized));
  EXPECT_GT(implicit_free, 5 * implicit_stabilized);
  // on the constraints the feedback is zero: the exact acceleration
  State<FourBar> s = initial_state<FourBar>();
  s.v << 2.0, 0.0, 0.0;
  project_onto_constraints<FourBar>(p, &s);
  const auto exact = constrained_acceleration<FourBar>(p, s.q, s.v, s.t);
  EXPECT_LT((baumgarte.acceleration(s) - exact).cwiseAbs().maxCoeff(), 1e-12 * exact.norm());
}

TEST(RollingCoin, RollsOnACircleWithConstantRatesAndEnergy) {
  const ReducedSystem<RollingCoin> system({});
  const RollingCoin::Params& p = system.params();
  State<RollingCoin> s;
  s.q << 0, 0, 0, 0;
  s.v << p.r * 12.0, 0, 0.8, 12.0;  // turning psi' = 0.8 rad/s, spinning phi' = 12 rad/s
  ASSERT_LT(constraint_residual<RollingCoin>(p, s), 1e-15);
  const double e0 = RollingCoin::energy(s.q, s.v, s.t, p);
  const double radius = p.r * 12.0 / 0.8;  // centre (0, radius)
  double worst_circle = 0;
  for (int k = 0; k < 10000; ++k) {
    s = step(system, Integrator::RK4, s, 1e-3);
    worst_circle = std::max(worst_circle, std::abs(std::hypot(s.q[0], s.q[1] - radius) - radius));
  }
  EXPECT_NEAR(RollingCoin::energy(s.q, s.v, s.t, p), e0, 1e-12 * e0);
  EXPECT_NEAR(s.v[2], 0.8, 1e-12);
  EXPECT_NEAR(s.v[3], 12.0, 1e-12);
  EXPECT_LT(worst_circle, 1e-10);
  EXPECT_LT(constraint_residual<RollingCoin>(p, s), 1e-14);
}

TEST(ConstrainedDynamics, DependentConstraintsAreADynamicsError) {
  // the four-bar folded flat: crank, coupler and rocker along the ground line, where the
  // two closure rows are dependent
  FourBar::Params p;
  p.a = 0.2;
  p.b = 0.2;
  p.c = 0.3;
  p.d = 0.7;
  State<FourBar> s;
  s.q << 0.0, 0.0, M_PI;
  s.v.setZero();
  try {
    constrained_acceleration<FourBar>(p, s.q, s.v, s.t);
    FAIL() << "no error at a folded four-bar";
  } catch (const DynamicsError& error) {
    EXPECT_EQ(error.reason(), DynamicsError::Reason::kDependentConstraints);
    EXPECT_NE(std::string(error.what()).find("kinematic constraints are dependent"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace gencoord::testing
