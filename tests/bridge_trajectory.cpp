// Membership by trajectories: rays deciding inside, the whole test against a membership computed
// from a torus's exact distance, and against the orbit intervals of random parts where paths graze
// their faces.
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <gp_Elips.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "base/internal.hpp"
#include "sweep/expr.hpp"
#include "sweep/stage_motion.hpp"
#include "util/random_parts.hpp"

namespace {

/// Signed distance from p to the torus (negative inside): exact away from its axis.
double torus_distance(const gp_Torus& t, const gp_Pnt& p) {
  const gp_Ax3& ax = t.Position();
  const gp_Vec d(ax.Location(), p);
  const double h = d.Dot(gp_Vec(ax.Direction()));
  const double rho = std::sqrt(std::max(0.0, d.SquareMagnitude() - h * h));
  return std::hypot(rho - t.MajorRadius(), h) - t.MinorRadius();
}

}  // namespace

TEST_CASE("Trajectory membership: rays agree with OCCT's classifier, and the swept set with the exact distance") {
  // a torus fused with a box through it: torus, plane and box faces
  const gp_Ax2 frame(gp_Pnt(1.0, 0.5, 0.2), gp_Dir(0.3, -0.2, 1.0));
  const gp_Torus tor(gp_Ax3(frame), 3.0, 1.0);
  BRepAlgoAPI_Fuse fuse(BRepPrimAPI_MakeTorus(frame, 3.0, 1.0).Shape(),
                        BRepPrimAPI_MakeBox(gp_Pnt(2.0, -1.0, -1.0), 3.0, 2.0, 2.0).Shape());
  REQUIRE(fuse.IsDone());
  const TopoDS_Shape body = fuse.Shape();
  auto in_body = [&](const gp_Pnt& p) {
    return torus_distance(tor, p) < 0 || (p.X() > 2 && p.X() < 5 && std::abs(p.Y()) < 1 && std::abs(p.Z()) < 1);
  };
  // margin from the body's boundary: at most the distance to the torus's and the box's surfaces
  auto margin = [&](const gp_Pnt& p) {
    const Eigen::Vector3d q = Eigen::Vector3d(std::abs(p.X() - 3.5), std::abs(p.Y()), std::abs(p.Z())) -
                              Eigen::Vector3d(1.5, 1.0, 1.0);
    const double db = q.maxCoeff() > 0 ? q.cwiseMax(0.0).norm() : -q.maxCoeff();
    return std::min(std::abs(torus_distance(tor, p)), db);
  };

  sweep::ScrewJoint j;
  j.type = sweep::JointType::Revolute;
  j.point = Eigen::Vector3d(-1.0, 0.0, 0.0);
  j.direction = Eigen::Vector3d(0.2, 1.0, 0.1).normalized();
  const double T = 2.0;
  j.lo = 0.0;
  j.hi = T;
  const sweep::ScrewStage motion(j);
  sweep::occt::TrajectoryMembership member(body, true, motion, 1e-9 * 10);

  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-6.0, 6.0);
  BRepClass3d_SolidClassifier cls(body);
  int decided = 0, compared = 0, inside = 0;
  for (int it = 0; it < 300; ++it) {
    const Eigen::Vector3d x(u(rng), u(rng), u(rng));
    const gp_Pnt p(x.x(), x.y(), x.z());
    // rays against OCCT's classifier and the exact set
    const int by_ray = member.ray_inside(x);
    if (by_ray >= 0) {
      ++decided;
      cls.Perform(p, 1e-9);
      CHECK(by_ray == int(cls.State() == TopAbs_IN));
      if (margin(p) > 1e-6) CHECK(by_ray == int(in_body(p)));
    }
    // the swept set: the path back through the motion, sampled densely; the point is decided
    // when the path comes well inside, or stays farther out than the sampling can hide
    const int m = 4000;
    double closest = 1e300;
    bool in = false;
    for (int k = 0; k <= m; ++k) {
      const Eigen::Vector3d y = j.transform(-T * k / m) * x;
      const gp_Pnt q(y.x(), y.y(), y.z());
      in = in || (in_body(q) && margin(q) > 1e-3);
      closest = std::min(closest, margin(q));
    }
    const double r = (x - j.point - j.direction * j.direction.dot(x - j.point)).norm();
    if (!in && closest < r * T / m + 1e-3) continue;
    ++compared;
    inside += in;
    CHECK(member(x) == in);
  }
  CHECK(decided > 290);
  CHECK(compared > 250);
  CHECK(inside > 30);
}

