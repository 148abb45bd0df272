// SPDX-License-Identifier: BSD-3-Clause
// GCC 12 warns (-Wmaybe-uninitialized, a false positive) inside Eigen's triangular
// matrix-vector product, which the Householder-based QR and Schur decompositions below
// instantiate. The warning is placed at Eigen's lines, so silencing it while Eigen's headers
// are read leaves it on for this file's code.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

#include "gencoord/control/lqr.hpp"

#include <cmath>
#include <complex>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace gencoord {
namespace {

using Eigen::Index;
using Eigen::MatrixXcd;
using Eigen::MatrixXd;

constexpr double kEps = std::numeric_limits<double>::epsilon();
// Newton's sign iteration with determinant scaling needs about 10 steps on well-posed problems
constexpr int kMaxSignIterations = 100;
// Relative residual above which the computed X is not trusted. A wrong invariant subspace
// leaves a residual of order 1; a right one is near working accuracy, though a badly
// conditioned problem (X of norm 1e9, as for one input driving many unstable modes) can lose
// seven or more digits in any method.
constexpr double kResidualTolerance = 1e-6;

std::string dims(Index rows, Index cols) {
  return std::to_string(rows) + " x " + std::to_string(cols);
}

[[noreturn]] void bad_argument(const char* fn, const std::string& what) {
  throw std::invalid_argument(std::string("gencoord: ") + fn + ": " + what);
}

[[noreturn]] void no_solution(const char* fn, const std::string& why) {
  throw std::runtime_error(std::string("gencoord: ") + fn + ": no stabilizing solution: " + why);
}

void check_finite(const char* fn, const char* name, const MatrixXd& M) {
  if (!M.allFinite()) bad_argument(fn, std::string(name) + " has a non-finite entry");
}

// Symmetric up to the rounding of how a caller forms it (C^T C, a product of factors).
void check_symmetric(const char* fn, const char* name, const MatrixXd& M) {
  const double scale = M.cwiseAbs().maxCoeff();
  if ((M - M.transpose()).cwiseAbs().maxCoeff() > 1e-10 * scale)
    bad_argument(fn, std::string(name) + " must be symmetric");
}

// Checks shapes and values; returns the Cholesky factorization of R.
Eigen::LLT<MatrixXd> check_arguments(const char* fn, const MatrixXd& A, const MatrixXd& B,
                                     const MatrixXd& Q, const MatrixXd& R) {
  const Index n = A.rows(), m = B.cols();
  if (n < 1 || A.cols() != n)
    bad_argument(fn, "A must be square, n x n with n >= 1, got " + dims(A.rows(), A.cols()));
  if (B.rows() != n || m < 1)
    bad_argument(fn, "B must be " + std::to_string(n) + " x m (as many rows as A, m >= 1), got " +
                         dims(B.rows(), B.cols()));
  if (Q.rows() != n || Q.cols() != n)
    bad_argument(fn, "Q must be " + dims(n, n) + " (n x n, as A), got " + dims(Q.rows(), Q.cols()));
  if (R.rows() != m || R.cols() != m)
    bad_argument(fn, "R must be " + dims(m, m) + " (m x m, m = columns of B), got " +
                         dims(R.rows(), R.cols()));
  check_finite(fn, "A", A);
  check_finite(fn, "B", B);
  check_finite(fn, "Q", Q);
  check_finite(fn, "R", R);
  check_symmetric(fn, "Q", Q);
  check_symmetric(fn, "R", R);
  Eigen::LLT<MatrixXd> llt(0.5 * (R + R.transpose()));
  if (llt.info() != Eigen::Success) bad_argument(fn, "R must be positive definite");
  return llt;
}

// sign(Z) by Newton's iteration Z <- (c Z + (c Z)^-1) / 2. The determinant scaling
// c = |det Z|^(-1/N) brings the eigenvalues' geometric mean to modulus 1, which shortens the
// slow first phase when they spread over orders of magnitude (a fast pole beside a slow one).
MatrixXd matrix_sign(const char* fn, MatrixXd Z) {
  const Index N = Z.rows();
  bool scaled = true;
  double previous_change = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < kMaxSignIterations; ++iteration) {
    const Eigen::PartialPivLU<MatrixXd> lu(Z);
    const MatrixXd inverse = lu.inverse();
    if (!inverse.allFinite())
      no_solution(fn,
                  "a sign iterate of the Hamiltonian matrix is singular (eigenvalues on the "
                  "imaginary axis)");
    double c = 1.0;
    if (scaled) {
      // log |det Z| from the LU diagonal: det itself over- or underflows for large N
      const double log_det = lu.matrixLU().diagonal().cwiseAbs().array().log().sum();
      c = std::exp(-log_det / static_cast<double>(N));
    }
    MatrixXd next = 0.5 * (c * Z + inverse / c);
    const double change = (next - Z).norm() / next.norm();
    Z.swap(next);
    if (!std::isfinite(change)) break;
    // near convergence the scaling only disturbs the quadratic convergence
    if (change < 1e-2) scaled = false;
    if (change <= 1e3 * kEps) return Z;
    // Quadratic convergence: from 1e-8 the next step is at rounding level. A change that no
    // longer halves in that phase has also reached the rounding level of this Z.
    if (previous_change < 1e-8 || (change < 1e-4 && change > 0.5 * previous_change)) return Z;
    previous_change = change;
  }
  no_solution(fn,
              "the matrix sign iteration on the Hamiltonian matrix did not converge (eigenvalues "
              "on or near the imaginary axis)");
}

