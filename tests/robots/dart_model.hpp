// SPDX-License-Identifier: BSD-3-Clause
// DART 6.12 (its own URDF loader, its own O(n) recursions) as a second reference for a
// generated robot loaded from the same URDF, whatever its joints: revolute and prismatic
// joints by name, a free joint (DART's FreeJoint: a rotation vector and a translation, the
// body twist with the angular part first), and mimic joints, which DART keeps as degrees of
// freedom of their own and gencoord eliminates.
//
// gencoord's speeds v map linearly onto DART's velocities, dq_DART = S v: S permutes a free
// joint's twist and gives a mimic joint its multiplier's column. Everything is compared in
// gencoord's speeds: the mass matrix S^T M_DART S, the inverse dynamics S^T tau_DART(q, S v,
// S v'), and the accelerations that solve them (where S is square they are DART's own forward
// dynamics, mimic joints held by no constraint there).
#pragma once

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <dart/dynamics/BodyNode.hpp>
#include <dart/dynamics/DegreeOfFreedom.hpp>
#include <dart/dynamics/FreeJoint.hpp>
#include <dart/dynamics/Joint.hpp>
#include <dart/dynamics/Skeleton.hpp>
#include <dart/utils/urdf/DartLoader.hpp>

#include "gencoord/model/model_traits.hpp"

namespace gencoord::robot_testing {

template <class M>
class DartReference {
 public:
  /// Loads `urdf` with DART: a link without <inertial> is massless (a frame), a root link
  /// without a joint is fixed, gravity is -g along z.
  DartReference(const std::string& urdf, double g) {
    dart::utils::DartLoader::Options options;
    options.mDefaultRootJointType = dart::utils::DartLoader::RootJointType::FIXED;
    options.mDefaultInertia =
        dart::dynamics::Inertia(0.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero());
    dart::utils::DartLoader loader(options);
    skeleton_ = loader.parseSkeleton(dart::common::Uri::createFromPath(urdf));
    if (!skeleton_) throw std::runtime_error("DART could not load " + urdf);
    skeleton_->setGravity(Eigen::Vector3d(0, 0, -g));
    // DART's joint damping is implicit for its time stepping, -D (v + h v'): at h = 1e-30 it
    // is the continuous equations' -D v
    skeleton_->setTimeStep(1e-30);
    map_speeds();
    typename M::Params params;
    const double* speed = params.find("joint_friction_speed");
    if (speed) friction_speed_ = *speed;
  }

  int dofs() const { return static_cast<int>(skeleton_->getNumDofs()); }
  const Eigen::MatrixXd& speed_map() const { return S_; }

  /// Puts DART at gencoord's state (q, v).
  void set_state(const QVec<M>& q, const VVec<M>& v) {
    Eigen::VectorXd positions(dofs());
    for (std::size_t j = 0; j < skeleton_->getNumJoints(); ++j) {
      dart::dynamics::Joint* joint = skeleton_->getJoint(j);
      if (joint->getNumDofs() == 0) continue;
      const auto first = static_cast<Eigen::Index>(joint->getIndexInSkeleton(0));
      if (auto* free = dynamic_cast<dart::dynamics::FreeJoint*>(joint)) {
        const int k = coordinate(joint->getChildBodyNode()->getName() + "_x");
        Eigen::Isometry3d link = Eigen::Isometry3d::Identity();
        link.translation() = q.template segment<3>(k);
        link.linear() =
            Eigen::Quaterniond(q[k + 3], q[k + 4], q[k + 5], q[k + 6]).normalized().matrix();
        positions.segment<6>(first) = dart::dynamics::FreeJoint::convertToPositions(
            free->getTransformFromParentBodyNode().inverse() * link *
            free->getTransformFromChildBodyNode());
      } else if (const dart::dynamics::Joint* followed = mimicked(joint)) {
        positions[first] = joint->getMimicMultiplier() * q[coordinate(followed->getName())] +
                           joint->getMimicOffset();
      } else {
        positions[first] = q[coordinate(joint->getName())];
      }
    }
    skeleton_->setPositions(positions);
    skeleton_->setVelocities(S_ * Eigen::VectorXd(v));
  }

