// SPDX-License-Identifier: BSD-3-Clause
// The linearized Whipple bicycle of Meijaard, Papadopoulos, Ruina and Schwab (2007),
// "Linearized dynamics equations for the balance and steer of a bicycle: a benchmark and
// review", Proc. R. Soc. A 463, 1955-1982, doi:10.1098/rspa.2007.1857:
//   M q'' + v C1 q' + (g K0 + v^2 K2) q = f,   q = (roll phi, steer delta),
// with M, C1, K0 and K2 built from the 25 design parameters by the paper's Appendix A (total
// mass and centre of mass, the front assembly's mass, centre and inertia about the steer axis,
// the mechanical trail ratio mu and the wheels' gyrostatic coefficients SR, SF, ST, SA).
// It is the independent reference that the generated nonlinear bicycle's linearization about
// upright straight-ahead rolling is checked against: matrices, eigenvalues and the weave and
// capsize speeds that bound the benchmark's self-stable speed range.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>

// GCC 12 warns (-Wmaybe-uninitialized, a false positive) inside Eigen's triangular
// matrix-vector product, which EigenSolver instantiates; the warning is placed at Eigen's
// lines, so it is silenced only while Eigen's headers are read.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <Eigen/Dense>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

namespace gencoord::testing::whipple {

/// The paper's 25 design parameters (SI units, axes as in the paper: x forward, z down, the
/// origin at the rear wheel's contact point), defaulted to the benchmark bicycle of Table 1.
/// The wheels' IRzz = IRxx and IFzz = IFxx (axisymmetric wheels, Appendix A).
struct BenchmarkParameters {
  double w = 1.02;                                        ///< wheel base [m]
  double c = 0.08;                                        ///< trail [m]
  double lambda = 3.14159265358979323846 / 10.0;          ///< steer axis tilt, pi/2 - head angle
  double g = 9.81;                                        ///< gravity [N/kg]
  double rR = 0.3, mR = 2.0, IRxx = 0.0603, IRyy = 0.12;  ///< rear wheel R
  double xB = 0.3, zB = -0.9, mB = 85.0;                  ///< rear body and frame B
  double IBxx = 9.2, IBxz = 2.4, IByy = 11.0, IBzz = 2.8;
  double xH = 0.9, zH = -0.7, mH = 4.0;  ///< front handlebar and fork assembly H
  double IHxx = 0.05892, IHxz = -0.00756, IHyy = 0.06, IHzz = 0.00708;
  double rF = 0.35, mF = 3.0, IFxx = 0.1405, IFyy = 0.28;  ///< front wheel F
};

/// The coefficient matrices of M q'' + v C1 q' + (g K0 + v^2 K2) q = f, rows and columns in
/// the order (phi, delta).
struct Linearized {
  Eigen::Matrix2d M, C1, K0, K2;
};

/// M, C1, K0 and K2 by the formulas of the paper's Appendix A, term by term.
inline Linearized linearize(const BenchmarkParameters& p) {
  const double sl = std::sin(p.lambda), cl = std::cos(p.lambda);
  // The whole bicycle T: mass, centre of mass and inertia about the rear contact point.
  const double mT = p.mR + p.mB + p.mH + p.mF;
  const double xT = (p.xB * p.mB + p.xH * p.mH + p.w * p.mF) / mT;
  const double zT = (-p.rR * p.mR + p.zB * p.mB + p.zH * p.mH - p.rF * p.mF) / mT;
  const double ITxx = p.IRxx + p.IBxx + p.IHxx + p.IFxx + p.mR * p.rR * p.rR + p.mB * p.zB * p.zB +
                      p.mH * p.zH * p.zH + p.mF * p.rF * p.rF;
  const double ITxz = p.IBxz + p.IHxz - p.mB * p.xB * p.zB - p.mH * p.xH * p.zH + p.mF * p.w * p.rF;
  const double IRzz = p.IRxx, IFzz = p.IFxx;
  const double ITzz =
      IRzz + p.IBzz + p.IHzz + IFzz + p.mB * p.xB * p.xB + p.mH * p.xH * p.xH + p.mF * p.w * p.w;
  // The front assembly A = H + F: mass, centre of mass, central inertia.
  const double mA = p.mH + p.mF;
  const double xA = (p.xH * p.mH + p.w * p.mF) / mA;
  const double zA = (p.zH * p.mH - p.rF * p.mF) / mA;
  const double IAxx =
      p.IHxx + p.IFxx + p.mH * (p.zH - zA) * (p.zH - zA) + p.mF * (p.rF + zA) * (p.rF + zA);
  const double IAxz = p.IHxz - p.mH * (p.xH - xA) * (p.zH - zA) + p.mF * (p.w - xA) * (p.rF + zA);
  const double IAzz =
      p.IHzz + IFzz + p.mH * (p.xH - xA) * (p.xH - xA) + p.mF * (p.w - xA) * (p.w - xA);
  // A's centre ahead of the steer axis (perpendicular distance), and A's inertia about the
  // steer axis and its products with the x and z axes through the rear contact point.
  const double uA = (xA - p.w - p.c) * cl - zA * sl;
  const double IAll = mA * uA * uA + IAxx * sl * sl + 2.0 * IAxz * sl * cl + IAzz * cl * cl;
  const double IAlx = -mA * uA * zA + IAxx * sl + IAxz * cl;
  const double IAlz = mA * uA * xA + IAxz * sl + IAzz * cl;
  // Trail ratio and the gyrostatic coefficients of the wheels.
  const double mu = p.c / p.w * cl;
  const double SR = p.IRyy / p.rR, SF = p.IFyy / p.rF, ST = SR + SF;
  const double SA = mA * uA + mu * mT * xT;

  Linearized l;
  l.M << ITxx, IAlx + mu * ITxz,  //
      IAlx + mu * ITxz, IAll + 2.0 * mu * IAlz + mu * mu * ITzz;
  l.K0 << mT * zT, -SA,  //
      -SA, -SA * sl;
  l.K2 << 0.0, (ST - mT * zT) / p.w * cl,  //
      0.0, (SA + SF * sl) / p.w * cl;
  l.C1 << 0.0, mu * ST + SF * cl + ITxz / p.w * cl - mu * mT * zT,  //
      -(mu * ST + SF * cl), IAlz / p.w * cl + mu * (SA + ITzz / p.w * cl);
  return l;
}

/// The first-order form x' = A x of the unforced equations at forward speed `speed`, with
/// x = (phi, delta, phi', delta'):  A = [0 I; -M^-1 (g K0 + v^2 K2)  -M^-1 v C1].
inline Eigen::Matrix4d state_matrix(const Linearized& l, double speed, double g) {
  const Eigen::Matrix2d Minv = l.M.inverse();
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  a.topRightCorner<2, 2>() = Eigen::Matrix2d::Identity();
  a.bottomLeftCorner<2, 2>() = -Minv * (g * l.K0 + speed * speed * l.K2);
  a.bottomRightCorner<2, 2>() = -Minv * (speed * l.C1);
  return a;
}

namespace detail {

/// det(M s^2 + v C1 s + g K0 + v^2 K2) and its derivative in s, for Newton polishing.
inline void characteristic(const Linearized& l, double v, double g, std::complex<double> s,
                           std::complex<double>& p, std::complex<double>& dp) {
  const Eigen::Matrix2d k = g * l.K0 + v * v * l.K2;
  const Eigen::Matrix2d cv = v * l.C1;
  std::complex<double> a[2][2], da[2][2];
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      a[i][j] = (l.M(i, j) * s + cv(i, j)) * s + k(i, j);
      da[i][j] = 2.0 * l.M(i, j) * s + cv(i, j);
    }
  }
  p = a[0][0] * a[1][1] - a[0][1] * a[1][0];
  dp = da[0][0] * a[1][1] + a[0][0] * da[1][1] - da[0][1] * a[1][0] - a[0][1] * da[1][0];
}

