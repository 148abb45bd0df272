// SPDX-License-Identifier: BSD-3-Clause
// The maximal-coordinate penalty model of a constrained model converges to the constrained
// reduced one as kappa grows: the particles move freely, the bodies' joints are the model
// files' pins, a loop closure is a penalty spring and a rolling wheel's contact a spring on
// its height and a viscous penalty on its slip (python/gencoord/derive/maximal_constraints.py).
//  - closed loops (the four-bar, the slider-crank, the Delta robot), moving under gravity
//    from a state at speed: the largest particle-position error falls like 1/kappa (fitted
//    log-log slope -0.8 or steeper), the largest violation too, and the maximal model
//    conserves its energy where no motor works;
//  - rolling (the disk, rolling and wobbling; the Whipple bicycle running at 5 m/s after a
//    push on its roll): the viscous penalty's coefficient grows like
//    sqrt(kappa) (so that its rate keeps pace with the springs' frequencies and one explicit
//    step suits both), and the error falls like its inverse: slope -0.5.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bicycle_stability.hpp"
#include "gencoord/control/constrained_inverse_dynamics.hpp"
#include "gencoord/maximal/crosscheck.hpp"
#include "gencoord/numerics/loglog_fit.hpp"
#include "generated/delta_robot.hpp"
#include "generated/four_bar.hpp"
#include "generated/rolling_disk.hpp"
#include "generated/slider_crank.hpp"
#include "initial_state.hpp"

