// SPDX-License-Identifier: BSD-3-Clause
// Scripted coordinates of a model with generalized speeds (scripted/model.hpp): the floating
// arm of the Python module tests (a free trunk, a ball-jointed arm and a revolute hand; nq = 12,
// nv = 10) with its hand scripted. Every integrator follows the script and keeps the
// quaternions unit; the split solve is the free model's where the script asks for the free
// model's hand acceleration; a hand driven in weightlessness moves the rest but not the
// momentum; generated Jacobians along the speeds give backward Euler's finite-difference steps;
// a free or ball joint's coordinate is refused.
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/scripted/model.hpp"
#include "generated/floating_arm.hpp"

namespace gencoord {
namespace {

using Arm = models::FloatingArm;
constexpr int kHand = 11;      // the hand joint's coordinate
constexpr int kHandSpeed = 9;  // and its speed

constexpr Integrator kAll[] = {Integrator::ForwardEuler, Integrator::SymplecticEuler,
                               Integrator::RK4,          Integrator::BackwardEuler,
                               Integrator::Trapezoidal,  Integrator::ImplicitMidpoint};

// hand = 0.4 sin(3 t)
Script waving_hand() {
  return Script::from_function({kHand}, [](double t) {
    ScriptSample s{Eigen::VectorXd(1), Eigen::VectorXd(1), Eigen::VectorXd(1)};
    s.q[0] = 0.4 * std::sin(3.0 * t);
    s.v[0] = 1.2 * std::cos(3.0 * t);
    s.a[0] = -3.6 * std::sin(3.0 * t);
    return s;
  });
}

State<Arm> spinning() {
  State<Arm> s;
  for (int i = 0; i < Arm::nq; ++i) s.q[i] = Arm::initial_q[static_cast<std::size_t>(i)];
  s.v << 0.1, -0.2, 0.3, 0.5, -0.4, 0.8, 1.0, 0.3, -0.6, 0.0;
  return s;
}

double worst_unit_norm_error(const QVec<Arm>& q) {
  double worst = 0.0;
  for (const int start : Arm::quaternion_starts)
    worst = std::max(worst, std::abs(q.segment<4>(start).norm() - 1.0));
  return worst;
}

TEST(ScriptedSpeeds, TheHandsCoordinateMapsToItsSpeed) {
  const ScriptedModel<Arm> sm(Arm::Params{}, waving_hand());
  EXPECT_EQ(sm.scripted_speeds(), std::vector<int>{kHandSpeed});
  EXPECT_EQ(sm.num_free(), Arm::nv - 1);
  const State<Arm> s = sm.imposed(spinning());
  EXPECT_EQ(s.q[kHand], 0.0);
  EXPECT_EQ(s.v[kHandSpeed], 1.2);
}

TEST(ScriptedSpeeds, EveryIntegratorFollowsTheScriptOnUnitQuaternions) {
  const ScriptedModel<Arm> sm(Arm::Params{}, waving_hand());
  for (Integrator integrator : kAll) {
    int checked = 0;
    double off_sphere = 0.0;
    simulate(sm, sm.imposed(spinning()), {integrator, 0.005, 1.0}, [&](const State<Arm>& s) {
      const ScriptSample x = sm.sample(s.t);
      EXPECT_EQ(s.q[kHand], x.q[0]) << to_string(integrator) << " t " << s.t;
      EXPECT_EQ(s.v[kHandSpeed], x.v[0]) << to_string(integrator) << " t " << s.t;
      off_sphere = std::max(off_sphere, worst_unit_norm_error(s.q));
      ++checked;
    });
    EXPECT_EQ(checked, 201);
    EXPECT_LT(off_sphere, 1e-14) << to_string(integrator);
  }
}

TEST(ScriptedSpeeds, ScriptingTheFreeHandAccelerationGivesTheFreeModel) {
  // at a state, a script asking for the hand acceleration the free model has: the other nine
  // speeds get the free model's accelerations and the hand needs no torque
  const Arm::Params p;
  const State<Arm> s = spinning();
  const VVec<Arm> free = acceleration<Arm>(p, s);
  const Script as_free = Script::from_function({kHand}, [&](double) {
    ScriptSample x{Eigen::VectorXd::Constant(1, s.q[kHand]),
                   Eigen::VectorXd::Constant(1, s.v[kHandSpeed]),
                   Eigen::VectorXd::Constant(1, free[kHandSpeed])};
    return x;
  });
  const ScriptedModel<Arm> sm(p, as_free);
  const VVec<Arm> a = sm.acceleration(s);
  EXPECT_LT((a - free).cwiseAbs().maxCoeff(), 1e-12 * std::max(1.0, free.cwiseAbs().maxCoeff()));
  EXPECT_LT(std::abs(sm.driving_force(s)[0]), 1e-12);
  // another hand acceleration needs the torque Mt's hand row says
  const ScriptedModel<Arm> waving(p, waving_hand());
  const State<Arm> w = waving.imposed(s);
  const VVec<Arm> aw = waving.acceleration(w);
  VMat<Arm> Mt;
  VVec<Arm> f;
  Arm::dynamics(w.q, w.v, w.t, p, &Mt, &f);
  EXPECT_NEAR(waving.driving_force(w)[0], Mt.row(kHandSpeed).dot(aw) - f[kHandSpeed], 1e-12);
  VVec<Arm> residual = Mt * aw - f;
  residual[kHandSpeed] = 0.0;
  EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-12);
}

TEST(ScriptedSpeeds, AHandDrivenInWeightlessnessKeepsTheMomentum) {
  // with g = 0 the hand's driving torque is internal: the trunk and arm turn and drift in
  // answer, and the linear and angular momenta stay those of the start
  Arm::Params p;
  p.g = 0.0;
  const ScriptedModel<Arm> sm(p, waving_hand());
  const State<Arm> start = sm.imposed(spinning());
  const auto p0 = Arm::linear_momentum(start.q, start.v, start.t, p);
  const auto l0 = Arm::angular_momentum(start.q, start.v, start.t, p);
  double drift = 0.0, trunk_turn = 0.0;
  simulate(sm, start, {Integrator::RK4, 1e-3, 2.0}, [&](const State<Arm>& s) {
    drift = std::max({drift, (Arm::linear_momentum(s.q, s.v, s.t, p) - p0).norm(),
                      (Arm::angular_momentum(s.q, s.v, s.t, p) - l0).norm()});
    trunk_turn = std::max(trunk_turn, (s.v.segment<3>(3) - start.v.segment<3>(3)).norm());
  });
  std::printf(
      "hand scripted in weightlessness, RK4 h = 1 ms, 2 s: momentum drift %.2e, "
      "trunk angular speed changed by up to %.3f rad/s\n",
      drift, trunk_turn);
  EXPECT_LT(drift, 1e-9);       // measured 2.3e-13
  EXPECT_GT(trunk_turn, 0.05);  // the hand does move the rest
}

TEST(ScriptedSpeeds, ImplicitStepsUseTheGeneratedJacobiansAlongTheSpeeds) {
  const ScriptedModel<Arm> sm(Arm::Params{}, waving_hand());
  // the free-free Jacobians, generated (dr/dq G) and by central differences along the speeds
  const State<Arm> s = sm.imposed(spinning());
  VVec<Arm> acc;
  ScriptedModel<Arm>::FreeMatrix gq, gv, dq, dv;
  sm.acceleration_and_jacobians(s.q, s.v, s.t, sm.sample(s.t), JacobianSource::Generated, &acc, &gq,
                                &gv);
  sm.acceleration_and_jacobians(s.q, s.v, s.t, sm.sample(s.t), JacobianSource::FiniteDifference,
                                &acc, &dq, &dv);
  EXPECT_LT((gq - dq).cwiseAbs().maxCoeff(), 1e-7 * gq.cwiseAbs().maxCoeff());
  EXPECT_LT((gv - dv).cwiseAbs().maxCoeff(), 1e-7 * gv.cwiseAbs().maxCoeff());
  NewtonOptions generated, differences;
  generated.jacobian = JacobianSource::Generated;
  differences.jacobian = JacobianSource::FiniteDifference;
  StepStats gs, fs;
  State<Arm> a = sm.imposed(spinning()), b = a;
  for (int k = 0; k < 50; ++k) {
    a = step(sm, Integrator::BackwardEuler, a, 0.01, generated, &gs);
    b = step(sm, Integrator::BackwardEuler, b, 0.01, differences, &fs);
  }
  std::printf(
      "scripted floating arm, backward Euler: Newton iterations generated %ld, finite "
      "differences %ld; max |q_gen - q_fd| = %.2e\n",
      gs.newton_iterations, fs.newton_iterations, (a.q - b.q).cwiseAbs().maxCoeff());
  EXPECT_LE(gs.newton_iterations, fs.newton_iterations);
  EXPECT_LT((a.q - b.q).cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT(worst_unit_norm_error(a.q), 1e-14);
}

TEST(ScriptedSpeeds, AFreeOrBallJointsCoordinateIsRefused) {
  for (const int coordinate : {0, 4, 8}) {  // trunk_x, a trunk and an arm quaternion entry
    try {
      const ScriptedModel<Arm> sm(Arm::Params{}, Script::from_function({coordinate}, [](double) {
                                    return ScriptSample{};
                                  }));
      ADD_FAILURE() << "coordinate " << coordinate << " was accepted";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what())
                    .find(std::string("coordinate '") + Arm::coordinate_names[coordinate] +
                          "' of model 'floating_arm' belongs to a free or ball joint"),
                std::string::npos)
          << error.what();
    }
  }
}

}  // namespace
}  // namespace gencoord
