// Membership in sweeps under one-parameter motions (sweep/stage_membership.hpp) against closed
// forms: a ball along a straight path (a capsule) and along a circle arc (a torus sector), with
// the motions' own speed bounds and with sampled ones; the box that holds the swept set. The search
// over a joint box with a distance bound that is loose near the boundary.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "sweep/stage_membership.hpp"

using namespace sweep;

namespace {

Expr texpr(const std::string& s) { return Expr::parse(s, {"t"}); }

EntitySpec ball(const Eigen::Vector3d& c, double r) {
  EntitySpec e;
  e.kind = EntityKind::Sphere;
  e.center = c;
  e.radius = r;
  return e;
}

/// Random points in `box`; those farther than `gap` from the boundary by `distance` (the exact
/// signed distance to the swept set) must be classified alike; none may stay undecided.
void check_against(const StageSweptSet& set, const std::function<double(const Eigen::Vector3d&)>& distance,
                   const Eigen::AlignedBox3d& box, double gap) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  int inside = 0, checked = 0;
  for (int k = 0; k < 3000; ++k) {
    const Eigen::Vector3d x = box.min() + box.sizes().cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const double d = distance(x);
    const int got = set(x);
    REQUIRE(got >= 0);
    if (std::abs(d) < gap) continue;
    INFO("x = " << x.transpose() << ", distance " << d);
    CHECK(got == (d < 0 ? 1 : 0));
    inside += d < 0;
    ++checked;
  }
  CHECK(inside > 300);
  CHECK(checked > 2500);
}

}  // namespace

TEST_CASE("Stage membership: a ball along a straight path is a capsule", "[stage_membership]") {
  const Expr tr[3] = {texpr("3*t"), texpr("0.5*t"), texpr("-t")};
  const PathMotion path(0, 2, tr, {});
  const Eigen::Vector3d c0(0.2, 0.1, -0.3), d(6, 1, -2);
  const double r = 0.7;
  const auto sd = make_signed_distance(ball(c0, r));
  const StageSweptSet set(*sd, path, 1e-9, 20000);
  CHECK(set.certified());  // interval enclosures of the path's expressions
  const auto capsule = [&](const Eigen::Vector3d& x) {
    const double s = std::clamp((x - c0).dot(d) / d.squaredNorm(), 0.0, 1.0);
    return (x - c0 - s * d).norm() - r;
  };
  const Eigen::AlignedBox3d box = stage_swept_box(Eigen::AlignedBox3d(c0.array() - r, c0.array() + r), path);
  // the box holds the capsule and is not much larger
  CHECK(box.contains(c0 + d + Eigen::Vector3d(r, 0, 0) * 0.999));
  CHECK(box.sizes().x() == Approx(6 + 2 * r).epsilon(1e-3));
  check_against(set, capsule, box, 1e-6);
}

TEST_CASE("Stage membership: a ball along a circle arc is a torus sector", "[stage_membership]") {
  // keyframes with screw interpolation about z (certified speed bound) and the same motion as a path
  std::vector<Eigen::Isometry3d> poses;
  for (double a : {0.0, 1.0, 2.0}) {
    Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
    M.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    poses.push_back(M);
  }
  const KeyframeMotion keys({0, 1, 2}, poses, KeyframeMotion::Interpolation::Screw);
  const Expr zero[3] = {texpr("0"), texpr("0"), texpr("0")};
  const PathMotion path(0, 2, zero, {PathRotation{{texpr("0"), texpr("0"), texpr("1")}, texpr("t")}});
  const Eigen::Vector3d c0(3, 0, 0.5);
  const double r = 1.0;
  const auto sd = make_signed_distance(ball(c0, r));
  const auto sector = [&](const Eigen::Vector3d& x) {
    const double a = std::atan2(x.y(), x.x());
    if (a >= 0 && a <= 2) return std::hypot(std::hypot(x.x(), x.y()) - 3, x.z() - 0.5) - r;
    const Eigen::Vector3d e0 = c0, e1(3 * std::cos(2.0), 3 * std::sin(2.0), 0.5);
    return std::min((x - e0).norm(), (x - e1).norm()) - r;
  };
  const Eigen::AlignedBox3d box(Eigen::Vector3d(-4.5, -1.5, -1), Eigen::Vector3d(4.5, 4.5, 2));
  for (const StageMotion* m : {static_cast<const StageMotion*>(&keys), static_cast<const StageMotion*>(&path)}) {
    const StageSweptSet set(*sd, *m, 1e-9, 20000);
    CHECK(set.certified());
    check_against(set, sector, box, 1e-6);
  }
}

