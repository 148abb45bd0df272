// SPDX-License-Identifier: BSD-3-Clause
// The Delta robot of models/delta_robot.py built in MuJoCo, as the reference for its
// constrained dynamics: each lower arm a rigid rod on a ball joint at its elbow (its mass at
// its two ends, as the model file has it: the same kinetic energy), the platform on three
// slide joints, and each rod's far end held to the platform by a `connect` equality.
//
// MuJoCo's equality constraints are soft: the constraint force solves (A + R) f = ... with the
// regularization R = (1 - d) / d diag(A), d the impedance (`solimp`), at most 0.9999. So its
// accelerations differ from the hard-constrained ones by O((1 - d) / d), and `forward` takes
// d to show that the difference is MuJoCo's softness and nothing else.
#pragma once

#include <cmath>
#include <sstream>
#include <string>

#include <mujoco/mujoco.h>
#include <Eigen/Dense>

#include "generated/delta_robot.hpp"
#include "mujoco_load.hpp"

namespace gencoord::constrained_testing {

class MujocoDelta {
 public:
  using M = models::DeltaRobot;
  using Vec = Eigen::Matrix<double, M::nv, 1>;

  /// MuJoCo's Delta with the parameters `p`, built in the configuration `reference` (which
  /// must satisfy the loops: MuJoCo places each connect's second point there).
  MujocoDelta(const M::Params& p, const Vec& reference)
      : p_(p), reference_(reference), mujoco_(mjcf()) {}

  // bench/constrained_bench.cc times mj_forward on them
  mjModel* model() { return mujoco_.model(); }
  mjData* data() { return mujoco_.data(); }

  /// Sets every equality's impedance to d (MuJoCo keeps it in [0.0001, 0.9999]).
  void set_impedance(double d) { mujoco_.set_impedance(d); }

