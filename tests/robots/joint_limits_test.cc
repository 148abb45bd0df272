// SPDX-License-Identifier: BSD-3-Clause
// Joint limits from URDF <limit> (gencoord/model/joint_limits.hpp) on the iiwa14 and on the
// floating quadruped, whose limited joints' speeds sit one index before their coordinates (a
// quaternion has four coordinates and three speeds). At random states past the limits, the
// impulse obeys Moreau's inelastic impact law: the generalized impulse Mt (v+ - v-) acts only
// on the speeds of limits the state is on, each pushes away from its limit and is zero where
// the speed after it leaves the limit, no limited speed enters its limit afterwards, and the
// kinetic energy never rises; for a single limit the energy lost is the closed form
// v_k^2 / (2 (Mt^-1)_kk). In a simulation every step ends inside the ranges, the arm comes
// to rest on a limit, and the energy never rises above its start; without the limits the
// same run leaves the range. The CSV has a column per limit saying where its coordinate is.
#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "gencoord/gencoord.hpp"
#include "generated/floating_quadruped.hpp"
#include "generated/iiwa14.hpp"

namespace gencoord {
namespace {

using Arm = models::Iiwa14;
using Quadruped = models::FloatingQuadruped;

template <class M>
double kinetic_energy(const ParamsOf<M>& p, const State<M>& s) {
  const Eigen::MatrixXd mass = M::mass_matrix(s.q, s.t, p);
  const Eigen::VectorXd v = s.v;
  return 0.5 * v.dot(mass * v);
}

// A state with every limited coordinate inside its range or up to 0.05 past an end (each in
// three), the speeds in (-3, 3), the base (if any) turned at random.
template <class M>
State<M> state_near_limits(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0), fraction(0.0, 1.0);
  State<M> s;
  for (int i = 0; i < M::nq; ++i) s.q[i] = M::initial_q[i] + 0.3 * unit(rng);
  if constexpr (has_generalized_speeds_v<M>) {
    for (const int start : M::quaternion_starts) s.q.template segment<4>(start).normalize();
  }
  for (int i = 0; i < M::num_limits; ++i) {
    const double lower = M::lower_limits[i], upper = M::upper_limits[i];
    const double where = fraction(rng);
    double& q = s.q[M::limited_coordinates[i]];
    if (where < 1.0 / 3.0) q = lower - 0.05 * fraction(rng);
    else if (where < 2.0 / 3.0) q = upper + 0.05 * fraction(rng);
    else q = lower + (upper - lower) * fraction(rng);
  }
  for (int i = 0; i < nv_of_v<M>; ++i) s.v[i] = 3.0 * unit(rng);
  return s;
}

// Moreau's law at each of 200 random states (see the top of this file)
template <class M>
void check_impact_law() {
  const ParamsOf<M> p;
  std::mt19937 rng(7);
  int impacts = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const State<M> before = state_near_limits<M>(rng);
    State<M> after = before;
    const LimitContacts contacts = enforce_joint_limits<M>(p, &after);
    impacts += contacts.stopped;
    const Eigen::MatrixXd mass = M::mass_matrix(after.q, after.t, p);
    const Eigen::VectorXd dv = after.v - before.v;
    const Eigen::VectorXd impulse = mass * dv;
    const double scale = 1.0 + (mass * Eigen::VectorXd(before.v)).cwiseAbs().maxCoeff();
    Eigen::VectorXd off_limits = impulse;  // the impulse where no limit holds a speed
    for (int i = 0; i < M::num_limits; ++i) {
      const int c = M::limited_coordinates[i], k = M::limited_speeds[i];
      const double lower = M::lower_limits[i], upper = M::upper_limits[i];
      ASSERT_GE(after.q[c], lower);
      ASSERT_LE(after.q[c], upper);
      const double side = after.q[c] == lower ? 1.0 : after.q[c] == upper ? -1.0 : 0.0;
      if (side == 0.0) continue;
      off_limits[k] = 0.0;
      EXPECT_GE(side * impulse[k], -1e-12 * scale) << M::limit_names[i] << " pulls";
      EXPECT_GE(side * after.v[k], -1e-12 * scale) << M::limit_names[i] << " entered";
      EXPECT_NEAR(impulse[k] * after.v[k], 0.0, 1e-11 * scale * scale)
          << M::limit_names[i] << ": an impulse on a speed that leaves";
    }
    EXPECT_LE(off_limits.cwiseAbs().maxCoeff(), 1e-12 * scale);
    State<M> clamped = before;  // the speeds before the impulse, at the clamped q
    clamped.q = after.q;
    EXPECT_LE(kinetic_energy<M>(p, after), kinetic_energy<M>(p, clamped) * (1 + 1e-14) + 1e-15);
  }
  EXPECT_GT(impacts, 100);  // the states did strike limits
}

TEST(JointLimits, TheArmsImpulseObeysTheInelasticImpactLaw) { check_impact_law<Arm>(); }

TEST(JointLimits, TheFloatingQuadrupedsImpulseActsOnTheLimitedJointsSpeeds) {
  for (int i = 0; i < Quadruped::num_limits; ++i)
    EXPECT_EQ(Quadruped::limited_speeds[i], Quadruped::limited_coordinates[i] - 1);
  check_impact_law<Quadruped>();
}

