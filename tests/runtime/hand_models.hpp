// SPDX-License-Identifier: BSD-3-Clause
// Hand-written models satisfying docs/model_interface.md, so the runtime can be tested
// independently of the generator. Written the way generated code will look: static members,
// templated on Scalar.
#pragma once

#include <array>
#include <cmath>

#include <Eigen/Dense>

namespace gencoord::test_models {

// What the hand models share (CRTP: Model derives from HandModel<Model, ...>): the sizes and
// types of docs/model_interface.md for Nq coordinates and NumParticles particles in Dim
// dimensions, and the members that follow from a model's own, written as the generator writes
// them: forces = applied + inertial, dynamics, qddot = Mt^-1 f, the kinetic energy
// v^T Mt v / 2, energy = kinetic + potential, velocities = J v and the momenta J Mt v and
// x cross it. A model's own member of the same name hides the one here. (The Model argument is
// a defaulted template parameter of each member, so that Model is complete when it is used.)
template <class Model, int Nq, int Dim, int NumParticles>
struct HandModel {
  static constexpr int nq = Nq;
  static constexpr int dim = Dim;
  static constexpr int num_particles = NumParticles;
  static constexpr int nx = dim * num_particles;
  static constexpr int angular_dim = dim == 3 ? 3 : 1;

  template <typename S>
  using QVector = Eigen::Matrix<S, nq, 1>;
  template <typename S>
  using QMatrix = Eigen::Matrix<S, nq, nq>;
  template <typename S>
  using XVector = Eigen::Matrix<S, nx, 1>;
  template <typename S>
  using XJacobian = Eigen::Matrix<S, nx, nq>;
  template <typename S>
  using SpaceVector = Eigen::Matrix<S, dim, 1>;
  template <typename S>
  using AngularVector = Eigen::Matrix<S, angular_dim, 1>;
  template <typename S>
  using ParticleVector = Eigen::Matrix<S, num_particles, 1>;

  template <typename S, class M = Model>
  static QVector<S> forces(const QVector<S>& q, const QVector<S>& v, const S& t,
                           const typename M::Params& p) {
    return M::applied_forces(q, v, t, p) + M::inertial_forces(q, v, t, p);
  }
  template <typename S, class M = Model>
  static void dynamics(const QVector<S>& q, const QVector<S>& v, const S& t,
                       const typename M::Params& p, QMatrix<S>* Mt, QVector<S>* f) {
    if (Mt) *Mt = M::mass_matrix(q, t, p);
    if (f) *f = M::forces(q, v, t, p);
  }
  template <typename S, class M = Model>
  static QVector<S> qddot(const QVector<S>& q, const QVector<S>& v, const S& t,
                          const typename M::Params& p) {
    return M::mass_matrix(q, t, p).llt().solve(M::forces(q, v, t, p));
  }
  template <typename S, class M = Model>
  static S kinetic_energy(const QVector<S>& q, const QVector<S>& v, const S& t,
                          const typename M::Params& p) {
    return S(0.5) * v.dot(M::mass_matrix(q, t, p) * v);
  }
  template <typename S, class M = Model>
  static S energy(const QVector<S>& q, const QVector<S>& v, const S& t,
                  const typename M::Params& p) {
    return M::kinetic_energy(q, v, t, p) + M::potential_energy(q, t, p);
  }
  template <typename S, class M = Model>
  static XVector<S> velocities(const QVector<S>& q, const QVector<S>& v, const S& t,
                               const typename M::Params& p) {
    return M::jacobian(q, t, p) * v;
  }
  template <typename S, class M = Model>
  static SpaceVector<S> linear_momentum(const QVector<S>& q, const QVector<S>& v, const S& t,
                                        const typename M::Params& p) {
    return M::jacobian(q, t, p) * (M::mass_matrix(q, t, p) * v);
  }
  template <typename S, class M = Model>
  static AngularVector<S> angular_momentum(const QVector<S>& q, const QVector<S>& v, const S& t,
                                           const typename M::Params& p) {
    return M::positions(q, t, p).cross(M::linear_momentum(q, v, t, p));
  }
};

// Planar pendulum: a bob of mass m on a massless rod of length l, angle theta from the
// downward vertical.
//
//        O
//        |\  l (rod)
//        |θ\ .
//        |  o bob   x = (l sin θ, -l cos θ)
//
// Mt = m l^2, Ft = -m g l sin θ, Fi = 0, so  m l^2 θ'' = -m g l sin θ.
struct HandPendulum : HandModel<HandPendulum, 1, 2, 1> {
  static constexpr const char* name = "hand_pendulum";
  static constexpr std::array<const char*, nq> coordinate_names{{"theta"}};
  static constexpr std::array<const char*, num_particles> particle_names{{"bob"}};