  /// MuJoCo's state for the generated model's (q, v), which must satisfy the constraints:
  /// the rods' orientations and angular velocities follow from the elbows and the platform
  /// (no spin about a rod's own axis).
  void set(const Vec& q, const Vec& v, const std::array<double, 3>& torques) {
    const Eigen::Vector3d platform = q.tail<3>(), platform_velocity = v.tail<3>();
    for (int i = 0; i < 3; ++i) {
      const Arm arm = this->arm(i, q[i]);
      const Eigen::Vector3d elbow_velocity = v[i] * arm.axis.cross(arm.elbow - arm.base);
      const Eigen::Vector3d d = (platform + p_.r * arm.radial - arm.elbow) / p_.l_b;
      const Eigen::Vector3d d_rate = (platform_velocity - elbow_velocity) / p_.l_b;
      const Eigen::Matrix3d parent = arm.axes * rod_offset(i);
      const Eigen::Quaterniond ball =
          Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), parent.transpose() * d);
      const Eigen::Matrix3d child = parent * ball.toRotationMatrix();
      const Eigen::Vector3d relative = d.cross(d_rate) - v[i] * arm.axis;
      const int hinge = joint("theta_" + std::to_string(i + 1));
      mujoco_.data()->qpos[mujoco_.model()->jnt_qposadr[hinge]] = q[i];
      mujoco_.data()->qvel[mujoco_.model()->jnt_dofadr[hinge]] = v[i];
      mujoco_.data()->qfrc_applied[mujoco_.model()->jnt_dofadr[hinge]] = torques[i];
      const int elbow = joint("elbow_" + std::to_string(i + 1));
      mjtNum* quat = mujoco_.data()->qpos + mujoco_.model()->jnt_qposadr[elbow];
      quat[0] = ball.w(), quat[1] = ball.x(), quat[2] = ball.y(), quat[3] = ball.z();
      const Eigen::Vector3d local = child.transpose() * relative;
      for (int k = 0; k < 3; ++k)
        mujoco_.data()->qvel[mujoco_.model()->jnt_dofadr[elbow] + k] = local[k];
    }
    const char* slides[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      const int slide = joint(slides[k]);
      mujoco_.data()->qpos[mujoco_.model()->jnt_qposadr[slide]] = q[3 + k] - reference_[3 + k];
      mujoco_.data()->qvel[mujoco_.model()->jnt_dofadr[slide]] = v[3 + k];
    }
  }

  /// mj_forward at the state `set` gave; the generated model's v' from MuJoCo's qacc.
  Vec forward() {
    mj_forward(mujoco_.model(), mujoco_.data());
    Vec acceleration;
    const char* names[6] = {"theta_1", "theta_2", "theta_3", "x", "y", "z"};
    for (int k = 0; k < 6; ++k)
      acceleration[k] = mujoco_.data()->qacc[mujoco_.model()->jnt_dofadr[joint(names[k])]];
    return acceleration;
  }

  /// The largest |position| and |velocity| of MuJoCo's constraint rows after `forward`: zero
  /// when `set` put MuJoCo on its constraints.
  double constraint_residual() const { return mujoco_.constraint_residual(); }

 private:
  struct Arm {
    Eigen::Vector3d radial, base, axis, elbow;
    Eigen::Matrix3d axes;  // x along the upper arm, y its motor's axis
  };

  Arm arm(int i, double theta) const {
    const double alpha = 2 * M_PI * i / 3;
    Arm arm;
    arm.radial = Eigen::Vector3d(std::cos(alpha), std::sin(alpha), 0);
    arm.base = p_.R * arm.radial;
    arm.axes = (Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
    arm.axis = arm.axes.col(1);
    arm.elbow = arm.base + p_.l_a * arm.axes.col(0);
    return arm;
  }

  // The rod's axes relative to its upper arm in the reference configuration, x along the rod.
  Eigen::Matrix3d rod_offset(int i) const {
    const Arm arm = this->arm(i, reference_[i]);
    const Eigen::Vector3d d = (reference_.tail<3>() + p_.r * arm.radial - arm.elbow).normalized();
    return Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), arm.axes.transpose() * d)
        .toRotationMatrix();
  }

  int joint(const std::string& name) const { return mujoco_.joint(name); }

  static std::string quat(const Eigen::Matrix3d& rotation) {
    const Eigen::Quaterniond q(rotation);
    std::ostringstream out;
    out.precision(17);
    out << q.w() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z();
    return out.str();
  }

  std::string mjcf() const {
    std::ostringstream x;
    x.precision(17);
    const double rod_inertia = p_.m_b * p_.l_b * p_.l_b / 4;
    const double arm_inertia = p_.m_a * (3 * p_.rho * p_.rho + p_.l_a * p_.l_a) / 12;
    x << "<mujoco model=\"delta_robot\"><compiler angle=\"radian\"/>"
      << "<option gravity=\"0 0 " << -p_.g << "\" timestep=\"0.001\" tolerance=\"1e-15\"/>"
      << "<worldbody>";
    for (int i = 0; i < 3; ++i) {
      const Arm arm = this->arm(i, reference_[i]);
      const std::string n = std::to_string(i + 1);
      x << "<body name=\"upper_" << n << "\" pos=\"" << arm.base.transpose() << "\" quat=\""
        << quat(arm.axes) << "\">"
        << "<joint name=\"theta_" << n << "\" type=\"hinge\" axis=\"0 1 0\" ref=\"" << reference_[i]
        << "\"/>"
        << "<inertial pos=\"" << p_.l_a / 2 << " 0 0\" mass=\"" << p_.m_a << "\" diaginertia=\""
        << p_.m_a * p_.rho * p_.rho / 2 << ' ' << arm_inertia << ' ' << arm_inertia << "\"/>"
        << "<body name=\"lower_" << n << "\" pos=\"" << p_.l_a << " 0 0\" quat=\""
        << quat(rod_offset(i)) << "\">"
        << "<joint name=\"elbow_" << n
        << "\" type=\"ball\"/>"
        // the rod's spin about its own axis is decoupled; MuJoCo needs a positive inertia
        << "<inertial pos=\"" << p_.l_b / 2 << " 0 0\" mass=\"" << p_.m_b << "\" diaginertia=\""
        << 1e-6 * rod_inertia << ' ' << rod_inertia << ' ' << rod_inertia << "\"/>"
        << "</body></body>";
    }
    x << "<body name=\"platform\" pos=\"" << reference_.tail<3>().transpose() << "\">"
      << "<joint name=\"x\" type=\"slide\" axis=\"1 0 0\"/>"
      << "<joint name=\"y\" type=\"slide\" axis=\"0 1 0\"/>"
      << "<joint name=\"z\" type=\"slide\" axis=\"0 0 1\"/>"
      << "<inertial pos=\"0 0 0\" mass=\"" << p_.m_p << "\" diaginertia=\"1e-3 1e-3 1e-3\"/>"
      << "</body></worldbody><equality>";
    for (int i = 0; i < 3; ++i) {
      x << "<connect body1=\"lower_" << i + 1 << "\" body2=\"platform\" anchor=\"" << p_.l_b
        << " 0 0\" solimp=\"0.9999 0.9999 0.001 0.5 2\"/>";
    }
    x << "</equality></mujoco>";
    return x.str();
  }

  M::Params p_;
  Vec reference_;
  MujocoModel mujoco_;
};

}  // namespace gencoord::constrained_testing
