#pragma once
/// @file stage_motion.hpp
/// One-parameter rigid motions M(t), t in [lo, hi]: a body point y is at M(t) y = R(t) y + p(t).
/// Every kind gives its pose with exact first and second derivatives in t; from those come the
/// velocity field, the backward trajectory of a world point, and a bound on point speed for
/// certified membership. A screw joint is one kind; paths given by expressions in t and keyframed
/// poses are others.
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sweep/expr.hpp"
#include "sweep/motion.hpp"

namespace sweep {

/// A pose and its first and second derivatives in t.
struct PoseJet {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity(), dR = Eigen::Matrix3d::Zero(), ddR = Eigen::Matrix3d::Zero();
  Eigen::Vector3d p = Eigen::Vector3d::Zero(), dp = Eigen::Vector3d::Zero(), ddp = Eigen::Vector3d::Zero();
};

/// The velocity field of a motion at one instant, in world coordinates: the point at world x
/// moves at omega x x + v.
struct Twist {
  Eigen::Vector3d omega = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
  Eigen::Vector3d at(const Eigen::Vector3d& x) const { return omega.cross(x) + v; }
};

/// A piece of a motion that is one screw joint: the body at `start` (the pose at t0) moved by
/// joint.transform(q) for q in [0, joint.hi] is the motion over [t0, t1] (q need not be
/// proportional to t).
struct ScrewSegment {
  ScrewJoint joint;
  Eigen::Isometry3d start = Eigen::Isometry3d::Identity();
  double t0 = 0, t1 = 0;
};

class StageMotion {
 public:
  virtual ~StageMotion() = default;
  virtual double lo() const = 0;
  virtual double hi() const = 0;
  /// The pose at t and its derivatives (t in [lo, hi]).
  virtual PoseJet pose(double t) const = 0;
  /// An upper bound on |d/dt M(t) y| over t in [lo, hi] and body points |y| <= radius; infinite
  /// when the kind has no certified bound.
  virtual double speed_bound(double radius) const = 0;

  /// The motion as one screw joint that moves the pose at lo() monotonically, when it is one (the
  /// closed forms of the screw engine then apply); none otherwise, or when it does not move.
  /// `radius`: the body lies within it of the origin. The default finds the screw from the
  /// twists at 1025 sampled t (the same axis and pitch at each, the rate of one sign) and checks
  /// that the screw's pose at every sample moves points within `radius` to 1e-10 of the reach.
  virtual std::optional<ScrewSegment> as_screw(double radius) const;

  Eigen::Isometry3d transform(double t) const;
  /// The velocity field at t: omega from dR R^T, v = dp - omega x p.
  Twist twist(double t) const;
  /// The body point that is at world point x at time t: M(t)^-1 x.
  Eigen::Vector3d body_point(double t, const Eigen::Vector3d& x) const;
};

/// The velocity field of a motion at one instant, in world coordinates: what grazing curves are
/// traced against (n . v = 0).
class VelocityField {
 public:
  /// A screw joint's field, the same at every joint value, as the joint computes it.
  explicit VelocityField(const ScrewJoint& joint);
  /// A stage motion's field at t: its screw's when the motion is one screw (as_screw(radius)), else
  /// its twist at t.
  VelocityField(const StageMotion& motion, double t, double radius);
  /// One instant's field as it is.
  explicit VelocityField(const Twist& twist) : twist_(twist) {}
  Eigen::Vector3d at(const Eigen::Vector3d& x) const { return screw_ ? screw_->velocity(x) : twist_.at(x); }
  /// The field's own length, for tolerances relative to the model: a joint's point plus its pitch,
  /// a twist's axis distance from the origin plus its pitch (0 for a translation).
  double reach() const;

 private:
  std::optional<ScrewJoint> screw_;
  Twist twist_;
};

/// One screw joint over its range, after a fixed home pose: M(q) = exp(xi q) home.
class ScrewStage : public StageMotion {
 public:
  ScrewStage(const ScrewJoint& joint, const Eigen::Isometry3d& home = Eigen::Isometry3d::Identity());
  double lo() const override { return joint_.lo; }
  double hi() const override { return joint_.hi; }
  PoseJet pose(double t) const override;
  double speed_bound(double radius) const override;
  /// Itself: the joint over [0, hi - lo] from the pose at lo.
  std::optional<ScrewSegment> as_screw(double radius) const override;
  const ScrewJoint& joint() const { return joint_; }

