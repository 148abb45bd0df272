// SPDX-License-Identifier: BSD-3-Clause
// The four-bar of models/four_bar.py built in MuJoCo, as the reference for its constrained
// dynamics: crank and coupler a chain of hinges from the ground pivot A, the rocker a hinge
// at D, and a `connect` equality holding the coupler's tip to the rocker's, in the x-y plane
// with gravity along -y. MuJoCo's hinges are relative (the coupler's angle is measured from
// the crank); the model's coordinates are the bars' absolute angles.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include <mujoco/mujoco.h>
#include <Eigen/Dense>

#include "generated/four_bar.hpp"
#include "mujoco_load.hpp"

namespace gencoord::constrained_testing {

class MujocoFourBar {
 public:
  using M = models::FourBar;
  using Vec = Eigen::Vector3d;

  /// MuJoCo's four-bar with the parameters `p`, built in the configuration `reference` (on
  /// the loop: MuJoCo places the connect's second point there).
  MujocoFourBar(const M::Params& p, const Vec& reference)
      : p_(p), reference_(reference), mujoco_(mjcf()) {}

  void set_impedance(double d) { mujoco_.set_impedance(d); }
  double constraint_residual() const { return mujoco_.constraint_residual(); }

  /// MuJoCo's state for the generated model's (q, v) and motor torque.
  void set(const Vec& q, const Vec& v, double torque) {
    const Vec relative_q(q[0], q[1] - q[0], q[2]), relative_v(v[0], v[1] - v[0], v[2]);
    for (int k = 0; k < 3; ++k) {
      const int joint = mujoco_.joint(kJoints[k]);
      mujoco_.data()->qpos[mujoco_.model()->jnt_qposadr[joint]] = relative_q[k];
      mujoco_.data()->qvel[mujoco_.model()->jnt_dofadr[joint]] = relative_v[k];
      mujoco_.data()->qfrc_applied[mujoco_.model()->jnt_dofadr[joint]] = k == 0 ? torque : 0.0;
    }
  }

  /// mj_forward at the state `set` gave; the generated model's v' from MuJoCo's qacc.
  Vec forward() {
    mj_forward(mujoco_.model(), mujoco_.data());
    Vec relative;
    for (int k = 0; k < 3; ++k)
      relative[k] = mujoco_.data()->qacc[mujoco_.model()->jnt_dofadr[mujoco_.joint(kJoints[k])]];
    return Vec(relative[0], relative[0] + relative[1], relative[2]);
  }

 private:
  static constexpr const char* kJoints[3] = {"crank", "coupler", "rocker"};

  // A bar along its body's x axis: mass, centre and inertia about the hinge axis z (the two
  // others only need to be valid for MuJoCo: the motion is planar).
  static std::string bar(double mass, double length) {
    std::ostringstream x;
    x.precision(17);
    const double inertia = mass * length * length / 12;
    x << "<inertial pos=\"" << length / 2 << " 0 0\" mass=\"" << mass << "\" diaginertia=\""
      << 1e-6 * inertia << ' ' << inertia << ' ' << inertia << "\"/>";
    return x.str();
  }

  std::string mjcf() const {
    std::ostringstream x;
    x.precision(17);
    const double crank = reference_[0], coupler = reference_[1] - reference_[0],
                 rocker = reference_[2];
    x << "<mujoco model=\"four_bar\"><compiler angle=\"radian\"/>"
      << "<option gravity=\"0 " << -p_.g << " 0\" timestep=\"0.001\" tolerance=\"1e-15\"/>"
      << "<worldbody>"
      << "<body name=\"crank\" euler=\"0 0 " << crank << "\">"
      << "<joint name=\"crank\" type=\"hinge\" axis=\"0 0 1\" ref=\"" << crank << "\"/>"
      << bar(p_.m_a, p_.a) << "<body name=\"coupler\" pos=\"" << p_.a << " 0 0\" euler=\"0 0 "
      << coupler << "\">"
      << "<joint name=\"coupler\" type=\"hinge\" axis=\"0 0 1\" ref=\"" << coupler << "\"/>"
      << bar(p_.m_b, p_.b) << "</body></body>"
      << "<body name=\"rocker\" pos=\"" << p_.d << " 0 0\" euler=\"0 0 " << rocker << "\">"
      << "<joint name=\"rocker\" type=\"hinge\" axis=\"0 0 1\" ref=\"" << rocker << "\"/>"
      << bar(p_.m_c, p_.c) << "</body></worldbody><equality>"
      << "<connect body1=\"coupler\" body2=\"rocker\" anchor=\"" << p_.b
      << " 0 0\" solimp=\"0.9999 0.9999 0.001 0.5 2\"/></equality></mujoco>";
    return x.str();
  }

  M::Params p_;
  Vec reference_;
  MujocoModel mujoco_;
};

}  // namespace gencoord::constrained_testing
