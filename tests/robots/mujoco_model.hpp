// MuJoCo, loaded from the same URDF as a generated model, as the reference for its dynamics.
//
// MuJoCo orders its degrees of freedom its own way; `MujocoReference` maps them to the
// generated model's coordinates by joint name (a coordinate is named after its joint).
// Contacts and joint-limit constraints are switched off: the comparison is of the smooth
// dynamics M(q) qdd + c(q, v) = tau, which is what the generated kernels compute.
#pragma once

#include <array>
#include <memory>
#include <stdexcept>
#include <string>

#include <mujoco/mujoco.h>
#include <Eigen/Core>

#include "gencoord/state.hpp"

namespace gencoord::robot_testing {

template <class M>
class MujocoReference {
 public:
  using QVec = Eigen::Matrix<double, M::nq, 1>;
  using QMat = Eigen::Matrix<double, M::nq, M::nq>;

  explicit MujocoReference(const std::string& urdf_path) {
    char error[1000] = "";
    model_.reset(mj_loadXML(urdf_path.c_str(), nullptr, error, sizeof error));
    if (!model_) throw std::runtime_error("MuJoCo cannot load " + urdf_path + ": " + error);
    if (model_->nq != M::nq || model_->nv != M::nq) {
      throw std::runtime_error(urdf_path + ": MuJoCo has nq = " + std::to_string(model_->nq) +
                               ", the generated model " + std::to_string(M::nq));
    }
    model_->opt.disableflags |= mjDSBL_CONTACT | mjDSBL_CONSTRAINT;
    model_->opt.integrator = mjINT_RK4;
    data_.reset(mj_makeData(model_.get()));
    for (int i = 0; i < M::nq; ++i) {
      const int joint = mj_name2id(model_.get(), mjOBJ_JOINT, M::coordinate_names[i]);
      if (joint < 0) {
        throw std::runtime_error(urdf_path + ": MuJoCo has no joint called " +
                                 std::string(M::coordinate_names[i]));
      }
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
  /// c(q, v) - passive forces: Coriolis, centrifugal and gravity minus joint damping; the
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

  struct FreeModel {
    void operator()(mjModel* m) const { mj_deleteModel(m); }
  };
  struct FreeData {
    void operator()(mjData* d) const { mj_deleteData(d); }
  };
  std::unique_ptr<mjModel, FreeModel> model_;
  std::unique_ptr<mjData, FreeData> data_;
  std::array<int, M::nq> qpos_{};
  std::array<int, M::nq> dof_{};
};

}  // namespace gencoord::robot_testing
