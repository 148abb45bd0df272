// SPDX-License-Identifier: BSD-3-Clause
// The linearized Whipple bicycle reference (whipple_benchmark.hpp) against the numbers
// published by Meijaard, Papadopoulos, Ruina and Schwab (2007), Proc. R. Soc. A 463:
//  - M, C1, K0 and K2 of the benchmark bicycle (printed there to 14 decimals);
//  - Table 2: the eigenvalues at 0..10 m/s, the weave and capsize speeds that bound the
//    self-stable range, the weave frequency at the weave speed, and the speed and value where
//    the two real unstable eigenvalues meet and become the weave pair.
// Table 2's entries, printed to 14 decimals, differ from a 50-digit evaluation of Appendix A
// by up to 6e-13 (the castering eigenvalue at 7 m/s; all others 1.1e-13 or less), so the
// eigenvalues are compared to 1e-12.
#include "whipple_benchmark.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>

#include <gtest/gtest.h>

namespace gencoord::testing {
namespace {

using whipple::BenchmarkParameters;
using whipple::Linearized;
using Complex = std::complex<double>;

/// |got - want| <= tol max(1, |want|): absolute near zero, relative for large entries.
void expect_close(double got, double want, double tol, const char* what) {
  EXPECT_LE(std::abs(got - want), tol * std::max(1.0, std::abs(want)))
      << what << ": got " << got << ", want " << want;
}

TEST(WhippleBenchmark, MatricesMatchThePublishedValues) {
  const Linearized l = whipple::linearize(BenchmarkParameters{});
  const Eigen::Matrix2d M{{80.81722, 2.31941332208709}, {2.31941332208709, 0.29784188199686}};
  const Eigen::Matrix2d C1{{0.0, 33.86641391492494}, {-0.85035641456978, 1.68540397397560}};
  const Eigen::Matrix2d K0{{-80.95, -2.59951685249872}, {-2.59951685249872, -0.80329488458618}};
  const Eigen::Matrix2d K2{{0.0, 76.59734589573222}, {0.0, 2.65431523794604}};
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      expect_close(l.M(i, j), M(i, j), 1e-13, "M");
      expect_close(l.C1(i, j), C1(i, j), 1e-13, "C1");
      expect_close(l.K0(i, j), K0(i, j), 1e-13, "K0");
      expect_close(l.K2(i, j), K2(i, j), 1e-13, "K2");
    }
  }
  // Structural zeros and the symmetry of M and K0 hold exactly.
  EXPECT_EQ(l.C1(0, 0), 0.0);
  EXPECT_EQ(l.K2(0, 0), 0.0);
  EXPECT_EQ(l.K2(1, 0), 0.0);
  EXPECT_EQ(l.M(0, 1), l.M(1, 0));
  EXPECT_EQ(l.K0(0, 1), l.K0(1, 0));
}

TEST(WhippleBenchmark, StateMatrixIsTheFirstOrderForm) {
  const BenchmarkParameters p;
  const Linearized l = whipple::linearize(p);
  const double v = 3.7;
  const Eigen::Matrix4d a = whipple::state_matrix(l, v, p.g);
  const Eigen::Vector4d x(0.03, -0.2, 0.7, 1.1);  // (phi, delta, phi', delta')
  const Eigen::Vector4d xd = a * x;
  EXPECT_EQ(xd.head<2>(), x.tail<2>());
  // M q'' + v C1 q' + (g K0 + v^2 K2) q = 0 for the unforced motion.
  const Eigen::Vector2d residual =
      l.M * xd.tail<2>() + v * l.C1 * x.tail<2>() + (p.g * l.K0 + v * v * l.K2) * x.head<2>();
  EXPECT_LT(residual.norm(), 1e-12);
}

/// Table 2 of the paper, in eigenvalues()'s order (ascending real part, a conjugate pair with
/// the negative imaginary part first). At 0 m/s: the two inverted-pendulum pairs; up to 4 m/s:
/// castering, a real mode, the unstable weave pair; from 5 m/s: castering, the weave pair,
/// capsize.
struct Row {
  double speed;
  std::array<Complex, 4> eig;
};