TEST_CASE("Trajectory membership: points just off an extruded ellipse, where a ray grazes the side") {
  // the elliptic side x^2 / 1.5^2 + y^2 / 0.7^2 = 1, z in [0, 2]; the first ray direction from these
  // points meets the side at under a degree, where OCCT's intersector found one crossing of two
  const gp_Elips el(gp_Ax2(gp_Pnt(0, 0, 0), gp::DZ(), gp::DX()), 1.5, 0.7);
  const TopoDS_Face base = BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(el).Edge()).Wire()).Face();
  const TopoDS_Shape body = BRepPrimAPI_MakePrism(base, gp_Vec(0, 0, 2)).Shape();
  sweep::ScrewJoint j;
  j.type = sweep::JointType::Prismatic;
  j.direction = Eigen::Vector3d::UnitX();
  j.hi = 3;
  const sweep::ScrewStage motion(j);
  sweep::occt::TrajectoryMembership member(body, true, motion, 6e-9);
  const Eigen::Vector3d p(-1.31276168, 0.338665238, 0.444533241);
  const Eigen::Vector3d n = Eigen::Vector3d(p.x() / 2.25, p.y() / 0.49, 0).normalized();
  for (const double off : {2.4e-5, 1e-4, 1e-3}) {
    CAPTURE(off);
    CHECK(member.ray_inside(p + off * n) == 0);
    CHECK_FALSE(member(p + off * n));  // its path back runs away from the body
    CHECK(member.ray_inside(p - off * n) == 1);
    CHECK(member(p - off * n));
  }
}

