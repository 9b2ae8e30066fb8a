#include "sweep/stage_motion.hpp"

#include "sweep/settings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sweep/error.hpp"
#include "sweep/interval.hpp"

namespace sweep {

namespace {

/// The largest and the smallest length of a vector in the box v.
double largest_norm(const Interval v[3]) { return Eigen::Vector3d(v[0].mag(), v[1].mag(), v[2].mag()).norm(); }
double smallest_norm(const Interval v[3]) { return Eigen::Vector3d(v[0].mig(), v[1].mig(), v[2].mig()).norm(); }

constexpr int kRatePieces = 256;  ///< pieces of [lo, hi] with their own rate bounds
constexpr int kRateSplits = 6;    ///< bisections of a piece whose enclosure has no finite bound

Eigen::Matrix3d hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d K;
  K << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return K;
}

/// A value with its first and second derivatives in t (forward-mode, second order).
struct Jet {
  double v = 0, d = 0, dd = 0;
};
Jet operator+(Jet a, Jet b) { return {a.v + b.v, a.d + b.d, a.dd + b.dd}; }
Jet operator-(Jet a, Jet b) { return {a.v - b.v, a.d - b.d, a.dd - b.dd}; }
Jet operator*(Jet a, Jet b) { return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2 * a.d * b.d + a.v * b.dd}; }
Jet inverse(Jet a) {
  const double i = 1 / a.v;
  return {i, -a.d * i * i, (2 * a.d * a.d * i - a.dd) * i * i};
}
Jet jet_sin(Jet a) { return {std::sin(a.v), std::cos(a.v) * a.d, std::cos(a.v) * a.dd - std::sin(a.v) * a.d * a.d}; }
Jet jet_cos(Jet a) { return {std::cos(a.v), -std::sin(a.v) * a.d, -std::sin(a.v) * a.dd - std::cos(a.v) * a.d * a.d}; }
Jet jet_sqrt(Jet a) {
  const double s = std::sqrt(a.v);
  return {s, a.d / (2 * s), (2 * a.v * a.dd - a.d * a.d) / (4 * a.v * s)};
}

/// An expression in the one variable t as a jet.
Jet jet_of(const Expr& e, double t) {
  double g = 0, h = 0;
  const double v = e.eval_d2(&t, &g, &h);
  return {v, g, h};
}

using JetMatrix = Jet[3][3];

/// R = I + sin(angle) K + (1 - cos(angle)) K^2, K the cross-product matrix of the unit axis.
void rotation_jet(const Jet axis[3], Jet angle, JetMatrix R) {
  const Jet inv_norm = inverse(jet_sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]));
  const Jet u[3] = {axis[0] * inv_norm, axis[1] * inv_norm, axis[2] * inv_norm};
  const Jet zero{};
  const Jet K[3][3] = {{zero, zero - u[2], u[1]}, {u[2], zero, zero - u[0]}, {zero - u[1], u[0], zero}};
  const Jet s = jet_sin(angle), c1 = Jet{1, 0, 0} - jet_cos(angle);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Jet k2{};
      for (int m = 0; m < 3; ++m) k2 = k2 + K[i][m] * K[m][j];
      R[i][j] = Jet{i == j ? 1.0 : 0.0, 0, 0} + s * K[i][j] + c1 * k2;
    }
}

/// The perpendicular distance of x from the axis through c along unit w.
double distance_to_axis(const Eigen::Vector3d& x, const Eigen::Vector3d& c, const Eigen::Vector3d& w) {
  const Eigen::Vector3d r = x - c;
  return (r - w * w.dot(r)).norm();
}

/// The screw of one twist, the rate along it 1: a turn about the axis through `point` with `pitch`,
/// or a slide along v when the twist does not turn.
ScrewJoint screw_of(const Twist& tw) {
  ScrewJoint j;
  const double w = tw.omega.norm();
  if (w == 0) {
    j.type = JointType::Prismatic;
    j.direction = tw.v.normalized();
    return j;
  }
  j.direction = tw.omega / w;
  j.point = tw.omega.cross(tw.v) / (w * w);
  j.pitch = tw.omega.dot(tw.v) / (w * w);
  j.type = JointType::Helical;
  return j;
}

/// The angle about unit w that rotation R turns a vector normal to w by.
double angle_about(const Eigen::Matrix3d& R, const Eigen::Vector3d& w) {
  const Eigen::Vector3d e = w.unitOrthogonal(), f = R * e;
  return std::atan2(w.dot(e.cross(f)), e.dot(f));
}

}  // namespace

