// SPDX-License-Identifier: BSD-3-Clause
// The Delta robot's constrained dynamics against MuJoCo's (mujoco_delta.hpp: the same
// mechanism with rods on ball joints and `connect` equalities). MuJoCo's constraints are soft,
// so its accelerations are off by O((1 - d) / d) at its stiffest impedance d = 0.9999, ten
// times more at d = 0.999; taken at d = 0.9999, 0.9998 and 0.9996 and extrapolated to d = 1
// (a quadratic in (1 - d) / d), they agree with the generated model to 1e-11.
//
// The states are at rest, with random poses and motor torques: MuJoCo's constraint rows ask
// J qacc = aref and leave out the curvature term J' qvel (its reference acceleration pulls
// the drift back afterwards), so at speed its accelerations are not the hard-constrained
// ones at any impedance. The velocity terms of the generated model are checked by energy,
// Newton's law for the platform (loop_models_test.cc) and the independent Kane derivation.
#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "figures.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "mujoco_delta.hpp"

namespace gencoord::testing {
namespace {

using constrained_testing::MujocoDelta;
using models::DeltaRobot;

TEST(DeltaRobotMujoco, AgreesWithMujocosConnectEqualitiesExtrapolatedToHardConstraints) {
  DeltaRobot::Params p;
  MujocoDelta::Vec reference;
  for (int i = 0; i < DeltaRobot::nq; ++i) reference[i] = DeltaRobot::initial_q[i];
  MujocoDelta mujoco(p, reference);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> offset(-0.1, 0.1), torque(-1.5, 1.5);
  const double stiff = 0.9999, softer = 0.999;
  double worst_stiff = 0, worst_extrapolated = 0, worst_residual = 0, worst_order = 1e300,
         best_order = 0;
  for (int k = 0; k < 20; ++k) {
    State<DeltaRobot> s;
    s.q = reference;
    for (int i = 3; i < 6; ++i) s.q[i] += offset(rng);
    s.v.setZero();
    project_onto_constraints<DeltaRobot>(p, &s);
    p.set_inputs({{torque(rng), torque(rng), torque(rng)}});
    const auto ours = constrained_acceleration<DeltaRobot>(p, s.q, s.v, s.t);
    const double scale = ours.cwiseAbs().maxCoeff();
    mujoco.set(s.q, s.v, p.inputs());
    mujoco.set_impedance(stiff);
    const MujocoDelta::Vec at_stiff = mujoco.forward();
    worst_residual = std::max(worst_residual, mujoco.constraint_residual());
    mujoco.set_impedance(softer);
    const MujocoDelta::Vec at_softer = mujoco.forward();
    std::vector<MujocoDelta::Vec> near_hard{at_stiff};
    for (const double d : {0.9998, 0.9996}) {
      mujoco.set_impedance(d);
      near_hard.push_back(mujoco.forward());
    }
    const MujocoDelta::Vec extrapolated =
        constrained_testing::extrapolated_to_hard({stiff, 0.9998, 0.9996}, near_hard);
    const double error_stiff = (at_stiff - ours).cwiseAbs().maxCoeff() / scale;
    const double error_softer = (at_softer - ours).cwiseAbs().maxCoeff() / scale;
    worst_stiff = std::max(worst_stiff, error_stiff);
    worst_extrapolated =
        std::max(worst_extrapolated, (extrapolated - ours).cwiseAbs().maxCoeff() / scale);
    worst_order = std::min(worst_order, error_softer / error_stiff);
    best_order = std::max(best_order, error_softer / error_stiff);
  }
  RecordProperty("worst_relative_at_0.9999", scientific(worst_stiff));
  RecordProperty("worst_relative_extrapolated", scientific(worst_extrapolated));
  // set() put MuJoCo on its constraints, positions and velocities
  EXPECT_LT(worst_residual, 1e-12);
  // MuJoCo at its stiffest: off by its softness, about 1e-4
  EXPECT_LT(worst_stiff, 1e-3);
  // ten times softer, ten times further off: the difference is the softness
  EXPECT_GT(worst_order, 8.0);
  EXPECT_LT(best_order, 12.0);
  EXPECT_LT(worst_extrapolated, 1e-9);  // 1.7e-11
}

}  // namespace
}  // namespace gencoord::testing