  struct Params {
    double l = 1.0;   // rod length (m)
    double m = 1.0;   // bob mass (kg)
    double g = 9.81;  // gravitational acceleration (m/s^2)
  };

  template <typename S>
  static QMatrix<S> mass_matrix(const QVector<S>&, const S&, const Params& p) {
    return QMatrix<S>::Constant(S(p.m * p.l * p.l));
  }
  template <typename S>
  static QVector<S> applied_forces(const QVector<S>& q, const QVector<S>&, const S&,
                                   const Params& p) {
    using std::sin;
    return QVector<S>::Constant(-p.m * p.g * p.l * sin(q[0]));
  }
  template <typename S>
  static QVector<S> inertial_forces(const QVector<S>&, const QVector<S>&, const S&, const Params&) {
    return QVector<S>::Zero();
  }
  template <typename S>
  static S kinetic_energy(const QVector<S>&, const QVector<S>& v, const S&, const Params& p) {
    return S(0.5 * p.m * p.l * p.l) * v[0] * v[0];
  }
  template <typename S>
  static S potential_energy(const QVector<S>& q, const S&, const Params& p) {
    using std::cos;
    return -p.m * p.g * p.l * cos(q[0]);
  }
  template <typename S>
  static XVector<S> positions(const QVector<S>& q, const S&, const Params& p) {
    using std::cos;
    using std::sin;
    return XVector<S>(p.l * sin(q[0]), -p.l * cos(q[0]));
  }
  template <typename S>
  static XJacobian<S> jacobian(const QVector<S>& q, const S&, const Params& p) {
    using std::cos;
    using std::sin;
    return XJacobian<S>(p.l * cos(q[0]), p.l * sin(q[0]));
  }
  template <typename S>
  static XVector<S> bias_acceleration(const QVector<S>& q, const QVector<S>& v, const S&,
                                      const Params& p) {
    using std::cos;
    using std::sin;
    return XVector<S>(-p.l * sin(q[0]), p.l * cos(q[0])) * (v[0] * v[0]);
  }
  template <typename S>
  static SpaceVector<S> linear_momentum(const QVector<S>& q, const QVector<S>& v, const S& t,
                                        const Params& p) {
    return p.m * velocities(q, v, t, p);
  }
  template <typename S>
  static AngularVector<S> angular_momentum(const QVector<S>&, const QVector<S>& v, const S&,
                                           const Params& p) {
    return AngularVector<S>::Constant(p.m * p.l * p.l * v[0]);
  }
  template <typename S>
  static ParticleVector<S> particle_masses(const Params& p) {
    return ParticleVector<S>::Constant(S(p.m));
  }
};

// Driven, damped harmonic oscillator: a mass on a line, x = (q, 0).
//   m q'' = -k q - c q' + F0 cos(Ω t)
// With F0 = 0 and c^2 < 4 k m the exact solution is oscillator_exact().
struct HandOscillator : HandModel<HandOscillator, 1, 2, 1> {
  static constexpr const char* name = "hand_oscillator";
  static constexpr std::array<const char*, nq> coordinate_names{{"q"}};
  static constexpr std::array<const char*, num_particles> particle_names{{"mass"}};

  struct Params {
    double m = 1.0;      // mass (kg)
    double k = 4.0;      // spring stiffness (N/m)
    double c = 0.0;      // damping (N s/m)
    double F0 = 0.0;     // drive amplitude (N)
    double Omega = 1.0;  // drive angular frequency (rad/s)
  };

