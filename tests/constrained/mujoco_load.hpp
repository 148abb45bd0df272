// SPDX-License-Identifier: BSD-3-Clause
// A MuJoCo model from an MJCF string (through MuJoCo's virtual file system), owned with its
// data: the reference mechanisms of the constrained tests are written in code.
#pragma once

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

namespace gencoord::constrained_testing {

/// An mjModel loaded from MJCF text and an mjData for it, freed together.
class MujocoModel {
 public:
  /// \throws std::runtime_error with MuJoCo's message when it cannot load `xml`.
  explicit MujocoModel(const std::string& xml) {
    auto vfs = std::make_unique<mjVFS>();
    mj_defaultVFS(vfs.get());
    mj_makeEmptyFileVFS(vfs.get(), "model.xml", static_cast<int>(xml.size()));
    const int file = mj_findFileVFS(vfs.get(), "model.xml");
    std::copy(xml.begin(), xml.end(), static_cast<char*>(vfs->filedata[file]));
    char error[1000] = "";
    model_ = mj_loadXML("model.xml", vfs.get(), error, sizeof error);
    mj_deleteVFS(vfs.get());
    if (!model_) throw std::runtime_error(std::string("MuJoCo cannot load the model: ") + error);
    data_ = mj_makeData(model_);
  }
  ~MujocoModel() {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }
  MujocoModel(const MujocoModel&) = delete;
  MujocoModel& operator=(const MujocoModel&) = delete;

  mjModel* model() const { return model_; }
  mjData* data() const { return data_; }

  /// The joint's id. \throws std::runtime_error if the model has no such joint.
  int joint(const std::string& name) const {
    const int id = mj_name2id(model_, mjOBJ_JOINT, name.c_str());
    if (id < 0) throw std::runtime_error("the MuJoCo model has no joint " + name);
    return id;
  }

  /// Sets every equality's impedance to d (MuJoCo keeps it in [0.0001, 0.9999]).
  void set_impedance(double d) {
    for (int e = 0; e < model_->neq; ++e) {
      mjtNum* solimp = model_->eq_solimp + e * mjNIMP;
      solimp[0] = solimp[1] = d;
    }
  }

  /// The largest |position| and |velocity| of MuJoCo's constraint rows after mj_forward:
  /// zero when the state is on its constraints.
  double constraint_residual() const {
    double worst = 0;
    for (int r = 0; r < data_->nefc; ++r)
      worst = std::max({worst, std::abs(data_->efc_pos[r]), std::abs(data_->efc_vel[r])});
    return worst;
  }

 private:
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
};

/// MuJoCo's accelerations at several impedances d extrapolated to a hard constraint (d = 1):
/// they are a smooth function of the softness (1 - d) / d, whose polynomial through the
/// given points (Neville's scheme) is evaluated at 0. Two points remove the linear term,
/// three the quadratic one too.
template <class Vector>
Vector extrapolated_to_hard(const std::vector<double>& impedances,
                            const std::vector<Vector>& accelerations) {
  std::vector<double> eps;
  for (double d : impedances) eps.push_back((1 - d) / d);
  std::vector<Vector> p = accelerations;
  for (std::size_t level = 1; level < p.size(); ++level)
    for (std::size_t i = 0; i + level < p.size(); ++i)
      p[i] = (eps[i + level] * p[i] - eps[i] * p[i + 1]) / (eps[i + level] - eps[i]);
  return p.front();
}

}  // namespace gencoord::constrained_testing
