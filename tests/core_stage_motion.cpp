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
    for (int k = 0; k <= 8; ++k) {
      ts.push_back(j.hi * k / 8.0);
      poses.push_back(exact.transform(ts.back()));
    }
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