TEST_CASE("Stage membership: the sampled speed bound is above sampled speeds", "[stage_membership]") {
  const Expr tr[3] = {texpr("sin(3*t)"), texpr("t^3"), texpr("cos(t)")};
  const PathMotion path(-1, 2, tr, {PathRotation{{texpr("1"), texpr("t"), texpr("1")}, texpr("2*t^2")}});
  const double radius = 1.5, bound = sampled_speed_bound(path, radius);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  double seen = 0;
  for (int k = 0; k < 4000; ++k) {
    const double t = 0.5 + 1.5 * u(rng);
    Eigen::Vector3d y(u(rng), u(rng), u(rng));
    y *= radius / std::max(1.0, y.norm()) * (y.norm() > 0 ? 1.0 : 0.0);
    const PoseJet P = path.pose(t);
    seen = std::max(seen, (P.dR * y + P.dp).norm());
  }
  CHECK(seen <= bound);
  CHECK(seen >= 0.5 * bound);
  // the certified bound from interval enclosures holds too, and is not far above
  CHECK(seen <= path.speed_bound(radius));
  CHECK(seen >= 0.3 * path.speed_bound(radius));
}

namespace {

/// A ball's distance made loose the way a triangulated solid's is: within `slack` of the sphere
/// the side is not told (the smallest positive double), elsewhere the distance less half the slack.
class LooseBall : public SignedDistance {
 public:
  LooseBall(const Eigen::Vector3d& c, double r, double slack) : c_(c), r_(r), slack_(slack) {}
  double operator()(const Eigen::Vector3d& p) const override {
    ++calls;
    const double d = (p - c_).norm() - r_;
    if (std::abs(d) < slack_) return std::numeric_limits<double>::min();
    return d < 0 ? d + 0.5 * slack_ : d - 0.5 * slack_;
  }
  double slack() const override { return slack_; }
  mutable std::size_t calls = 0;

 private:
  Eigen::Vector3d c_;
  double r_, slack_;
};

}  // namespace

TEST_CASE("Joint-box membership: a loose distance bound is never wrong, and undecided only near the boundary",
          "[stage_membership]") {
  // a ball slid by two prismatic joints: the swept set is the rectangle of its centre's positions
  // grown by the radius
  const Eigen::Vector3d c(0.3, -0.2, 0.1), a(2, 0, 0), b(0, 1.5, 0.5);
  const double r = 0.6, slack = 1e-3;
  Motion m;
  for (const Eigen::Vector3d& dir : {a, b}) {
    ScrewJoint j;
    j.type = JointType::Prismatic;
    j.direction = dir.normalized();
    j.hi = dir.norm();
    m.joints.push_back(j);
  }
  const auto swept_distance = [&](const Eigen::Vector3d& x) {
    // the distance to the centre's parallelogram: to x's projection onto its plane when that falls
    // inside it, else to the nearest of 401 points on each side (within 1e-5 here)
    const Eigen::Matrix<double, 3, 2> E = (Eigen::Matrix<double, 3, 2>() << a, b).finished();
    Eigen::Vector2d s = (E.transpose() * E).ldlt().solve(E.transpose() * (x - c));
    double best = 1e300;
    for (int k = 0; k <= 400; ++k) {  // the nearest point on the parallelogram's boundary
      const double f = k / 400.0;
      for (const Eigen::Vector2d& q :
           {Eigen::Vector2d(f, 0), Eigen::Vector2d(f, 1), Eigen::Vector2d(0, f), Eigen::Vector2d(1, f)})
        best = std::min(best, (x - c - E * q).norm());
    }
    if (s.minCoeff() >= 0 && s.maxCoeff() <= 1) best = std::min(best, (x - c - E * s).norm());
    return best - r;
  };
  const LooseBall loose(c, r, slack);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  int decided = 0, undecided_far = 0, inside = 0;
  for (int k = 0; k < 1500; ++k) {
    const Eigen::Vector3d x = c + 0.5 * (a + b) + Eigen::Vector3d(1.8 * u(rng), 1.6 * u(rng), 1.2 * u(rng));
    const double d = swept_distance(x);
    const int got = swept_set_membership(loose, m, x, 1e-6, 20000);
    INFO("x = " << x.transpose() << ", distance " << d);
    // the boundary search above is within 1e-5 of the distance
    if (got >= 0 && std::abs(d) > 1e-4) CHECK(got == (d < 0 ? 1 : 0));
    if (got >= 0) ++decided;
    if (got < 0 && std::abs(d) > 10 * slack) ++undecided_far;
    inside += got == 1;
  }
  CHECK(decided > 1400);
  CHECK(undecided_far == 0);
  CHECK(inside > 200);
  // Points within a few slacks of the faces the parallelogram's plane carries (their distance is
  // their offset): never wrong, and the search stops at the first sub-box the bound cannot
  // decide, not at the budget's end.
  const Eigen::Vector3d n = a.cross(b).normalized();
  loose.calls = 0;
  for (int k = 0; k < 300; ++k) {
    const double delta = 3 * slack * u(rng);
    const double side = u(rng) < 0 ? -1 : 1;
    const Eigen::Vector3d x = c + (0.5 + 0.4 * u(rng)) * a + (0.5 + 0.4 * u(rng)) * b + side * (r + delta) * n;
    const int got = swept_set_membership(loose, m, x, 1e-6, 20000);
    INFO("x = " << x.transpose() << ", distance " << delta);
    if (got >= 0) CHECK(got == (delta < 0 ? 1 : 0));
  }
  CAPTURE(loose.calls);
  CHECK(loose.calls < 300 * 10000);  // (17,000 each when the search runs to its budget)
}

