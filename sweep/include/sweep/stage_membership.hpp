#pragma once
/// @file stage_membership.hpp
/// Point membership in the sweep of a solid under a one-parameter motion, independent of any
/// B-rep: x is in the set when some t in [lo, hi] puts M(t)^-1 x inside the solid. The signed
/// distance along the backward trajectory, g(t) = sd(M(t)^-1 x), changes at most as fast as the
/// trajectory moves; a branch and bound over t discards an interval when g at its middle exceeds
/// that speed times half its length.
#include <Eigen/Geometry>
#include <cstddef>

#include "sweep/membership.hpp"
#include "sweep/stage_motion.hpp"

namespace sweep {

/// A bound on |d/dt M(t) y| over t and |y| <= radius from the motion's poses sampled at `samples`
/// points with exact derivatives: the largest sampled speed plus the sample spacing times the
/// largest sampled acceleration. Not certified between samples; used where the motion has no
/// certified bound (StageMotion::speed_bound infinite).
double sampled_speed_bound(const StageMotion& motion, double radius, int samples = 4096);

/// The largest |p(t)| of the motion's origin over its range (sampled, widened by the speed bound
/// times half the spacing).
double origin_reach(const StageMotion& motion, int samples = 4096);

/// A box that holds the sweep of `body` (a box in the moving frame) under the motion: the box of its
/// corners at sampled t, widened by what a corner can move between samples.
Eigen::AlignedBox3d stage_swept_box(const Eigen::AlignedBox3d& body, const StageMotion& motion, int samples = 1024);

class StageSweptSet {
 public:
  /// `resolution`: the length of backward trajectory below which the search stops and decides by
  /// the sign at the best t (only points within about `resolution` of the boundary are at stake).
  StageSweptSet(const SignedDistance& sd, const StageMotion& motion, double resolution, std::size_t budget);
  /// 1 when x is in the swept set, 0 when out, -1 when the budget ran out first.
  int operator()(const Eigen::Vector3d& x) const;
  /// Whether the speed bound is certified (the motion's own) or sampled.
  bool certified() const { return certified_; }

 private:
  double speed(const Eigen::Vector3d& x) const;
  const SignedDistance& sd_;
  const StageMotion& motion_;
  double resolution_;
  std::size_t budget_;
  double reach_;                  ///< origin_reach of the motion
  bool certified_;
  double omega_ = 0, origin_ = 0;  ///< sampled bound: speed(radius) = omega_ radius + origin_
};

}  // namespace sweep