/// A few Newton steps on the characteristic determinant from the eigensolver's estimate s0,
/// each kept only while it lowers |det| and stays within 1e-8 max(1, |s0|) of s0 (a
/// refinement, never a jump to a neighbouring root); real estimates stay real.
inline std::complex<double> polish(const Linearized& l, double v, double g,
                                   std::complex<double> s0) {
  const bool real = s0.imag() == 0.0;
  const double reach = 1e-8 * std::max(1.0, std::abs(s0));
  std::complex<double> s = s0, p, dp;
  characteristic(l, v, g, s, p, dp);
  for (int it = 0; it < 4 && std::abs(p) > 0.0 && std::abs(dp) > 0.0; ++it) {
    std::complex<double> next = s - p / dp;
    if (real) next = {next.real(), 0.0};
    if (!(std::abs(next - s0) <= reach)) break;
    std::complex<double> pn, dpn;
    characteristic(l, v, g, next, pn, dpn);
    if (!(std::abs(pn) < std::abs(p))) break;
    s = next, p = pn, dp = dpn;
  }
  return s;
}

}  // namespace detail

/// The four eigenvalues of state_matrix(linearize(p), speed, p.g), from Eigen's EigenSolver,
/// each refined by Newton's method on det(M s^2 + v C1 s + g K0 + v^2 K2) (conjugate pairs
/// kept exactly conjugate, real ones exactly real). Order: ascending real part; a conjugate
/// pair (equal real parts) with the negative imaginary part first. So at the benchmark's
/// v = 5 m/s: castering, weave - i, weave + i, capsize.
inline std::array<std::complex<double>, 4> eigenvalues(const BenchmarkParameters& p, double speed) {
  const Linearized l = linearize(p);
  const Eigen::EigenSolver<Eigen::Matrix4d> solver(state_matrix(l, speed, p.g), false);
  const Eigen::Vector4cd raw = solver.eigenvalues();
  std::array<std::complex<double>, 4> e;
  for (int i = 0; i < 4; ++i) {
    e[i] = raw[i];
    if (raw[i].imag() >= 0.0) {
      const std::complex<double> s = detail::polish(l, speed, p.g, raw[i]);
      if (raw[i].imag() == 0.0 || s.imag() > 0.0) e[i] = s;  // a pair stays a pair
    }
  }
  // EigenSolver gives a complex pair as (a + ib, a - ib) from one 2x2 block of the real Schur
  // form: the member with the negative imaginary part becomes the conjugate of its polished
  // twin.
  for (int i = 0; i < 4; ++i) {
    if (raw[i].imag() < 0.0) {
      for (int j = 0; j < 4; ++j) {
        if (raw[j] == std::conj(raw[i])) {
          e[i] = std::conj(e[j]);
          break;
        }
      }
    }
  }
  std::sort(e.begin(), e.end(), [](const std::complex<double>& a, const std::complex<double>& b) {
    return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag();
  });
  return e;
}