TEST_CASE("Joint-box membership: a box under a helical, a revolute and a prismatic joint against a dense grid",
          "[stage_membership]") {
  // Each sub-box's move bound comes from the point's distance to each axis at the box's centre;
  // a bound too small would call a swept point out. The grid's values of the box's distance decide
  // the points it can: inside where one is negative, outside where all exceed what the grid's
  // spacing can hide.
  EntitySpec box;
  box.kind = EntityKind::Box;
  box.min = Eigen::Vector3d(0.2, -0.3, 0.1);
  box.max = Eigen::Vector3d(0.9, 0.4, 0.5);
  const auto sd = make_signed_distance(box);
  Motion m;
  ScrewJoint h;
  h.type = JointType::Helical;
  h.point = Eigen::Vector3d(0.1, 0.2, -0.3);
  h.direction = Eigen::Vector3d(0.3, -0.2, 1).normalized();
  h.pitch = 0.15;
  h.hi = 2.0;
  ScrewJoint r;
  r.point = Eigen::Vector3d(1.2, 0.3, 0.2);
  r.direction = Eigen::Vector3d(1, 0.4, -0.2).normalized();
  r.lo = -0.6;
  r.hi = 0.5;
  ScrewJoint p;
  p.type = JointType::Prismatic;
  p.direction = Eigen::Vector3d(0.2, 1, 0.3).normalized();
  p.hi = 0.7;
  m.joints = {h, r, p};
  const int N = 40;
  // the grid hides at most half a spacing of each joint times a speed bound over the region
  double hidden = 0;
  for (const ScrewJoint& j : m.joints) hidden += 0.5 * (j.hi - j.lo) / N * (j.is_rotation() ? 8.0 + j.pitch : 1.0);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  int inside = 0, outside = 0, decided = 0;
  for (int k = 0; k < 200; ++k) {
    const Eigen::Vector3d x(0.5 + 1.3 * u(rng), 0.3 + 1.3 * u(rng), 0.4 + 1.0 * u(rng));
    double least = 1e300;
    std::vector<double> q(3);
    for (int a = 0; a <= N; ++a)
      for (int b = 0; b <= N; ++b)
        for (int c = 0; c <= N; ++c) {
          q = {h.lo + (h.hi - h.lo) * a / N, r.lo + (r.hi - r.lo) * b / N, p.lo + (p.hi - p.lo) * c / N};
          least = std::min(least, (*sd)(m.transform(q).inverse() * x));
        }
    const int got = swept_set_membership(*sd, m, x, 1e-9, 20000);
    INFO("x = " << x.transpose() << ", least distance on the grid " << least);
    decided += got >= 0;
    if (least < -1e-9) {
      ++inside;
      CHECK(got != 0);
    } else if (least > hidden) {
      ++outside;
      CHECK(got != 1);
    }
  }
  CHECK(inside > 20);
  CHECK(outside > 20);
  CHECK(decided > 190);
}