MatrixXd care_residual(const MatrixXd& A, const MatrixXd& G, const MatrixXd& Q, const MatrixXd& X) {
  const MatrixXd AtX = A.transpose() * X;
  return AtX + AtX.transpose() - X * G * X + Q;
}

// The residual's norm over the size of its terms (0 when all vanish: Q = 0, X = 0).
double relative_residual(const MatrixXd& A, const MatrixXd& G, const MatrixXd& Q,
                         const MatrixXd& X) {
  const double residual = care_residual(A, G, Q, X).norm();
  if (residual == 0.0) return 0.0;
  return residual / (Q.norm() + 2.0 * (A.transpose() * X).norm() + (X * G * X).norm());
}

// Solves F^T D + D F = C (C symmetric, F real) by Bartels-Stewart on the complex Schur form
// F = U T U^H: with Y = U^H D U, T^H Y + Y T = U^H C U is solved entry by entry, row by row.
// Returns false if the equation is (numerically) singular: eigenvalues l_i + conj(l_j) = 0.
bool solve_lyapunov(const MatrixXd& F, const MatrixXd& C, MatrixXd& D) {
  const Index n = F.rows();
  const Eigen::ComplexSchur<MatrixXd> schur(F);
  if (schur.info() != Eigen::Success) return false;
  const MatrixXcd& T = schur.matrixT();
  const MatrixXcd& U = schur.matrixU();
  MatrixXcd Y = U.adjoint() * C.cast<std::complex<double>>() * U;
  const double floor = kEps * (T.norm() + 1e-300);
  for (Index i = 0; i < n; ++i) {
    for (Index j = 0; j < n; ++j) {
      std::complex<double> rhs = Y(i, j);
      for (Index k = 0; k < i; ++k) rhs -= std::conj(T(k, i)) * Y(k, j);
      for (Index k = 0; k < j; ++k) rhs -= Y(i, k) * T(k, j);
      const std::complex<double> diagonal = std::conj(T(i, i)) + T(j, j);
      if (!(std::abs(diagonal) > floor)) return false;
      Y(i, j) = rhs / diagonal;
    }
  }
  D = (U * Y * U.adjoint()).real();
  D = 0.5 * (D + D.transpose()).eval();
  return D.allFinite();
}