  template <typename S>
  static QMatrix<S> mass_matrix(const QVector<S>&, const S&, const Params& p) {
    return QMatrix<S>::Constant(S(p.m));
  }
  template <typename S>
  static QVector<S> applied_forces(const QVector<S>& q, const QVector<S>& v, const S& t,
                                   const Params& p) {
    using std::cos;
    return QVector<S>::Constant(-p.k * q[0] - p.c * v[0] + p.F0 * cos(p.Omega * t));
  }
  template <typename S>
  static QVector<S> inertial_forces(const QVector<S>&, const QVector<S>&, const S&, const Params&) {
    return QVector<S>::Zero();
  }
  template <typename S>
  static QVector<S> qddot(const QVector<S>& q, const QVector<S>& v, const S& t, const Params& p) {
    return forces(q, v, t, p) / S(p.m);
  }
  template <typename S>
  static S kinetic_energy(const QVector<S>&, const QVector<S>& v, const S&, const Params& p) {
    return S(0.5 * p.m) * v[0] * v[0];
  }
  template <typename S>
  static S potential_energy(const QVector<S>& q, const S&, const Params& p) {
    return S(0.5 * p.k) * q[0] * q[0];
  }
  template <typename S>
  static XVector<S> positions(const QVector<S>& q, const S&, const Params&) {
    return XVector<S>(q[0], S(0));
  }
  template <typename S>
  static XJacobian<S> jacobian(const QVector<S>&, const S&, const Params&) {
    return XJacobian<S>(S(1), S(0));
  }
  template <typename S>
  static XVector<S> velocities(const QVector<S>&, const QVector<S>& v, const S&, const Params&) {
    return XVector<S>(v[0], S(0));
  }
  template <typename S>
  static XVector<S> bias_acceleration(const QVector<S>&, const QVector<S>&, const S&,
                                      const Params&) {
    return XVector<S>::Zero();
  }
  template <typename S>
  static SpaceVector<S> linear_momentum(const QVector<S>& q, const QVector<S>& v, const S& t,
                                        const Params& p) {
    return p.m * velocities(q, v, t, p);
  }
  template <typename S>
  static AngularVector<S> angular_momentum(const QVector<S>&, const QVector<S>&, const S&,
                                           const Params&) {
    return AngularVector<S>::Zero();  // the mass moves along the x axis through the origin
  }
  template <typename S>
  static ParticleVector<S> particle_masses(const Params& p) {
    return ParticleVector<S>::Constant(S(p.m));
  }
};

/// Exact (q, v) of the undriven, underdamped HandOscillator (F0 = 0, c^2 < 4 k m) at time t,
/// from q(0) = q0, v(0) = v0.
inline Eigen::Vector2d oscillator_exact(const HandOscillator::Params& p, double q0, double v0,
                                        double t) {
  const double w0 = std::sqrt(p.k / p.m);
  const double zeta = p.c / (2.0 * std::sqrt(p.k * p.m));
  const double wd = w0 * std::sqrt(1.0 - zeta * zeta);
  const double decay = zeta * w0;
  const double a = q0, b = (v0 + decay * q0) / wd;  // q = e^{-decay t} (a cos + b sin)
  const double e = std::exp(-decay * t), c = std::cos(wd * t), s = std::sin(wd * t);
  const double q = e * (a * c + b * s);
  const double v = -decay * q + e * wd * (-a * s + b * c);
  return {q, v};
}

// Two coordinates with a coupled mass matrix Mt = [[m1, c], [c, m2]] that parameters can make
// indefinite (c^2 >= m1 m2) or NaN, to exercise DynamicsError. One particle in 3D at
// x = (u, w, 0); Mt is deliberately not J^T M J (it is a test double, not physics).
//   Mt a = -k q + f_bias
struct HandCoupled : HandModel<HandCoupled, 2, 3, 1> {
  static constexpr const char* name = "hand_coupled";
  static constexpr std::array<const char*, nq> coordinate_names{{"u", "w"}};
  static constexpr std::array<const char*, num_particles> particle_names{{"body"}};

  struct Params {
    double m1 = 1.0;      // mass of u (kg)
    double m2 = 2.0;      // mass of w (kg)
    double c = 0.5;       // inertial coupling (kg); |c| >= sqrt(m1 m2) makes Mt indefinite
    double k = 3.0;       // spring stiffness of both coordinates (N/m)
    double f_bias = 0.0;  // constant force on u (N); NaN makes the forces non-finite
  };