 private:
  ScrewJoint joint_;
  Eigen::Isometry3d home_;
};

/// One rotation of a path: about `axis` (three expressions in t, or constants) by `angle` (an
/// expression in t, radians).
struct PathRotation {
  Expr axis[3];
  Expr angle;
};

/// A path: M(t) = (translate(t), R_1(t) R_2(t) ...), each expression in the one variable t.
class PathMotion : public StageMotion {
 public:
  /// @throws InputError at JSON pointer `field` when the range is empty or a rotation axis vanishes at a
  /// sampled t.
  PathMotion(double lo, double hi, const Expr translate[3], std::vector<PathRotation> rotations,
             const std::string& field = "/motion");
  double lo() const override { return lo_; }
  double hi() const override { return hi_; }
  PoseJet pose(double t) const override;
  /// From interval enclosures of the expressions and their derivatives over pieces of [lo, hi]:
  /// |dp| and |omega| <= sum over rotations of |angle'| + 2 |axis'| / |axis|. Infinite when an
  /// enclosure has no finite bound (an axis whose box holds 0, a function across a pole).
  double speed_bound(double radius) const override;

 private:
  /// Bounds of the angular speed and of the origin's speed over each piece of [lo, hi].
  struct RateBound {
    double omega, origin;
  };
  RateBound rates_over(double a, double b) const;
  double lo_, hi_;
  Expr translate_[3];
  std::vector<PathRotation> rotations_;
  std::vector<RateBound> rates_;
};

/// Poses at increasing times, each segment between neighbours either the constant-twist screw
/// motion from one pose to the next (exact), or translation linear and rotation by slerp.
class KeyframeMotion : public StageMotion {
 public:
  enum class Interpolation { Screw, Linear };
  /// @throws InputError at JSON pointer `field` when there are fewer than two poses or the times do not
  /// increase.
  KeyframeMotion(std::vector<double> times, std::vector<Eigen::Isometry3d> poses, Interpolation interpolation,
                 const std::string& field = "/motion");
  double lo() const override { return times_.front(); }
  double hi() const override { return times_.back(); }
  PoseJet pose(double t) const override;
  double speed_bound(double radius) const override;
  /// The one screw its merged screw segments make, when they make one.
  std::optional<ScrewSegment> as_screw(double radius) const override;
  Interpolation interpolation() const { return interpolation_; }
  const std::vector<double>& times() const { return times_; }
  const std::vector<Eigen::Isometry3d>& poses() const { return poses_; }

  /// The segments as screw motions, those that keep the pose left out: every segment of screw
  /// interpolation; linear segments when each only slides, only turns, or turns about an axis it
  /// slides along (else none).
  std::optional<std::vector<ScrewSegment>> screw_segments() const;
  /// Neighbouring segments that continue one screw (the same kind, axis line and pitch, and the
  /// second starting where the first ends, each to 1e-12 of `scale`, the model's size) as one
  /// segment over both ranges: keyframes sampled from one screw motion become that motion.
  static std::vector<ScrewSegment> merged(const std::vector<ScrewSegment>& segments, double scale);

 private:
  /// Segment k: from pose k, the rotation angle rate `rate` (radians per unit t) about unit axis
  /// `w`; for a screw segment the axis passes through `c` and advances `pitch` per radian plus
  /// `slide` per unit t (a translation without rotation); for a linear one p moves at `dp`.
  struct Segment {
    Eigen::Vector3d w = Eigen::Vector3d::UnitZ(), c = Eigen::Vector3d::Zero(), dp = Eigen::Vector3d::Zero();
    double rate = 0, pitch = 0;
    Eigen::Vector3d slide = Eigen::Vector3d::Zero();
  };
  std::size_t segment_of(double t) const;
  std::vector<double> times_;
  std::vector<Eigen::Isometry3d> poses_;
  Interpolation interpolation_;
  std::vector<Segment> segments_;
};

}  // namespace sweep
