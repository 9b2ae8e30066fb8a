// Varieties as patches (sweep/variety.hpp): moved copies and swept curves with exact derivatives,
// and grazing sets at one instant: a ball's great circle normal to its centre's velocity, the
// fixed curves of a screw, and the facts of seed 001's rolling cylinder.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>

#include "sweep/variety.hpp"
#include "util/core_entities.hpp"

using Eigen::Vector2d;
using Eigen::Vector3d;
using namespace sweep;

namespace {

using sweep_test::entity_of;
using sweep_test::texpr;

using sweep_test::wandering_path;

/// A screw about a tilted axis, q in [0, 4].
ScrewJoint tilted_screw() {
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = Vector3d(0, 0.5, 0);
  j.direction = Vector3d(0.2, 0, 1).normalized();
  j.pitch = 0.3;
  j.lo = 0;
  j.hi = 4;
  return j;
}

/// Seed 001's motion: x -> (0, 4t, 0) + R_x(pi t) x, t in [0, 1].
std::shared_ptr<const StageMotion> rolling() {
  const Expr tr[3] = {texpr("0"), texpr("4*t"), texpr("0")};
  return std::make_shared<PathMotion>(0, 1, tr,
                                      std::vector<PathRotation>{{{texpr("1"), texpr("0"), texpr("0")}, texpr("pi*t")}});
}

/// Every traced point of the face's grazing set at t, in the body frame.
/// Points of the grazing set: its curves' points and points along the sides on which it lies (a
/// seam on a grazing line), poles left out.
std::vector<Vector3d> grazing_points(const Patch& face, const StageMotion& m, double t, int n = 64) {
  std::vector<Vector3d> out;
  const GrazingSet g = grazing_set(face, m, t, n);
  for (const auto& line : g.curves)
    for (const Vector2d& s : line) out.push_back(face.eval(s.x(), s.y()).x);
  for (int side : g.sides) {
    if ((side_point(face, side, 0) - side_point(face, side, 0.5)).norm() < 1e-12) continue;  // a pole
    for (int i = 0; i <= n; ++i) out.push_back(side_point(face, side, double(i) / n));
  }
  return out;
}

/// Whether some point of `pts` lies within `d` of p.
bool near_one(const std::vector<Vector3d>& pts, const Vector3d& p, double d) {
  for (const Vector3d& q : pts)
    if ((q - p).norm() <= d) return true;
  return false;
}

}  // namespace

TEST_CASE("Varieties: moved copies and swept curves have the motion's points and exact derivatives", "[variety]") {
  const auto m = rolling();
  const EntityPtr cyl = entity_of(R"({"kind": "cylinder", "base": [0, 0, -1], "axis": [0, 0, 1], "radius": 0.5, "height": 2})");
  REQUIRE(cyl);
  const PatchPtr copy = moved_patch(cyl->faces()[0], m, 0.7, "the lateral face at t = 0.7");
  const Eigen::Isometry3d M = m->transform(0.7);
  const double h = 1e-6;
  for (double u : {0.3, 2.0, 5.1})
    for (double v : {0.2, 1.7}) {
      CHECK((copy->eval(u, v).x - M * cyl->faces()[0]->eval(u, v).x).norm() < 1e-14);
      CHECK((copy->eval(u, v).xu - (copy->eval(u + h, v).x - copy->eval(u - h, v).x) / (2 * h)).norm() < 1e-7);
    }
  REQUIRE(copy->fixed.size() == 1);
  CHECK(copy->fixed[0].second == 0.7);
  CHECK(copy->orientation() == cyl->faces()[0]->orientation());
  CHECK((copy->form().origin - M * cyl->faces()[0]->form().origin).norm() < 1e-14);

  const PatchPtr rim = swept_curve(cyl->edges()[0], m, "the base rim swept");
  for (double s : {0.4, 3.0})
    for (double t : {0.1, 0.55, 0.9}) {
      const PatchPoint p = rim->eval(s, t);
      CHECK((p.x - m->transform(t) * cyl->edges()[0]->eval(s).x).norm() < 1e-14);
      CHECK((p.xu - (rim->eval(s + h, t).x - rim->eval(s - h, t).x) / (2 * h)).norm() < 1e-7);
      CHECK((p.xv - (rim->eval(s, t + h).x - rim->eval(s, t - h).x) / (2 * h)).norm() < 1e-6);
    }

  // a radial segment from r = 1 to 2 turned a quarter turn about z sweeps a quarter annulus
  const EntityPtr seg = entity_of(R"J({"kind": "curve", "params": {"s": [1, 2]}, "xyz": ["s", "0", "0"]})J");
  ScrewJoint j;
  j.lo = 0;
  j.hi = M_PI / 2;
  const PatchPtr sector = swept_curve(seg->faces()[0], std::make_shared<ScrewStage>(j), "the sector");
  double area = 0;
  const int n = 200;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const PatchPoint p = sector->eval(1 + (a + 0.5) / n, (b + 0.5) / n * M_PI / 2);
      area += p.xu.cross(p.xv).norm() / n * (M_PI / 2) / n;
    }
  CHECK(area == Approx(3 * M_PI / 4).epsilon(1e-9));  // half the angle times (2^2 - 1^2)
}

