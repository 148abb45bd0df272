// SPDX-License-Identifier: BSD-3-Clause
// MuJoCo, loaded from the same URDF as a generated model, as the reference for its dynamics.
//
// MuJoCo orders its degrees of freedom its own way; `MujocoReference` maps them to the
// generated model's coordinates by joint name (a coordinate is named after its joint).
// Contacts and joint-limit constraints are switched off: the comparison is of the smooth
// dynamics M(q) qdd + c(q, v) = tau, which is what the generated kernels compute.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include <mujoco/mujoco.h>
#include <Eigen/Core>

#include "gencoord/model/state.hpp"

namespace gencoord::robot_testing {

struct FreeModel {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct FreeData {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, FreeModel>;
using DataPtr = std::unique_ptr<mjData, FreeData>;

/// MuJoCo's model of a URDF for the smooth dynamics: contacts and joint-limit constraints
/// off, RK4 as its integrator.
inline ModelPtr load_smooth_model(const std::string& urdf_path) {
  char error[1000] = "";
  ModelPtr model(mj_loadXML(urdf_path.c_str(), nullptr, error, sizeof error));
  if (!model) throw std::runtime_error("MuJoCo cannot load " + urdf_path + ": " + error);
  model->opt.disableflags |= mjDSBL_CONTACT | mjDSBL_CONSTRAINT;
  model->opt.integrator = mjINT_RK4;
  return model;
}

/// The smoothing speed s of the generated model's joint friction -F tanh(v / s); infinite (no
/// friction) for a model without any.
inline double& joint_friction_speed() {
  static double speed = std::numeric_limits<double>::infinity();
  return speed;
}

/// MuJoCo's passive-force callback: the generated models' joint friction -F tanh(v / s), F
/// MuJoCo's frictionloss (its URDF reader takes it from <dynamics friction>). MuJoCo's own
/// friction loss is a constraint, and constraints are off in the smooth model.
inline void smooth_joint_friction(const mjModel* model, mjData* data) {
  for (int i = 0; i < model->nv; ++i) {
    data->qfrc_passive[i] -=
        model->dof_frictionloss[i] * std::tanh(data->qvel[i] / joint_friction_speed());
  }
}

/// Gives MuJoCo the joint friction of model M (its parameter joint_friction_speed).
template <class M>
void use_joint_friction_of() {
  typename M::Params params;
  const double* speed = params.find("joint_friction_speed");
  joint_friction_speed() = speed ? *speed : std::numeric_limits<double>::infinity();
  mjcb_passive = smooth_joint_friction;
}

/// The joint called `name` (a generated coordinate's name), or an error naming the URDF.
inline int joint_called(const mjModel* model, const std::string& urdf_path, const char* name) {
  const int joint = mj_name2id(model, mjOBJ_JOINT, name);
  if (joint < 0) {
    throw std::runtime_error(urdf_path + ": MuJoCo has no joint called " + std::string(name));
  }
  return joint;
}

template <class M>
class MujocoReference {
 public:
  using QVec = Eigen::Matrix<double, M::nq, 1>;
  using QMat = Eigen::Matrix<double, M::nq, M::nq>;

  explicit MujocoReference(const std::string& urdf_path) : model_(load_smooth_model(urdf_path)) {
    use_joint_friction_of<M>();
    if (model_->nq != M::nq || model_->nv != M::nq) {
      throw std::runtime_error(urdf_path + ": MuJoCo has nq = " + std::to_string(model_->nq) +
                               ", the generated model " + std::to_string(M::nq));
    }
    data_.reset(mj_makeData(model_.get()));
    for (int i = 0; i < M::nq; ++i) {
      const int joint = joint_called(model_.get(), urdf_path, M::coordinate_names[i]);
      qpos_[i] = model_->jnt_qposadr[joint];
      dof_[i] = model_->jnt_dofadr[joint];
    }
  }

  mjModel* model() { return model_.get(); }
  mjData* data() { return data_.get(); }

  /// Sets MuJoCo's state to the generated model's (q, v) and runs mj_forward.
  void forward(const QVec& q, const QVec& v) {
    set(q, v);
    mj_forward(model_.get(), data_.get());
  }

  void set(const QVec& q, const QVec& v) {
    for (int i = 0; i < M::nq; ++i) {
      data_->qpos[qpos_[i]] = q[i];
      data_->qvel[dof_[i]] = v[i];
    }
    data_->time = 0.0;
  }

  QVec q() const { return gather(data_->qpos, qpos_); }
  QVec v() const { return gather(data_->qvel, dof_); }
  QVec qacc() const { return gather(data_->qacc, dof_); }
  /// c(q, v) - passive forces: Coriolis, centrifugal and gravity minus joint damping and
  /// friction; the
  /// generated model's Ft + Fi is its negative.
  QVec bias() const {
    QVec out;
    for (int i = 0; i < M::nq; ++i) {
      out[i] = data_->qfrc_bias[dof_[i]] - data_->qfrc_passive[dof_[i]];
    }
    return out;
  }

  /// The joint-space inertia matrix, from the last forward().
  QMat mass_matrix() const {
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> full(model_->nv,
                                                                                model_->nv);
    mj_fullM(model_.get(), full.data(), data_->qM);
    QMat out;
    for (int i = 0; i < M::nq; ++i) {
      for (int j = 0; j < M::nq; ++j) out(i, j) = full(dof_[i], dof_[j]);
    }
    return out;
  }

  /// Inverse dynamics at the last forward()'s (q, v) for accelerations qdd: mj_rne with
  /// acceleration, the generalized force M qdd + c.
  QVec inverse_dynamics(const QVec& qdd) {
    for (int i = 0; i < M::nq; ++i) data_->qacc[dof_[i]] = qdd[i];
    std::array<mjtNum, M::nq> result{};
    mj_rne(model_.get(), data_.get(), 1, result.data());
    QVec out;
    for (int i = 0; i < M::nq; ++i) out[i] = result[dof_[i]] - data_->qfrc_passive[dof_[i]];
    return out;
  }

 private:
  static QVec gather(const mjtNum* values, const std::array<int, M::nq>& index) {
    QVec out;
    for (int i = 0; i < M::nq; ++i) out[i] = values[index[i]];
    return out;
  }

  ModelPtr model_;
  DataPtr data_;
  std::array<int, M::nq> qpos_{};
  std::array<int, M::nq> dof_{};
};

}  // namespace gencoord::robot_testing
