// One-parameter rigid motions (sweep/stage_motion.hpp): derivatives against central differences,
// screw keyframes against the screw joint they sample, the velocity field against moved points,
// speed bounds against sampled speeds, and bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "sweep/error.hpp"
#include "sweep/stage_motion.hpp"

using namespace sweep;

namespace {

/// Checks pose(t)'s derivatives against central differences of the pose and of its first
/// derivatives, at sampled t inside the range.
void check_derivatives(const StageMotion& m, double tol) {
  const double h = 1e-5 * (m.hi() - m.lo());
  for (int s = 1; s < 10; ++s) {
    const double t = m.lo() + (m.hi() - m.lo()) * (s + 0.37) / 11.0;
    const PoseJet P = m.pose(t), A = m.pose(t - h), B = m.pose(t + h);
    INFO("t = " << t);
    CHECK((P.dR - (B.R - A.R) / (2 * h)).norm() < tol);
    CHECK((P.dp - (B.p - A.p) / (2 * h)).norm() < tol);
    CHECK((P.ddR - (B.dR - A.dR) / (2 * h)).norm() < tol);
    CHECK((P.ddp - (B.dp - A.dp) / (2 * h)).norm() < tol);
    CHECK((P.R.transpose() * P.R - Eigen::Matrix3d::Identity()).norm() < 1e-12);
    CHECK(P.R.determinant() == Approx(1.0).margin(1e-12));
  }
}

Eigen::Isometry3d random_pose(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  M.linear() = Eigen::AngleAxisd(3 * u(rng), Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  M.translation() = Eigen::Vector3d(2 * u(rng), 2 * u(rng), 2 * u(rng));
  return M;
}

Expr texpr(const std::string& s) { return Expr::parse(s, {"t"}); }

/// The poses of `m` at n + 1 equally spaced times over its range, and those times.
void sample_poses(const StageMotion& m, int n, std::vector<double>& ts, std::vector<Eigen::Isometry3d>& poses) {
  for (int k = 0; k <= n; ++k) {
    ts.push_back(m.lo() + (m.hi() - m.lo()) * k / n);
    poses.push_back(m.transform(ts.back()));
  }
}

/// A joint of kind `k` % 3 (prismatic, revolute, helical) on a random axis, its range left to the caller.
ScrewJoint random_joint(std::mt19937& rng, int k) {
  std::uniform_real_distribution<double> u(-1, 1);
  ScrewJoint j;
  j.type = k % 3 == 0 ? JointType::Prismatic : k % 3 == 1 ? JointType::Revolute : JointType::Helical;
  j.point = {u(rng), u(rng), u(rng)};
  j.direction = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
  j.pitch = j.type == JointType::Helical ? u(rng) : 0.0;
  return j;
}

}  // namespace

TEST_CASE("Stage motions: a screw stage's derivatives and velocity field", "[stage_motion]") {
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = {0.4, -1.2, 0.3};
  j.direction = Eigen::Vector3d(0.2, 0.5, 1).normalized();
  j.pitch = 0.35;
  j.lo = -0.5;
  j.hi = 4.0;
  std::mt19937 rng(3);
  const ScrewStage m(j, random_pose(rng));
  check_derivatives(m, 1e-6);
  // the twist moves each world point as the joint's velocity does
  const Eigen::Vector3d x(1.5, 0.2, -0.7);
  CHECK((m.twist(1.3).at(x) - j.velocity(x)).norm() < 1e-12);
  CHECK((m.transform(1.3) * m.body_point(1.3, x) - x).norm() < 1e-12);
}

TEST_CASE("Stage motions: screw keyframes reproduce the screw joint they sample", "[stage_motion]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    ScrewJoint j;
    j.type = JointType::Helical;
    j.point = {u(rng), u(rng), u(rng)};
    j.direction = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    j.pitch = u(rng);
    j.lo = 0;
    j.hi = 2.5;  // segments below half a turn: the keyframes fix the screw
    const Eigen::Isometry3d home = random_pose(rng);
    const ScrewStage exact(j, home);
    std::vector<double> ts;
    std::vector<Eigen::Isometry3d> poses;
    sample_poses(exact, 8, ts, poses);
    const KeyframeMotion keys(ts, poses, KeyframeMotion::Interpolation::Screw);
    for (double t : {0.1, 0.77, 1.3, 2.49}) {
      const PoseJet a = exact.pose(t), b = keys.pose(t);
      INFO("trial " << trial << " t " << t);
      CHECK((a.R - b.R).norm() < 1e-9);
      CHECK((a.p - b.p).norm() < 1e-9);
      CHECK((a.dp - b.dp).norm() < 1e-9);
      CHECK((a.ddR - b.ddR).norm() < 1e-9);
    }
    check_derivatives(keys, 1e-6);
  }
}