namespace gencoord::testing {
namespace {

using models::DeltaRobot;
using models::FourBar;
using models::RollingDisk;
using models::SliderCrank;

struct Sweep {
  std::vector<double> error, violation, drift;
  LogLogFit error_fit, violation_fit;
};

template <class M>
Sweep sweep(const ParamsOf<M>& p, const State<M>& start, double duration, double lo, double hi,
            int count) {
  CrosscheckOptions o;
  o.duration = duration;
  o.points = 40;
  const ReducedReference<M> ref = reduced_reference<M>(p, start, o);
  std::vector<double> kappas = log_spaced(lo, hi, count);
  Sweep out;
  for (double kappa : kappas) {
    // RK4 alone: the other integrators of the maximal model would treble the compile time
    const CrosscheckRow row = crosscheck_at<M, IntegratorSet<Integrator::RK4>>(p, ref, kappa, o);
    std::printf("  %-14s kappa %8.1e  dt %8.2e  error %10.3e  violation %10.3e  drift %9.2e\n",
                M::name, kappa, row.dt, row.max_position_error, row.max_constraint_violation,
                row.energy_drift);
    out.error.push_back(row.max_position_error);
    out.violation.push_back(row.max_constraint_violation);
    out.drift.push_back(row.energy_drift);
  }
  out.error_fit = fit_loglog(kappas, out.error);
  out.violation_fit = fit_loglog(kappas, out.violation);
  std::printf("  %-14s slopes: error %.3f, violation %.3f\n", M::name, out.error_fit.slope,
              out.violation_fit.slope);
  ::testing::Test::RecordProperty(std::string(M::name) + "_error_slope",
                                  std::to_string(out.error_fit.slope));
  for (std::size_t i = 1; i < out.error.size(); ++i)
    EXPECT_LT(out.error[i], out.error[i - 1]) << M::name << ": error grew";
  return out;
}

template <class M>
void expect_loop_convergence(const ParamsOf<M>& p, const State<M>& start, double duration,
                             bool conservative = true) {
  const Sweep s = sweep<M>(p, start, duration, 1e4, 1e7, 4);
  EXPECT_LE(s.error_fit.slope, -0.8) << M::name << ": position error falls too slowly";
  EXPECT_NEAR(s.violation_fit.slope, -1.0, 0.2) << M::name << ": violation is not ~ 1/kappa";
  EXPECT_LT(s.error.back(), 1e-3) << M::name;
  if (conservative) {
    for (double drift : s.drift) EXPECT_LT(drift, 1e-5) << M::name << ": energy not conserved";
  }
}

TEST(PenaltyCrosscheck, FourBarConvergesLikeOneOverKappa) {
  State<FourBar> s = initial_state<FourBar>();
  s.v << 4.0, 0.0, 0.0;  // the crank's rate; the projection sets the others
  expect_loop_convergence<FourBar>({}, s, 1.0);
}

TEST(PenaltyCrosscheck, SliderCrankConvergesLikeOneOverKappa) {
  State<SliderCrank> s = initial_state<SliderCrank>();
  s.v << 6.0, 0.0, 0.0;
  expect_loop_convergence<SliderCrank>({}, s, 1.0);
}

TEST(PenaltyCrosscheck, DeltaRobotConvergesLikeOneOverKappa) {
  // the motors hold the platform's weight where it starts (inverse dynamics), and it drifts
  // sideways: a Delta falling freely soon stretches an arm straight, a singular
  // configuration past which the two models need not take the same branch
  DeltaRobot::Params p;
  State<DeltaRobot> s = initial_state<DeltaRobot>();
  project_onto_constraints<DeltaRobot>(p, &s);
  const auto hold =
      constrained_inverse_dynamics<DeltaRobot>(p, s, {3, 4, 5}, Eigen::Vector3d::Zero());
  p.u_1 = hold.inputs[0];
  p.u_2 = hold.inputs[1];
  p.u_3 = hold.inputs[2];
  s.v << 0.0, 0.0, 0.0, 0.3, -0.2, 0.1;  // the platform's velocity; the projection sets the arms'
  expect_loop_convergence<DeltaRobot>(p, s, 0.5, /*conservative=*/false);  // the motors work
}

TEST(PenaltyCrosscheck, RollingDiskConvergesLikeOneOverSqrtKappa) {
  // rolling along x at 3 m/s, leaning and wobbling (the coordinates: x, y, psi, phi, theta)
  State<RollingDisk> s;
  s.q << 0.0, 0.0, 0.0, 0.1, 0.0;
  s.v << 3.0, 0.0, 0.0, 0.5, 10.0;  // the projection makes them roll
  // the thin disk's point masses are 6 mm apart across it: below kappa ~ 1e5 the penalty
  // forces fold them over
  const Sweep s_sweep = sweep<RollingDisk>({}, s, 0.5, 1e5, 1e8, 4);
  EXPECT_NEAR(s_sweep.error_fit.slope, -0.5, 0.15) << "rolling: not ~ kappa^-1/2";
  EXPECT_NEAR(s_sweep.violation_fit.slope, -1.0, 0.2);
  EXPECT_LT(s_sweep.error.back(), 1e-3);
}

TEST(PenaltyCrosscheck, WhippleBicycleConvergesLikeOneOverSqrtKappa) {
  // running at 5 m/s, between the weave and capsize speeds, after a push on the roll; the
  // bodies' hinges are the model file's pins. Over kappa 1e6..1e9 the error's decade ratios
  // fall toward sqrt(10) (7.3, 4.7, 3.7): the fitted slope is between -1 and -1/2.
  const bicycle::Bicycle::Params p;
  const Sweep s = sweep<bicycle::Bicycle>(p, bicycle::upright(p, 5.0, 0.5), 1.0, 1e6, 1e9, 4);
  EXPECT_LE(s.error_fit.slope, -0.45);
  EXPECT_GE(s.error_fit.slope, -0.95);
  const double last_ratio = s.error[2] / s.error[3];
  EXPECT_GT(last_ratio, 2.5) << "rolling: not ~ kappa^-1/2";
  EXPECT_LT(last_ratio, 5.0) << "rolling: not ~ kappa^-1/2";
  EXPECT_NEAR(s.violation_fit.slope, -1.0, 0.2);
  EXPECT_LT(s.error.back(), 1e-3);  // m, after 5 m of riding
}

}  // namespace
}  // namespace gencoord::testing