  /// S^T M S at the state set.
  Eigen::MatrixXd mass_matrix() const { return S_.transpose() * skeleton_->getMassMatrix() * S_; }

  /// S^T tau: the generalized force that gives v' (gravity, Coriolis, damping and friction
  /// included).
  Eigen::VectorXd inverse_dynamics(const VVec<M>& vdot) {
    skeleton_->setAccelerations(S_ * Eigen::VectorXd(vdot));
    skeleton_->computeInverseDynamics(false, true, true);
    return S_.transpose() * (skeleton_->getForces() + friction());
  }

  /// The generated models' joint friction F tanh(v / s) that each degree of freedom's motion
  /// meets, F DART's Coulomb friction (its URDF reader takes it from <dynamics friction>),
  /// which DART itself applies only in its constraint solver.
  Eigen::VectorXd friction() const {
    Eigen::VectorXd out(dofs());
    for (int i = 0; i < dofs(); ++i) {
      const dart::dynamics::DegreeOfFreedom* dof = skeleton_->getDof(static_cast<std::size_t>(i));
      out[i] = dof->getCoulombFriction() * std::tanh(dof->getVelocity() / friction_speed_);
    }
    return out;
  }

  /// v' with no force applied: S^T M S v' = -S^T tau(q, v, 0).
  Eigen::VectorXd qddot() {
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(S_.cols());
    return mass_matrix().llt().solve(-inverse_dynamics(zero));
  }

  /// DART's own forward dynamics, in gencoord's speeds (S square: no mimic joints).
  Eigen::VectorXd forward_dynamics() {
    skeleton_->resetCommands();
    skeleton_->setForces(-friction());
    skeleton_->computeForwardDynamics();
    return S_.partialPivLu().solve(skeleton_->getAccelerations());
  }

 private:
  static const dart::dynamics::Joint* mimicked(const dart::dynamics::Joint* joint) {
    return joint->getActuatorType() == dart::dynamics::Joint::MIMIC ? joint->getMimicJoint()
                                                                    : nullptr;
  }

  static int index_of(const char* const* names, int count, const std::string& name) {
    for (int i = 0; i < count; ++i)
      if (name == names[i]) return i;
    throw std::runtime_error("the generated model has no '" + name + "'");
  }
  static int coordinate(const std::string& name) {
    return index_of(M::coordinate_names.data(), M::nq, name);
  }
  static int speed(const std::string& name) {
    if constexpr (has_generalized_speeds_v<M>) {
      return index_of(M::speed_names.data(), nv_of_v<M>, name);
    } else {
      return index_of(M::coordinate_names.data(), M::nq, name);
    }
  }

  void map_speeds() {
    S_ = Eigen::MatrixXd::Zero(dofs(), nv_of_v<M>);
    for (std::size_t j = 0; j < skeleton_->getNumJoints(); ++j) {
      const dart::dynamics::Joint* joint = skeleton_->getJoint(j);
      if (joint->getNumDofs() == 0) continue;
      const auto first = static_cast<Eigen::Index>(joint->getIndexInSkeleton(0));
      if (dynamic_cast<const dart::dynamics::FreeJoint*>(joint)) {  // DART: (omega, v)
        const std::string link = joint->getChildBodyNode()->getName();
        for (int i = 0; i < 3; ++i) {
          S_(first + i, speed(link + "_w" + "xyz"[i])) = 1.0;
          S_(first + 3 + i, speed(link + "_v" + "xyz"[i])) = 1.0;
        }
      } else if (const dart::dynamics::Joint* followed = mimicked(joint)) {
        S_(first, speed(followed->getName())) = joint->getMimicMultiplier();
      } else if (joint->getNumDofs() == 1) {
        S_(first, speed(joint->getName())) = 1.0;
      } else {
        throw std::runtime_error("DartReference: no mapping for DART's " + joint->getType());
      }
    }
  }

  dart::dynamics::SkeletonPtr skeleton_;
  Eigen::MatrixXd S_;  // DART's velocities per unit speed of gencoord's
  double friction_speed_ = std::numeric_limits<double>::infinity();  // none without friction
};

}  // namespace gencoord::robot_testing