namespace detail {

/// Bisection for the sign change of f on [a, b], down to adjacent doubles (f(a), f(b) of
/// opposite signs); NaN when f does not change sign there.
template <class F>
double bisect(F f, double a, double b) {
  const bool fa_negative = f(a) < 0.0;
  if (fa_negative == (f(b) < 0.0)) return std::numeric_limits<double>::quiet_NaN();
  for (int it = 0; it < 200; ++it) {
    const double m = 0.5 * (a + b);
    if (m <= a || m >= b) break;
    if ((f(m) < 0.0) == fa_negative) {
      a = m;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}

}  // namespace detail

/// The weave speed: where the largest real part of the eigenvalues (the weave pair's, there)
/// turns negative, by bisection on [0.5, 6] m/s to adjacent doubles (well under 1e-12 m/s).
/// NaN when the largest real part does not change sign on that interval.
inline double weave_speed(const BenchmarkParameters& p) {
  return detail::bisect([&](double v) { return eigenvalues(p, v)[3].real(); }, 0.5, 6.0);
}

/// The capsize speed: above the weave speed, where the largest real eigenvalue (the capsize
/// mode) turns positive, by bisection on [weave speed, 10] m/s to adjacent doubles. NaN when
/// it does not change sign there (or there is no weave speed).
inline double capsize_speed(const BenchmarkParameters& p) {
  const auto capsize = [&](double v) {
    double largest = -std::numeric_limits<double>::infinity();
    for (const auto& e : eigenvalues(p, v)) {
      if (e.imag() == 0.0) largest = std::max(largest, e.real());
    }
    return largest;
  };
  const double vw = weave_speed(p);
  if (std::isnan(vw)) return vw;
  return detail::bisect(capsize, vw, 10.0);
}

}  // namespace gencoord::testing::whipple
