// SPDX-License-Identifier: BSD-3-Clause
// A hand-written model with generalized speeds (docs/model_interface.md): a free rigid body
// whose orientation is a unit quaternion, so the runtime's speeds path is tested without the
// generator.
//
//   q = (x, y, z, qw, qx, qy, qz)   centre of mass in world axes; orientation body -> world
//   v = (vx, vy, vz, wx, wy, wz)    centre-of-mass velocity and angular velocity, body axes
//   q' = G(q) v:  x' = R v_b,  quat' = 1/2 quat (x) (0, omega)
//   Newton-Euler in body axes:  m (v_b' + omega x v_b) = R^T (0, 0, -m g),
//                               I omega' + omega x I omega = 0,   I = diag(I1, I2, I3).
//
// Its particles are six point masses m/6 at +-a_k along the body axes, a_k chosen so that they
// have the inertia I (which needs the triangle inequalities I_i <= I_j + I_k); J^T M J is then
// Mt = diag(m, m, m, I1, I2, I3), and velocities, energy and momenta agree with the particles.
#pragma once

#include <array>
#include <cmath>
#include <string>

#include <Eigen/Dense>

namespace gencoord::test_models {

struct FreeBody {
  static constexpr const char* name = "free_body";
  static constexpr int nq = 7;
  static constexpr int nv = 6;
  static constexpr int dim = 3;
  static constexpr int num_particles = 6;
  static constexpr int nx = dim * num_particles;
  static constexpr int angular_dim = 3;
  static constexpr std::array<const char*, nq> coordinate_names{
      {"x", "y", "z", "qw", "qx", "qy", "qz"}};
  static constexpr std::array<const char*, nv> speed_names{{"vx", "vy", "vz", "wx", "wy", "wz"}};
  static constexpr std::array<const char*, num_particles> particle_names{
      {"e1p", "e1m", "e2p", "e2m", "e3p", "e3m"}};
  static constexpr int num_quaternions = 1;
  static constexpr std::array<int, num_quaternions> quaternion_starts{{3}};
  static constexpr std::array<double, nq> initial_q{{0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0}};
  static constexpr std::array<double, nv> initial_v{{0.0, 0.0, 0.0, 0.0, 0.0, 0.0}};

  template <typename S>
  using QVector = Eigen::Matrix<S, nq, 1>;
  template <typename S>
  using QMatrix = Eigen::Matrix<S, nq, nq>;
  template <typename S>
  using VVector = Eigen::Matrix<S, nv, 1>;
  template <typename S>
  using VMatrix = Eigen::Matrix<S, nv, nv>;
  template <typename S>
  using VQMatrix = Eigen::Matrix<S, nv, nq>;
  template <typename S>
  using XVector = Eigen::Matrix<S, nx, 1>;
  template <typename S>
  using XJacobian = Eigen::Matrix<S, nx, nv>;
  template <typename S>
  using SpaceVector = Eigen::Matrix<S, dim, 1>;
  template <typename S>
  using AngularVector = Eigen::Matrix<S, angular_dim, 1>;
  template <typename S>
  using ParticleVector = Eigen::Matrix<S, num_particles, 1>;

  struct Params {
    double m = 2.0;   // mass (kg)
    double I1 = 1.0;  // principal moments of inertia (kg m^2), all different
    double I2 = 1.5;
    double I3 = 2.0;
    double g = 9.81;  // gravitational acceleration along -z (m/s^2)

    double* find(const std::string& name) {
      if (name == "m") return &m;
      if (name == "I1") return &I1;
      if (name == "I2") return &I2;
      if (name == "I3") return &I3;
      if (name == "g") return &g;
      return nullptr;
    }
  };

  template <typename S>
  using Matrix3 = Eigen::Matrix<S, 3, 3>;
  template <typename S>
  using Vector3 = Eigen::Matrix<S, 3, 1>;