std::optional<ScrewSegment> StageMotion::as_screw(double radius) const {
  constexpr int n = 1024;
  const double a = lo(), b = hi();
  if (!(b > a)) return std::nullopt;
  std::vector<double> ts(n + 1);
  std::vector<Eigen::Isometry3d> M(n + 1);
  std::vector<Twist> tw(n + 1);
  double reach = std::max(radius, 0.0), wmax = 0, vmax = 0;
  int kw = 0, kv = 0;
  for (int i = 0; i <= n; ++i) {
    ts[i] = a + (b - a) * i / n;
    M[i] = transform(ts[i]);
    tw[i] = twist(ts[i]);
    reach = std::max(reach, radius + M[i].translation().norm());
    if (tw[i].omega.norm() > wmax) wmax = tw[i].omega.norm(), kw = i;
    if (tw[i].v.norm() > vmax) vmax = tw[i].v.norm(), kv = i;
  }
  if (!std::isfinite(reach) || !(wmax * reach + vmax > 0)) return std::nullopt;  // no motion
  // the screw of the fastest turning twist (or of the fastest slide when none turns), rate 1
  const bool turns = wmax * reach > Settings::screw_rounding * vmax;
  ScrewJoint j = screw_of(turns ? tw[kw] : Twist{Eigen::Vector3d::Zero(), tw[kv].v});
  const Twist unit{turns ? j.direction : Eigen::Vector3d::Zero(),
                   turns ? Eigen::Vector3d(j.point.cross(j.direction) + j.pitch * j.direction) : j.direction};
  const double speed = wmax * reach + vmax;
  // each twist is that screw's at some rate r, of one sign; q is its value, from the poses
  std::vector<double> q(n + 1, 0.0);
  double r_min = 0, r_max = 0;
  for (int i = 0; i <= n; ++i) {
    const double r = turns ? tw[i].omega.dot(unit.omega) : tw[i].v.dot(unit.v);
    if ((tw[i].omega - r * unit.omega).norm() * reach + (tw[i].v - r * unit.v).norm() > Settings::screw_twist_match * speed)
      return std::nullopt;
    r_min = std::min(r_min, r), r_max = std::max(r_max, r);
    if (i == 0) continue;
    if (turns) {
      const double d = std::remainder(angle_about(M[i].linear() * M[0].linear().transpose(), j.direction) -
                                          angle_about(M[i - 1].linear() * M[0].linear().transpose(), j.direction),
                                      2 * M_PI);
      // the step agrees with the rates, so the angle was unwrapped on the right turn
      if (std::abs(d - 0.5 * (r + (tw[i - 1].omega.dot(unit.omega))) * (ts[i] - ts[i - 1])) > M_PI / 4)
        return std::nullopt;
      q[i] = q[i - 1] + d;
    } else {
      q[i] = (M[i].translation() - M[0].translation()).dot(j.direction);
    }
  }
  if (r_min < -Settings::screw_rounding * std::abs(r_max) && r_max > Settings::screw_rounding * std::abs(r_min))
    return std::nullopt;  // turns back
  double range = q[n];
  if (range < 0) {  // the same screw the other way round
    j.direction = -j.direction;
    range = -range;
    for (double& qi : q) qi = -qi;
  }
  if (!(range > 0)) return std::nullopt;
  if (turns && std::abs(j.pitch) * 2 * M_PI <= Settings::screw_rounding * reach) {
    j.pitch = 0;
    j.type = JointType::Revolute;
  }
  j.lo = 0;
  j.hi = range;
  // the screw's pose at every sample moves the body's points as the motion does
  for (int i = 0; i <= n; ++i) {
    const Eigen::Isometry3d S = j.transform(q[i]) * M[0];
    if ((S.linear() - M[i].linear()).norm() * radius + (S.translation() - M[i].translation()).norm() >
        Settings::screw_pose_match * reach)
      return std::nullopt;
  }
  return ScrewSegment{j, M[0], a, b};
}

Eigen::Isometry3d StageMotion::transform(double t) const {
  const PoseJet P = pose(t);
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  M.linear() = P.R;
  M.translation() = P.p;
  return M;
}

Twist StageMotion::twist(double t) const {
  const PoseJet P = pose(t);
  const Eigen::Matrix3d W = P.dR * P.R.transpose();
  Twist tw;
  tw.omega = Eigen::Vector3d(0.5 * (W(2, 1) - W(1, 2)), 0.5 * (W(0, 2) - W(2, 0)), 0.5 * (W(1, 0) - W(0, 1)));
  tw.v = P.dp - tw.omega.cross(P.p);
  return tw;
}

Eigen::Vector3d StageMotion::body_point(double t, const Eigen::Vector3d& x) const {
  const PoseJet P = pose(t);
  return P.R.transpose() * (x - P.p);
}