// The eigenvalue of A - G X with the largest real part's real part.
double closed_loop_abscissa(const MatrixXd& A, const MatrixXd& G, const MatrixXd& X) {
  const Eigen::ComplexSchur<MatrixXd> schur(A - G * X, false);
  if (schur.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  return schur.matrixT().diagonal().real().maxCoeff();
}

MatrixXd solve_care(const char* fn, const MatrixXd& A, const MatrixXd& B, const MatrixXd& Q,
                    const Eigen::LLT<MatrixXd>& R_llt) {
  const Index n = A.rows();
  // G = B R^-1 B^T = (L^-1 B^T)^T (L^-1 B^T), symmetric PSD by construction
  const MatrixXd LinvBt = R_llt.matrixL().solve(B.transpose());
  const MatrixXd G = LinvBt.transpose() * LinvBt;
  const MatrixXd Qs = 0.5 * (Q + Q.transpose());

  // X = s Y turns the equation into one for Y with G -> s G and Q -> Q / s; choosing
  // s = sqrt(|Q| / |G|) gives both blocks of the Hamiltonian the same size, which keeps
  // physical units (a heavy Q, a cheap R) from costing digits in the sign iteration.
  double s = 1.0;
  if (Qs.norm() > 0.0 && G.norm() > 0.0) s = std::sqrt(Qs.norm() / G.norm());

  // H = [A, -G; -Q, -A^T]: its stable invariant subspace is spanned by [I; X]
  MatrixXd H(2 * n, 2 * n);
  H << A, -s * G, -Qs / s, -A.transpose();
  const MatrixXd W = matrix_sign(fn, H);
  // A Hamiltonian matrix without imaginary eigenvalues has n on each side, so trace(W) = 0
  if (std::abs(W.trace()) > 0.5)
    no_solution(fn,
                "the Hamiltonian matrix does not have n eigenvalues in each half-plane "
                "(eigenvalues on the imaginary axis)");

  // (W + I) [I; Y] = 0: solve [W12; W22 + I] Y = -[W11 + I; W21] in the least-squares sense
  const MatrixXd I = MatrixXd::Identity(n, n);
  MatrixXd lhs(2 * n, n), rhs(2 * n, n);
  lhs << W.topRightCorner(n, n), W.bottomRightCorner(n, n) + I;
  rhs << -(W.topLeftCorner(n, n) + I), -W.bottomLeftCorner(n, n);
  const Eigen::ColPivHouseholderQR<MatrixXd> qr(lhs);
  if (qr.rank() < n)
    no_solution(fn,
                "the stable invariant subspace of the Hamiltonian matrix is not of the form "
                "[I; X] ((A, B) not stabilizable?)");
  MatrixXd X = s * qr.solve(rhs);
  X = 0.5 * (X + X.transpose()).eval();
  if (!X.allFinite()) no_solution(fn, "the computed X is not finite ((A, B) not stabilizable?)");

  // Newton steps on the Riccati equation itself, kept only while they reduce the residual:
  // the sign function's X carries the conditioning of H, the Newton step that of the CARE.
  double relative = relative_residual(A, G, Qs, X);
  for (int step = 0; step < 2 && relative > 10 * kEps; ++step) {
    MatrixXd D;
    if (!solve_lyapunov(A - G * X, -care_residual(A, G, Qs, X), D)) break;
    const MatrixXd candidate = X + D;
    const double candidate_relative = relative_residual(A, G, Qs, candidate);
    if (!(candidate_relative < relative)) break;
    X = candidate;
    relative = candidate_relative;
  }

  if (!(relative <= kResidualTolerance)) {
    std::ostringstream why;
    why << "the residual of the computed X is " << relative
        << " of its terms' size (ill-conditioned, or (A, B) not stabilizable)";
    no_solution(fn, why.str());
  }
  const double abscissa = closed_loop_abscissa(A, G, X);
  if (!(abscissa < 0.0)) {
    std::ostringstream why;
    why << "A - B R^-1 B^T X has an eigenvalue with real part " << abscissa
        << " >= 0 ((A, B) not stabilizable, or (Q, A) has an unobservable mode on the "
           "imaginary axis)";
    no_solution(fn, why.str());
  }
  return X;
}

}  // namespace

Eigen::MatrixXd solve_continuous_are(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                     const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R) {
  const char* fn = "solve_continuous_are";
  return solve_care(fn, A, B, Q, check_arguments(fn, A, B, Q, R));
}

Eigen::MatrixXd lqr_gain(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                         const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R) {
  const char* fn = "lqr_gain";
  const Eigen::LLT<MatrixXd> R_llt = check_arguments(fn, A, B, Q, R);
  const MatrixXd X = solve_care(fn, A, B, Q, R_llt);
  return R_llt.solve(B.transpose() * X);
}

}  // namespace gencoord
