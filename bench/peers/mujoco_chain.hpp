// SPDX-License-Identifier: BSD-3-Clause
// MuJoCo peer: the planar n-link chain of models/n_link_chain.py as an MJCF model.
//
// MuJoCo is 3D with gravity along -z, so the chain hangs in the x-z plane: hinge k turns about
// -y, which makes a positive angle swing the link towards +x, as theta<k> does in
// models/n_link_chain.py ((sin theta, -cos theta) in (x, z)). Each link's mass sits at its end
// as an <inertial> point of tiny rotational inertia: exactly where gencoord puts it, and no
// geoms, so there is nothing to collide (contacts are disabled as well). No damping, armature
// or joint limits. MuJoCo's hinge angles are *relative* (nested bodies): phi_1 = theta_1,
// phi_k = theta_k - theta_{k-1}; set_state() and absolute_qacc() convert.
#pragma once

#include <algorithm>
#include <cstring>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

namespace peers {

/// One file of an MJCF model: its name in MuJoCo's virtual file system and its text.
struct MjcfFile {
  std::string name, text;
};

/// Bodies per MJCF file. MuJoCo's XML parser (tinyxml2) refuses elements nested 100 deep, and
/// each link nests one body deeper (one file holds at most 96 links), so a longer chain is
/// split across files: the innermost body of each file holds <include file="..."/> of the
/// next, and MuJoCo puts the children of that file's <mujoco> root (the next body) where the
/// include stands. Each file is parsed on its own, so only its own bodies count towards the
/// limit. The merged model is the one a single file gives: body positions are relative to the
/// parent.
constexpr int kChainBodiesPerFile = 32;

/// The n-link chain as MJCF files, main file first; params = g, l1, m1, l2, m2, ...
/// (gencoord's order). For n <= kChainBodiesPerFile the main file is the whole model.
inline std::vector<MjcfFile> chain_mjcf(int n, const std::vector<double>& params) {
  // tiny but positive inertia about the mass point: MuJoCo refuses bodies without one
  constexpr double kPointInertia = 1e-10;
  const int files = std::max(1, (n + kChainBodiesPerFile - 1) / kChainBodiesPerFile);
  const auto file_name = [](int file) {
    return file == 0 ? std::string("n_link_chain.xml")
                     : "n_link_chain_part" + std::to_string(file) + ".xml";
  };
  std::vector<MjcfFile> mjcf;
  for (int file = 0; file < files; ++file) {
    std::ostringstream x;
    x.precision(17);
    if (file == 0) {
      x << "<mujoco model=\"n_link_chain_" << n << "\">\n"
        << "  <option gravity=\"0 0 " << -params[0] << "\" timestep=\"1e-4\">\n"
        << "    <flag contact=\"disable\"/>\n"
        << "  </option>\n"
        << "  <worldbody>\n";
    } else {
      x << "<mujoco>\n";
    }
    const int first = file * kChainBodiesPerFile;
    const int end = std::min(n, first + kChainBodiesPerFile);
    for (int k = first; k < end; ++k) {
      const double length = params[1 + 2 * k], mass = params[2 + 2 * k];
      const double previous_length = k == 0 ? 0.0 : params[1 + 2 * (k - 1)];
      // body k's origin is joint k, at the end of link k - 1
      x << "    <body name=\"link" << k + 1 << "\" pos=\"0 0 " << -previous_length << "\">\n"
        << "      <joint name=\"theta" << k + 1 << "\" type=\"hinge\" axis=\"0 -1 0\"/>\n"
        << "      <inertial pos=\"0 0 " << -length << "\" mass=\"" << mass << "\" diaginertia=\""
        << kPointInertia << " " << kPointInertia << " " << kPointInertia << "\"/>\n";
    }
    if (file + 1 < files) x << "    <include file=\"" << file_name(file + 1) << "\"/>\n";
    for (int k = first; k < end; ++k) x << "    </body>\n";
    x << (file == 0 ? "  </worldbody>\n</mujoco>\n" : "</mujoco>\n");
    mjcf.push_back({file_name(file), x.str()});
  }
  return mjcf;
}

/// A loaded MuJoCo model and data of the n-link chain.
class MujocoChain {
 public:
  /// \throws std::runtime_error with MuJoCo's message if the model does not compile.
  MujocoChain(int n, const std::vector<double>& params) : n_(n) {
    // mjVFS holds thousands of file names: far too big for the stack; the deleter frees the
    // files as well, on a throw too
    const auto delete_vfs = [](mjVFS* vfs) {
      mj_deleteVFS(vfs);
      delete vfs;
    };
    std::unique_ptr<mjVFS, decltype(delete_vfs)> vfs(new mjVFS, delete_vfs);
    mj_defaultVFS(vfs.get());
    const std::vector<MjcfFile> files = chain_mjcf(n, params);
    for (const MjcfFile& file : files) {
      const int size = static_cast<int>(file.text.size());
      if (mj_makeEmptyFileVFS(vfs.get(), file.name.c_str(), size) != 0)
        throw std::runtime_error("mujoco: cannot make the VFS file " + file.name);
      std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), file.name.c_str())], file.text.data(),
                  file.text.size());
    }
    char error[1000] = "";
    model_ = mj_loadXML(files.front().name.c_str(), vfs.get(), error, sizeof error);
    if (!model_) throw std::runtime_error(std::string("mujoco: ") + error);
    data_ = mj_makeData(model_);
  }
  ~MujocoChain() {
    mj_deleteData(data_);
    mj_deleteModel(model_);
  }
  MujocoChain(const MujocoChain&) = delete;
  MujocoChain& operator=(const MujocoChain&) = delete;

  /// Sets qpos, qvel from absolute angles and rates (size n each).
  void set_state(const double* theta, const double* theta_dot) {
    for (int k = 0; k < n_; ++k) {
      data_->qpos[k] = theta[k] - (k == 0 ? 0.0 : theta[k - 1]);
      data_->qvel[k] = theta_dot[k] - (k == 0 ? 0.0 : theta_dot[k - 1]);
    }
  }
  /// Everything mj_step computes before integrating, qacc included.
  void forward() { mj_forward(model_, data_); }
  /// One step of MuJoCo's RK4 integrator of size dt.
  void rk4_step(double dt) {
    model_->opt.integrator = mjINT_RK4;
    model_->opt.timestep = dt;
    mj_step(model_, data_);
  }
  /// The joint torques that give the relative accelerations qacc (size n): mj_rne after
  /// the position and velocity stages it reads, which are counted in its cost.
  void inverse_dynamics(const double* qacc, double* torque) {
    mj_fwdPosition(model_, data_);
    mj_fwdVelocity(model_, data_);
    for (int k = 0; k < n_; ++k) data_->qacc[k] = qacc[k];
    mj_rne(model_, data_, 1, torque);
  }
  /// qacc as absolute angle accelerations (size n): running sums of the relative ones.
  void absolute_qacc(double* out) const {
    double sum = 0.0;
    for (int k = 0; k < n_; ++k) out[k] = sum += data_->qacc[k];
  }
  const mjData* data() const { return data_; }

 private:
  int n_;
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
};

}  // namespace peers