TEST_CASE("Stage motions: screw segments that continue one screw merge into it, others stay apart", "[stage_motion]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    // keyframes sampled from one random screw (of each kind), then a second screw after the last pose
    ScrewJoint j = random_joint(rng, trial);
    j.lo = 0;
    j.hi = 2.5;
    const Eigen::Isometry3d home = random_pose(rng);
    const ScrewStage exact(j, home);
    std::vector<double> ts;
    std::vector<Eigen::Isometry3d> poses;
    sample_poses(exact, 8, ts, poses);
    ScrewJoint other = j;
    other.direction = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    ts.push_back(3.0);
    poses.push_back(other.transform(0.4) * poses.back());
    const KeyframeMotion keys(ts, poses, KeyframeMotion::Interpolation::Screw);
    const auto segments = keys.screw_segments();
    REQUIRE(segments);
    REQUIRE(segments->size() == 9);
    const auto merged = KeyframeMotion::merged(*segments, 5.0);
    INFO("trial " << trial);
    REQUIRE(merged.size() == 2);
    const auto& m = merged.front();
    CHECK(m.t0 == 0.0);
    CHECK(m.t1 == 2.5);
    // the merged segment moves the start pose as the screw does, over the whole range
    for (double t : {0.0, 0.3, 1.7, 2.5}) {
      const double q = (t - m.t0) / (m.t1 - m.t0) * (m.joint.hi - m.joint.lo);
      const Eigen::Isometry3d a = m.joint.transform(m.joint.lo + q) * m.start, b = exact.transform(t);
      CHECK((a.matrix() - b.matrix()).norm() < 1e-9);
    }
    CHECK(merged.back().t0 == 2.5);
    // a segment that turns back the way it came does not continue the screw
    std::vector<ScrewSegment> back_and_forth{segments->front(), segments->front()};
    back_and_forth.back().start = segments->front().start;
    CHECK(KeyframeMotion::merged(back_and_forth, 5.0).size() == 2);
  }
}

TEST_CASE("Stage motions: linear keyframes move the origin on a segment and turn at one rate", "[stage_motion]") {
  std::mt19937 rng(7);
  std::vector<Eigen::Isometry3d> poses = {random_pose(rng), random_pose(rng), random_pose(rng)};
  const KeyframeMotion m({0, 1, 3}, poses, KeyframeMotion::Interpolation::Linear);
  check_derivatives(m, 1e-6);
  CHECK((m.transform(0.5).translation() - 0.5 * (poses[0].translation() + poses[1].translation())).norm() < 1e-12);
  CHECK((m.transform(3).linear() - poses[2].linear()).norm() < 1e-9);
  // the rotation angle grows linearly within a segment
  const double a1 = Eigen::AngleAxisd(Eigen::Matrix3d(m.transform(2).linear() * poses[1].linear().transpose())).angle();
  const double a2 = Eigen::AngleAxisd(Eigen::Matrix3d(poses[2].linear() * poses[1].linear().transpose())).angle();
  CHECK(a1 == Approx(0.5 * a2).margin(1e-9));
}

