// SPDX-License-Identifier: BSD-3-Clause
// MuJoCo's free joint as the reference for a generated model with a free-floating base.
//
// The generated model's first chart moves the base link by x, y, z (the link frame's origin
// in the world) and three Euler angles of one of python/gencoord/dsl/joints.py's EULER_CHARTS (zyx:
// R = Rz(yaw) Ry(pitch) Rx(roll); yzx: R = Ry(heading) Rz(attitude) Rx(bank)); its velocities
// are the coordinates' time derivatives. MuJoCo's free joint has qpos = (x, y, z, qw, qx, qy,
// qz), the same origin and R as a unit quaternion, and qvel = (the origin's velocity in world
// axes, the angular velocity in the base's own axes). So qvel = T v with
// T = diag(I, E(angles), I), E the chart's map from the angle rates to the body angular
// velocity and I on the joints (rows in MuJoCo's order), and MuJoCo's qacc = T qdd + Tdot v.
// Virtual power gives the generated model's forces from MuJoCo's as T^T f; hence
//   Mt = T^T M T,   Ft + Fi = -T^T (c + M Tdot v),   tau = T^T (M qacc + c).
// Contacts and joint-limit constraints are switched off (load_smooth_model).
#pragma once

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string>

#include <mujoco/mujoco.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mujoco_model.hpp"

namespace gencoord::robot_testing {

/// An Euler chart: R = Ra(q0) Rb(q1) Rc(q2), rotations about the fixed axes a, b, c (0, 1, 2:
/// x, y, z), outermost (world) first; singular where the middle angle q1 is +-pi/2. One
/// formula for every axis order, so the charts cannot drift apart.
struct EulerChart {
  const char* name;
  std::array<const char*, 3> angles;  // the generated model's names for q0, q1, q2
  std::array<int, 3> axes;

  Eigen::Vector3d axis(int i) const { return Eigen::Vector3d::Unit(axes[i]); }

  Eigen::AngleAxisd rotation(int i, double angle) const {
    return Eigen::AngleAxisd(angle, axis(i));
  }

  /// R as a unit quaternion (w, x, y, z): the product of the three rotations' quaternions.
  Eigen::Vector4d quaternion(const Eigen::Vector3d& q) const {
    const Eigen::Quaterniond r = rotation(0, q[0]) * rotation(1, q[1]) * rotation(2, q[2]);
    return {r.w(), r.x(), r.y(), r.z()};
  }

  /// E(q): the angular velocity in the body's axes, R^T Rdot = q2' c + Rc^T q1' b +
  /// Rc^T Rb^T q0' a, is E q'; column i is angle i's axis seen from the body, through the
  /// rotations inside it.
  Eigen::Matrix3d body_rates(const Eigen::Vector3d& q) const {
    const Eigen::Matrix3d inner = rotation(2, q[2]).inverse().toRotationMatrix();
    Eigen::Matrix3d e;
    e.col(0) = inner * (rotation(1, q[1]).inverse() * axis(0));
    e.col(1) = inner * axis(1);
    e.col(2) = axis(2);
    return e;
  }

