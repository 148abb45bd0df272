// SPDX-License-Identifier: BSD-3-Clause
// The four-bar's constrained dynamics against MuJoCo's (mujoco_four_bar.hpp: hinges and a
// `connect` equality), as the Delta robot's are in mujoco_delta_test.cc: at rest, in poses
// along the loop with random motor torques, MuJoCo's accelerations at its stiffest impedance
// are off by its softness, ten times more at a tenth of it, and extrapolated to a hard
// constraint (from d = 0.9999, 0.9998, 0.9996) they agree with the generated model.
#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "figures.hpp"
#include "gencoord/model/constrained_dynamics.hpp"
#include "initial_state.hpp"
#include "mujoco_four_bar.hpp"

namespace gencoord::testing {
namespace {

using constrained_testing::MujocoFourBar;
using models::FourBar;

TEST(FourBarMujoco, AgreesWithMujocosConnectEqualityExtrapolatedToAHardConstraint) {
  FourBar::Params p;
  State<FourBar> reference = initial_state<FourBar>();
  project_onto_constraints<FourBar>(p, &reference);
  MujocoFourBar mujoco(p, reference.q);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> offset(-0.4, 0.4), torque(-3.0, 3.0);
  const double stiff = 0.9999, softer = 0.999;
  double worst_stiff = 0, worst_extrapolated = 0, worst_residual = 0, worst_order = 1e300,
         best_order = 0;
  for (int k = 0; k < 20; ++k) {
    State<FourBar> s = reference;
    s.q[0] += offset(rng);  // the crank; the projection moves the coupler and the rocker
    project_onto_constraints<FourBar>(p, &s);
    p.u = torque(rng);
    const auto ours = constrained_acceleration<FourBar>(p, s.q, s.v, s.t);
    const double scale = ours.cwiseAbs().maxCoeff();
    mujoco.set(s.q, s.v, p.u);
    mujoco.set_impedance(stiff);
    const MujocoFourBar::Vec at_stiff = mujoco.forward();
    worst_residual = std::max(worst_residual, mujoco.constraint_residual());
    mujoco.set_impedance(softer);
    const MujocoFourBar::Vec at_softer = mujoco.forward();
    std::vector<MujocoFourBar::Vec> near_hard{at_stiff};
    for (const double d : {0.9998, 0.9996}) {
      mujoco.set_impedance(d);
      near_hard.push_back(mujoco.forward());
    }
    const MujocoFourBar::Vec extrapolated =
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
  EXPECT_LT(worst_residual, 1e-12);  // set() put MuJoCo on its constraint
  EXPECT_LT(worst_stiff, 1e-2);      // off by MuJoCo's softness: 6.7e-3
  EXPECT_GT(worst_order, 8.0);       // ten times softer, ten times further off
  EXPECT_LT(best_order, 12.0);
  EXPECT_LT(worst_extrapolated, 1e-9);  // 1.2e-10
}

}  // namespace
}  // namespace gencoord::testing