ScrewStage::ScrewStage(const ScrewJoint& joint, const Eigen::Isometry3d& home) : joint_(joint), home_(home) {}

PoseJet ScrewStage::pose(double t) const {
  const Eigen::Isometry3d M = joint_.transform(t) * home_;
  PoseJet P;
  P.R = M.linear();
  P.p = M.translation();
  if (joint_.type == JointType::Prismatic) {
    P.dp = joint_.direction;
    return P;
  }
  const Eigen::Matrix3d W = hat(joint_.direction);
  P.dR = W * P.R;
  P.ddR = W * P.dR;
  P.dp = joint_.velocity(P.p);
  P.ddp = joint_.direction.cross(P.dp);
  return P;
}

VelocityField::VelocityField(const ScrewJoint& joint) : screw_(joint) {}

VelocityField::VelocityField(const StageMotion& motion, double t, double radius) {
  if (const auto s = motion.as_screw(radius)) {
    screw_ = s->joint;
  } else {
    twist_ = motion.twist(t);
  }
}

double VelocityField::reach() const {
  if (screw_) return std::abs(screw_->pitch) + screw_->point.norm();  // (the point a joint gives, on its axis)
  const double w2 = twist_.omega.squaredNorm();
  if (w2 == 0) return 0.0;
  // the axis's point nearest the origin, omega x v / |omega|^2, and the pitch, omega . v / |omega|^2
  return (twist_.omega.cross(twist_.v).norm() + std::abs(twist_.omega.dot(twist_.v))) / w2;
}

std::optional<ScrewSegment> ScrewStage::as_screw(double) const {
  if (!(joint_.hi > joint_.lo)) return std::nullopt;
  ScrewSegment s;
  s.joint = joint_;
  s.joint.lo = 0;
  s.joint.hi = joint_.hi - joint_.lo;
  s.start = joint_.transform(joint_.lo) * home_;
  s.t0 = joint_.lo;
  s.t1 = joint_.hi;
  return s;
}

double ScrewStage::speed_bound(double radius) const {
  if (joint_.type == JointType::Prismatic) return 1.0;
  // the rotation keeps the distance of the home origin from the axis
  return radius + distance_to_axis(home_.translation(), joint_.point, joint_.direction) + std::abs(joint_.pitch);
}

PathMotion::PathMotion(double lo, double hi, const Expr translate[3], std::vector<PathRotation> rotations,
                       const std::string& field)
    : lo_(lo), hi_(hi), rotations_(std::move(rotations)) {
  if (!(lo < hi)) throw InputError(field + "/t", "the range is empty (lo must be below hi)");
  for (int i = 0; i < 3; ++i) translate_[i] = translate[i];
  for (std::size_t k = 0; k < rotations_.size(); ++k)
    for (int s = 0; s <= 256; ++s) {
      double t = lo + (hi - lo) * s / 256.0;
      Eigen::Vector3d a;
      for (int i = 0; i < 3; ++i) a[i] = rotations_[k].axis[i].eval(&t);
      if (!(a.norm() > Settings::screw_rounding))
        throw InputError(field + "/rotate/" + std::to_string(k) + "/axis",
                         "the rotation axis vanishes at t = " + std::to_string(t));
    }
  rates_.reserve(kRatePieces);
  const auto cut = [&](int k) { return k == kRatePieces ? hi : lo + (hi - lo) * k / kRatePieces; };
  for (int k = 0; k < kRatePieces; ++k) rates_.push_back(rates_over(cut(k), cut(k + 1)));
}

PoseJet PathMotion::pose(double t) const {
  // R(t) = R_1(t) R_2(t) ... as jets
  Jet R[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = Jet{i == j ? 1.0 : 0.0, 0, 0};
  for (const auto& rot : rotations_) {
    const Jet axis[3] = {jet_of(rot.axis[0], t), jet_of(rot.axis[1], t), jet_of(rot.axis[2], t)};
    Jet Rk[3][3];
    rotation_jet(axis, jet_of(rot.angle, t), Rk);
    Jet out[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        Jet s{};
        for (int m = 0; m < 3; ++m) s = s + R[i][m] * Rk[m][j];
        out[i][j] = s;
      }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) R[i][j] = out[i][j];
  }
  PoseJet P;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      P.R(i, j) = R[i][j].v;
      P.dR(i, j) = R[i][j].d;
      P.ddR(i, j) = R[i][j].dd;
    }
    const Jet p = jet_of(translate_[i], t);
    P.p[i] = p.v;
    P.dp[i] = p.d;
    P.ddp[i] = p.dd;
  }
  return P;
}