  /// Edot q': what the body angular acceleration has beyond E q''. With w_i = E.col(i) q_i',
  /// each column turns with the angular velocity of the rotations inside it (w_2 for column
  /// 1, w_1 + w_2 for column 0), so Edot q' = w_0 x w_1 + (w_0 + w_1) x w_2.
  Eigen::Vector3d body_rates_bias(const Eigen::Vector3d& q, const Eigen::Vector3d& rates) const {
    const Eigen::Matrix3d e = body_rates(q);
    const Eigen::Vector3d w0 = e.col(0) * rates[0], w1 = e.col(1) * rates[1];
    const Eigen::Vector3d w2 = e.col(2) * rates[2];
    return w0.cross(w1) + (w0 + w1).cross(w2);
  }
};

// python/gencoord/dsl/joints.py's EULER_CHARTS, in its order
inline constexpr std::array<EulerChart, 2> kEulerCharts{{
    {"zyx", {{"yaw", "pitch", "roll"}}, {{2, 1, 0}}},
    {"yzx", {{"heading", "attitude", "bank"}}, {{1, 2, 0}}},
}};

/// The chart whose angles the generated model M's coordinates 3 to 5 are, or an error.
template <class M>
const EulerChart& euler_chart_of() {
  for (const EulerChart& chart : kEulerCharts) {
    const auto same = [](const char* a, const char* b) { return std::strcmp(a, b) == 0; };
    if (std::equal(chart.angles.begin(), chart.angles.end(), M::coordinate_names.begin() + 3,
                   same)) {
      return chart;
    }
  }
  throw std::runtime_error(std::string(M::name) + ": coordinates 3 to 5 (" +
                           M::coordinate_names[3] + ", " + M::coordinate_names[4] + ", " +
                           M::coordinate_names[5] + ") are the angles of no Euler chart");
}

/// MuJoCo on a URDF whose floating joint frees the base, against a generated model M's
/// first chart (coordinates x, y, z, the three angles of an Euler chart, then the joints, each
/// named after its joint). Vectors of MuJoCo's degrees of freedom are in MuJoCo's order; the
/// others in M's.
template <class M>
class FreeBaseReference {
 public:
  static constexpr int nv = M::nq;      // MuJoCo's degrees of freedom: the free joint has 6
  static constexpr int nq = M::nq + 1;  // its positions: the quaternion has 4
  using QVec = Eigen::Matrix<double, M::nq, 1>;
  using QMat = Eigen::Matrix<double, M::nq, M::nq>;
  using PosVec = Eigen::Matrix<double, nq, 1>;

  explicit FreeBaseReference(const std::string& urdf_path)
      : model_(load_smooth_model(urdf_path)), chart_(&euler_chart_of<M>()) {
    use_joint_friction_of<M>();
    if (model_->nq != nq || model_->nv != nv) {
      throw std::runtime_error(urdf_path + ": MuJoCo has nq = " + std::to_string(model_->nq) +
                               " and nv = " + std::to_string(model_->nv) +
                               "; a free base and the generated model's joints make " +
                               std::to_string(nq) + " and " + std::to_string(nv));
    }
    const std::array<const char*, 3> origin{{"x", "y", "z"}};
    for (int i = 0; i < 3; ++i) {
      if (std::strcmp(M::coordinate_names[i], origin[i]) != 0) {
        throw std::runtime_error(std::string("the generated model's coordinate ") +
                                 std::to_string(i) + " is " + M::coordinate_names[i] +
                                 ", not the base's " + origin[i]);
      }
    }
    data_.reset(mj_makeData(model_.get()));
    for (int j = 0; j < model_->njnt; ++j) {
      if (model_->jnt_type[j] == mjJNT_FREE) free_ = j;
    }
    if (free_ < 0) throw std::runtime_error(urdf_path + ": MuJoCo has no free joint");
    for (int i = 6; i < M::nq; ++i) {
      const int joint = joint_called(model_.get(), urdf_path, M::coordinate_names[i]);
      qpos_[i] = model_->jnt_qposadr[joint];
      dof_[i] = model_->jnt_dofadr[joint];
    }
  }

  mjModel* model() { return model_.get(); }
  mjData* data() { return data_.get(); }
  const EulerChart& chart() const { return *chart_; }

  /// MuJoCo's qpos for the generated model's q.
  PosVec qpos(const QVec& q) const {
    PosVec out = PosVec::Zero();
    const int base = model_->jnt_qposadr[free_];
    out.template segment<3>(base) = q.template head<3>();
    out.template segment<4>(base + 3) = chart_->quaternion(q.template segment<3>(3));
    for (int i = 6; i < M::nq; ++i) out[qpos_[i]] = q[i];
    return out;
  }

