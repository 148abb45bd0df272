// SPDX-License-Identifier: BSD-3-Clause
// DissipatedWork (gencoord/model/dissipated_work.hpp): on the damped oscillator's exact motion
// W(t) equals E(t) - E(0) to the quadrature's error, which falls as h^4 from the fourth state
// on; along an RK4 run the
// balance E - E(0) - W is the integrator's energy error, far below the energy change; a last
// step of another size is summed by the trapezoidal rule; the CSV of a dissipative model has
// the work column.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gencoord/integrate/simulate.hpp"
#include "gencoord/io/csv_writer.hpp"
#include "gencoord/model/dissipated_work.hpp"
#include "gencoord/model/reduced_system.hpp"
#include "hand_models.hpp"

namespace gencoord {
namespace {

using test_models::HandOscillator;
using test_models::oscillator_exact;

// the oscillator, marked as its generated counterpart would be: damping is all that changes E
struct DampedOscillator : HandOscillator {
  static constexpr bool dissipative = true;
};

HandOscillator::Params damped() {
  HandOscillator::Params p;
  p.c = 0.6;
  return p;
}

State<HandOscillator> exact_state(const HandOscillator::Params& p, double t) {
  const Eigen::Vector2d qv = oscillator_exact(p, 1.0, 0.5, t);
  State<HandOscillator> s;
  s.t = t;
  s.q[0] = qv[0];
  s.v[0] = qv[1];
  return s;
}

// max over [3 h, 3] of |W - (E - E0)| with W summed at step h along the exact motion (the
// first two steps' W has the lower-order rules' error, which does not stay in W)
double quadrature_error(double h) {
  const HandOscillator::Params p = damped();
  DissipatedWork<HandOscillator> work(p);
  const double e0 = HandOscillator::energy(exact_state(p, 0).q, exact_state(p, 0).v, 0.0, p);
  double worst = 0.0;
  const int steps = static_cast<int>(std::lround(3.0 / h));
  for (int k = 0; k <= steps; ++k) {
    const State<HandOscillator> s = exact_state(p, k * h);
    const double w = work(s);
    if (k >= 3)
      worst = std::max(worst, std::abs(w - (HandOscillator::energy(s.q, s.v, s.t, p) - e0)));
  }
  return worst;
}

TEST(DissipatedWork, IsTheEnergyChangeOfTheExactMotionToFourthOrder) {
  const double coarse = quadrature_error(0.02), fine = quadrature_error(0.01);
  const double order = std::log2(coarse / fine);
  RecordProperty("order", std::to_string(order));
  EXPECT_GT(order, 3.7);
  EXPECT_LT(order, 4.5);
  EXPECT_LT(fine, 1e-7);  // the energy falls by about 1.8 J over the 3 s
  std::printf(
      "W against E - E0 on the exact motion: %.2g (h = 0.02), %.2g (h = 0.01), order %.2f\n",
      coarse, fine, order);
}

TEST(DissipatedWork, TheBalanceOfAnRk4RunIsTheIntegratorsError) {
  const HandOscillator::Params p = damped();
  State<HandOscillator> start = exact_state(p, 0.0);
  const double e0 = HandOscillator::energy(start.q, start.v, 0.0, p);
  DissipatedWork<HandOscillator> work(p);
  double change = 0.0, balance = 0.0, start_up = 0.0;
  int k = 0;
  simulate(ReducedSystem<HandOscillator>(p), start, SimulateOptions(Integrator::RK4, 1e-3, 3.0),
           [&](const State<HandOscillator>& s) {
             const double w = work(s);
             change = HandOscillator::energy(s.q, s.v, s.t, p) - e0;
             double& worst = k++ < 3 ? start_up : balance;
             worst = std::max(worst, std::abs(change - w));
           });
  EXPECT_LT(start_up, 1e-8);  // h^3 P'' / 12 at the first two states
  EXPECT_LT(change, -1.0);    // most of the energy is gone
  EXPECT_LT(balance, 1e-10);  // RK4's own error at this step
  EXPECT_GT(std::abs(change), 1e9 * balance);
}

TEST(DissipatedWork, ALastShorterStepIsSummedByTheTrapezoidalRule) {
  const HandOscillator::Params p = damped();
  DissipatedWork<HandOscillator> work(p);
  for (int k = 0; k <= 10; ++k) work(exact_state(p, 0.1 * k));
  const double before = work.work();
  const State<HandOscillator> a = exact_state(p, 1.0), b = exact_state(p, 1.03);
  const double trapezoid = 0.015 * (-p.c * a.v[0] * a.v[0] - p.c * b.v[0] * b.v[0]);
  EXPECT_NEAR(work(b) - before, trapezoid, 1e-15);
}

TEST(DissipatedWork, TheCsvOfADissipativeModelHasTheWorkColumn) {
  static_assert(is_dissipative_v<DampedOscillator>);
  static_assert(!is_dissipative_v<HandOscillator>);
  const HandOscillator::Params p = damped();
  std::ostringstream out, plain_out;
  TrajectoryCsvWriter<DampedOscillator> csv(out, p);
  TrajectoryCsvWriter<HandOscillator> plain(plain_out, p);
  for (int k = 0; k < 3; ++k) {
    const State<HandOscillator> s = exact_state(p, 0.1 * k);
    State<DampedOscillator> d;
    d.t = s.t;
    d.q = s.q;
    d.v = s.v;
    csv(d);
    plain(s);
  }
  std::istringstream rows(out.str());
  std::string header, line;
  std::getline(rows, header);
  EXPECT_EQ(header, "t,q_q,v_q,energy,work,mass_x,mass_y");
  EXPECT_EQ(plain_out.str().substr(0, plain_out.str().find('\n')),
            "t,q_q,v_q,energy,mass_x,mass_y");
  std::vector<double> work;
  while (std::getline(rows, line)) {
    std::istringstream fields(line);
    std::string field;
    for (int column = 0; column <= 4; ++column) std::getline(fields, field, ',');
    work.push_back(std::stod(field));
  }
  ASSERT_EQ(work.size(), 3u);
  EXPECT_EQ(work[0], 0.0);
  EXPECT_LT(work[1], 0.0);  // the damper takes energy out
  EXPECT_LT(work[2], work[1]);
  EXPECT_NEAR(csv.work(), work[2], 1e-12 * std::abs(work[2]));  // the column's last value
  EXPECT_EQ(plain.work(), 0.0);
}

}  // namespace
}  // namespace gencoord
