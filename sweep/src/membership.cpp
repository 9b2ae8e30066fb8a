#include "sweep/membership.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sweep/error.hpp"

namespace sweep {
namespace {

using Eigen::Vector3d;

/// Wraps a local-frame distance with the entity placement (rigid, so still 1-Lipschitz).
class Placed : public SignedDistance {
 public:
  Placed(Eigen::Isometry3d placement, std::function<double(const Vector3d&)> f)
      : inv_(placement.inverse()), f_(std::move(f)) {}
  double operator()(const Vector3d& p) const override { return f_(inv_ * p); }

 private:
  Eigen::Isometry3d inv_;
  std::function<double(const Vector3d&)> f_;
};

/// Orthonormal frame with `axis` as its third column.
Eigen::Matrix3d frame_of(const Vector3d& axis) {
  Vector3d z = axis.normalized();
  Vector3d t = std::abs(z.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
  Vector3d x = z.cross(t).normalized();
  Eigen::Matrix3d F;
  F.col(0) = x;
  F.col(1) = z.cross(x);
  F.col(2) = z;
  return F;
}

}  // namespace

std::unique_ptr<SignedDistance> make_signed_distance(const EntitySpec& e) {
  switch (e.kind) {
    case EntityKind::Sphere: {
      Vector3d c = e.center;
      double r = e.radius;
      return std::make_unique<Placed>(e.placement, [c, r](const Vector3d& p) { return (p - c).norm() - r; });
    }
    case EntityKind::Box: {
      Vector3d c = 0.5 * (e.min + e.max), h = 0.5 * (e.max - e.min);
      return std::make_unique<Placed>(e.placement, [c, h](const Vector3d& p) {
        Vector3d q = (p - c).cwiseAbs() - h;
        return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
      });
    }
    case EntityKind::Cylinder: {
      Eigen::Matrix3d F = frame_of(e.axis);
      Vector3d b = e.base;
      double r = e.radius, hh = 0.5 * e.height;
      return std::make_unique<Placed>(e.placement, [F, b, r, hh](const Vector3d& p) {
        Vector3d l = F.transpose() * (p - b);
        double dr = std::hypot(l.x(), l.y()) - r, dz = std::abs(l.z() - hh) - hh;
        return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0)) + std::min(std::max(dr, dz), 0.0);
      });
    }
    case EntityKind::Cone: {
      // Intersection of the slab 0<=z<=h and the infinite cone through the two rims: the maximum
      // of the two signed distances is 1-Lipschitz with the right sign.
      Eigen::Matrix3d F = frame_of(e.axis);
      Vector3d b = e.base;
      double r1 = e.radius1, r2 = e.radius2, h = e.height;
      return std::make_unique<Placed>(e.placement, [F, b, r1, r2, h](const Vector3d& p) {
        Vector3d l = F.transpose() * (p - b);
        double rho = std::hypot(l.x(), l.y());
        double slab = std::abs(l.z() - 0.5 * h) - 0.5 * h;
        // line from (r1, 0) to (r2, h) in (rho, z); outward normal (h, r1 - r2) normalized
        double nx = h, nz = r1 - r2, len = std::hypot(nx, nz);
        double side = ((rho - r1) * nx + (l.z()) * nz) / len;
        return std::max(slab, side);
      });
    }
    case EntityKind::Torus: {
      Eigen::Matrix3d F = frame_of(e.axis);
      Vector3d c = e.center;
      double R = e.major, r = e.minor;
      return std::make_unique<Placed>(e.placement, [F, c, R, r](const Vector3d& p) {
        Vector3d l = F.transpose() * (p - c);
        return std::hypot(std::hypot(l.x(), l.y()) - R, l.z()) - r;
      });
    }
    default:
      return nullptr;
  }
}

bool in_swept_set(const SignedDistance& sd, const Motion& motion, const Vector3d& x,
                  double resolution) {
  const std::size_t n = motion.dof();
  SWEEP_ASSERT(n >= 1, "motion without joints");
  // Branch and bound over the joint box. For a sub-box with half-widths w_i around centre c, the
  // body-frame point y(q) = M(q)^-1 x moves at most sum_i S_i w_i from y(c), with S_i the speed
  // bound of joint i at the distance of x from the origin; sd is 1-Lipschitz.
  const double reach = x.norm() + motion.home.translation().norm();
  std::vector<double> speed(n);
  double lever = reach;
  for (const auto& j : motion.joints) lever += j.point.norm();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& j = motion.joints[i];
    speed[i] = j.is_rotation() ? lever + std::abs(j.pitch) + j.point.norm() : 1.0;
  }
  struct Box { std::vector<double> lo, hi; };
  std::vector<Box> stack;
  Box root;
  for (const auto& j : motion.joints) { root.lo.push_back(j.lo); root.hi.push_back(j.hi); }
  stack.push_back(root);
  std::vector<double> c(n);
  std::size_t iterations = 0;
  while (!stack.empty()) {
    Box b = std::move(stack.back());
    stack.pop_back();
    double move = 0.0, widest = -1.0;
    std::size_t split = 0;
    for (std::size_t i = 0; i < n; ++i) {
      c[i] = 0.5 * (b.lo[i] + b.hi[i]);
      double m = speed[i] * 0.5 * (b.hi[i] - b.lo[i]);
      move += m;
      if (m > widest) { widest = m; split = i; }
    }
    const Vector3d y = motion.transform(c).inverse() * x;
    const double d = sd(y);
    if (d <= 0.0) return true;
    if (d > move) continue;
    if (move < resolution || ++iterations > 2000000) continue;  // within resolution of the boundary: outside
    Box b2 = b;
    const double mid = c[split];
    b.hi[split] = mid;
    b2.lo[split] = mid;
    stack.push_back(std::move(b2));
    stack.push_back(std::move(b));
  }
  return false;
}

MonteCarloResult monte_carlo_volume(const std::function<bool(const Vector3d&)>& inside,
                                    const Eigen::AlignedBox3d& box, std::size_t samples,
                                    std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t hits = 0;
  const Vector3d lo = box.min(), ext = box.sizes();
  for (std::size_t k = 0; k < samples; ++k) {
    Vector3d p(lo.x() + ext.x() * u(rng), lo.y() + ext.y() * u(rng), lo.z() + ext.z() * u(rng));
    if (inside(p)) ++hits;
  }
  const double vbox = ext.prod();
  const double f = samples ? double(hits) / double(samples) : 0.0;
  MonteCarloResult r;
  r.samples = samples;
  r.volume = vbox * f;
  r.stderr_ = samples ? vbox * std::sqrt(f * (1.0 - f) / double(samples)) : 0.0;
  return r;
}

}  // namespace sweep