  // R(quat), body -> world; the unit-quaternion formula, also used off the unit sphere
  template <typename S>
  static Matrix3<S> rotation(const QVector<S>& q) {
    const S w = q[3], x = q[4], y = q[5], z = q[6];
    Matrix3<S> R;
    R << 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),  //
        2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),   //
        2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y);
    return R;
  }
  template <typename S>
  static Matrix3<S> skew(const Vector3<S>& a) {
    Matrix3<S> K;
    K << S(0), -a[2], a[1], a[2], S(0), -a[0], -a[1], a[0], S(0);
    return K;
  }
  template <typename S>
  static Vector3<S> inertia(const Params& p) {
    return Vector3<S>(S(p.I1), S(p.I2), S(p.I3));
  }
  // body point of particle k: +-a_j e_j, 2 mu (a_j^2 + a_k^2) = I_i for {i, j, k} = {1, 2, 3}
  template <typename S>
  static Vector3<S> body_point(int k, const Params& p) {
    using std::sqrt;
    const double four_mu = 4.0 * p.m / num_particles;
    const double a[3] = {sqrt((p.I2 + p.I3 - p.I1) / four_mu), sqrt((p.I1 + p.I3 - p.I2) / four_mu),
                         sqrt((p.I1 + p.I2 - p.I3) / four_mu)};
    Vector3<S> r = Vector3<S>::Zero();
    r[k / 2] = S(k % 2 == 0 ? a[k / 2] : -a[k / 2]);
    return r;
  }

  template <typename S>
  static QVector<S> coordinate_rates(const QVector<S>& q, const VVector<S>& v, const S&,
                                     const Params&) {
    const S w = q[3], x = q[4], y = q[5], z = q[6];
    const S wx = v[3], wy = v[4], wz = v[5];
    QVector<S> rate;
    rate.template head<3>() = rotation(q) * v.template head<3>();
    rate[3] = -(x * wx + y * wy + z * wz) / 2;
    rate[4] = (w * wx + y * wz - z * wy) / 2;
    rate[5] = (w * wy + z * wx - x * wz) / 2;
    rate[6] = (w * wz + x * wy - y * wx) / 2;
    return rate;
  }

  template <typename S>
  static VMatrix<S> mass_matrix(const QVector<S>&, const S&, const Params& p) {
    VVector<S> d;
    d << S(p.m), S(p.m), S(p.m), S(p.I1), S(p.I2), S(p.I3);
    return d.asDiagonal();
  }
  template <typename S>
  static VVector<S> applied_forces(const QVector<S>& q, const VVector<S>&, const S&,
                                   const Params& p) {
    VVector<S> f = VVector<S>::Zero();
    f.template head<3>() = rotation(q).transpose() * Vector3<S>(S(0), S(0), S(-p.m * p.g));
    return f;
  }
  template <typename S>
  static VVector<S> inertial_forces(const QVector<S>&, const VVector<S>& v, const S&,
                                    const Params& p) {
    const Vector3<S> vb = v.template head<3>(), omega = v.template tail<3>();
    VVector<S> f;
    f.template head<3>() = -S(p.m) * omega.cross(vb);
    f.template tail<3>() = -omega.cross(inertia<S>(p).cwiseProduct(omega));
    return f;
  }
  template <typename S>
  static VVector<S> forces(const QVector<S>& q, const VVector<S>& v, const S& t, const Params& p) {
    return applied_forces(q, v, t, p) + inertial_forces(q, v, t, p);
  }
  template <typename S>
  static void dynamics(const QVector<S>& q, const VVector<S>& v, const S& t, const Params& p,
                       VMatrix<S>* Mt, VVector<S>* f) {
    if (Mt) *Mt = mass_matrix(q, t, p);
    if (f) *f = forces(q, v, t, p);
  }
  template <typename S>
  static VVector<S> qddot(const QVector<S>& q, const VVector<S>& v, const S& t, const Params& p) {
    return forces(q, v, t, p).cwiseQuotient(mass_matrix(q, t, p).diagonal());
  }
  template <typename S>
  static VVector<S> inverse_dynamics(const QVector<S>& q, const VVector<S>& v,
                                     const VVector<S>& vdot, const S& t, const Params& p) {
    return mass_matrix(q, t, p) * vdot - forces(q, v, t, p);
  }
  // r = Mt v' - F: gravity's R^T e_z gives dr/dq, the gyroscopic terms dr/dv
  template <typename S>
  static void residual_jacobians(const QVector<S>& q, const VVector<S>& v, const VVector<S>&,
                                 const S&, const Params& p, VQMatrix<S>* dr_dq, VMatrix<S>* dr_dv) {
    const S w = q[3], x = q[4], y = q[5], z = q[6];
    const Vector3<S> vb = v.template head<3>(), omega = v.template tail<3>();
    const Vector3<S> I = inertia<S>(p);
    Eigen::Matrix<S, 3, 4> d_row3;           // d(R^T e_z)/d(w, x, y, z)
    d_row3 << -2 * y, 2 * z, -2 * w, 2 * x,  //
        2 * x, 2 * w, 2 * z, 2 * y,          //
        S(0), -4 * x, -4 * y, S(0);
    dr_dq->setZero();
    dr_dq->template block<3, 4>(0, 3) = S(p.m * p.g) * d_row3;
    dr_dv->setZero();
    dr_dv->template block<3, 3>(0, 0) = S(p.m) * skew(omega);
    dr_dv->template block<3, 3>(0, 3) = -S(p.m) * skew(vb);
    dr_dv->template block<3, 3>(3, 3) =
        skew(omega) * I.asDiagonal().toDenseMatrix() - skew<S>(I.cwiseProduct(omega));
  }

  template <typename S>
  static S kinetic_energy(const QVector<S>&, const VVector<S>& v, const S&, const Params& p) {
    const Vector3<S> vb = v.template head<3>(), omega = v.template tail<3>();
    return S(0.5 * p.m) * vb.squaredNorm() + S(0.5) * omega.dot(inertia<S>(p).cwiseProduct(omega));
  }
  template <typename S>
  static S potential_energy(const QVector<S>& q, const S&, const Params& p) {
    return S(p.m * p.g) * q[2];
  }
  template <typename S>
  static S energy(const QVector<S>& q, const VVector<S>& v, const S& t, const Params& p) {
    return kinetic_energy(q, v, t, p) + potential_energy(q, t, p);
  }
  template <typename S>
  static XVector<S> positions(const QVector<S>& q, const S&, const Params& p) {
    const Matrix3<S> R = rotation(q);
    XVector<S> x;
    for (int k = 0; k < num_particles; ++k)
      x.template segment<3>(3 * k) = q.template head<3>() + R * body_point<S>(k, p);
    return x;
  }
  // xdot_k = R (v_b + omega x r_k) = R v_b - R [r_k]x omega
  template <typename S>
  static XJacobian<S> jacobian(const QVector<S>& q, const S&, const Params& p) {
    const Matrix3<S> R = rotation(q);
    XJacobian<S> J;
    for (int k = 0; k < num_particles; ++k) {
      J.template block<3, 3>(3 * k, 0) = R;
      J.template block<3, 3>(3 * k, 3) = -R * skew(body_point<S>(k, p));
    }
    return J;
  }
  template <typename S>
  static XVector<S> velocities(const QVector<S>& q, const VVector<S>& v, const S& t,
                               const Params& p) {
    return jacobian(q, t, p) * v;
  }
  // xddot_k at v' = 0: R omega x (v_b + omega x r_k)
  template <typename S>
  static XVector<S> bias_acceleration(const QVector<S>& q, const VVector<S>& v, const S&,
                                      const Params& p) {
    const Matrix3<S> R = rotation(q);
    const Vector3<S> vb = v.template head<3>(), omega = v.template tail<3>();
    XVector<S> a;
    for (int k = 0; k < num_particles; ++k)
      a.template segment<3>(3 * k) = R * omega.cross(vb + omega.cross(body_point<S>(k, p)));
    return a;
  }
  template <typename S>
  static SpaceVector<S> linear_momentum(const QVector<S>& q, const VVector<S>& v, const S&,
                                        const Params& p) {
    return S(p.m) * (rotation(q) * v.template head<3>());
  }
  // about the world origin, world axes: m x (R v_b) + R I omega
  template <typename S>
  static AngularVector<S> angular_momentum(const QVector<S>& q, const VVector<S>& v, const S&,
                                           const Params& p) {
    const Matrix3<S> R = rotation(q);
    const Vector3<S> x = q.template head<3>(), omega = v.template tail<3>();
    return S(p.m) * x.cross(R * v.template head<3>()) + R * inertia<S>(p).cwiseProduct(omega);
  }
  template <typename S>
  static ParticleVector<S> particle_masses(const Params& p) {
    return ParticleVector<S>::Constant(S(p.m / num_particles));
  }
};

}  // namespace gencoord::test_models
