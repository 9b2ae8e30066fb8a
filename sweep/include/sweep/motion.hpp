#pragma once
/// @file motion.hpp
/// Rigid motions T(q) in SE(3) over a box of joint values. Revolute, prismatic and helical joints
/// are all screws (pitch 0, infinite, finite); a chain is a product of exponentials with its axes
/// given in world coordinates at q = 0, outermost first:
///   T(q) = exp(xi_1 q_1) ... exp(xi_n q_n) * home.
#include <Eigen/Geometry>
#include <vector>

namespace sweep {

enum class JointType { Revolute, Prismatic, Helical };
const char* to_string(JointType t);

/// One screw joint. For revolute and helical joints q is an angle in radians; for prismatic
/// joints q is a length along `direction`.
struct ScrewJoint {
  JointType type = JointType::Revolute;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();      ///< a point on the axis (ignored for prismatic)
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit axis direction
  double pitch = 0.0;  ///< helical: translation per radian along direction (SPEC pitch / 2 pi)
  double lo = 0.0, hi = 0.0;  ///< range of q, lo <= hi

  /// exp(xi q): the rigid motion of this joint alone at value q.
  Eigen::Isometry3d transform(double q) const;
  /// Velocity at world point x of the motion exp(xi q) (derivative in q, at q's pose, of the
  /// point that was x at q): omega x (x - point) + pitch * omega, or direction for prismatic.
  Eigen::Vector3d velocity(const Eigen::Vector3d& x) const;
  bool is_rotation() const { return type != JointType::Prismatic; }
};

/// A chain of screw joints and the pose at q = 0 of the frame the entity lives in.
struct Motion {
  std::vector<ScrewJoint> joints;  ///< outermost first
  Eigen::Isometry3d home = Eigen::Isometry3d::Identity();

  std::size_t dof() const { return joints.size(); }
  Eigen::Isometry3d transform(const std::vector<double>& q) const;
  /// Largest speed |dx/dq_i| over points within `radius` of the origin for any joint, used as a
  /// Lipschitz bound when sampling the motion.
  double max_speed(double radius) const;
};

}  // namespace sweep
