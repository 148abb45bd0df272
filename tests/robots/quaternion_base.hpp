// SPDX-License-Identifier: BSD-3-Clause
// MuJoCo's free joint as the reference for a generated model whose base is a free joint with
// a unit quaternion (the URDF's floating joint).
//
// The generated model's q starts with the base's position and quaternion (w, x, y, z), as
// MuJoCo's qpos does; its speeds start with the body twist, the origin's velocity v and the
// angular velocity w, both in the base's axes, where MuJoCo's qvel has the origin's velocity in
// world axes R v and the same w. So qvel = T v with T = diag(R, I, I), and MuJoCo's qacc =
// T v' + Tdot v, Tdot v = (R (w x v), 0, 0). Virtual power gives the generated model's forces
// from MuJoCo's as T^T f. The joints are matched by name.
#pragma once

#include <array>
#include <stdexcept>
#include <string>

#include <mujoco/mujoco.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mujoco_model.hpp"

namespace gencoord::robot_testing {

template <class M>
class QuaternionBaseReference {
 public:
  using QVec = Eigen::Matrix<double, M::nq, 1>;
  using VVec = Eigen::Matrix<double, M::nv, 1>;
  using VMat = Eigen::Matrix<double, M::nv, M::nv>;

  explicit QuaternionBaseReference(const std::string& urdf_path)
      : model_(load_smooth_model(urdf_path)) {
    use_joint_friction_of<M>();
    static_assert(M::num_quaternions >= 1, "the model's base is a free joint");
    if (model_->nq != M::nq || model_->nv != M::nv || model_->jnt_type[0] != mjJNT_FREE) {
      throw std::runtime_error(urdf_path + ": MuJoCo has nq = " + std::to_string(model_->nq) +
                               " and nv = " + std::to_string(model_->nv) +
                               " and no free first joint; the generated model has " +
                               std::to_string(M::nq) + " and " + std::to_string(M::nv));
    }
    data_.reset(mj_makeData(model_.get()));
    for (int i = 7; i < M::nq; ++i) {
      const int joint = joint_called(model_.get(), urdf_path, M::coordinate_names[i]);
      qpos_[i] = model_->jnt_qposadr[joint];
      dof_[i - 1] = model_->jnt_dofadr[joint];
    }
  }

  mjModel* model() { return model_.get(); }
  mjData* data() { return data_.get(); }

  /// MuJoCo's qpos for the generated model's q.
  QVec qpos(const QVec& q) const {
    QVec out = q;
    for (int i = 7; i < M::nq; ++i) out[qpos_[i]] = q[i];
    return out;
  }

  /// set(q, v) and mj_forward.
  void forward(const QVec& q, const VVec& v) {
    set(q, v);
    mj_forward(model_.get(), data_.get());
  }

  /// Sets MuJoCo's state to the generated model's (q, v).
  void set(const QVec& q, const VVec& v) {
    const Eigen::Matrix3d R = Eigen::Quaterniond(q[3], q[4], q[5], q[6]).toRotationMatrix();
    t_.setZero();
    t_.template block<3, 3>(0, 0) = R;
    t_.template block<3, 3>(3, 3).setIdentity();
    for (int i = 6; i < M::nv; ++i) t_(dof_[i], i) = 1.0;
    tdot_v_.setZero();
    tdot_v_.template head<3>() = R * v.template segment<3>(3).cross(v.template head<3>());
    Eigen::Map<QVec>(data_->qpos) = qpos(q);
    Eigen::Map<VVec>(data_->qvel) = t_ * v;
    data_->time = 0.0;
  }

  /// The generated model's speeds' rates v' at the last forward() as MuJoCo's qacc.
  VVec qacc_from(const VVec& vdot) const { return t_ * vdot + tdot_v_; }
  VVec qacc() const { return Eigen::Map<const VVec>(data_->qacc); }

  /// T^T M T: the inertia matrix in the generated model's speeds.
  VMat mass_matrix() const {
    Eigen::Matrix<double, M::nv, M::nv, Eigen::RowMajor> full;
    mj_fullM(model_.get(), full.data(), data_->qM);
    return t_.transpose() * full * t_;
  }

  /// The generated model's inverse dynamics from mj_rne at qacc = T v' + Tdot v.
  VVec inverse_dynamics(const VVec& vdot) {
    Eigen::Map<VVec>(data_->qacc) = qacc_from(vdot);
    VVec result;
    mj_rne(model_.get(), data_.get(), 1, result.data());
    return t_.transpose() * (result - Eigen::Map<const VVec>(data_->qfrc_passive));
  }

  /// MuJoCo's velocity that takes qpos `from` to `to` in unit time (mj_differentiatePos).
  VVec difference(const QVec& from, const QVec& to) const {
    VVec out;
    mj_differentiatePos(model_.get(), out.data(), 1.0, from.data(), to.data());
    return out;
  }

 private:
  ModelPtr model_;
  DataPtr data_;
  std::array<int, M::nq> qpos_{};  // the joints' entries of qpos (from 7 on) and qvel (6 on)
  std::array<int, M::nv> dof_{};
  VMat t_ = VMat::Identity();
  VVec tdot_v_ = VVec::Zero();
};

}  // namespace gencoord::robot_testing
