// SPDX-License-Identifier: BSD-3-Clause
// Generated rigid-body models against closed forms that do not come from our code: the
// compound pendulum's small-angle period, the heavy top's cuspidal motion (its nutation
// range, nutation period and mean precession from the quadrature of the exact solution) and
// its steady precession, and the free box's spin about its principal axes (stable about the
// smallest and largest moments, flipping about the intermediate one, the Dzhanibekov effect)
// with energy and angular momentum conserved. The box is a model file of this folder
// (body_models/), one model.body().
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/model/dynamics.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "generated/compound_pendulum.hpp"
#include "generated/free_box.hpp"
#include "generated/heavy_top.hpp"

namespace gencoord::testing {
namespace {

using models::CompoundPendulum;
using models::FreeBox;
using models::HeavyTop;

TEST(CompoundPendulum, SmallAnglePeriodIsTwoPiSqrtOfPivotInertiaOverMgd) {
  // the defaults, and a short, stout bar whose own inertia I_c outweighs m d^2 six times
  CompoundPendulum::Params stout;
  stout.m = 1.5;
  stout.I_c = 0.36;
  stout.d = 0.2;
  for (const CompoundPendulum::Params& p : {CompoundPendulum::Params{}, stout}) {
    State<CompoundPendulum> s;
    s.q[0] = 1e-3;
    const double expected = 2.0 * M_PI * std::sqrt((p.I_c + p.m * p.d * p.d) / (p.m * p.g * p.d));
    // period from upward zero crossings of theta, located by linear interpolation (theta'' is
    // zero at a crossing, so its error is third order in the step)
    std::vector<double> crossings;
    double previous_theta = s.q[0], previous_t = 0.0;
    const double dt = 1e-3, duration = std::ceil(8.0 * expected / dt) * dt;
    simulate(ReducedSystem<CompoundPendulum>(p), s, {Integrator::RK4, dt, duration},
             [&](const State<CompoundPendulum>& x) {
               if (previous_theta < 0.0 && x.q[0] >= 0.0) {
                 crossings.push_back(previous_t + (x.t - previous_t) * (-previous_theta) /
                                                      (x.q[0] - previous_theta));
               }
               previous_theta = x.q[0];
               previous_t = x.t;
             });
    ASSERT_GE(crossings.size(), 7u);
    const double measured =
        (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    std::printf("compound pendulum (I_c = %g, d = %g): period %.12g s, relative error %.2e\n",
                p.I_c, p.d, measured, measured / expected - 1.0);
    EXPECT_NEAR(measured / expected, 1.0, 1e-6)
        << "measured " << measured << " s, expected " << expected << " s";
    // what is left is the finite-amplitude correction, theta0^2 / 16 = 6.25e-8 (the next
    // term, 11 theta0^4 / 3072, is 4e-15)
    EXPECT_NEAR(measured / expected, 1.0 + s.q[0] * s.q[0] / 16.0, 1e-10);
    // a point mass at the centre of mass (I_c left out) would be far off
    const double point_mass = 2.0 * M_PI * std::sqrt(p.d / p.g);
    EXPECT_GT(std::abs(measured / point_mass - 1.0), 0.1);
  }
}

// --- the heavy top ----------------------------------------------------------------------------
// A = m (3 r^2 + h^2) / 12 + m d^2 is the transverse moment about the tip, C = m r^2 / 2 the
// axial one, M = m g d the gravity torque's scale. With u = cos(theta), omega_3 = psi_dot +
// phi_dot u and p_phi = A phi_dot (1 - u^2) + C omega_3 u are conserved, and so is the energy;
// with a = C omega_3 / A, b = p_phi / A, beta = 2 M / A and alpha = 2 (E - C omega_3^2 / 2) / A:
//   udot^2 = (1 - u^2) (alpha - beta u) - (b - a u)^2,   phi_dot = (b - a u) / (1 - u^2).
struct Top {
  explicit Top(const HeavyTop::Params& p)
      : A(p.m * (3.0 * p.r * p.r + p.h * p.h) / 12.0 + p.m * p.d * p.d),
        C(p.m * p.r * p.r / 2.0),
        M(p.m * p.g * p.d) {}
  double A, C, M;
};

/// The motion from rest in theta and phi at theta0 (a cusp: u0 = cos(theta0), b = a u0,
/// alpha = beta u0) by quadrature: udot^2 = beta (u0 - u) (u - u1) (u2 - u), with u1 < u0 the
/// lowest point. u = u1 + (u0 - u1) (1 - cos s) / 2 turns dt = du / sqrt(udot^2) into
/// ds / sqrt(beta (u2 - u)), smooth and even in s, so the trapezoidal rule over s in [0, pi]
/// converges geometrically.
struct CuspidalMotion {
  double theta_max;        // the top's lowest tilt, acos(u1)
  double nutation_period;  // from one cusp to the next
  double mean_precession;  // phi's advance over a nutation period, divided by the period
};

CuspidalMotion cuspidal_motion(const Top& top, double theta0, double omega3) {
  const double a = top.C * omega3 / top.A, beta = 2.0 * top.M / top.A, u0 = std::cos(theta0);
  const double b = a * u0;
  // the roots of beta (1 - u^2) - a^2 (u0 - u): u2 > 1 without cancellation, u1 = product / u2
  const double u2 =
      (a * a + std::sqrt(a * a * a * a + 4.0 * beta * (beta - a * a * u0))) / (2.0 * beta);
  const double u1 = (a * a * u0 - beta) / (beta * u2);
  const int n = 400;
  double time = 0.0, advance = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double s = M_PI * k / n, weight = (k == 0 || k == n) ? 0.5 : 1.0;
    const double u = u1 + (u0 - u1) * (1.0 - std::cos(s)) / 2.0;
    const double dt = weight / std::sqrt(beta * (u2 - u));
    time += dt;
    advance += dt * (b - a * u) / (1.0 - u * u);
  }
  return {std::acos(u1), 2.0 * time * M_PI / n, advance / time};
}

/// One RK4 step's worth of a scalar signal: value and derivative at both ends, for cubic
/// Hermite interpolation.
struct Bracket {
  double t0, t1, x0, x1, dx0, dx1;