  template <typename S>
  static QMatrix<S> mass_matrix(const QVector<S>&, const S&, const Params& p) {
    QMatrix<S> Mt;
    Mt << S(p.m1), S(p.c), S(p.c), S(p.m2);
    return Mt;
  }
  template <typename S>
  static QVector<S> applied_forces(const QVector<S>& q, const QVector<S>&, const S&,
                                   const Params& p) {
    return QVector<S>(-p.k * q[0] + p.f_bias, -p.k * q[1]);
  }
  template <typename S>
  static QVector<S> inertial_forces(const QVector<S>&, const QVector<S>&, const S&, const Params&) {
    return QVector<S>::Zero();
  }
  template <typename S>
  static S potential_energy(const QVector<S>& q, const S&, const Params& p) {
    return S(0.5 * p.k) * q.squaredNorm() - p.f_bias * q[0];
  }
  template <typename S>
  static XVector<S> positions(const QVector<S>& q, const S&, const Params&) {
    return XVector<S>(q[0], q[1], S(0));
  }
  template <typename S>
  static XJacobian<S> jacobian(const QVector<S>&, const S&, const Params&) {
    return XJacobian<S>::Identity();
  }
  template <typename S>
  static XVector<S> bias_acceleration(const QVector<S>&, const QVector<S>&, const S&,
                                      const Params&) {
    return XVector<S>::Zero();
  }
  template <typename S>
  static ParticleVector<S> particle_masses(const Params& p) {
    return ParticleVector<S>::Constant(S(p.m1));
  }
};

// N unit masses on a line, each held by a spring and a damper, their inertias coupled with
// their neighbours' and growing with the square of their own coordinate:
//   Mt_ii = 1 + 0.1 q_i^2,  Mt_i,i+1 = coupling,  f = -k q - c v + f_bias,
// so that the residual r = Mt(q) a - f has the closed-form Jacobians
//   dr/dq = diag(0.2 q_i a_i) + k I,  dr/dv = c I.
// Of any size, so that both of the derivative path's ways to Mt^-1 are exercised (the small
// dense kernels up to 24 coordinates, Eigen's Cholesky factor above).
template <int N>
struct HandSpringChain : HandModel<HandSpringChain<N>, N, 3, 1> {
  // the base depends on N, so its names are brought in
  using Base = HandModel<HandSpringChain<N>, N, 3, 1>;
  using Base::nq;
  using Base::num_particles;
  template <typename S>
  using QVector = typename Base::template QVector<S>;
  template <typename S>
  using QMatrix = typename Base::template QMatrix<S>;
  template <typename S>
  using XVector = typename Base::template XVector<S>;
  template <typename S>
  using XJacobian = typename Base::template XJacobian<S>;
  template <typename S>
  using ParticleVector = typename Base::template ParticleVector<S>;

  static constexpr const char* name = "hand_spring_chain";
  static constexpr std::array<const char*, nq> coordinate_names = [] {
    std::array<const char*, nq> names{};
    for (auto& name : names) name = "q";
    return names;
  }();
  static constexpr std::array<const char*, num_particles> particle_names{{"first"}};

  struct Params {
    double coupling = 0.2;  // inertial coupling of neighbours (kg); 3 makes Mt indefinite
    double k = 3.0;         // spring stiffness (N/m)
    double c = 0.5;         // damping (N s/m)
    double f_bias = 0.0;    // constant force on every mass (N); NaN makes the forces non-finite
  };

  template <typename S>
  static QMatrix<S> mass_matrix(const QVector<S>& q, const S&, const Params& p) {
    QMatrix<S> Mt = QMatrix<S>::Zero();
    for (int i = 0; i < nq; ++i) {
      Mt(i, i) = S(1) + S(0.1) * q[i] * q[i];
      if (i + 1 < nq) Mt(i, i + 1) = Mt(i + 1, i) = S(p.coupling);
    }
    return Mt;
  }
  template <typename S>
  static QVector<S> applied_forces(const QVector<S>& q, const QVector<S>& v, const S&,
                                   const Params& p) {
    return -p.k * q - p.c * v + QVector<S>::Constant(S(p.f_bias));
  }
  template <typename S>
  static QVector<S> inertial_forces(const QVector<S>&, const QVector<S>&, const S&, const Params&) {
    return QVector<S>::Zero();
  }
  template <typename S>
  static void residual_jacobians(const QVector<S>& q, const QVector<S>&, const QVector<S>& qdd,
                                 const S&, const Params& p, QMatrix<S>* dr_dq, QMatrix<S>* dr_dv) {
    *dr_dq = S(p.k) * QMatrix<S>::Identity();
    dr_dq->diagonal() += S(0.2) * q.cwiseProduct(qdd);
    *dr_dv = S(p.c) * QMatrix<S>::Identity();
  }
  template <typename S>
  static S potential_energy(const QVector<S>& q, const S&, const Params& p) {
    return S(0.5 * p.k) * q.squaredNorm() - p.f_bias * q.sum();
  }
  // the particle follows the first coordinate
  template <typename S>
  static XVector<S> positions(const QVector<S>& q, const S&, const Params&) {
    return XVector<S>(q[0], S(0), S(0));
  }
  template <typename S>
  static XJacobian<S> jacobian(const QVector<S>&, const S&, const Params&) {
    XJacobian<S> J = XJacobian<S>::Zero();
    J(0, 0) = S(1);
    return J;
  }
  template <typename S>
  static XVector<S> bias_acceleration(const QVector<S>&, const QVector<S>&, const S&,
                                      const Params&) {
    return XVector<S>::Zero();
  }
  template <typename S>
  static ParticleVector<S> particle_masses(const Params&) {
    return ParticleVector<S>::Constant(S(1));
  }
};

}  // namespace gencoord::test_models
