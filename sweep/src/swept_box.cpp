#include "sweep/swept_box.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sweep/orbit.hpp"

namespace sweep {

namespace {

/// The range of a joint that matters: a revolute joint beyond a whole turn covers nothing new.
double effective_hi(const ScrewJoint& j) {
  return j.type == JointType::Revolute ? std::min(j.hi, j.lo + 2 * M_PI) : j.hi;
}

}  // namespace

Eigen::AlignedBox3d swept_box(const Eigen::AlignedBox3d& body, const Motion& motion) {
  Eigen::AlignedBox3d out;
  const std::size_t n = motion.dof();
  if (n == 0) {
    for (int k = 0; k < 8; ++k) out.extend(motion.home * body.corner(Eigen::AlignedBox3d::CornerType(k)));
    return out;
  }
  if (n == 1) {
    const ScrewJoint& j = motion.joints[0];
    const double lo = j.lo, hi = effective_hi(j);
    // a step of 1/2 degree; a coordinate c + a cos t + b sin t + d t bends by at most |(a, b)|, so its
    // samples miss its extremes by at most |(a, b)| step^2 / 8
    const int steps = std::max(1, int(std::ceil((hi - lo) / (M_PI / 360))));
    const double h = (hi - lo) / steps;
    for (int k = 0; k < 8; ++k) {
      const OrbitCurve o = orbit_of(j, motion.home * body.corner(Eigen::AlignedBox3d::CornerType(k)));
      for (int i = 0; i <= steps; ++i) out.extend(o.at(lo + h * i));
      const double bend = std::max(o.a.norm(), o.b.norm());
      out.extend(out.min() - Eigen::Vector3d::Constant(bend * h * h / 8));
      out.extend(out.max() + Eigen::Vector3d::Constant(bend * h * h / 8));
    }
    return out;
  }
  // Grid of joint values: about 20000 poses in all.
  const int per = std::max(2, int(std::floor(std::pow(20000.0, 1.0 / double(n)))));
  std::vector<double> step(n);
  for (std::size_t i = 0; i < n; ++i) step[i] = (effective_hi(motion.joints[i]) - motion.joints[i].lo) / (per - 1);
  // radius of a ball about the origin that holds every point of the motion (from the corners, the
  // joints' points and their reach)
  double radius = 0;
  for (int k = 0; k < 8; ++k) radius = std::max(radius, (motion.home * body.corner(Eigen::AlignedBox3d::CornerType(k))).norm());
  for (const auto& j : motion.joints) {
    // a rotation about an axis through p moves x to within |x| + 2 |p| of the origin; a screw and a
    // slide add their translation
    const double reach = std::max(std::abs(j.lo), std::abs(j.hi));
    const double shift = j.type == JointType::Prismatic ? reach : std::abs(j.pitch) * reach;
    radius += (j.type == JointType::Prismatic ? 0.0 : 2 * j.point.norm()) + shift;
  }
  double margin = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& j = motion.joints[i];
    const double speed = j.type == JointType::Prismatic ? 1.0 : radius + j.point.norm() + std::abs(j.pitch);
    margin += speed * 0.5 * step[i];
  }
  std::vector<double> q(n);
  std::vector<int> idx(n, 0);
  for (;;) {
    for (std::size_t i = 0; i < n; ++i) q[i] = motion.joints[i].lo + step[i] * idx[i];
    const Eigen::Isometry3d T = motion.transform(q);
    for (int k = 0; k < 8; ++k) out.extend(T * body.corner(Eigen::AlignedBox3d::CornerType(k)));
    std::size_t i = 0;
    while (i < n && ++idx[i] == per) idx[i++] = 0;
    if (i == n) break;
  }
  out.extend(out.min() - Eigen::Vector3d::Constant(margin));
  out.extend(out.max() + Eigen::Vector3d::Constant(margin));
  return out;
}

}  // namespace sweep
