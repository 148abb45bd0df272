// SPDX-License-Identifier: BSD-3-Clause
// The integrators on generalized speeds (q' = G(q) v), with a hand-written free rigid body
// whose orientation is a unit quaternion (free_body_model.hpp): conservation while it tumbles
// about its intermediate axis, the centre of mass's parabola, unit quaternions after every
// step, and the measured order of every integrator on the rotation and position (not the raw
// quaternion entries).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "convergence.hpp"
#include "free_body_model.hpp"
#include "gencoord/integrate/simulate.hpp"
#include "gencoord/integrate/step.hpp"
#include "gencoord/io/csv_writer.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/pendulum.hpp"

namespace gencoord::testing {
// a namespace of its own: its helpers share names with its neighbours', which compile in
// the same batch (cmake/unity.cmake)
namespace free_body {
namespace {

using test_models::FreeBody;
using Matrix3 = Eigen::Matrix3d;
using Vector3 = Eigen::Vector3d;

static_assert(assert_model_v<FreeBody>);
static_assert(has_generalized_speeds_v<FreeBody> && nv_of_v<FreeBody> == 6);
static_assert(std::is_same_v<decltype(State<FreeBody>::v), Eigen::Matrix<double, 6, 1>>);
// a generated model without speeds keeps nv == nq and v = q'
static_assert(!has_generalized_speeds_v<models::Pendulum>);
static_assert(nv_of_v<models::Pendulum> == models::Pendulum::nq);
static_assert(std::is_same_v<VVec<models::Pendulum>, QVec<models::Pendulum>>);
static_assert(has_coordinate_rate_v<ReducedSystem<FreeBody>>);
static_assert(!has_coordinate_rate_v<ReducedSystem<models::Pendulum>>);

// Spinning mostly about the intermediate axis (I2), slightly off it: the spin axis flips
// over and back within 10 s. Thrown upwards, moving sideways.
State<FreeBody> tumbling_state() {
  State<FreeBody> s;
  const Eigen::Quaterniond orientation =
      Eigen::AngleAxisd(0.3, Vector3(1.0, 2.0, -0.5).normalized()) * Eigen::Quaterniond::Identity();
  s.q << 0.1, -0.2, 0.0, orientation.w(), orientation.x(), orientation.y(), orientation.z();
  s.v << 1.0, 0.5, 2.0, 0.05, 3.0, 0.02;
  return s;
}

Matrix3 rotation_of(const State<FreeBody>& s) { return FreeBody::rotation<double>(s.q); }

// angular momentum about the centre of mass, world axes: R I omega
Vector3 spin_momentum(const State<FreeBody>& s, const FreeBody::Params& p) {
  return rotation_of(s) * FreeBody::inertia<double>(p).cwiseProduct(s.v.tail<3>());
}

TEST(FreeBody, Rk4ConservesEnergyAndSpinWhileTumbling) {
  const FreeBody::Params p;
  const State<FreeBody> initial = tumbling_state();
  const double e0 = FreeBody::energy(initial.q, initial.v, initial.t, p);
  const Vector3 l0 = spin_momentum(initial, p);
  double worst_energy = 0.0, worst_spin = 0.0, worst_norm = 0.0;
  double min_omega2 = 1e300, max_omega2 = -1e300;  // the flip: omega_2 changes sign
  long long k = 0;
  simulate(ReducedSystem<FreeBody>(p), initial, {Integrator::RK4, 1e-3, 10.0},
           [&](const State<FreeBody>& s) {
             worst_energy =
                 std::max(worst_energy, std::abs(FreeBody::energy(s.q, s.v, s.t, p) - e0));
             worst_spin = std::max(worst_spin, (spin_momentum(s, p) - l0).norm());
             if (k++ > 0) worst_norm = std::max(worst_norm, std::abs(s.q.segment<4>(3).norm() - 1));
             min_omega2 = std::min(min_omega2, s.v[4]);
             max_omega2 = std::max(max_omega2, s.v[4]);
           });
  std::printf(
      "[ free body] RK4 dt 1e-3 10 s: max |E - E0| / E0 %.3e, |L - L0| / |L0| %.3e, "
      "max ||quat| - 1| %.3e, omega_2 in [%.3f, %.3f]\n",
      worst_energy / e0, worst_spin / l0.norm(), worst_norm, min_omega2, max_omega2);
  EXPECT_LT(min_omega2, -2.0) << "the body must tumble over its intermediate axis";
  EXPECT_LE(worst_energy, 1e-8 * e0);
  EXPECT_LE(worst_spin, 1e-8 * l0.norm());
  EXPECT_LE(worst_norm, 1e-14);
  EXPECT_EQ(k, 10001);
}

TEST(FreeBody, QuaternionStaysUnitWithEveryIntegrator) {
  const FreeBody::Params p;
  const ReducedSystem<FreeBody> system(p);
  for (const Integrator integrator :
       {Integrator::ForwardEuler, Integrator::SymplecticEuler, Integrator::RK4,
        Integrator::BackwardEuler, Integrator::Trapezoidal, Integrator::ImplicitMidpoint}) {
    State<FreeBody> s = tumbling_state();
    double worst = 0.0;
    for (int k = 0; k < 200; ++k) {
      s = step(system, integrator, s, 1e-2);
      worst = std::max(worst, std::abs(s.q.segment<4>(3).norm() - 1));
    }
    EXPECT_LE(worst, 1e-14) << to_string(integrator);
  }
}

TEST(FreeBody, CentreOfMassFollowsItsParabola) {
  const FreeBody::Params p;
  const State<FreeBody> initial = tumbling_state();
  const Vector3 x0 = initial.q.head<3>();
  const Vector3 v0 = rotation_of(initial) * initial.v.head<3>();
  double worst = 0.0, scale = 0.0;
  simulate(ReducedSystem<FreeBody>(p), initial, {Integrator::RK4, 1e-3, 10.0},
           [&](const State<FreeBody>& s) {
             const Vector3 exact = x0 + v0 * s.t - Vector3(0.0, 0.0, 0.5 * p.g * s.t * s.t);
             worst = std::max(worst, (s.q.head<3>() - exact).norm());
             scale = std::max(scale, exact.norm());
           });
  std::printf(
      "[ free body] RK4 dt 1e-3 10 s: centre of mass off its parabola by %.3e m "
      "(%.3e relative)\n",
      worst, worst / scale);
  EXPECT_LE(worst, 1e-9 * scale);
}

TEST(FreeBody, GeneratedAndFiniteDifferenceJacobiansGiveTheSameStep) {
  const FreeBody::Params p;
  const ReducedSystem<FreeBody> system(p);
  NewtonOptions generated, finite;
  generated.jacobian = JacobianSource::Generated;
  finite.jacobian = JacobianSource::FiniteDifference;
  StepStats stats;
  const State<FreeBody> a =
      step(system, Integrator::BackwardEuler, tumbling_state(), 1e-2, generated, &stats);
  const State<FreeBody> b = step(system, Integrator::BackwardEuler, tumbling_state(), 1e-2, finite);
  EXPECT_LE((a.q - b.q).norm(), 1e-12);
  EXPECT_LE((a.v - b.v).norm(), 1e-11);
  // quasi-Newton (G frozen at the iterate): still a handful of updates
  EXPECT_LE(stats.max_newton_iterations, 6);
  // backward_euler_step() itself does not normalize (step() does): its end state solves
  // q1 = q0 + h G(q1) v1
  const State<FreeBody> s0 = tumbling_state();
  State<FreeBody> end = backward_euler_step(system, s0, 1e-2, generated);
  const auto rate = FreeBody::coordinate_rates(end.q, end.v, end.t, p);
  EXPECT_LE((end.q - s0.q - 1e-2 * rate).norm(), 1e-14);
}

TEST(FreeBody, CsvNamesSpeedColumnsBySpeedNames) {
  std::ostringstream out;
  TrajectoryCsvWriter<FreeBody> csv(out, FreeBody::Params{});
  csv(tumbling_state());
  const std::string text = out.str();
  const std::string header = text.substr(0, text.find('\n'));
  EXPECT_EQ(header.substr(0, header.find(",energy")),
            "t,q_x,q_y,q_z,q_qw,q_qx,q_qy,q_qz,v_vx,v_vy,v_vz,v_wx,v_wy,v_wz");
  const std::string row = text.substr(text.find('\n') + 1);
  EXPECT_EQ(std::count(row.begin(), row.end(), ','), std::count(header.begin(), header.end(), ','));
}

// --- orders of accuracy ---------------------------------------------------------------------

// the error of a run: the largest over the sample times of the distance of the rotation
// matrices (Frobenius), of the centre of mass and of a body point off the centre, and of v
double free_body_error(const std::vector<State<FreeBody>>& run,
                       const std::vector<State<FreeBody>>& reference) {
  const Vector3 body_point(0.3, -0.2, 0.5);
  double worst = 0.0;
  for (std::size_t k = 0; k < run.size() && k < reference.size(); ++k) {
    const Matrix3 R = rotation_of(run[k]), R_ref = rotation_of(reference[k]);
    const Vector3 x = run[k].q.head<3>(), x_ref = reference[k].q.head<3>();
    const double e = std::sqrt((R - R_ref).squaredNorm() + (x - x_ref).squaredNorm() +
                               (x + R * body_point - x_ref - R_ref * body_point).squaredNorm() +
                               (run[k].v - reference[k].v).squaredNorm());
    worst = std::max(worst, e);
  }
  return worst;
}

struct OrderCase {
  Integrator integrator;
  long long coarsest_steps;
};

void PrintTo(const OrderCase& c, std::ostream* os) {
  *os << to_string(c.integrator) << " from " << c.coarsest_steps << " steps";
}

class FreeBodyOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(FreeBodyOrder, FittedSlopeIsNominal) {
  constexpr double kDuration = 2.0;
  const FreeBody::Params p;
  const State<FreeBody> initial = tumbling_state();
  static const std::vector<State<FreeBody>> reference =
      sampled_run<FreeBody>(p, initial, Integrator::RK4, kDuration, kSamples << 13);
  const OrderCase c = GetParam();
  std::vector<double> dts, errors;
  for (int k = 0; k < 5; ++k) {
    const long long steps = c.coarsest_steps << k;
    dts.push_back(kDuration / static_cast<double>(steps));
    errors.push_back(free_body_error(
        sampled_run<FreeBody>(p, initial, c.integrator, kDuration, steps), reference));
  }
  const double slope = fit_loglog(dts, errors).slope;
  std::printf("[ order    ] free body, %s: fitted slope %.3f (nominal %d)\n",
              to_string(c.integrator), slope, order(c.integrator));
  for (std::size_t k = 0; k < dts.size(); ++k)
    std::printf("[          ]   dt %.4e  error %.4e\n", dts[k], errors[k]);
  EXPECT_NEAR(slope, order(c.integrator), 0.15);
  EXPECT_GT(errors.back(), 1e-11) << "finest step too small to measure the order";
}

INSTANTIATE_TEST_SUITE_P(Integrators, FreeBodyOrder,
                         ::testing::Values(OrderCase{Integrator::ForwardEuler, 800},
                                           OrderCase{Integrator::SymplecticEuler, 800},
                                           OrderCase{Integrator::BackwardEuler, 800},
                                           OrderCase{Integrator::Trapezoidal, 100},
                                           OrderCase{Integrator::ImplicitMidpoint, 100},
                                           OrderCase{Integrator::RK4, 40}),
                         [](const ::testing::TestParamInfo<OrderCase>& info) {
                           return std::string(to_string(info.param.integrator));
                         });

}  // namespace
}  // namespace free_body
}  // namespace gencoord::testing