TEST_CASE("Varieties: a ball's grazing set is the great circle normal to its centre's velocity", "[variety]") {
  const Vector3d c(0.3, -0.2, 0.5);
  const EntityPtr ball = entity_of(R"({"kind": "sphere", "center": [0.3, -0.2, 0.5], "radius": 0.8})");
  const PathMotion path = wandering_path();
  for (double t : {0.2, 1.1, 1.9}) {
    const PoseJet P = path.pose(t);
    const Vector3d w = P.R.transpose() * (P.dR * c + P.dp);  // the centre's velocity, body frame
    const GrazingSet g = grazing_set(*ball->faces()[0], path, t);
    double length = 0;
    for (const auto& line : g.curves)
      for (std::size_t k = 0; k < line.size(); ++k) {
        const Vector3d x = ball->faces()[0]->eval(line[k].x(), line[k].y()).x;
        INFO("at (" << line[k].x() << ", " << line[k].y() << ")");
        CHECK(std::abs((x - c).dot(w.normalized())) < 1e-9);
        if (k > 0) length += (x - ball->faces()[0]->eval(line[k - 1].x(), line[k - 1].y()).x).norm();
      }
    CHECK(length == Approx(2 * M_PI * 0.8).epsilon(2e-3));  // a polyline through the circle
  }
}

TEST_CASE("Varieties: under a screw the grazing set stays on the same body curves", "[variety]") {
  const EntityPtr cyl = entity_of(R"({"kind": "cylinder", "base": [1, 0.2, 0], "axis": [1, 0.3, 0.4], "radius": 0.4, "height": 1.5})");
  const ScrewStage screw(tilted_screw());
  const Patch& side = *cyl->faces()[0];
  const std::vector<Vector3d> early = grazing_points(side, screw, 0.5);
  REQUIRE(early.size() > 20);
  const PoseJet later = screw.pose(3.2);
  for (const auto& line : grazing_set(side, screw, 0.5).curves)
    for (const Vector2d& s : line) {
      const PatchPoint p = side.eval(s.x(), s.y());
      const Vector3d w = later.R.transpose() * (later.dR * p.x + later.dp);
      CHECK(std::abs(p.xu.cross(p.xv).normalized().dot(w)) < 1e-9 * w.norm());
    }
}

