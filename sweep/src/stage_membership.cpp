#include "sweep/stage_membership.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sweep {

namespace {

/// The largest angular speed |omega| and origin speed |dp| at the samples, and the largest
/// angular and origin accelerations (norms of ddR and ddp).
struct SampledRates {
  double omega = 0, dp = 0, ddR = 0, ddp = 0, spacing = 0;
};

SampledRates sampled_rates(const StageMotion& m, int samples) {
  SampledRates r;
  const double lo = m.lo(), hi = m.hi();
  r.spacing = (hi - lo) / samples;
  for (int k = 0; k <= samples; ++k) {
    const PoseJet P = m.pose(k == samples ? hi : lo + r.spacing * k);
    r.omega = std::max(r.omega, (P.dR * P.R.transpose()).norm() / std::sqrt(2.0));
    r.dp = std::max(r.dp, P.dp.norm());
    r.ddR = std::max(r.ddR, P.ddR.norm());
    r.ddp = std::max(r.ddp, P.ddp.norm());
  }
  return r;
}

}  // namespace

double sampled_speed_bound(const StageMotion& motion, double radius, int samples) {
  const SampledRates r = sampled_rates(motion, samples);
  return r.omega * radius + r.dp + r.spacing * (r.ddR * radius + r.ddp);
}

double origin_reach(const StageMotion& motion, int samples) {
  const double lo = motion.lo(), hi = motion.hi(), h = (hi - lo) / samples;
  double reach = 0;
  for (int k = 0; k <= samples; ++k) reach = std::max(reach, motion.pose(k == samples ? hi : lo + h * k).p.norm());
  double v = motion.speed_bound(0.0);
  if (!std::isfinite(v)) v = sampled_speed_bound(motion, 0.0, samples);
  return reach + 0.5 * h * v;
}

Eigen::AlignedBox3d stage_swept_box(const Eigen::AlignedBox3d& body, const StageMotion& motion, int samples) {
  double radius = 0;
  for (int k = 0; k < 8; ++k) radius = std::max(radius, body.corner(Eigen::AlignedBox3d::CornerType(k)).norm());
  double v = motion.speed_bound(radius);
  if (!std::isfinite(v)) v = sampled_speed_bound(motion, radius);
  const double lo = motion.lo(), hi = motion.hi(), h = (hi - lo) / samples;
  Eigen::AlignedBox3d out;
  for (int s = 0; s <= samples; ++s) {
    const Eigen::Isometry3d M = motion.transform(s == samples ? hi : lo + h * s);
    for (int k = 0; k < 8; ++k) out.extend(M * body.corner(Eigen::AlignedBox3d::CornerType(k)));
  }
  const Eigen::Vector3d pad = Eigen::Vector3d::Constant(0.5 * h * v);
  return Eigen::AlignedBox3d(out.min() - pad, out.max() + pad);
}

StageSweptSet::StageSweptSet(const SignedDistance& sd, const StageMotion& motion, double resolution,
                             std::size_t budget)
    : sd_(sd), motion_(motion), resolution_(resolution), budget_(budget), reach_(origin_reach(motion)) {
  certified_ = std::isfinite(motion.speed_bound(1.0));
  if (!certified_) {
    const SampledRates r = sampled_rates(motion, 4096);
    omega_ = r.omega + r.spacing * r.ddR;
    origin_ = r.dp + r.spacing * r.ddp;
  }
}

double StageSweptSet::speed(const Eigen::Vector3d& x) const {
  // the body point y(t) = R^T (x - p) moves at |omega x (x - p) - dp|, the speed of a body point
  // at distance |x - p| <= |x| + reach from the origin
  const double radius = x.norm() + reach_;
  return certified_ ? motion_.speed_bound(radius) : omega_ * radius + origin_;
}

int StageSweptSet::operator()(const Eigen::Vector3d& x) const {
  const double v = speed(x);
  struct Interval {
    double a, b;
  };
  std::vector<Interval> stack{{motion_.lo(), motion_.hi()}};
  std::size_t split = 0;
  while (!stack.empty()) {
    const Interval I = stack.back();
    stack.pop_back();
    const double m = 0.5 * (I.a + I.b);
    const double g = sd_(motion_.body_point(m, x));
    if (g <= 0) return 1;
    const double half = v * 0.5 * (I.b - I.a);
    if (g > half) continue;
    if (2 * half < resolution_) continue;  // within the resolution of the boundary: counts as out
    if (++split > budget_) return -1;
    stack.push_back({m, I.b});
    stack.push_back({I.a, m});
  }
  return 0;
}

}  // namespace sweep