// One limit struck: the energy lost is v_k^2 / (2 (Mt^-1)_kk), and the other speeds change
// by Mt^-1 e_k mu.
TEST(JointLimits, OneLimitLosesTheClosedFormEnergy) {
  const ParamsOf<Arm> p;
  State<Arm> s;
  for (int i = 0; i < Arm::nq; ++i) s.q[i] = 0.1 * (i + 1);
  s.v << 0.3, 2.0, -0.4, 0.5, 0.2, -0.1, 0.7;
  s.q[1] = Arm::upper_limits[1] + 0.01;
  State<Arm> after = s;
  const LimitContacts contacts = enforce_joint_limits<Arm>(p, &after);
  EXPECT_EQ(contacts.on_limit, 1);
  EXPECT_EQ(contacts.stopped, 1);
  EXPECT_EQ(after.q[1], Arm::upper_limits[1]);
  EXPECT_NEAR(after.v[1], 0.0, 1e-14);
  State<Arm> on_limit = s;
  on_limit.q[1] = Arm::upper_limits[1];
  const Eigen::MatrixXd mass = Arm::mass_matrix(on_limit.q, 0.0, p);
  const double inverse_kk = mass.ldlt().solve(Eigen::VectorXd::Unit(Arm::nv, 1))[1];
  const double lost = kinetic_energy<Arm>(p, on_limit) - kinetic_energy<Arm>(p, after);
  EXPECT_NEAR(lost, s.v[1] * s.v[1] / (2.0 * inverse_kk), 1e-12 * lost);
}

// A state inside every range, or on a limit and leaving it, is left as it is.
TEST(JointLimits, AStateThatEntersNoLimitIsUnchanged) {
  const ParamsOf<Arm> p;
  State<Arm> s;
  s.v.setConstant(0.5);
  State<Arm> after = s;
  EXPECT_EQ(enforce_joint_limits<Arm>(p, &after).on_limit, 0);
  EXPECT_EQ(after.q, s.q);
  EXPECT_EQ(after.v, s.v);
  s.q[3] = Arm::lower_limits[3];  // on the lower end, moving up
  after = s;
  const LimitContacts contacts = enforce_joint_limits<Arm>(p, &after);
  EXPECT_EQ(contacts.on_limit, 1);
  EXPECT_EQ(contacts.stopped, 0);
  EXPECT_EQ(after.v, s.v);
}

// The arm thrown towards the end of joint 2's range: it strikes the limit and stays in
// every range, its energy (damped joints, inelastic stops) never rises, and it ends resting
// on the limit. Without the limits the same run leaves the range.
TEST(JointLimits, TheArmComesToRestOnItsLimit) {
  const ParamsOf<Arm> p;
  State<Arm> initial;
  initial.q[1] = 1.5;
  initial.v[1] = 3.0;
  const double e0 = Arm::energy(initial.q, initial.v, 0.0, p);
  double highest = -INFINITY, beyond = 0.0;
  long long on_limit = 0;
  ReducedSystem<Arm> system(p);
  const State<Arm> end = simulate(
      system, initial, SimulateOptions(Integrator::RK4, 1e-3, 5.0), [&](const State<Arm>& s) {
        highest = std::max(highest, Arm::energy(s.q, s.v, s.t, p));
        for (int i = 0; i < Arm::num_limits; ++i) {
          const double q = s.q[Arm::limited_coordinates[i]];
          beyond = std::max({beyond, q - Arm::upper_limits[i], Arm::lower_limits[i] - q});
        }
        if (s.q[1] == Arm::upper_limits[1]) ++on_limit;
      });
  EXPECT_LE(beyond, 0.0);
  EXPECT_LE(highest, e0 + 1e-9 * std::abs(e0));
  EXPECT_GT(on_limit, 100);
  EXPECT_EQ(end.q[1], Arm::upper_limits[1]);
  EXPECT_LT(std::abs(end.v[1]), 1e-3);

  system.set_joint_limits(false);
  EXPECT_FALSE(system.joint_limits_enforced());
  double largest = -INFINITY;
  simulate(system, initial, SimulateOptions(Integrator::RK4, 1e-3, 1.0),
           [&](const State<Arm>& s) { largest = std::max(largest, s.q[1]); });
  EXPECT_GT(largest, Arm::upper_limits[1] + 0.1);
}

// The CSV ends each row with every limit's side: -1 lower end, +1 upper end, 0 inside.
TEST(JointLimits, TheCsvSaysWhichLimitsAreActive) {
  std::ostringstream out;
  TrajectoryCsvWriter<Arm> csv(out, ParamsOf<Arm>{});
  State<Arm> s;
  s.q[1] = Arm::upper_limits[1];
  s.q[3] = Arm::lower_limits[3] - 0.1;  // beyond it, as a run with the limits off may be
  csv(s);
  std::istringstream lines(out.str());
  std::string header, row;
  std::getline(lines, header);
  std::getline(lines, row);
  EXPECT_NE(header.find(",energy,"), std::string::npos);
  const std::string names =
      ",limit:iiwa_joint_1,limit:iiwa_joint_2,limit:iiwa_joint_3,limit:iiwa_joint_4,"
      "limit:iiwa_joint_5,limit:iiwa_joint_6,limit:iiwa_joint_7";
  ASSERT_GE(header.size(), names.size());
  EXPECT_EQ(header.substr(header.size() - names.size()), names);
  const std::string sides = ",0,1,0,-1,0,0,0";
  EXPECT_EQ(row.substr(row.size() - sides.size()), sides);
}

}  // namespace
}  // namespace gencoord