namespace {

/// Signed distance to the box [lo, hi] (negative inside), exact.
double box_distance(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = (p - 0.5 * (lo + hi)).cwiseAbs() - 0.5 * (hi - lo);
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

/// The trajectory test of a box under `m` against the box's exact distance along each point's path
/// back through the motion, sampled densely: points whose sampled path comes well inside, or stays
/// farther out than the sampling can hide, are compared. Returns {compared, inside}.
std::pair<int, int> compare_box_sweep(const sweep::StageMotion& m, double speed, int n = 10000, int points = 400) {
  const Eigen::Vector3d lo(-0.5, -0.4, -1), hi(0.5, 0.4, 1);
  const TopoDS_Shape body = BRepPrimAPI_MakeBox(gp_Pnt(lo.x(), lo.y(), lo.z()), gp_Pnt(hi.x(), hi.y(), hi.z())).Shape();
  sweep::occt::TrajectoryMembership member(body, true, m, 1e-8);
  Eigen::AlignedBox3d reach;
  for (int k = 0; k <= 64; ++k)
    for (int c = 0; c < 8; ++c)
      reach.extend(m.transform(m.lo() + (m.hi() - m.lo()) * k / 64) *
                   Eigen::Vector3d(Eigen::AlignedBox3d(lo, hi).corner(Eigen::AlignedBox3d::CornerType(c))));
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int compared = 0, inside = 0;
  for (int it = 0; it < points; ++it) {
    const Eigen::Vector3d x = reach.min() + (reach.sizes().array() * Eigen::Array3d(u(rng), u(rng), u(rng))).matrix();
    double closest = 1e300;
    for (int k = 0; k <= n; ++k) {
      const double t = m.lo() + (m.hi() - m.lo()) * k / n;
      closest = std::min(closest, box_distance(lo, hi, m.body_point(t, x)));
    }
    // between two samples the path moves at most speed (|x| + 1) (hi - lo) / n
    const double gap = speed * (x.norm() + 1) * (m.hi() - m.lo()) / n;
    if (std::abs(closest) < gap + 1e-3) continue;
    ++compared;
    inside += closest < 0;
    CAPTURE(x.transpose(), closest);
    CHECK(member(x) == (closest < 0));
  }
  return {compared, inside};
}

sweep::Expr texpr(const std::string& s) { return sweep::Expr::parse(s, {"t"}); }

/// A helical joint about the line through `point` along `direction`, over [lo, hi].
sweep::ScrewJoint helical(const Eigen::Vector3d& point, const Eigen::Vector3d& direction, double pitch, double lo,
                          double hi) {
  sweep::ScrewJoint j;
  j.type = sweep::JointType::Helical;
  j.point = point;
  j.direction = direction.normalized();
  j.pitch = pitch;
  j.lo = lo;
  j.hi = hi;
  return j;
}

}  // namespace

TEST_CASE("Trajectory membership: a box rolled along a path that is no screw, against its exact distance") {
  // seed 001's rolling motion (x -> (0, 4t, 0) + R_x(pi t) x), and a path that keeps no plane
  const sweep::Expr roll[3] = {texpr("0"), texpr("4*t"), texpr("0")};
  const sweep::PathMotion rolling(0, 1, roll, {sweep::PathRotation{{texpr("1"), texpr("0"), texpr("0")}, texpr("pi*t")}});
  const sweep::Expr wander[3] = {texpr("t"), texpr("t^2"), texpr("sin(t)")};
  const sweep::PathMotion wandering(0, 2, wander, {sweep::PathRotation{{texpr("0.3"), texpr("1"), texpr("t")}, texpr("0.7*t")}});
  for (const auto& [m, speed] : {std::pair<const sweep::StageMotion*, double>{&rolling, 20.0}, {&wandering, 20.0}}) {
    REQUIRE_FALSE(m->as_screw(2.0));
    const auto [compared, inside] = compare_box_sweep(*m, speed);
    CHECK(compared > 300);
    CHECK(inside > 40);
  }
}

TEST_CASE("Trajectory membership: a screw that does not start at the body's frame") {
  // a helical joint after a home pose: the paths are the screw's from its start, carried back
  const sweep::ScrewJoint j = helical(Eigen::Vector3d(1.5, 0.2, 0), Eigen::Vector3d(0.1, 0.3, 1), 0.4, 0.5, 3.5);
  Eigen::Isometry3d home = Eigen::Isometry3d::Identity();
  home.linear() = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  home.translation() = Eigen::Vector3d(0.3, -0.2, 0.4);
  const sweep::ScrewStage motion(j, home);
  REQUIRE(motion.as_screw(2.0));
  REQUIRE_FALSE(motion.as_screw(2.0)->start.isApprox(Eigen::Isometry3d::Identity(), 1e-6));
  const auto [compared, inside] = compare_box_sweep(motion, 4.0);
  CHECK(compared > 300);
  CHECK(inside > 40);
}

TEST_CASE("Paths of a helix of many turns: one fit does not hold them, each point's is fitted") {
  const sweep::ScrewStage motion(helical(Eigen::Vector3d(1.2, 0.1, 0), Eigen::Vector3d(0.2, -0.1, 1), 0.3, 0, 2 * M_PI * 14));
  const auto [compared, inside] = compare_box_sweep(motion, 4.0, 100000, 120);
  CHECK(compared > 60);
  CHECK(inside > 10);
}

TEST_CASE("Trajectory membership: a collar screwed 2.3 turns agrees with its orbit intervals where helices cut short chords through its cylinders") {
  // a shaft with a collar (random part 13 of seed 43) screwed 2.3 turns: the path back of a point
  // near the end copy cuts a chord 0.066 radians long, 0.022 deep, through the collar's cylinder
  // 0.1 radians before the range's end. OCCT's curve-face intersector, run over the whole path,
  // stepped over it (it found both crossings over the last 0.75 turns): points inside the swept set
  // were taken to be outside, a piece of the end copy inside the set was kept and the boundary did
  // not close
  const sweep::testing::RandomPart p = sweep::testing::random_part_case(43, 13);
  REQUIRE(p.name == "collar_helical_13");
  const sweep::testing::JointSweep s = sweep::testing::part_joint_sweep(p);
  REQUIRE(s.j.lo == 0.0);
  const sweep::ScrewStage motion(s.j);
  sweep::occt::TrajectoryMembership member(p.shape, true, motion, 1e-8);
  const Eigen::Vector3d n(-0.139388, -0.861620, 0.488039);
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(-2.579321263, 4.898892455, -4.238677006),
                                   Eigen::Vector3d(-2.611902941, 4.902428494, -4.241739815)})
    for (const double off : {-1e-4, 1e-5, 1e-4, 1e-3}) {
      CAPTURE(x.transpose(), off);
      REQUIRE(sweep::in_joint_sweep(*s.body, s.j, s.T, x + off * n));
      CHECK(member(x + off * n));
    }
  // random points of the swept set's box
  Eigen::AlignedBox3d reach;
  for (int k = 0; k <= 256; ++k)
    for (int c = 0; c < 8; ++c)
      reach.extend(s.j.transform(s.T * k / 256) * Eigen::Vector3d(s.body->bounds().corner(Eigen::AlignedBox3d::CornerType(c))));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int inside = 0, disagree = 0;
  for (int it = 0; it < 3000; ++it) {
    const double a = u(rng), b = u(rng), c = u(rng);
    const Eigen::Vector3d x = reach.min() + (reach.sizes().array() * Eigen::Array3d(a, b, c)).matrix();
    const bool in = sweep::in_joint_sweep(*s.body, s.j, s.T, x);
    inside += in;
    disagree += member(x) != in;
  }
  CHECK(inside > 250);
  CHECK(disagree == 0);
}

