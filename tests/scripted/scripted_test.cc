// SPDX-License-Identifier: BSD-3-Clause
// Scripted coordinates on the double pendulum: the script is followed exactly by every
// integrator; an empty script is the free model; a held joint gives the closed-form motion
// and torque; scripting theta1 with its own free motion reproduces the free run.
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "gencoord/integrate/integrator.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "gencoord/scripted/model.hpp"
#include "generated/double_pendulum.hpp"
#include "generated/n_link_chain_10.hpp"

namespace gencoord {
namespace {

using DP = models::DoublePendulum;

constexpr Integrator kAll[] = {Integrator::ForwardEuler, Integrator::SymplecticEuler,
                               Integrator::RK4,          Integrator::BackwardEuler,
                               Integrator::Trapezoidal,  Integrator::ImplicitMidpoint};

// theta1 = 0.3 sin(2 t)
Script swinging_theta1() {
  return Script::from_function({0}, [](double t) {
    ScriptSample s{Eigen::VectorXd(1), Eigen::VectorXd(1), Eigen::VectorXd(1)};
    s.q[0] = 0.3 * std::sin(2.0 * t);
    s.v[0] = 0.6 * std::cos(2.0 * t);
    s.a[0] = -1.2 * std::sin(2.0 * t);
    return s;
  });
}

State<DP> dp_state(double q1, double q2, double v1, double v2) {
  State<DP> s;
  s.q << q1, q2;
  s.v << v1, v2;
  return s;
}

TEST(Scripted, EveryIntegratorFollowsTheScriptExactly) {
  const ScriptedModel<DP> sm(DP::Params{}, swinging_theta1());
  for (Integrator integrator : kAll) {
    int checked = 0;
    simulate(sm, dp_state(9.0, 0.4, 9.0, 0.0), {integrator, 0.01, 2.0}, [&](const State<DP>& s) {
      const ScriptSample x = sm.sample(s.t);
      EXPECT_EQ(s.q[0], x.q[0]) << to_string(integrator) << " t " << s.t;
      EXPECT_EQ(s.v[0], x.v[0]) << to_string(integrator) << " t " << s.t;
      ++checked;
    });
    EXPECT_EQ(checked, 201);
  }
}

TEST(Scripted, EmptyScriptIsTheFreeModel) {
  const ScriptedModel<DP> sm(DP::Params{}, Script{});
  const State<DP> s = dp_state(1.0, -0.5, 0.3, 0.7);
  for (Integrator integrator : kAll) {
    const State<DP> a = step(sm, integrator, s, 0.01);
    const State<DP> b = step(ReducedSystem<DP>(DP::Params{}), integrator, s, 0.01);
    EXPECT_LT((a.q - b.q).cwiseAbs().maxCoeff(), 1e-14) << to_string(integrator);
    EXPECT_LT((a.v - b.v).cwiseAbs().maxCoeff(), 1e-13) << to_string(integrator);
  }
}

TEST(Scripted, HeldJointGivesTheSimplePendulumAndTheHoldingTorque) {
  // theta1 held at 0.5: theta2 swings as a simple pendulum of length l2 on a fixed point,
  // and the joint must supply tau1 = m2 l1 l2 (cos d a2 + sin d w2^2) + (m1 + m2) g l1 sin th1
  const double held = 0.5;
  const Script hold = Script::from_function({0}, [held](double) {
    ScriptSample s{Eigen::VectorXd::Constant(1, held), Eigen::VectorXd::Zero(1),
                   Eigen::VectorXd::Zero(1)};
    return s;
  });
  const DP::Params p;
  const ScriptedModel<DP> sm(p, hold);
  for (const double th2 : {-1.0, 0.2, 2.0})
    for (const double w2 : {0.0, 1.5}) {
      const State<DP> s = sm.imposed(dp_state(0.0, th2, 0.0, w2));
      const QVec<DP> a = sm.acceleration(s.q, s.v, s.t);
      EXPECT_EQ(a[0], 0.0);
      EXPECT_NEAR(a[1], -p.g / p.l2 * std::sin(th2), 1e-12);
      const double d = held - th2;
      const double tau1 = p.m2 * p.l1 * p.l2 * (std::cos(d) * a[1] + std::sin(d) * w2 * w2) +
                          (p.m1 + p.m2) * p.g * p.l1 * std::sin(held);
      EXPECT_NEAR(sm.driving_force(s)[0], tau1, 1e-12) << "theta2 " << th2 << " w2 " << w2;
    }
}

// the free run of the double pendulum, and theta1 scripted by a clamped spline through every
// `stride`-th state of it: max |theta2 - free theta2| and max |tau1| over the run
struct Replay {
  double theta2_error = 0.0;
  double max_torque = 0.0;
};

Replay replay_free_run(const std::vector<State<DP>>& free_run, double h, int stride,
                       Integrator integrator) {
  std::vector<double> times, values;
  for (std::size_t k = 0; k < free_run.size(); k += static_cast<std::size_t>(stride)) {
    times.push_back(free_run[k].t);
    values.push_back(free_run[k].q[0]);
  }
  const State<DP>& first = free_run.front();
  const State<DP>& last = free_run[static_cast<std::size_t>(stride) * (times.size() - 1)];
  const Script script =
      Script::from_splines({0}, {CubicSpline::clamped(times, values, first.v[0], last.v[0])});
  const ScriptedModel<DP> sm(DP::Params{}, script);
  Replay out;
  std::size_t k = 0;
  simulate(sm, first, {integrator, h, last.t - first.t}, [&](const State<DP>& s) {
    out.theta2_error = std::max(out.theta2_error, std::abs(s.q[1] - free_run[k].q[1]));
    out.max_torque = std::max(out.max_torque, std::abs(sm.driving_force(s)[0]));
    ++k;
  });
  return out;
}

TEST(Scripted, ScriptingTheFreeMotionReproducesTheFreeRun) {
  const double h = 1e-3, duration = 3.0;
  std::vector<State<DP>> free_run;
  simulate(ReducedSystem<DP>(DP::Params{}), dp_state(0.8, -0.4, 0.0, 1.0),
           {Integrator::RK4, h, duration}, [&](const State<DP>& s) { free_run.push_back(s); });
  std::vector<double> errors, torques;
  for (const int stride : {80, 40, 20}) {
    const Replay r = replay_free_run(free_run, h, stride, Integrator::RK4);
    std::printf(
        "theta1 scripted by a clamped spline through keyframes every %.3f s: "
        "max |theta2 - free| = %.3e rad, max |driving torque| = %.3e N m\n",
        stride * h, r.theta2_error, r.max_torque);
    errors.push_back(r.theta2_error);
    torques.push_back(r.max_torque);
  }
  // the free run needs no torque; the spline's acceleration error is O(spacing^2), so
  // halving the spacing divides the residual torque by ~4 and the theta2 error at least so
  for (int i = 1; i < 3; ++i) {
    EXPECT_LT(errors[i], errors[i - 1] / 3.0) << "spacing " << i;
    EXPECT_LT(torques[i], torques[i - 1] / 3.0) << "spacing " << i;
  }
  EXPECT_LT(errors[2], 1e-5);
  // the implicit integrators replay it too (dense keyframes; their own error is O(h^2))
  for (Integrator integrator : {Integrator::ImplicitMidpoint, Integrator::Trapezoidal}) {
    const Replay r = replay_free_run(free_run, h, 20, integrator);
    std::printf("  %s replay (keyframes every 0.020 s): max |theta2 - free| = %.3e rad\n",
                to_string(integrator), r.theta2_error);
    EXPECT_LT(r.theta2_error, 1e-4) << to_string(integrator);
  }
}

TEST(Scripted, ImplicitStepsUseTheFreeBlocksOfTheGeneratedJacobians) {
  // chain of 10 with links 3 and 7 scripted: generated and finite-difference Jacobians give
  // the same steps, generated needing no more Newton iterations
  using Chain = models::NLinkChain10;
  const Script script = Script::from_function({2, 6}, [](double t) {
    ScriptSample s{Eigen::VectorXd(2), Eigen::VectorXd(2), Eigen::VectorXd(2)};
    s.q << 0.5 * std::cos(3.0 * t), -0.2 + 0.1 * t * t;
    s.v << -1.5 * std::sin(3.0 * t), 0.2 * t;
    s.a << -4.5 * std::cos(3.0 * t), 0.2;
    return s;
  });
  const ScriptedModel<Chain> sm(ParamsOf<Chain>{}, script);
  EXPECT_EQ(sm.num_free(), 8);
  NewtonOptions gen, fd;
  gen.jacobian = JacobianSource::Generated;
  fd.jacobian = JacobianSource::FiniteDifference;
  StepStats gs, fs;
  State<Chain> a, b;
  for (int i = 0; i < Chain::nq; ++i) a.q[i] = 0.3 - 0.05 * i;
  b = a;
  for (int k = 0; k < 50; ++k) {
    a = step(sm, Integrator::BackwardEuler, a, 0.01, gen, &gs);
    b = step(sm, Integrator::BackwardEuler, b, 0.01, fd, &fs);
  }
  std::printf(
      "scripted chain (2 of 10 scripted), backward Euler: Newton iterations generated "
      "%ld, finite differences %ld; max |q_gen - q_fd| = %.2e\n",
      gs.newton_iterations, fs.newton_iterations, (a.q - b.q).cwiseAbs().maxCoeff());
  EXPECT_LE(gs.newton_iterations, fs.newton_iterations);
  EXPECT_LT((a.q - b.q).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(Scripted, BadScriptsAreReported) {
  const DP::Params p;
  EXPECT_THROW(
      ScriptedModel<DP>(p, Script::from_function({2}, [](double) { return ScriptSample{}; })),
      std::invalid_argument);  // index out of range
  EXPECT_THROW(Script::from_function({0, 0}, [](double) { return ScriptSample{}; }),
               std::invalid_argument);  // scripted twice
  EXPECT_THROW(Script::from_splines({0, 1}, {CubicSpline::natural({0.0, 1.0}, {0.0, 1.0})}),
               std::invalid_argument);  // one spline for two coordinates
  // a motion returning the wrong size
  const ScriptedModel<DP> wrong(
      p, Script::from_function({0}, [](double) {
        return ScriptSample{Eigen::VectorXd(2), Eigen::VectorXd(2), Eigen::VectorXd(2)};
      }));
  EXPECT_THROW(step(wrong, Integrator::RK4, State<DP>{}, 0.01), std::invalid_argument);
  // keyframes that do not cover the run
  const ScriptedModel<DP> short_script(
      p, Script::from_keyframes({0}, {0.0, 0.5, 1.0}, {{0.0, 0.1, 0.0}}));
  EXPECT_THROW(
      (simulate(short_script, State<DP>{}, {Integrator::RK4, 0.01, 2.0}, [](const State<DP>&) {})),
      std::out_of_range);
}

}  // namespace
}  // namespace gencoord
