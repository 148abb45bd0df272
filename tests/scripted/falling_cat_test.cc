// SPDX-License-Identifier: BSD-3-Clause
// The falling cat: joint angles scripted through a closed cycle, root (x, y, psi) free, no
// gravity. Angular momentum about the centre of mass stays zero and linear momentum is
// conserved, yet the body ends the cycle rotated (a geometric phase).
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/scripted/model.hpp"
#include "generated/falling_cat.hpp"

namespace gencoord {
namespace {

using Cat = models::FallingCat;
constexpr int kAlpha = 3, kBeta = 4;  // q = (x, y, psi, alpha, beta)
constexpr double kA = 0.6, kPeriod = 1.0, kW = 2.0 * M_PI / kPeriod;

// alpha = alpha0 + A sin(w t), beta = beta0 + A (cos(w t) - 1): a loop in shape space that
// starts and ends at (alpha0, beta0)
Script cat_script() {
  const double alpha0 = Cat::initial_q[kAlpha], beta0 = Cat::initial_q[kBeta];
  return Script::from_function({kAlpha, kBeta}, [=](double t) {
    const double s = std::sin(kW * t), c = std::cos(kW * t);
    ScriptSample x{Eigen::VectorXd(2), Eigen::VectorXd(2), Eigen::VectorXd(2)};
    x.q << alpha0 + kA * s, beta0 + kA * (c - 1.0);
    x.v << kA * kW * c, -kA * kW * s;
    x.a << -kA * kW * kW * s, -kA * kW * kW * c;
    return x;
  });
}

// at rest overall: the free velocities cancel the root momenta (Mt v)_f = 0 that the
// scripted joint velocities would cause (x, y, psi are cyclic: p_x, p_y is the linear
// momentum and p_psi the angular momentum about the origin)
State<Cat> zero_momentum_start(const ScriptedModel<Cat>& sm) {
  State<Cat> s = sm.imposed(State<Cat>{});
  for (int i = 0; i < 3; ++i) s.q[i] = Cat::initial_q[static_cast<std::size_t>(i)];
  const QMat<Cat> Mt = Cat::mass_matrix(s.q, 0.0, sm.params());
  s.v.head<3>() = -Mt.topLeftCorner<3, 3>().ldlt().solve(Mt.topRightCorner<3, 2>() * s.v.tail<2>());
  return s;
}

struct Momenta {
  double L_com;       // angular momentum about the centre of mass (z)
  Eigen::Vector2d p;  // linear momentum
};

// from particle positions, velocities and masses, not from the generated momenta
Momenta momenta(const State<Cat>& s, const Cat::Params& p) {
  const XVec<Cat> x = Cat::positions(s.q, s.t, p), xd = Cat::velocities(s.q, s.v, s.t, p);
  const auto m = Cat::particle_masses<double>(p);
  Eigen::Vector2d c = Eigen::Vector2d::Zero(), cd = Eigen::Vector2d::Zero();
  for (int i = 0; i < Cat::num_particles; ++i) {
    c += m[i] * x.segment<2>(2 * i);
    cd += m[i] * xd.segment<2>(2 * i);
  }
  Momenta out{0.0, cd};
  c /= m.sum();
  cd /= m.sum();
  for (int i = 0; i < Cat::num_particles; ++i) {
    const Eigen::Vector2d r = x.segment<2>(2 * i) - c, u = xd.segment<2>(2 * i) - cd;
    out.L_com += m[i] * (r.x() * u.y() - r.y() * u.x());
  }
  return out;
}

// one cycle with RK4 at step T / steps; returns the net rotation psi(T) - psi(0)
double one_cycle(int steps, double* max_L, double* max_dp, double* shape_error) {
  const ScriptedModel<Cat> sm(Cat::Params{}, cat_script());
  const State<Cat> s0 = zero_momentum_start(sm);
  const Eigen::Vector2d p0 = momenta(s0, sm.params()).p;
  *max_L = *max_dp = 0.0;
  const State<Cat> end =
      simulate(sm, s0, {Integrator::RK4, kPeriod / steps, kPeriod}, [&](const State<Cat>& s) {
        const Momenta m = momenta(s, sm.params());
        *max_L = std::max(*max_L, std::abs(m.L_com));
        *max_dp = std::max(*max_dp, (m.p - p0).cwiseAbs().maxCoeff());
      });
  *shape_error = (end.q.tail<2>() - s0.q.tail<2>()).cwiseAbs().maxCoeff();
  return end.q[2] - s0.q[2];
}

TEST(FallingCat, ZeroAngularMomentumYetANetRotationThatConverges) {
  std::vector<double> rotations;
  for (int steps : {250, 500, 1000}) {
    double max_L, max_dp, shape_error;
    rotations.push_back(one_cycle(steps, &max_L, &max_dp, &shape_error));
    std::printf(
        "falling cat, RK4 h = T/%d: net rotation %.12f rad, max |L_com| = %.2e, "
        "max |p - p0| = %.2e, shape error after the cycle %.1e\n",
        steps, rotations.back(), max_L, max_dp, shape_error);
    if (steps >= 500) {  // h <= T/500: RK4's O(h^4) momentum error below 1e-9
      EXPECT_LT(max_L, 1e-9) << "steps " << steps;
      EXPECT_LT(max_dp, 1e-9) << "steps " << steps;
    }
    EXPECT_LT(shape_error, 1e-12) << "the cycle must close";
  }
  // a clear, converging net rotation: successive differences shrink (RK4: ~16x)
  const double d1 = std::abs(rotations[1] - rotations[0]);
  const double d2 = std::abs(rotations[2] - rotations[1]);
  std::printf("successive differences %.2e, %.2e (ratio %.1f)\n", d1, d2, d1 / d2);
  EXPECT_GT(std::abs(rotations[2]), 0.01);
  EXPECT_LT(d2, 1e-6);
  EXPECT_LT(d2, d1 / 8.0);
}

TEST(FallingCat, ImplicitIntegratorsAgreeOnTheNetRotation) {
  // implicit midpoint and trapezoidal (Newton over the free velocities only) reach the same
  // rotation as RK4, to their second-order error
  double max_L, max_dp, shape_error;
  const double reference = one_cycle(1000, &max_L, &max_dp, &shape_error);
  const ScriptedModel<Cat> sm(Cat::Params{}, cat_script());
  for (Integrator integrator : {Integrator::ImplicitMidpoint, Integrator::Trapezoidal}) {
    const State<Cat> s0 = zero_momentum_start(sm);
    StepStats stats;
    const State<Cat> end = simulate(sm, s0, {integrator, kPeriod / 1000, kPeriod, {}, &stats},
                                    [](const State<Cat>&) {});
    const double rotation = end.q[2] - s0.q[2];
    std::printf(
        "falling cat, %s h = T/1000: net rotation %.9f rad (RK4 %.9f), %.2f Newton "
        "iterations per solve\n",
        to_string(integrator), rotation, reference,
        double(stats.newton_iterations) / stats.newton_solves);
    EXPECT_NEAR(rotation, reference, 1e-4) << to_string(integrator);
    EXPECT_LT(std::abs(momenta(end, sm.params()).L_com), 1e-6) << to_string(integrator);
  }
}

}  // namespace
}  // namespace gencoord