namespace {

/// Points q of the faces of `shape` where joint j's orbit through q grazes the face (the velocity
/// j.velocity(q) is tangent to it), with the face's outward normal there: sign changes of
/// normal . velocity along lines of constant u and of constant v, bisected.
std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> grazing_points(const TopoDS_Shape& shape,
                                                                        const sweep::ScrewJoint& j) {
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> out;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& f = TopoDS::Face(ex.Current());
    const BRepAdaptor_Surface surf(f);
    BRepTopAdaptor_FClass2d fc(f, 1e-9);
    double u0, u1, v0, v1;
    BRepTools::UVBounds(f, u0, u1, v0, v1);
    const double flip = f.Orientation() == TopAbs_REVERSED ? -1.0 : 1.0;
    auto at = [&](double u, double v, Eigen::Vector3d* q, Eigen::Vector3d* n) {
      gp_Pnt p;
      gp_Vec du, dv;
      surf.D1(u, v, p, du, dv);
      *q = sweep::occt::to_eigen(p);
      *n = flip * sweep::occt::to_eigen(du.Crossed(dv)).normalized();
      return n->dot(j.velocity(*q));
    };
    for (int line = 1; line < 8; ++line)
      for (const bool along_v : {true, false}) {
        const int m = 200;
        auto uv = [&](double s) {
          const double fixed = line / 8.0;
          return along_v ? gp_Pnt2d(u0 + (u1 - u0) * fixed, v0 + (v1 - v0) * s)
                         : gp_Pnt2d(u0 + (u1 - u0) * s, v0 + (v1 - v0) * fixed);
        };
        Eigen::Vector3d q, n;
        double before = at(uv(0).X(), uv(0).Y(), &q, &n);
        for (int k = 1; k <= m; ++k) {
          double s0 = double(k - 1) / m, s1 = double(k) / m;
          const double now = at(uv(s1).X(), uv(s1).Y(), &q, &n);
          if ((before < 0) == (now < 0) || fc.Perform(uv(s0)) != TopAbs_IN || fc.Perform(uv(s1)) != TopAbs_IN) {
            before = now;
            continue;
          }
          for (int it = 0; it < 60; ++it) {
            const double sm = 0.5 * (s0 + s1);
            ((at(uv(sm).X(), uv(sm).Y(), &q, &n) < 0) == (before < 0) ? s0 : s1) = sm;
          }
          at(uv(s0).X(), uv(s0).Y(), &q, &n);
          out.push_back({q, n});
          before = now;
        }
      }
  }
  return out;
}

}  // namespace

TEST_CASE("Trajectory membership: paths that dip 1e-5 and 1e-7 deep into random parts' faces where they graze them agree with their orbit intervals") {
  // x = exp(xi t) (q - e n) for a point q of a face where the joint's orbit grazes it: the path
  // back of x passes e inside the face, along it, for a stretch of about the square root of e. Kept
  // where that dip is the path's only stretch in the part: a sampled curve-face intersection that
  // steps over the dip takes x to be outside the swept set
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int all_dips = 0, all_outside = 0;
  for (const int index : {0, 1, 2, 3, 4, 10, 11, 12, 13, 14}) {
    const sweep::testing::RandomPart p = sweep::testing::random_part_case(43, index);
    const sweep::testing::JointSweep s = sweep::testing::part_joint_sweep(p);
    REQUIRE(s.j.lo == 0.0);
    const sweep::ScrewStage motion(s.j);
    sweep::occt::TrajectoryMembership member(p.shape, true, motion, 1e-9);
    int dips = 0, outside = 0, disagree = 0;
    for (const auto& [q, n] : grazing_points(p.shape, s.j))
      for (const double e : {1e-5, 1e-7}) {
        const Eigen::Vector3d y = q - e * n;
        for (int trial = 0; trial < 4; ++trial) {
          const double t = s.T * u(rng);
          // the orbit of y over [t - T, t] is the path of x run forwards
          const sweep::Intervals in_part = s.body->on_curve(sweep::orbit_of(s.j, y), t - s.T, t);
          if (in_part.size() != 1 || in_part[0].first > 0 || in_part[0].second < 0 ||
              in_part[0].second - in_part[0].first > 0.05)
            continue;
          const Eigen::Vector3d x = s.j.transform(t) * y;
          REQUIRE(sweep::in_joint_sweep(*s.body, s.j, s.T, x));
          disagree += !member(x);
          ++dips;
          // just outside the face, the path keeps out of the part
          const Eigen::Vector3d z = s.j.transform(t) * Eigen::Vector3d(q + e * n);
          if (!s.body->on_curve(sweep::orbit_of(s.j, Eigen::Vector3d(q + e * n)), t - s.T, t).empty()) continue;
          REQUIRE_FALSE(sweep::in_joint_sweep(*s.body, s.j, s.T, z));
          disagree += member(z);
          ++outside;
          break;
        }
      }
    CAPTURE(p.name, dips, outside, disagree);
    CHECK(disagree == 0);
    all_dips += dips;
    all_outside += outside;
  }
  CHECK(all_dips >= 100);
  CHECK(all_outside >= 50);
}