std::array<Row, 11> table2() {
  const auto pair = [](double re, double im) {
    return std::array<Complex, 2>{Complex(re, -im), Complex(re, im)};
  };
  std::array<Row, 11> t;
  t[0] = {0.0, {-5.53094371765393, -3.13164324790656, 3.13164324790656, 5.53094371765393}};
  const double low[4][4] = {
      // castering, real mode, weave (real part, imaginary part)
      {-7.11008014637442, -3.13423125066578, 3.52696170990070, 0.80774027519930},
      {-8.67387984831735, -3.07158645641514, 2.68234517512745, 1.68066296590675},
      {-10.35101467245920, -2.63366137253667, 1.70675605663975, 2.31582447384325},
      {-12.15861426576447, -1.42944427361326, 0.41325331521125, 3.07910818603206}};
  for (int k = 0; k < 4; ++k) {
    const auto w = pair(low[k][2], low[k][3]);
    t[k + 1] = {k + 1.0, {low[k][0], low[k][1], w[0], w[1]}};
  }
  const double high[6][4] = {
      // castering, weave (real part, imaginary part), capsize
      {-14.07838969279822, -0.77534188219585, 4.46486771378823, -0.32286642900409},
      {-16.08537123098030, -1.52644486584142, 5.87673060598709, -0.00406690076970},
      {-18.15788466125262, -2.13875644258362, 7.19525913329805, 0.10268170574766},
      {-20.27940894394569, -2.69348683581097, 8.46037971396931, 0.14327879765713},
      {-22.43788559040858, -3.21675402252485, 9.69377351531791, 0.15790184030917},
      {-24.62459635017404, -3.72016840437287, 10.90681139476287, 0.16105338653172}};
  for (int k = 0; k < 6; ++k) {
    const auto w = pair(high[k][1], high[k][2]);
    t[k + 5] = {k + 5.0, {high[k][0], w[0], w[1], high[k][3]}};
  }
  return t;
}

TEST(WhippleBenchmark, EigenvaluesMatchTable2) {
  const BenchmarkParameters p;
  for (const Row& row : table2()) {
    const auto e = whipple::eigenvalues(p, row.speed);
    for (int i = 0; i < 4; ++i) {
      EXPECT_LE(std::abs(e[i] - row.eig[i]), 1e-12)
          << "v = " << row.speed << " m/s, eigenvalue " << i << ": got " << e[i] << ", want "
          << row.eig[i];
    }
  }
}

TEST(WhippleBenchmark, EigenvalueOrderAndConjugatePairs) {
  const BenchmarkParameters p;
  // Standing still: four real eigenvalues, symmetric about zero (no speed, no damping terms).
  const auto still = whipple::eigenvalues(p, 0.0);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(still[i].imag(), 0.0);
  EXPECT_NEAR(still[0].real(), -still[3].real(), 1e-13);
  EXPECT_NEAR(still[1].real(), -still[2].real(), 1e-13);
  for (double v : {1.0, 4.5, 5.0, 8.0}) {
    const auto e = whipple::eigenvalues(p, v);
    for (int i = 0; i + 1 < 4; ++i) EXPECT_LE(e[i].real(), e[i + 1].real()) << "v = " << v;
    int pairs = 0;
    for (int i = 0; i < 4; ++i) {
      if (e[i].imag() < 0.0) {
        ASSERT_LT(i + 1, 4);
        EXPECT_EQ(e[i + 1], std::conj(e[i])) << "v = " << v;
        ++pairs;
      }
    }
    EXPECT_EQ(pairs, 1) << "v = " << v;  // the weave pair, two real modes
  }
}

TEST(WhippleBenchmark, WeaveAndCapsizeSpeeds) {
  const BenchmarkParameters p;
  const double vw = whipple::weave_speed(p);
  const double vc = whipple::capsize_speed(p);
  // Table 2 prints 4.29238253634111 and 6.02426201538837 m/s.
  EXPECT_NEAR(vw, 4.29238253634111, 1e-10);
  EXPECT_NEAR(vc, 6.02426201538837, 1e-10);
  // At the weave speed the weave pair sits on the imaginary axis at +-3.43503384866144 i
  // (Table 2); at the capsize speed the capsize eigenvalue is zero.
  const auto ew = whipple::eigenvalues(p, vw);
  EXPECT_NEAR(ew[2].real(), 0.0, 1e-12);
  EXPECT_NEAR(ew[3].imag(), 3.43503384866144, 1e-12);
  const auto ec = whipple::eigenvalues(p, vc);
  EXPECT_NEAR(ec[3].real(), 0.0, 1e-12);
  EXPECT_EQ(ec[3].imag(), 0.0);
  // Self-stable strictly between the two, unstable just outside.
  const auto largest = [&](double v) { return whipple::eigenvalues(p, v)[3].real(); };
  EXPECT_GT(largest(vw - 1e-3), 0.0);
  EXPECT_LT(largest(vw + 1e-3), 0.0);
  EXPECT_LT(largest(0.5 * (vw + vc)), 0.0);
  EXPECT_LT(largest(vc - 1e-3), 0.0);
  EXPECT_GT(largest(vc + 1e-3), 0.0);
}