TEST_CASE("Stage motions: a path of expressions, rotations composed left to right", "[stage_motion]") {
  const Expr tr[3] = {texpr("2*t"), texpr("sin(t)"), texpr("t^2/3")};
  std::vector<PathRotation> rots(2);
  rots[0] = {{texpr("0"), texpr("0"), texpr("1")}, texpr("t")};
  rots[1] = {{texpr("1"), texpr("cos(t)"), texpr("0.5+t")}, texpr("0.3*t^2")};
  const PathMotion m(0, 2, tr, rots);
  check_derivatives(m, 1e-6);
  const double t = 1.1;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(t, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                            Eigen::AngleAxisd(0.3 * t * t, Eigen::Vector3d(1, std::cos(t), 0.5 + t).normalized())
                                .toRotationMatrix();
  CHECK((m.transform(t).linear() - R).norm() < 1e-12);
  CHECK((m.transform(t).translation() - Eigen::Vector3d(2 * t, std::sin(t), t * t / 3)).norm() < 1e-12);
  // a path whose rotation is a fixed axis at a uniform rate is the screw joint about it
  ScrewJoint j;
  j.point = Eigen::Vector3d::Zero();
  j.direction = Eigen::Vector3d::UnitZ();
  j.lo = 0;
  j.hi = 2;
  const Expr tz[3] = {texpr("0"), texpr("0"), texpr("0")};
  const PathMotion turn(0, 2, tz, {PathRotation{{texpr("0"), texpr("0"), texpr("1")}, texpr("t")}});
  const ScrewStage screw(j);
  CHECK((turn.pose(0.9).dR - screw.pose(0.9).dR).norm() < 1e-12);
  CHECK(turn.speed_bound(1.0) == Approx(1.0).epsilon(1e-9));
  CHECK(turn.speed_bound(2.0) == Approx(2.0).epsilon(1e-9));
  // an angle across a pole of tan has no finite bound
  const PathMotion pole(0, 2, tz, {PathRotation{{texpr("0"), texpr("0"), texpr("1")}, texpr("tan(t)")}});
  CHECK(std::isinf(pole.speed_bound(1.0)));
}

namespace {

/// A screw stage seen only through its poses (so the default as_screw finds its screw), run at
/// the rate q'(t) = 3 t^2 / (hi - lo)^2 over the joint's range.
class EasedScrew : public StageMotion {
 public:
  explicit EasedScrew(const ScrewStage& s) : s_(s) {}
  double lo() const override { return s_.lo(); }
  double hi() const override { return s_.hi(); }
  PoseJet pose(double t) const override {
    const double L = hi() - lo(), f = (t - lo()) / L;
    const double q = lo() + L * f * f * f, dq = 3 * f * f, ddq = 6 * f / L;
    PoseJet P = s_.pose(q);
    P.ddR = P.ddR * dq * dq + P.dR * ddq;
    P.ddp = P.ddp * dq * dq + P.dp * ddq;
    P.dR *= dq;
    P.dp *= dq;
    return P;
  }
  double speed_bound(double radius) const override { return 3 * s_.speed_bound(radius); }

 private:
  const ScrewStage& s_;
};

}  // namespace

TEST_CASE("Stage motions: a motion that is one screw says so, with the range it covers", "[stage_motion]") {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 30; ++trial) {
    ScrewJoint j = random_joint(rng, trial);
    j.lo = u(rng);
    j.hi = j.lo + 0.2 + 7 * std::abs(u(rng));  // up to more than a whole turn
    const ScrewStage stage(j, random_pose(rng));
    const EasedScrew eased(stage);
    for (const StageMotion* m : {static_cast<const StageMotion*>(&stage), static_cast<const StageMotion*>(&eased)}) {
      INFO("trial " << trial << (m == &stage ? " (the stage)" : " (eased)"));
      const auto s = m->as_screw(2.0);
      REQUIRE(s);
      CHECK(s->joint.type == j.type);
      CHECK(s->joint.hi - s->joint.lo == Approx(j.hi - j.lo).epsilon(1e-9));
      CHECK(std::abs(s->joint.direction.dot(j.direction)) == Approx(1.0).epsilon(1e-12));
      CHECK(std::abs(s->joint.pitch - j.pitch) < 1e-9);
      if (j.type != JointType::Prismatic) CHECK((s->joint.point - j.point).cross(j.direction).norm() < 1e-9);
      CHECK(s->t0 == m->lo());
      CHECK(s->t1 == m->hi());
      // the ends of the range are the motion's first and last poses
      CHECK((s->start.matrix() - m->transform(m->lo()).matrix()).norm() < 1e-9);
      CHECK(((s->joint.transform(s->joint.hi) * s->start).matrix() - m->transform(m->hi()).matrix()).norm() < 1e-9);
    }
  }
  // paths of expressions: a helix, a turn about a point off the origin at a growing rate, an eased slide
  const Expr none[3] = {texpr("0"), texpr("0"), texpr("0")};
  const PathRotation about_z{{texpr("0"), texpr("0"), texpr("1")}, texpr("4*pi*t")};
  const Expr rise[3] = {texpr("0"), texpr("0"), texpr("6*t")};
  const auto helix = PathMotion(0, 1, rise, {about_z}).as_screw(6.0);
  REQUIRE(helix);
  CHECK(helix->joint.type == JointType::Helical);
  CHECK(helix->joint.hi == Approx(4 * M_PI).epsilon(1e-12));
  CHECK(helix->joint.pitch == Approx(6 / (4 * M_PI)).epsilon(1e-9));
  CHECK(helix->joint.point.head<2>().norm() < 1e-12);
  // x -> c + R(t^2) (x - c) with c = (2, 1, 0): translate c - R c
  const Expr off[3] = {texpr("2 - (2*cos(t^2) - sin(t^2))"), texpr("1 - (2*sin(t^2) + cos(t^2))"), texpr("0")};
  const auto turn = PathMotion(0.5, 2, off, {PathRotation{{texpr("0"), texpr("0"), texpr("1")}, texpr("t^2")}}).as_screw(1.0);
  REQUIRE(turn);
  CHECK(turn->joint.type == JointType::Revolute);
  CHECK(turn->joint.hi == Approx(4 - 0.25).epsilon(1e-9));
  CHECK((turn->joint.point - Eigen::Vector3d(2, 1, 0)).head<2>().norm() < 1e-9);
  const Expr slide[3] = {texpr("t^3"), texpr("2*t^3"), texpr("0")};
  const auto line = PathMotion(0, 1, slide, {}).as_screw(1.0);
  REQUIRE(line);
  CHECK(line->joint.type == JointType::Prismatic);
  CHECK(line->joint.hi == Approx(std::sqrt(5.0)).epsilon(1e-12));
  CHECK((line->joint.direction - Eigen::Vector3d(1, 2, 0) / std::sqrt(5.0)).norm() < 1e-12);
  // not one screw: seed 001's rolling cylinder, a turn that goes back, a circle without turning,
  // and a path that stays
  const Expr roll[3] = {texpr("0"), texpr("4*t"), texpr("0")};
  CHECK(!PathMotion(0, 1, roll, {PathRotation{{texpr("1"), texpr("0"), texpr("0")}, texpr("pi*t")}}).as_screw(1.0));
  CHECK(!PathMotion(0, 2, none, {PathRotation{{texpr("0"), texpr("0"), texpr("1")}, texpr("sin(3*t)")}}).as_screw(1.0));
  const Expr circle[3] = {texpr("cos(t)"), texpr("sin(t)"), texpr("0")};
  CHECK(!PathMotion(0, 2, circle, {}).as_screw(1.0));
  CHECK(!PathMotion(0, 2, none, {}).as_screw(1.0));
}