TEST_CASE("Varieties: seed 001's rolling cylinder grazes as the seed's facts say", "[variety]") {
  const auto m = rolling();
  const EntityPtr cyl = entity_of(R"({"kind": "cylinder", "base": [0, 0, -1], "axis": [0, 0, 1], "radius": 0.5, "height": 2})");
  REQUIRE(cyl);
  const Patch& side = *cyl->faces()[0];
  // the lines x = +-0.5 of the lateral face graze at every t
  for (double t : {0.05, 0.3, 0.5, 0.95}) {
    INFO("t = " << t);
    const std::vector<Vector3d> pts = grazing_points(side, *m, t);
    const double zc = 4 * std::cos(M_PI * t) / M_PI;  // the plane of the circle that grazes too
    for (const Vector3d& x : pts) CHECK(std::min(std::abs(std::abs(x.x()) - 0.5), std::abs(x.z() - zc)) < 1e-9);
    for (double z : {-0.8, 0.1, 0.9}) {
      CHECK(near_one(pts, Vector3d(0.5, 0, z), 0.05));
      CHECK(near_one(pts, Vector3d(-0.5, 0, z), 0.05));
    }
    // the circle z = 4 cos(pi t) / pi lies on the face for t in [0.2125, 0.7875]
    const bool circle = std::abs(zc) <= 1;
    CHECK(near_one(pts, Vector3d(0, 0.5, zc), 0.05) == circle);
    CHECK(near_one(pts, Vector3d(0, -0.5, zc), 0.05) == circle);
  }
  CHECK(std::acos(M_PI / 4) / M_PI == Approx(0.2125).margin(1e-4));
  // on the caps, the line y = 4 sin(pi t) / pi for t below about 0.128 and above about 0.872
  for (double t : {0.05, 0.1, 0.2, 0.5, 0.8, 0.9}) {
    INFO("t = " << t);
    const double yc = 4 * std::sin(M_PI * t) / M_PI;
    for (std::size_t k = 1; k < cyl->faces().size(); ++k) {
      const std::vector<Vector3d> pts = grazing_points(*cyl->faces()[k], *m, t);
      for (const Vector3d& x : pts) CHECK(std::abs(x.y() - yc) < 1e-9);
      CHECK(pts.empty() == (yc > 0.5));
    }
  }
  CHECK(std::asin(M_PI / 8) / M_PI == Approx(0.128).margin(1e-3));
}

TEST_CASE("Varieties: the grazing function's rate in t agrees with differences, and vanishes under a screw",
          "[variety]") {
  const EntityPtr cyl = entity_of(R"({"kind": "cylinder", "base": [1, 0.2, 0], "axis": [1, 0.3, 0.4], "radius": 0.4, "height": 1.5})");
  const Patch& side = *cyl->faces()[0];
  const PathMotion path = wandering_path();
  const ScrewStage screw(tilted_screw());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> fu(side.lo(0), side.hi(0)), fv(side.lo(1), side.hi(1));
  for (int k = 0; k < 40; ++k) {
    const double u = fu(rng), v = fv(rng), t = 0.2 + 0.04 * k, h = 1e-5;
    const double fd = (grazing_value(side, path.pose(t + h), u, v) - grazing_value(side, path.pose(t - h), u, v)) / (2 * h);
    const double rate = grazing_rate(side, path.pose(t), u, v);
    CHECK(rate == Approx(fd).margin(1e-7 * (1 + std::abs(fd))));
    // the screw's field is the same in the body frame at every t (its n . w is of order 1 here)
    CHECK(std::abs(grazing_rate(side, screw.pose(0.1 * k), u, v)) < 1e-12);
  }
}

TEST_CASE("Varieties: the grazing set's drift carries a ball's great circle to the next instant's", "[variety]") {
  const EntityPtr ball = entity_of(R"({"kind": "sphere", "center": [0.3, -0.2, 0.5], "radius": 0.8})");
  const Patch& face = *ball->faces()[0];
  const PathMotion path = wandering_path();
  const double t = 0.9, dt = 1e-3;
  const PoseJet now = path.pose(t), next = path.pose(t + dt);
  int moved = 0;
  for (const auto& line : grazing_set(face, path, t).curves)
    for (const Vector2d& s : line) {
      // away from the poles, where the parametrization degenerates
      if (std::abs(s.y()) > 1.3) continue;
      const Vector2d d = grazing_drift(face, now, s.x(), s.y());
      const double stay = grazing_value(face, next, s.x(), s.y());
      const Vector2d s2 = s + dt * d;
      const double carried = grazing_value(face, next, s2.x(), s2.y());
      // left where it was, the point is off the next set to first order in dt; carried, to second
      // (about dt^2 = 1e-6 here: compared where the set moves enough for that to be small)
      if (std::abs(stay) > 1e-4) {
        CHECK(std::abs(carried) < 0.05 * std::abs(stay));
        ++moved;
      }
    }
  CHECK(moved > 20);
}

