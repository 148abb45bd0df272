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

#include <cstring>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <mujoco/mujoco.h>

namespace peers {

/// MJCF text of the n-link chain; params = g, l1, m1, l2, m2, ... (gencoord's order).
inline std::string chain_mjcf(int n, const std::vector<double>& params) {
  // tiny but positive inertia about the mass point: MuJoCo refuses bodies without one
  constexpr double kPointInertia = 1e-10;
  std::ostringstream x;
  x.precision(17);
  x << "<mujoco model=\"n_link_chain_" << n << "\">\n"
    << "  <option gravity=\"0 0 " << -params[0] << "\" timestep=\"1e-4\">\n"
    << "    <flag contact=\"disable\"/>\n"
    << "  </option>\n"
    << "  <worldbody>\n";
  for (int k = 0; k < n; ++k) {
    const double length = params[1 + 2 * k], mass = params[2 + 2 * k];
    const double previous_length = k == 0 ? 0.0 : params[1 + 2 * (k - 1)];
    // body k's origin is joint k, at the end of link k - 1
    x << "    <body name=\"link" << k + 1 << "\" pos=\"0 0 " << -previous_length << "\">\n"
      << "      <joint name=\"theta" << k + 1 << "\" type=\"hinge\" axis=\"0 -1 0\"/>\n"
      << "      <inertial pos=\"0 0 " << -length << "\" mass=\"" << mass << "\" diaginertia=\""
      << kPointInertia << " " << kPointInertia << " " << kPointInertia << "\"/>\n";
  }
  for (int k = 0; k < n; ++k) x << "    </body>\n";
  x << "  </worldbody>\n</mujoco>\n";
  return x.str();
}

/// A loaded MuJoCo model and data of the n-link chain.
class MujocoChain {
 public:
  /// \throws std::runtime_error with MuJoCo's message if the model does not compile.
  MujocoChain(int n, const std::vector<double>& params) : n_(n) {
    const std::string xml = chain_mjcf(n, params);
    // mjVFS holds thousands of file names: far too big for the stack
    auto vfs = std::make_unique<mjVFS>();
    mj_defaultVFS(vfs.get());
    const char* file = "n_link_chain.xml";
    if (mj_makeEmptyFileVFS(vfs.get(), file, static_cast<int>(xml.size())) != 0)
      throw std::runtime_error("mujoco: cannot make a VFS file");
    std::memcpy(vfs->filedata[mj_findFileVFS(vfs.get(), file)], xml.data(), xml.size());
    char error[1000] = "";
    model_ = mj_loadXML(file, vfs.get(), error, sizeof error);
    mj_deleteVFS(vfs.get());
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
