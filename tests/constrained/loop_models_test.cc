// SPDX-License-Identifier: BSD-3-Clause
// The closed-loop models of models/ against what they must be, independently of the
// constrained formulation:
//  - the slider-crank (models/slider_crank.py) follows the same mechanism written in its one
//    independent coordinate with the loop's closed form (slider_crank_reduced.py), and its
//    multiplier is the rod's force on the slider (Newton for the slider alone);
//  - the Delta robot (models/delta_robot.py) holds still under the motor torques that statics
//    gives by hand, with each lower arm carrying a third of the platform's weight; its
//    platform obeys Newton under the three arms' forces; it stays on its three loops and
//    conserves energy over 100 s;
//  - inverse dynamics (constrained_inverse_dynamics): the motor torques for a prescribed
//    motion of the Delta's platform and of the four-bar's crank, which forward dynamics turns
//    back into that motion, and at rest the torques of statics.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "figures.hpp"
#include "gencoord/control/constrained_inverse_dynamics.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/delta_robot.hpp"
#include "generated/four_bar.hpp"
#include "generated/slider_crank.hpp"
#include "generated/slider_crank_reduced.hpp"
#include "initial_state.hpp"

namespace gencoord::testing {
namespace {

using models::DeltaRobot;
using models::FourBar;
using models::SliderCrank;
using models::SliderCrankReduced;

static_assert(SliderCrank::num_constraints == 2 && DeltaRobot::num_constraints == 3);

// The slider-crank's state on its loop for a crank angle and rate: the loop's closed form,
// sin(rod) = -a sin(crank) / b and s = a cos(crank) + b cos(rod), and its time derivative.
State<SliderCrank> on_the_loop(const SliderCrank::Params& p, double crank, double rate) {
  const double rod = std::asin(-p.a * std::sin(crank) / p.b);
  const double rod_rate = -p.a * std::cos(crank) * rate / (p.b * std::cos(rod));
  State<SliderCrank> s;
  s.q << crank, rod, p.a * std::cos(crank) + p.b * std::cos(rod);
  s.v << rate, rod_rate, -p.a * std::sin(crank) * rate - p.b * std::sin(rod) * rod_rate;
  return s;
}

TEST(SliderCrank, MovesAsTheLoopsClosedFormInTheCrankAngle) {
  SliderCrank::Params p;
  p.u = 1.5;
  p.p = -4.0;  // a load pushing the slider back toward the crank
  SliderCrankReduced::Params p_reduced;
  p_reduced.u = p.u;
  p_reduced.p = p.p;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), rate(-20.0, 20.0);
  double worst_acceleration = 0, worst_newton = 0, worst_residual = 0;
  for (int k = 0; k < 50; ++k) {
    const State<SliderCrank> s = on_the_loop(p, angle(rng), rate(rng));
    worst_residual = std::max(worst_residual, constraint_residual<SliderCrank>(p, s));
    SliderCrank::CVector<double> lambda;
    const auto a = constrained_acceleration<SliderCrank>(p, s.q, s.v, s.t, &lambda);
    const auto expected =
        acceleration<SliderCrankReduced>(p_reduced, s.q.head<1>(), s.v.head<1>(), s.t);
    worst_acceleration =
        std::max(worst_acceleration, std::abs(a[0] - expected[0]) / (1 + std::abs(expected[0])));
    // the slider alone: m_s s'' = p + the rod's force on it along the guide
    worst_newton = std::max(worst_newton,
                            std::abs(p.m_s * a[2] - (p.p + lambda[0])) / (1 + std::abs(lambda[0])));
  }
  RecordProperty("worst_acceleration", scientific(worst_acceleration));
  ASSERT_LT(worst_residual, 1e-12);  // on_the_loop is on the loop
  EXPECT_LT(worst_acceleration, 1e-12);
  EXPECT_LT(worst_newton, 1e-12);
}

TEST(SliderCrank, FollowsTheReducedModelsTrajectory) {
  // the same motion integrated in two sets of coordinates: they part by RK4's own error
  SliderCrank::Params p;
  p.p = -3.0;
  SliderCrankReduced::Params p_reduced;
  p_reduced.p = p.p;
  const ReducedSystem<SliderCrank> loop(p);
  const ReducedSystem<SliderCrankReduced> reduced(p_reduced);
  State<SliderCrank> s = on_the_loop(p, 0.8, 3.0);
  State<SliderCrankReduced> r;
  r.q << s.q[0];
  r.v << s.v[0];
  double worst_crank = 0, worst_slider = 0;
  for (int k = 0; k < 1500; ++k) {
    s = step(loop, Integrator::RK4, s, 1e-3);
    r = step(reduced, Integrator::RK4, r, 1e-3);
    const State<SliderCrank> expected = on_the_loop(p, r.q[0], r.v[0]);
    worst_crank = std::max(worst_crank, std::abs(s.q[0] - r.q[0]));
    worst_slider = std::max(worst_slider, std::abs(s.q[2] - expected.q[2]));
  }
  RecordProperty("worst_crank", scientific(worst_crank));
  EXPECT_LT(worst_crank, 1e-8);
  EXPECT_LT(worst_slider, 1e-8);
  EXPECT_GT(std::abs(r.q[0] - 0.8), 6.3);  // a full turn and more
}

TEST(SliderCrank, StaysOnTheLoopAndConservesEnergyOver100Seconds) {
  const ReducedSystem<SliderCrank> system({});
  State<SliderCrank> s = on_the_loop(system.params(), 0.8, 3.0);
  const double e0 = SliderCrank::energy(s.q, s.v, s.t, system.params());
  double worst_drift = 0, worst_energy = 0;
  for (int k = 0; k < 100000; ++k) {
    s = step(system, Integrator::RK4, s, 1e-3);
    worst_drift = std::max(worst_drift, constraint_residual<SliderCrank>(system.params(), s));
    if (k % 100 == 0)
      worst_energy = std::max(
          worst_energy,
          std::abs(SliderCrank::energy(s.q, s.v, s.t, system.params()) - e0) / std::abs(e0));
  }
  RecordProperty("worst_drift", scientific(worst_drift));
  RecordProperty("worst_energy", scientific(worst_energy));
  EXPECT_LT(worst_drift, 1e-10);
  EXPECT_LT(worst_energy, 2e-7);  // RK4's own error at dt = 1e-3 (8e-8 here)
}

// The Delta robot's geometry at one arm, in that arm's vertical plane (radial, up).
struct DeltaArm {
  double radial, up;  // the lower arm's unit direction, elbow to platform
};

DeltaArm lower_arm(const DeltaRobot::Params& p, double theta, double platform_z) {
  const double radial = p.r - p.R - p.l_a * std::cos(theta);
  const double up = platform_z + p.l_a * std::sin(theta);
  return {radial / p.l_b, up / p.l_b};
}

// The motor torque that holds the Delta still in its symmetric pose (every arm at s.q[0]):
// each lower arm carries a third of the platform's weight W along its length,
// lambda = W / (3 d_up) (negative: tension); the motor balances the arm's own weight, the
// elbow's half of the lower arm and the lower arm's pull at the elbow.
double holding_torque(const DeltaRobot::Params& p, const State<DeltaRobot>& s, double* lambda) {
  const double theta = s.q[0];
  const DeltaArm d = lower_arm(p, theta, s.q[5]);
  const double weight = (p.m_p + 1.5 * p.m_b) * p.g;
  *lambda = weight / (3 * d.up);
  // dJ/dtheta = l_a (-sin theta, -cos theta) in (radial, up); the arm pulls the elbow with
  // -lambda d, gravity pulls the arm's middle and the elbow's mass down
  return -(p.m_a / 2 + p.m_b / 2) * p.g * p.l_a * std::cos(theta) -
         *lambda * p.l_a * (std::sin(theta) * d.radial + std::cos(theta) * d.up);
}

TEST(DeltaRobot, HoldsStillUnderTheTorquesOfStatics) {
  DeltaRobot::Params p;
  const State<DeltaRobot> s = initial_state<DeltaRobot>();
  double lambda = 0;
  const double torque = holding_torque(p, s, &lambda);
  p.set_inputs({{torque, torque, torque}});
  DeltaRobot::CVector<double> multipliers;
  const auto a = constrained_acceleration<DeltaRobot>(p, s.q, s.v, s.t, &multipliers);
  EXPECT_LT(lambda, 0.0);
  EXPECT_LT(a.cwiseAbs().maxCoeff(), 1e-12) << a.transpose();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(multipliers[i], lambda, 1e-12 * std::abs(lambda));
  // one torque off the statics' and the robot moves
  p.u_1 += 0.1;
  EXPECT_GT(constrained_acceleration<DeltaRobot>(p, s.q, s.v, s.t).cwiseAbs().maxCoeff(), 0.1);
}

TEST(DeltaRobot, ThePlatformObeysNewtonUnderTheArmsForces) {
  DeltaRobot::Params p;
  p.set_inputs({{0.4, -0.2, 0.7}});
  State<DeltaRobot> s = initial_state<DeltaRobot>();
  s.q.tail<3>() += Eigen::Vector3d(0.08, -0.05, 0.03);  // off centre, projected back
  s.v << 0.5, -1.0, 0.3, 0.0, 0.0, 0.0;
  project_onto_constraints<DeltaRobot>(p, &s);
  DeltaRobot::CVector<double> lambda;
  const auto a = constrained_acceleration<DeltaRobot>(p, s.q, s.v, s.t, &lambda);
  const Eigen::Vector3d platform = s.q.tail<3>();
  Eigen::Vector3d force(0, 0, -(p.m_p + 1.5 * p.m_b) * p.g);
  for (int i = 0; i < 3; ++i) {
    const double alpha = 2 * M_PI * i / 3, theta = s.q[i];
    const Eigen::Vector3d radial(std::cos(alpha), std::sin(alpha), 0), up(0, 0, 1);
    const Eigen::Vector3d elbow =
        p.R * radial + p.l_a * (std::cos(theta) * radial - std::sin(theta) * up);
    const Eigen::Vector3d joint = platform + p.r * radial;
    ASSERT_NEAR((joint - elbow).norm(), p.l_b, 1e-12);
    force += lambda[i] * (joint - elbow) / p.l_b;
  }
  const Eigen::Vector3d mass_times_acceleration = (p.m_p + 1.5 * p.m_b) * a.tail<3>();
  EXPECT_LT((mass_times_acceleration - force).norm(), 1e-12 * force.norm());
  EXPECT_GT(a.tail<3>().norm(), 0.1);
}

// The Delta's hanging equilibrium: every upper arm at the angle that minimizes the potential
// energy of the symmetric pose (a ternary search; the potential is unimodal on (0, pi)).
State<DeltaRobot> hanging(const DeltaRobot::Params& p) {
  const auto platform_z = [&](double theta) {
    const double reach = p.r - p.R - p.l_a * std::cos(theta);
    return -p.l_a * std::sin(theta) - std::sqrt(p.l_b * p.l_b - reach * reach);
  };
  const auto potential = [&](double theta) {
    return -3 * (p.m_a + p.m_b) / 2 * p.g * p.l_a * std::sin(theta) +
           (p.m_p + 1.5 * p.m_b) * p.g * platform_z(theta);
  };
  double low = 0, high = M_PI;
  for (int k = 0; k < 200; ++k) {
    const double a = low + (high - low) / 3, b = high - (high - low) / 3;
    if (potential(a) < potential(b)) {
      high = b;
    } else {
      low = a;
    }
  }
  State<DeltaRobot> s;
  s.q << low, low, low, 0, 0, platform_z(low);
  s.v.setZero();
  return s;
}

TEST(DeltaRobot, StaysOnItsLoopsAndConservesEnergyOver100Seconds) {
  // swinging about its hanging equilibrium (from the model's initial pose it would fall
  // through near-singular poses, a lower arm in line with its upper arm)
  const ReducedSystem<DeltaRobot> system({});
  State<DeltaRobot> s = hanging(system.params());
  ASSERT_LT(
      constrained_acceleration<DeltaRobot>(system.params(), s.q, s.v, s.t).cwiseAbs().maxCoeff(),
      1e-6);  // the search finds the flat minimum to about 1e-8 rad
  s.v << 1.0, -0.5, 0.2, 0.0, 0.0, 0.0;
  normalize(system, &s);
  const double e0 = DeltaRobot::energy(s.q, s.v, s.t, system.params());
  double worst_drift = 0, worst_energy = 0, farthest = 0;
  for (int k = 0; k < 100000; ++k) {
    s = step(system, Integrator::RK4, s, 1e-3);
    worst_drift = std::max(worst_drift, constraint_residual<DeltaRobot>(system.params(), s));
    farthest = std::max(farthest, s.q.segment<2>(3).norm());
    if (k % 100 == 0)
      worst_energy =
          std::max(worst_energy, std::abs(DeltaRobot::energy(s.q, s.v, s.t, system.params()) - e0) /
                                     std::abs(e0));
  }
  RecordProperty("worst_drift", scientific(worst_drift));
  RecordProperty("worst_energy", scientific(worst_energy));
  EXPECT_LT(worst_drift, 1e-10);
  EXPECT_LT(worst_energy, 1e-9);
  EXPECT_GT(farthest, 0.01);  // the platform swung
}

TEST(DeltaRobot, InverseDynamicsGivesTheTorquesOfAPrescribedMotion) {
  DeltaRobot::Params p;
  State<DeltaRobot> s = initial_state<DeltaRobot>();
  // at rest with no platform acceleration: the torques of statics
  double lambda = 0;
  const double torque = holding_torque(p, s, &lambda);
  const auto still =
      constrained_inverse_dynamics<DeltaRobot>(p, s, {3, 4, 5}, Eigen::Vector3d::Zero());
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(still.inputs[i], torque, 1e-12 * std::abs(torque));
    EXPECT_NEAR(still.multipliers[i], lambda, 1e-12 * std::abs(lambda));
  }
  // moving off centre, the platform accelerating: forward dynamics with the torques found
  // gives back the prescribed acceleration
  s.q.tail<3>() += Eigen::Vector3d(0.06, -0.04, 0.05);
  s.v << 0.7, -0.3, 0.4, 0.0, 0.0, 0.0;
  project_onto_constraints<DeltaRobot>(p, &s);
  const Eigen::Vector3d prescribed(0.8, -0.5, 2.0);
  const auto found = constrained_inverse_dynamics<DeltaRobot>(p, s, {3, 4, 5}, prescribed);
  p.set_inputs({{found.inputs[0], found.inputs[1], found.inputs[2]}});
  DeltaRobot::CVector<double> multipliers;
  const auto a = constrained_acceleration<DeltaRobot>(p, s.q, s.v, s.t, &multipliers);
  EXPECT_LT((a.tail<3>() - prescribed).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_LT((a - found.acceleration).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_LT((multipliers - found.multipliers).cwiseAbs().maxCoeff(),
            1e-11 * found.multipliers.cwiseAbs().maxCoeff());
  EXPECT_THROW(constrained_inverse_dynamics<DeltaRobot>(p, s, {3, 4}, prescribed.head<2>()),
               std::invalid_argument);
}

TEST(FourBar, InverseDynamicsGivesTheMotorTorqueOfAPrescribedCrankMotion) {
  FourBar::Params p;
  State<FourBar> s = initial_state<FourBar>();
  s.v << 2.5, 0.0, 0.0;
  project_onto_constraints<FourBar>(p, &s);
  Eigen::VectorXd prescribed(1);
  prescribed << -3.0;
  const auto found = constrained_inverse_dynamics<FourBar>(p, s, {0}, prescribed);
  p.u = found.inputs[0];
  const auto a = constrained_acceleration<FourBar>(p, s.q, s.v, s.t);
  EXPECT_NEAR(a[0], -3.0, 1e-11);
  EXPECT_LT((a - found.acceleration).cwiseAbs().maxCoeff(), 1e-11);
  EXPECT_GT(std::abs(found.inputs[0]), 0.1);
}

}  // namespace
}  // namespace gencoord::testing
