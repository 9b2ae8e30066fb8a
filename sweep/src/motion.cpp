#include "sweep/motion.hpp"

#include <cmath>

namespace sweep {

const char* to_string(JointType t) {
  switch (t) {
    case JointType::Revolute: return "revolute";
    case JointType::Prismatic: return "prismatic";
    case JointType::Helical: return "helical";
  }
  return "?";
}

Eigen::Isometry3d ScrewJoint::transform(double q) const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  if (type == JointType::Prismatic) {
    T.translation() = direction * q;
    return T;
  }
  const Eigen::Matrix3d R = Eigen::AngleAxisd(q, direction).toRotationMatrix();
  T.linear() = R;
  T.translation() = point - R * point + direction * (pitch * q);
  return T;
}

Eigen::Vector3d ScrewJoint::velocity(const Eigen::Vector3d& x) const {
  if (type == JointType::Prismatic) return direction;
  return direction.cross(x - point) + direction * pitch;
}

Eigen::Isometry3d Motion::transform(const std::vector<double>& q) const {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < joints.size(); ++i) T = T * joints[i].transform(q[i]);
  return T * home;
}

double Motion::max_speed(double radius) const {
  double s = 0.0;
  for (const auto& j : joints) {
    double v = 1.0;
    if (j.is_rotation()) v = radius + j.point.norm() + std::abs(j.pitch);
    s = std::max(s, v);
  }
  return s;
}

}  // namespace sweep