  double at(double t) const {
    const double h = t1 - t0, s = (t - t0) / h;
    const double h00 = (1 + 2 * s) * (1 - s) * (1 - s), h10 = s * (1 - s) * (1 - s);
    const double h01 = s * s * (3 - 2 * s), h11 = s * s * (s - 1);
    return h00 * x0 + h10 * h * dx0 + h01 * x1 + h11 * h * dx1;
  }

  /// The zero of the interpolant, by bisection (x0 and x1 have opposite signs).
  double root() const {
    double low = t0, high = t1;
    for (int k = 0; k < 100; ++k) {
      const double mid = 0.5 * (low + high);
      ((at(mid) < 0.0) == (x0 < 0.0) ? low : high) = mid;
    }
    return 0.5 * (low + high);
  }
};

TEST(HeavyTop, CuspidalMotionMatchesTheQuadratureOfTheExactSolution) {
  // the model's initial state: tilted 0.5 rad, spinning at 150 rad/s, phi_dot = theta_dot = 0
  const HeavyTop::Params p;
  const Top top(p);
  State<HeavyTop> s;
  for (int k = 0; k < HeavyTop::nq; ++k) {
    s.q[k] = HeavyTop::initial_q[k];
    s.v[k] = HeavyTop::initial_v[k];
  }
  const double theta0 = s.q[1], omega3 = s.v[2] + s.v[0] * std::cos(theta0);
  ASSERT_EQ(s.v[0], 0.0);
  ASSERT_EQ(s.v[1], 0.0);
  const CuspidalMotion exact = cuspidal_motion(top, theta0, omega3);

  // cusps (theta back at theta0, theta_dot from - to +) and lowest points (from + to -),
  // located on the cubic through theta_dot and theta_ddot at both ends of a step
  std::vector<double> cusp_times, cusp_phis, lowest_thetas;
  State<HeavyTop> previous = s;
  QVec<HeavyTop> previous_a = acceleration<HeavyTop>(p, s);
  simulate(ReducedSystem<HeavyTop>(p), s, {Integrator::RK4, 1e-4, 2.0},
           [&](const State<HeavyTop>& x) {
             const QVec<HeavyTop> a = acceleration<HeavyTop>(p, x);
             if (x.t > 0.0 && (previous.v[1] < 0.0) != (x.v[1] < 0.0)) {
               const Bracket rate{previous.t, x.t, previous.v[1], x.v[1], previous_a[1], a[1]};
               const double t = rate.root();
               if (x.v[1] >= 0.0) {
                 cusp_times.push_back(t);
                 cusp_phis.push_back(
                     Bracket{previous.t, x.t, previous.q[0], x.q[0], previous.v[0], x.v[0]}.at(t));
               } else {
                 lowest_thetas.push_back(
                     Bracket{previous.t, x.t, previous.q[1], x.q[1], previous.v[1], x.v[1]}.at(t));
               }
             }
             previous = x;
             previous_a = a;
           });
  ASSERT_GE(cusp_times.size(), 10u);
  ASSERT_GE(lowest_thetas.size(), 10u);
  const double cycles = static_cast<double>(cusp_times.size());
  const double period = cusp_times.back() / cycles;  // the run starts at a cusp
  const double precession = (cusp_phis.back() - s.q[0]) / cusp_times.back();
  double theta_max_error = 0.0;
  for (double theta : lowest_thetas) {
    theta_max_error = std::max(theta_max_error, std::abs(theta - exact.theta_max));
  }
  std::printf(
      "heavy top, cuspidal: nutation period %.12g s (relative error %.2e), mean precession "
      "%.12g rad/s (relative error %.2e), lowest tilt %.12g rad (error %.2e rad)\n",
      period, period / exact.nutation_period - 1.0, precession,
      precession / exact.mean_precession - 1.0, exact.theta_max, theta_max_error);
  EXPECT_NEAR(period / exact.nutation_period, 1.0, 1e-8);
  EXPECT_NEAR(precession / exact.mean_precession, 1.0, 1e-8);
  EXPECT_LT(theta_max_error, 1e-8);

  // The fast-top estimate M / (C omega_3) keeps the leading order in
  // eps = A M / (C omega_3)^2 (0.044 here) and drops the next: its relative error is
  // eps cos(theta0) + O(eps^2) (0.041 measured), hence the bound 1.5 eps.
  const double estimate = top.M / (top.C * omega3);
  const double eps = top.A * top.M / (top.C * omega3 * top.C * omega3);
  std::printf("heavy top: fast-top estimate %.6g rad/s, relative error %.4f, eps %.4f\n", estimate,
              precession / estimate - 1.0, eps);
  EXPECT_GT(precession / estimate - 1.0, 0.0);
  EXPECT_LT(precession / estimate - 1.0, 1.5 * eps);
}

struct PrecessionRun {
  double theta_change;  // max |theta - theta0|
  double theta_rate;    // max |theta_dot|
  double rate_change;   // max |phi_dot / phi_dot(0) - 1|
};

/// The run from theta0 with precession rate `phi_dot` and spin omega_3, theta_dot = 0.
PrecessionRun precession_run(const HeavyTop::Params& p, double theta0, double omega3,
                             double phi_dot) {
  State<HeavyTop> s;
  s.q << 0.0, theta0, 0.0;
  s.v << phi_dot, 0.0, omega3 - phi_dot * std::cos(theta0);
  PrecessionRun run{0.0, 0.0, 0.0};
  simulate(ReducedSystem<HeavyTop>(p), s, {Integrator::RK4, 1e-4, 2.0},
           [&](const State<HeavyTop>& x) {
             run.theta_change = std::max(run.theta_change, std::abs(x.q[1] - theta0));
             run.theta_rate = std::max(run.theta_rate, std::abs(x.v[1]));
             run.rate_change = std::max(run.rate_change, std::abs(x.v[0] / phi_dot - 1.0));
           });
  return run;
}

TEST(HeavyTop, SteadyPrecessionAtTheExactRateKeepsTheTiltAndTheRate) {
  // theta_ddot = 0 at theta_dot = 0 where M = phi_dot (C omega_3 - A phi_dot cos(theta)): two
  // rates, the slow one (the fast-top estimate's) and the fast one, about C omega_3 / (A cos)
  const HeavyTop::Params p;
  const Top top(p);
  const double theta0 = HeavyTop::initial_q[1], omega3 = HeavyTop::initial_v[2];
  const double spin = top.C * omega3, c = std::cos(theta0);
  const double root = std::sqrt(spin * spin - 4.0 * top.A * top.M * c);
  const double slow = 2.0 * top.M / (spin + root), fast = (spin + root) / (2.0 * top.A * c);
  for (double phi_dot : {slow, fast}) {
    ASSERT_NEAR(top.M, phi_dot * (spin - top.A * phi_dot * c), 1e-12 * top.M);
    const PrecessionRun run = precession_run(p, theta0, omega3, phi_dot);
    std::printf(
        "heavy top, steady precession at %.9g rad/s: |theta - theta0| <= %.2e rad, "
        "|theta_dot| <= %.2e rad/s, |phi_dot / phi_dot0 - 1| <= %.2e\n",
        phi_dot, run.theta_change, run.theta_rate, run.rate_change);
    EXPECT_LT(run.theta_change, 1e-8) << "phi_dot = " << phi_dot;
    EXPECT_LT(run.theta_rate, 1e-8) << "phi_dot = " << phi_dot;
    EXPECT_LT(run.rate_change, 1e-8) << "phi_dot = " << phi_dot;
  }
  // the test tells: the fast-top estimate, 4% below the slow rate, sets the top nutating
  const PrecessionRun estimated = precession_run(p, theta0, omega3, top.M / (top.C * omega3));
  std::printf("heavy top, started at the fast-top estimate: |theta - theta0| <= %.2e rad\n",
              estimated.theta_change);
  EXPECT_GT(estimated.theta_change, 1e-4);
  EXPECT_GT(estimated.rate_change, 1e-2);
}

// --- the free body: spin about each principal axis -------------------------------------------
/// The body angular velocity of R = Rz(yaw) Ry(pitch) Rx(roll) from the Euler angle rates.
Eigen::Vector3d body_angular_velocity(const State<FreeBox>& s) {
  const double pitch = s.q[4], roll = s.q[5];
  const double yaw_dot = s.v[3], pitch_dot = s.v[4], roll_dot = s.v[5];
  return {roll_dot - yaw_dot * std::sin(pitch),
          pitch_dot * std::cos(roll) + yaw_dot * std::sin(roll) * std::cos(pitch),
          -pitch_dot * std::sin(roll) + yaw_dot * std::cos(roll) * std::cos(pitch)};
}

/// Euler angle rates that give the body angular velocity w at the state's angles.
void set_body_angular_velocity(const Eigen::Vector3d& w, State<FreeBox>* s) {
  const double pitch = s->q[4], roll = s->q[5];
  const double yaw_dot = (w[1] * std::sin(roll) + w[2] * std::cos(roll)) / std::cos(pitch);
  s->v[3] = yaw_dot;
  s->v[4] = w[1] * std::cos(roll) - w[2] * std::sin(roll);
  s->v[5] = w[0] + yaw_dot * std::sin(pitch);
}

Eigen::Matrix3d rotation(const State<FreeBox>& s) {
  return (Eigen::AngleAxisd(s.q[3], Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(s.q[4], Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(s.q[5], Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

struct SpinRun {
  double min_axis_component;  // the smallest w_k / |w| over the run (body axis k spun about)
  double max_pitch;           // the largest |pitch|: the chart's lock is at pi/2
  double energy_error;        // max |E - E0| / E0
  double momentum_error;      // max |L - L0| / |L0|
};

/// Spins the box at 4 rad/s about body axis k, the other two components 1e-3 of that, from
/// an orientation that puts the spin axis along a world axis that the body's x axis never
/// reaches (so pitch stays clear of +-pi/2): x along world x, y and z along world z.
SpinRun spin_about(int k) {
  const FreeBox::Params p;
  State<FreeBox> s;
  s.q[5] = k == 1 ? M_PI / 2 : 0.0;  // roll: body y up
  Eigen::Vector3d w = Eigen::Vector3d::Constant(4e-3);
  w[k] = 4.0;
  set_body_angular_velocity(w, &s);

  // the kernels against their closed forms at the start: E = w.I w / 2, L = R I w
  const Eigen::Vector3d moments =
      Eigen::Vector3d(p.b * p.b + p.c * p.c, p.a * p.a + p.c * p.c, p.a * p.a + p.b * p.b) * p.m /
      12.0;
  const double e0 = FreeBox::energy(s.q, s.v, s.t, p);
  const Eigen::Vector3d l0 = FreeBox::angular_momentum(s.q, s.v, s.t, p);
  EXPECT_NEAR(e0, 0.5 * w.dot(moments.cwiseProduct(w)), 1e-13 * e0);
  EXPECT_LT((l0 - rotation(s) * moments.cwiseProduct(w)).norm(), 1e-13 * l0.norm());
  EXPECT_LT((body_angular_velocity(s) - w).norm(), 1e-15 * w.norm());

  SpinRun run{1.0, 0.0, 0.0, 0.0};
  simulate(ReducedSystem<FreeBox>(p), s, {Integrator::RK4, 2.5e-4, 20.0},
           [&](const State<FreeBox>& x) {
             const Eigen::Vector3d omega = body_angular_velocity(x);
             run.min_axis_component = std::min(run.min_axis_component, omega[k] / omega.norm());
             run.max_pitch = std::max(run.max_pitch, std::abs(x.q[4]));
             run.energy_error =
                 std::max(run.energy_error, std::abs(FreeBox::energy(x.q, x.v, x.t, p) - e0) / e0);
             run.momentum_error =
                 std::max(run.momentum_error,
                          (FreeBox::angular_momentum(x.q, x.v, x.t, p) - l0).norm() / l0.norm());
           });
  std::printf(
      "free box spun about body axis %d: min w_k/|w| %.6f, max |pitch| %.3f, "
      "energy error %.2e, momentum error %.2e\n",
      k + 1, run.min_axis_component, run.max_pitch, run.energy_error, run.momentum_error);
  return run;
}

TEST(FreeBox, SpinIsStableAboutTheSmallestAndLargestMomentsAndFlipsAboutTheMiddle) {
  const FreeBox::Params p;
  ASSERT_EQ(p.g, 0.0);
  ASSERT_GT(p.a, p.b);  // moments grow from x to z
  ASSERT_GT(p.b, p.c);
  for (int k : {0, 1, 2}) {
    const SpinRun run = spin_about(k);
    if (k == 1) {
      // about the intermediate axis the perturbation grows (rate about 1.3 / s) until the
      // body turns over: w_2 changes sign
      EXPECT_LT(run.min_axis_component, -0.9) << "no flip about the intermediate axis";
    } else {
      // stable: w stays within a few times the perturbation of the axis
      EXPECT_GT(run.min_axis_component, 1.0 - 1e-4) << "axis " << k + 1;
    }
    EXPECT_LT(run.max_pitch, 1.2) << "axis " << k + 1;
    EXPECT_LT(run.energy_error, 1e-10) << "axis " << k + 1;
    EXPECT_LT(run.momentum_error, 1e-10) << "axis " << k + 1;
  }
}

}  // namespace
}  // namespace gencoord::testing
