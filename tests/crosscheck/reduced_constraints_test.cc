// SPDX-License-Identifier: BSD-3-Clause
// Reduced coordinates cannot drift: the reduced model keeps every declared constraint to
// 1e-12 over 1e5 RK4 steps (Maximal::constraint_violations at x = X(q)), while the maximal
// penalty model's violation over the same motion is only O(1/kappa) (reported, not bounded).
// Each model runs at its default parameters and at parameters drawn around them, since a
// constraint that holds at the defaults only is still a wrong one.
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "../models/random_states.hpp"
#include "gencoord/maximal/crosscheck.hpp"
#include "test_models.hpp"

namespace gencoord {
namespace {

template <class M>
void expect_no_drift(const ParamsOf<M>& p = {}) {
  State<M> s0;
  s0.q = initial_q_of<M>();
  s0.v = initial_v_of<M>();
  CrosscheckOptions o;
  o.duration = 10.0;  // 1e5 steps of 1e-4
  o.points = 10;
  o.reference_dt = 1e-4;
  const ReducedReference<M> ref = reduced_reference<M>(p, s0, o);
  ASSERT_EQ(ref.steps, 100000);
  EXPECT_LE(ref.max_constraint_violation, 1e-12) << M::name;
  // the maximal model over 1 s at kappa = 1e6, for comparison
  o.duration = 1.0;
  const ReducedReference<M> short_ref = reduced_reference<M>(p, s0, o);
  const CrosscheckRow row =
      crosscheck_at<M, IntegratorSet<Integrator::RK4>>(p, short_ref, 1e6, o);  // RK4 alone
  std::printf("  %-16s reduced max |C| over 1e5 steps %.2e; maximal (kappa 1e6, 1 s) %.2e\n",
              M::name, ref.max_constraint_violation, row.max_constraint_violation);
  ::testing::Test::RecordProperty(std::string(M::name) + "_reduced_violation",
                                  std::to_string(ref.max_constraint_violation));
  ::testing::Test::RecordProperty(std::string(M::name) + "_maximal_violation_kappa_1e6",
                                  std::to_string(row.max_constraint_violation));
  EXPECT_GT(row.max_constraint_violation, 1e3 * ref.max_constraint_violation);
}

template <class M>
void expect_no_drift_at_defaults_and_samples() {
  expect_no_drift<M>();
  for (unsigned seed : {1u, 2u}) {
    std::mt19937 rng(seed);
    expect_no_drift<M>(gencoord::testing::sampled_params<M>(rng));
  }
}

TEST(ReducedConstraints, PendulumDoesNotDrift) {
  expect_no_drift_at_defaults_and_samples<models::Pendulum>();
}
TEST(ReducedConstraints, Pendulum3dDoesNotDrift) {
  expect_no_drift_at_defaults_and_samples<models::Pendulum3d>();
}
TEST(ReducedConstraints, DoublePendulumDoesNotDrift) {
  expect_no_drift_at_defaults_and_samples<models::DoublePendulum>();
}
TEST(ReducedConstraints, CartPoleDoesNotDrift) {
  expect_no_drift_at_defaults_and_samples<models::CartPole>();
}
TEST(ReducedConstraints, BeadOnRotatingHoopDoesNotDrift) {
  // a moving plane: C depends on t
  expect_no_drift_at_defaults_and_samples<models::BeadOnRotatingHoop>();
}
TEST(ReducedConstraints, NLinkChain5DoesNotDrift) {
  expect_no_drift_at_defaults_and_samples<models::NLinkChain5>();
}

}  // namespace
}  // namespace gencoord
