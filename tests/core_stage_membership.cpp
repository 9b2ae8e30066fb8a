// Membership in sweeps under one-parameter motions (sweep/stage_membership.hpp) against closed
// forms: a ball along a straight path (a capsule) and along a circle arc (a torus sector), with
// the motions' own speed bounds and with sampled ones; the box that holds the swept set.
#include <catch2/catch.hpp>

#include <cmath>
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