TEST_CASE("Varieties: on faces of revolution the grazing function is A cos u + B sin u + C on each circle",
          "[variety]") {
  const PathMotion path = wandering_path();
  const char* entities[] = {
      R"({"kind": "cylinder", "base": [0.2, 0, 0.1], "axis": [1, 0.3, 0.4], "radius": 0.4, "height": 1.5,
          "placement": {"translate": [0.1, 0.2, 0.3], "rotate": {"axis": [0.2, 1, 0], "angle": 0.7}}})",
      R"({"kind": "cone", "base": [0, 0.3, 0], "axis": [0.3, 1, 0.2], "radius1": 0.6, "radius2": 0.25, "height": 1.2})",
      R"({"kind": "sphere", "center": [0.3, -0.2, 0.5], "radius": 0.8})",
      R"({"kind": "torus", "center": [0.2, 0, 0], "axis": [0.3, 0.2, 1], "major": 0.8, "minor": 0.25})"};
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int circles = 0, grazing = 0;
  for (const char* json : entities) {
    const EntityPtr e = entity_of(json);
    REQUIRE(e);
    for (const PatchPtr& face : e->faces()) {
      INFO(face->what());
      REQUIRE(face->form().revolved);
      auto scale_at = [&face](const PoseJet& P) {  // |g| at the face's size
        double scale = 0;
        for (int i = 0; i <= 32; ++i)
          for (int j = 0; j <= 32; ++j)
            scale = std::max(scale, std::abs(grazing_value(*face, P, face->lo(0) + (face->hi(0) - face->lo(0)) * i / 32,
                                                           face->lo(1) + (face->hi(1) - face->lo(1)) * j / 32)));
        return scale;
      };
      for (double t : {0.3, 1.1, 1.7}) {
        const PoseJet P = path.pose(t);
        const double scale = scale_at(P);
        for (int k = 0; k < 9; ++k) {
          const double v = face->lo(1) + (face->hi(1) - face->lo(1)) * (k + 0.5) / 9;
          // the form itself, at random u, against three samples
          const double g0 = grazing_value(*face, P, 0, v), g1 = grazing_value(*face, P, M_PI / 2, v),
                       g2 = grazing_value(*face, P, M_PI, v);
          const double C = 0.5 * (g0 + g2), A = 0.5 * (g0 - g2), B = g1 - C;
          for (int r = 0; r < 5; ++r) {
            const double u = 2 * M_PI * unit(rng);
            CHECK(std::abs(grazing_value(*face, P, u, v) - (A * std::cos(u) + B * std::sin(u) + C)) <= 1e-12 * scale);
          }
          // the roots are roots, and as many as the sign changes of g round the circle
          const std::vector<double> roots = grazing_roots_on_circle(*face, P, v, scale);
          for (double u : roots) CHECK(std::abs(grazing_value(*face, P, u, v)) <= 1e-11 * scale);
          const int n = 4000;
          int changes = 0;
          double smallest = std::numeric_limits<double>::infinity(), prev = grazing_value(*face, P, 0, v);
          for (int i = 1; i <= n; ++i) {
            const double g = grazing_value(*face, P, 2 * M_PI * i / n, v);
            changes += (g > 0) != (prev > 0);
            smallest = std::min(smallest, std::abs(g));
            prev = g;
          }
          if (std::abs(std::abs(C) - std::hypot(A, B)) < 1e-6 * scale) continue;  // a circle that nearly touches
          ++circles;
          grazing += !roots.empty();
          CHECK(int(roots.size()) == changes);
        }
      }
      // every point the tracer finds lies on a root of its circle
      for (double t : {0.3, 1.7}) {
        const PoseJet P = path.pose(t);
        for (const auto& line : grazing_set(*face, path, t).curves)
          for (const Vector2d& s : line) {
            bool whole = false;
            const std::vector<double> roots = grazing_roots_on_circle(*face, P, s.y(), scale_at(P), &whole);
            if (whole) continue;  // a pole, or a circle that grazes all round
            double nearest = 10;
            for (double u : roots) nearest = std::min(nearest, std::abs(std::remainder(s.x() - u, 2 * M_PI)));
            CHECK(nearest < 1e-7);
          }
      }
    }
  }
  CHECK(circles > 100);
  CHECK(grazing > 20);
}