TEST_CASE("Stage motions: speed bounds hold at sampled points and times", "[stage_motion]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = {0.5, 1, -0.2};
  j.direction = Eigen::Vector3d(1, 1, 0.3).normalized();
  j.pitch = -0.4;
  j.lo = 0;
  j.hi = 6;
  const ScrewStage screw(j, random_pose(rng));
  const KeyframeMotion screw_keys({0, 1, 2.5}, {random_pose(rng), random_pose(rng), random_pose(rng)},
                                  KeyframeMotion::Interpolation::Screw);
  const KeyframeMotion linear_keys({0, 1, 2.5}, {random_pose(rng), random_pose(rng), random_pose(rng)},
                                   KeyframeMotion::Interpolation::Linear);
  const Expr tr[3] = {texpr("2*cos(3*t)"), texpr("t^3/4-t"), texpr("exp(-t)*sin(t)")};
  const PathMotion fixed_axes(0, 2.5, tr,
                              {PathRotation{{texpr("0"), texpr("0"), texpr("1")}, texpr("1.5*t")},
                               PathRotation{{texpr("1"), texpr("0"), texpr("0")}, texpr("sin(2*t)")}});
  const PathMotion turning_axis(-1, 2, tr, {PathRotation{{texpr("1"), texpr("t"), texpr("cos(t)")}, texpr("2*t^2")}});
  // a fixed angle about an axis that turns: all of the angular speed comes from the axis
  const PathMotion axis_only(0, 2, tr, {PathRotation{{texpr("cos(3*t)"), texpr("sin(3*t)"), texpr("0.2")}, texpr("2")}});
  for (const StageMotion* m : {static_cast<const StageMotion*>(&screw), static_cast<const StageMotion*>(&screw_keys),
                               static_cast<const StageMotion*>(&linear_keys),
                               static_cast<const StageMotion*>(&fixed_axes),
                               static_cast<const StageMotion*>(&turning_axis),
                               static_cast<const StageMotion*>(&axis_only)}) {
    const double r = 1.5, bound = m->speed_bound(r);
    double seen = 0;
    for (int s = 0; s < 2000; ++s) {
      const double t = m->lo() + (m->hi() - m->lo()) * (s + 0.5) / 2000;
      Eigen::Vector3d y(u(rng), u(rng), u(rng));
      y *= r / std::max(1.0, y.norm()) * (s % 2 ? 1.0 : 1.0 / std::sqrt(3.0));
      const PoseJet P = m->pose(t);
      seen = std::max(seen, (P.dR * y + P.dp).norm());
    }
    CHECK(seen <= bound * (1 + 1e-12));
    CHECK(seen >= 0.3 * bound);  // a bound, not a wild one
  }
}

TEST_CASE("Stage motions: bad input names its field", "[stage_motion]") {
  const Expr tr[3] = {texpr("t"), texpr("0"), texpr("0")};
  CHECK_THROWS_WITH(PathMotion(1, 1, tr, {}), Catch::Contains("range is empty"));
  try {
    PathMotion(0, 2, tr, {PathRotation{{texpr("1-t"), texpr("0"), texpr("0")}, texpr("t")}});
    FAIL("a vanishing axis was accepted");
  } catch (const InputError& e) {
    CHECK(e.pointer() == "/motion/rotate/0/axis");
  }
  std::mt19937 rng(1);
  try {
    KeyframeMotion({0, 2, 1}, {random_pose(rng), random_pose(rng), random_pose(rng)},
                   KeyframeMotion::Interpolation::Screw);
    FAIL("decreasing keyframe times were accepted");
  } catch (const InputError& e) {
    CHECK(e.pointer() == "/motion/poses/2/t");
  }
  CHECK_THROWS_AS(KeyframeMotion({0}, {random_pose(rng)}, KeyframeMotion::Interpolation::Linear), InputError);
}