PathMotion::RateBound PathMotion::rates_over(double a, double b) const {
  const Interval t{a, b};
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Interval value, d[3], axis[3], daxis[3];
  bool defined = true;
  for (int i = 0; i < 3; ++i) defined = translate_[i].enclose_d1(&t, 0, value, d[i]) && defined;
  RateBound r{0.0, defined ? largest_norm(d) : kInf};
  // R = R_1 R_2 ...: omega = omega_1 + R_1 omega_2 + ...; the rotation by angle th about the unit
  // axis u turns at th' u + sin(th) u' + (1 - cos(th)) u x u', of length at most |th'| + 2 |u'|,
  // and |u'| <= |axis'| / |axis|
  for (const PathRotation& rot : rotations_) {
    r.omega += rot.angle.enclose_d1(&t, 0, value, d[0]) ? d[0].mag() : kInf;
    if (rot.axis[0].is_constant() && rot.axis[1].is_constant() && rot.axis[2].is_constant()) continue;
    defined = true;
    for (int i = 0; i < 3; ++i) defined = rot.axis[i].enclose_d1(&t, 0, axis[i], daxis[i]) && defined;
    const double least = smallest_norm(axis);
    r.omega += defined && least > 0 ? 2 * largest_norm(daxis) / least : kInf;
  }
  // the norms above are computed in rounded arithmetic from rounded-out enclosures
  r.omega *= 1 + Settings::rate_bound_rounding;
  r.origin *= 1 + Settings::rate_bound_rounding;
  if (std::isfinite(r.omega) && std::isfinite(r.origin)) return r;
  if (b - a <= (hi_ - lo_) / (kRatePieces << kRateSplits) || !(r.omega == r.omega)) return r;
  const double m = 0.5 * (a + b);
  const RateBound left = rates_over(a, m), right = rates_over(m, b);
  return {std::max(left.omega, right.omega), std::max(left.origin, right.origin)};
}

double PathMotion::speed_bound(double radius) const {
  double v = 0;
  for (const RateBound& r : rates_) v = std::max(v, r.omega * radius + r.origin);
  return v;
}

KeyframeMotion::KeyframeMotion(std::vector<double> times, std::vector<Eigen::Isometry3d> poses,
                               Interpolation interpolation, const std::string& field)
    : times_(std::move(times)), poses_(std::move(poses)), interpolation_(interpolation) {
  if (times_.size() < 2 || times_.size() != poses_.size())
    throw InputError(field + "/poses", "at least two poses are needed, each with its t");
  for (std::size_t k = 0; k + 1 < times_.size(); ++k) {
    if (!(times_[k] < times_[k + 1]))
      throw InputError(field + "/poses/" + std::to_string(k + 1) + "/t",
                       "the times must increase (" + std::to_string(times_[k + 1]) + " after " +
                           std::to_string(times_[k]) + ")");
    const Eigen::Isometry3d& A = poses_[k];
    const Eigen::Isometry3d& B = poses_[k + 1];
    const double dt = times_[k + 1] - times_[k];
    // the rotation from A to B in world coordinates: R_B = R_D R_A
    const Eigen::AngleAxisd aa(Eigen::Matrix3d(B.linear() * A.linear().transpose()));
    Segment s;
    const double phi = aa.angle();
    if (phi > Settings::screw_rounding) {
      s.w = aa.axis();
      s.rate = phi / dt;
    }
    if (interpolation_ == Interpolation::Linear || phi <= Settings::screw_rounding) {
      s.dp = (B.translation() - A.translation()) / dt;
      s.slide = s.dp;
    } else {
      // D = B A^-1 as a screw: rotation R_D about the axis through c along w, advancing h along w
      const Eigen::Matrix3d RD = aa.toRotationMatrix();
      const Eigen::Vector3d tD = B.translation() - RD * A.translation();
      const double h = s.w.dot(tD);
      s.pitch = h / phi;
      s.c = (Eigen::Matrix3d::Identity() - RD + s.w * s.w.transpose()).lu().solve(tD - h * s.w);
    }
    segments_.push_back(s);
  }
}

std::size_t KeyframeMotion::segment_of(double t) const {
  std::size_t k = 0;
  while (k + 2 < times_.size() && t >= times_[k + 1]) ++k;
  return k;
}