  /// T = d qvel / d v at q: the origin's velocity as is, the angle rates to the body
  /// angular velocity, the joints' rates as they are.
  QMat velocity_map(const QVec& q) const {
    QMat t = QMat::Zero();
    const int base = model_->jnt_dofadr[free_];
    t.template block<3, 3>(base, 0).setIdentity();
    t.template block<3, 3>(base + 3, 3) = chart_->body_rates(q.template segment<3>(3));
    for (int i = 6; i < M::nq; ++i) t(dof_[i], i) = 1.0;
    return t;
  }

  /// Tdot v at (q, v): MuJoCo's qacc is T qdd + Tdot v.
  QVec velocity_map_bias(const QVec& q, const QVec& v) const {
    QVec out = QVec::Zero();
    out.template segment<3>(model_->jnt_dofadr[free_] + 3) =
        chart_->body_rates_bias(q.template segment<3>(3), v.template segment<3>(3));
    return out;
  }

  /// Sets MuJoCo's state to the generated model's (q, v).
  void set(const QVec& q, const QVec& v) {
    Eigen::Map<PosVec>(data_->qpos) = qpos(q);
    Eigen::Map<QVec>(data_->qvel) = velocity_map(q) * v;
    data_->time = 0.0;
    t_ = velocity_map(q);
    tdot_v_ = velocity_map_bias(q, v);
  }

  /// set(q, v) and mj_forward.
  void forward(const QVec& q, const QVec& v) {
    set(q, v);
    mj_forward(model_.get(), data_.get());
  }

  PosVec qpos() const { return Eigen::Map<const PosVec>(data_->qpos); }
  /// MuJoCo's qacc from the last forward().
  QVec qacc() const { return Eigen::Map<const QVec>(data_->qacc); }
  /// The generated model's accelerations qdd at the last set()'s (q, v) as MuJoCo's qacc.
  QVec qacc_from(const QVec& qdd) const { return t_ * qdd + tdot_v_; }

  /// MuJoCo's joint-space inertia matrix from the last forward(), in its own coordinates.
  QMat mujoco_mass_matrix() const {
    Eigen::Matrix<double, nv, nv, Eigen::RowMajor> full;
    mj_fullM(model_.get(), full.data(), data_->qM);
    return full;
  }

  /// T^T M T: the inertia matrix in the generated model's coordinates.
  QMat mass_matrix() const { return t_.transpose() * mujoco_mass_matrix() * t_; }

  /// T^T (c + M Tdot v) with c = qfrc_bias - qfrc_passive: the generated model's Ft + Fi is
  /// its negative.
  QVec bias() const {
    const QVec c =
        Eigen::Map<const QVec>(data_->qfrc_bias) - Eigen::Map<const QVec>(data_->qfrc_passive);
    return t_.transpose() * (c + mujoco_mass_matrix() * tdot_v_);
  }

  /// Inverse dynamics at the last forward()'s (q, v) for the generated model's
  /// accelerations qdd: T^T (M qacc + c) by mj_rne at qacc = T qdd + Tdot v.
  QVec inverse_dynamics(const QVec& qdd) {
    Eigen::Map<QVec>(data_->qacc) = qacc_from(qdd);
    QVec result;
    mj_rne(model_.get(), data_.get(), 1, result.data());
    return t_.transpose() * (result - Eigen::Map<const QVec>(data_->qfrc_passive));
  }

  /// MuJoCo's velocity that takes qpos `from` to `to` in unit time (mj_differentiatePos): the
  /// origin's displacement, the rotation vector in the body's axes, the joints' differences.
  QVec difference(const PosVec& from, const PosVec& to) const {
    QVec out;
    mj_differentiatePos(model_.get(), out.data(), 1.0, from.data(), to.data());
    return out;
  }

 private:
  ModelPtr model_;
  const EulerChart* chart_;  // one of kEulerCharts
  DataPtr data_;
  int free_ = -1;
  std::array<int, M::nq> qpos_{};  // the joints' entries (from 6 on) of qpos and qvel
  std::array<int, M::nq> dof_{};
  QMat t_ = QMat::Identity();
  QVec tdot_v_ = QVec::Zero();
};

}  // namespace gencoord::robot_testing