TEST(WhippleBenchmark, CapsizeSpeedIsWhereTheStiffnessIsSingular) {
  // A real eigenvalue passes through zero exactly where det(g K0 + v^2 K2) = 0; since K2's
  // first column is zero that determinant is linear in v^2.
  const BenchmarkParameters p;
  const Linearized l = whipple::linearize(p);
  const double v2 = p.g * (l.K0(0, 1) * l.K0(1, 0) - l.K0(0, 0) * l.K0(1, 1)) /
                    (l.K0(0, 0) * l.K2(1, 1) - l.K0(1, 0) * l.K2(0, 1));
  EXPECT_NEAR(whipple::capsize_speed(p), std::sqrt(v2), 1e-12);
}

/// Coefficients (s^4 first) of det(M s^2 + v C1 s + g K0 + v^2 K2).
std::array<double, 5> characteristic_polynomial(const Linearized& l, double v, double g) {
  const Eigen::Matrix2d k = g * l.K0 + v * v * l.K2;
  const Eigen::Matrix2d c = v * l.C1;
  const auto entry = [&](int i, int j) {
    return std::array<double, 3>{l.M(i, j), c(i, j), k(i, j)};
  };
  const auto a = entry(0, 0), b = entry(1, 1), x = entry(0, 1), y = entry(1, 0);
  std::array<double, 5> r{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[i + j] += a[i] * b[j] - x[i] * y[j];
  }
  return r;
}

TEST(WhippleBenchmark, RealPairMeetsAtTheTabulatedBifurcation) {
  // Below the bifurcation speed the characteristic polynomial p has two real roots near
  // 3.8 /s; they meet (p = p' = 0) at 0.68428307889246 m/s at 3.78290405129320 /s and go on
  // as the weave pair (Table 2). Found here as the zero in v of p at p's local minimum.
  const BenchmarkParameters p;
  const Linearized l = whipple::linearize(p);
  const auto critical = [&](double v) {  // (s with p'(s) = 0 near 3.8, p(s))
    const auto c = characteristic_polynomial(l, v, p.g);
    double s = 3.8;
    for (int it = 0; it < 50; ++it) {
      const double d1 = ((4.0 * c[0] * s + 3.0 * c[1]) * s + 2.0 * c[2]) * s + c[3];
      const double d2 = (12.0 * c[0] * s + 6.0 * c[1]) * s + 2.0 * c[2];
      const double step = d1 / d2;
      s -= step;
      if (std::abs(step) <= 1e-16 * std::abs(s)) break;
    }
    return std::array<double, 2>{s, (((c[0] * s + c[1]) * s + c[2]) * s + c[3]) * s + c[4]};
  };
  double a = 0.6, b = 0.8;
  ASSERT_LT(critical(a)[1], 0.0);
  ASSERT_GT(critical(b)[1], 0.0);
  while (0.5 * (a + b) > a && 0.5 * (a + b) < b) {
    const double m = 0.5 * (a + b);
    (critical(m)[1] < 0.0 ? a : b) = m;
  }
  EXPECT_NEAR(a, 0.68428307889246, 1e-12);
  EXPECT_NEAR(critical(a)[0], 3.78290405129320, 1e-12);
  // eigenvalues() agrees on either side: two real roots below, the pair above.
  const auto below = whipple::eigenvalues(p, a - 1e-3);
  EXPECT_EQ(below[2].imag(), 0.0);
  EXPECT_GT(below[2].real(), 3.6);
  const auto above = whipple::eigenvalues(p, a + 1e-3);
  EXPECT_LT(above[2].imag(), 0.0);
  EXPECT_EQ(above[3], std::conj(above[2]));
}

TEST(WhippleBenchmark, NoSelfStableRangeMeansNaN) {
  // Without trail, steer axis tilt or spinning wheels the bicycle is unstable at every speed:
  // the largest real part never changes sign, so there is no weave speed to bracket.
  BenchmarkParameters p;
  p.c = 0.0;
  p.lambda = 0.0;
  p.IRyy = p.IFyy = 0.0;
  for (double v : {0.5, 1.0, 3.0, 6.0, 10.0}) EXPECT_GT(whipple::eigenvalues(p, v)[3].real(), 0.0);
  EXPECT_TRUE(std::isnan(whipple::weave_speed(p)));
  EXPECT_TRUE(std::isnan(whipple::capsize_speed(p)));
}

}  // namespace
}  // namespace gencoord::testing