PoseJet KeyframeMotion::pose(double t) const {
  const std::size_t k = segment_of(t);
  const Segment& s = segments_[k];
  const Eigen::Isometry3d& A = poses_[k];
  const double tau = t - times_[k];
  const Eigen::Matrix3d W = hat(s.w) * s.rate;
  PoseJet P;
  const Eigen::Matrix3d Rj = Eigen::AngleAxisd(s.rate * tau, s.w).toRotationMatrix();
  P.R = Rj * A.linear();
  P.dR = W * P.R;
  P.ddR = W * P.dR;
  if (interpolation_ == Interpolation::Linear || s.rate == 0) {
    P.p = A.translation() + s.slide * tau;
    P.dp = s.slide;
    return P;
  }
  P.p = s.c + Rj * (A.translation() - s.c) + s.w * (s.pitch * s.rate * tau);
  P.dp = s.rate * (s.w.cross(P.p - s.c) + s.pitch * s.w);
  P.ddp = s.rate * s.w.cross(P.dp);
  return P;
}

std::optional<ScrewSegment> KeyframeMotion::as_screw(double radius) const {
  const auto segments = screw_segments();
  if (!segments || segments->empty()) return std::nullopt;
  double reach = std::max(radius, 0.0);
  for (const auto& P : poses_) reach = std::max(reach, radius + P.translation().norm());
  const auto one = merged(*segments, reach);
  if (one.size() != 1) return std::nullopt;
  return one.front();
}

double KeyframeMotion::speed_bound(double radius) const {
  double bound = 0;
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    const Segment& s = segments_[k];
    double v = 0;
    if (interpolation_ == Interpolation::Linear || s.rate == 0)
      v = s.rate * radius + s.slide.norm();
    else  // the rotation keeps the pose origin's distance from the axis
      v = s.rate * (radius + distance_to_axis(poses_[k].translation(), s.c, s.w) + std::abs(s.pitch));
    bound = std::max(bound, v);
  }
  return bound;
}

std::optional<std::vector<ScrewSegment>> KeyframeMotion::screw_segments() const {
  std::vector<ScrewSegment> out;
  for (std::size_t k = 0; k < segments_.size(); ++k) {
    const Segment& s = segments_[k];
    const double dt = times_[k + 1] - times_[k];
    ScrewSegment seg;
    seg.start = poses_[k];
    seg.t0 = times_[k];
    seg.t1 = times_[k + 1];
    if (s.rate > 0) {
      seg.joint.direction = s.w;
      seg.joint.hi = s.rate * dt;
      if (interpolation_ == Interpolation::Screw) {
        seg.joint.point = s.c;
        seg.joint.pitch = s.pitch;
      } else {
        // turning about the pose origin while it slides: a screw only when it slides along the axis
        const double slide = s.slide.norm();
        if (s.slide.cross(s.w).norm() > Settings::screw_rounding * std::max(1.0, slide)) return std::nullopt;
        seg.joint.point = poses_[k].translation();
        seg.joint.pitch = s.slide.dot(s.w) / s.rate;
      }
      seg.joint.type = seg.joint.pitch == 0 ? JointType::Revolute : JointType::Helical;
    } else {
      const double length = s.slide.norm() * dt;
      if (!(length > 0)) continue;  // the pose stays: nothing new is swept
      seg.joint.type = JointType::Prismatic;
      seg.joint.direction = s.slide.normalized();
      seg.joint.hi = length;
    }
    out.push_back(seg);
  }
  return out;
}

namespace {

/// Whether segment b continues the screw of segment a (see KeyframeMotion::merged).
bool continues(const ScrewSegment& a, const ScrewSegment& b, double scale) {
  const ScrewJoint &ja = a.joint, &jb = b.joint;
  const double eps = Settings::screw_rounding * std::max(scale, 1e-300);
  // (a revolute joint and a helical one of pitch 0 to rounding are one screw)
  if (ja.is_rotation() != jb.is_rotation() || (ja.direction - jb.direction).norm() > Settings::screw_rounding) return false;
  if (ja.type != JointType::Prismatic) {
    if (std::abs(ja.pitch - jb.pitch) > eps || (jb.point - ja.point).cross(ja.direction).norm() > eps) return false;
  }
  // b starts where a ends: the two poses move every point of the model's size alike
  const Eigen::Isometry3d end = ja.transform(ja.hi) * a.start;
  return (end.translation() - b.start.translation()).norm() <= eps &&
         (end.linear() - b.start.linear()).norm() * scale <= eps;
}

}  // namespace

std::vector<ScrewSegment> KeyframeMotion::merged(const std::vector<ScrewSegment>& segments, double scale) {
  std::vector<ScrewSegment> out;
  for (const ScrewSegment& s : segments) {
    if (!out.empty() && continues(out.back(), s, scale)) {
      out.back().joint.hi += s.joint.hi - s.joint.lo;
      out.back().t1 = s.t1;
    } else {
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace sweep
