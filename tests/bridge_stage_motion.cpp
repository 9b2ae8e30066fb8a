// Sweeps under one-parameter motions that are not screw chains (SPEC.md `path`, `keyframes`):
// keyframes with screw interpolation against the screw motion they sample, balls along random
// smooth paths against the tube formula (a tube of radius r about a curve of length L whose reach
// exceeds r has volume pi r^2 L, whatever its curvature and torsion: H. Weyl, 1939), the rotation
// minimising frame, and what is not built yet failing with its reason.
#include <catch2/catch.hpp>

#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <cmath>
#include <random>
#include <sstream>

#include "base/internal.hpp"
#include "occt_bridge/sweeper.hpp"
#include "sweep/spec.hpp"
#include "varieties/ball_path.hpp"

namespace {

sweep::occt::Report run(const std::string& text) {
  const sweep::Spec spec = sweep::parse_spec(text, ".");
  return sweep::occt::run_sweep(spec).report;
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

/// The length of the curve c(t) over [0, 1] by composite Gauss-Legendre quadrature of |c'|.
double curve_length(const std::function<Eigen::Vector3d(double)>& dc) {
  const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                       0.2369268850561891};
  const int n = 2000;
  double L = 0;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 5; ++i) L += w[i] * 0.5 / n * dc((k + 0.5 + 0.5 * x[i]) / n).norm();
  return L;
}

}  // namespace

TEST_CASE("Stage motions: keyframes with screw interpolation give the solid of the screw they sample") {
  // a box turned 200 degrees about a vertical axis beside it, in three segments and in one joint
  const std::string entity = R"({"kind": "box", "min": [2, -0.5, 0], "max": [3, 0.5, 1]})";
  const Eigen::Vector3d c(1.0, 0.5, 0);
  std::string poses;
  for (int k = 0; k < 4; ++k) {
    const double a = std::vector<double>{0, 70, 140, 200}[k] * M_PI / 180;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Vector3d t = c - R * c;
    poses += std::string(k ? ", " : "") + "{\"t\": " + num(0.5 * k) + ", \"translate\": [" + num(t.x()) + ", " +
             num(t.y()) + ", 0], \"rotate\": {\"axis\": [0, 0, 1], \"angle\": " + num(a) + "}}";
  }
  const auto keys = run("{\"sweep\": 1, \"entity\": " + entity +
                        ", \"motion\": {\"kind\": \"keyframes\", \"poses\": [" + poses + "]}}");
  const auto screw = run("{\"sweep\": 1, \"entity\": " + entity +
                         ", \"motion\": {\"kind\": \"screw\", \"point\": [1, 0.5, 0], \"direction\": [0, 0, 1], "
                         "\"pitch\": 0, \"range\": [0, " + num(200 * M_PI / 180) + "]}}");
  CAPTURE(keys.to_json().dump(), screw.to_json().dump());
  REQUIRE(keys.ok());
  REQUIRE(screw.ok());
  CHECK(keys.volume_brep == Approx(screw.volume_brep).epsilon(1e-9));
  CHECK(keys.volume_divergence == Approx(screw.volume_divergence).epsilon(1e-9));
  CHECK(keys.volume_brep == Approx(1 + 20 * M_PI / 9).epsilon(1e-9));
}

TEST_CASE("Stage motions: keyframes whose segments are different screws give the union of their sweeps") {
  // slid 2 along x then 2 along y: an L of two boxes, 3 + 3 - 1 (their common unit square)
  const auto slides = run(R"({"sweep": 1, "entity": {"kind": "box", "min": [0, 0, 0], "max": [1, 1, 1]},
      "motion": {"kind": "keyframes", "interpolation": "linear", "poses": [
        {"t": 0}, {"t": 1, "translate": [2, 0, 0]}, {"t": 2, "translate": [2, 2, 0]}]}})");
  CAPTURE(slides.to_json().dump());
  REQUIRE(slides.ok());
  CHECK(slides.volume_brep == Approx(5.0).epsilon(1e-9));
  // a unit disk of height 1 at distance 3 turned 90 degrees about z, then slid 2 along z: the
  // annular sector with its end disks (area 2 theta R r + pi r^2, height 1) and the last disk
  // extruded 2 further
  const auto turn_slide = run(R"({"sweep": 1, "angles": "deg",
      "entity": {"kind": "cylinder", "base": [3, 0, 0], "axis": [0, 0, 1], "radius": 1, "height": 1},
      "motion": {"kind": "keyframes", "interpolation": "screw", "poses": [
        {"t": 0}, {"t": 1, "rotate": {"axis": [0, 0, 1], "angle": 90}},
        {"t": 2, "translate": [0, 0, 2], "rotate": {"axis": [0, 0, 1], "angle": 90}}]}})");
  CAPTURE(turn_slide.to_json().dump());
  REQUIRE(turn_slide.ok());
  CHECK(turn_slide.volume_brep == Approx(2 * (M_PI / 2) * 3 + M_PI + 2 * M_PI).epsilon(1e-7));
}

TEST_CASE("Stage motions: keyframes along a helix give the screw's solid within the tolerance", "[bench]") {
  const std::string entity = R"({"kind": "box", "min": [2, -0.5, 0], "max": [3, 0.5, 1]})";
  std::string poses;
  for (int k = 0; k < 4; ++k) {
    const double a = M_PI * k / 3;
    poses += std::string(k ? ", " : "") + "{\"t\": " + num(k) + ", \"translate\": [0, 0, " + num(2 * a / M_PI) +
             "], \"rotate\": {\"axis\": [0, 0, 1], \"angle\": " + num(a) + "}}";
  }
  const auto keys = run("{\"sweep\": 1, \"entity\": " + entity +
                        ", \"motion\": {\"kind\": \"keyframes\", \"interpolation\": \"screw\", \"poses\": [" + poses + "]}}");
  const auto screw = run("{\"sweep\": 1, \"entity\": " + entity +
                         ", \"motion\": {\"kind\": \"screw\", \"point\": [0, 0, 0], \"direction\": [0, 0, 1], "
                         "\"pitch\": 4, \"range\": [0, " + num(M_PI) + "]}}");
  CAPTURE(keys.to_json().dump(), screw.to_json().dump());
  REQUIRE(keys.ok());
  REQUIRE(screw.ok());
  // both fitted within the requested tolerance: the volumes differ by at most area x tolerance
  CHECK(std::abs(keys.volume_brep - screw.volume_brep) <= 2 * screw.area * screw.tol_requested);
}

TEST_CASE("Stage motions: balls along random smooth paths against the tube formula") {
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(-1, 1);
  int ok = 0, refused = 0;
  for (int n = 0; n < 14; ++n) {
    // c(t) = R(t) c0 + p(t): p a sum of a line and a sine wave per axis, R a turn about a fixed axis
    double a[3], b[3], f[3], ph[3];
    for (int i = 0; i < 3; ++i) {
      a[i] = 4 * u(rng);
      b[i] = 1.5 * u(rng);
      f[i] = 1 + 2 * std::abs(u(rng));
      ph[i] = 3 * u(rng);
    }
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const double spin = 2 * u(rng), r = 0.25 + 0.3 * std::abs(u(rng));
    const Eigen::Vector3d c0(u(rng), u(rng), u(rng));
    std::string tr[3];
    for (int i = 0; i < 3; ++i) tr[i] = num(a[i]) + "*t+" + num(b[i]) + "*sin(" + num(f[i]) + "*t+" + num(ph[i]) + ")";
    const std::string text = "{\"sweep\": 1, \"entity\": {\"kind\": \"sphere\", \"center\": [" + num(c0.x()) + ", " +
                             num(c0.y()) + ", " + num(c0.z()) + "], \"radius\": " + num(r) +
                             "}, \"motion\": {\"kind\": \"path\", \"t\": [0, 1], \"translate\": [\"" + tr[0] + "\", \"" +
                             tr[1] + "\", \"" + tr[2] + "\"], \"rotate\": {\"axis\": [" + num(axis.x()) + ", " +
                             num(axis.y()) + ", " + num(axis.z()) + "], \"angle\": \"" + num(spin) + "*t\"}}}";
    const auto dc = [&](double t) {
      const Eigen::Matrix3d K = (Eigen::Matrix3d() << 0, -axis.z(), axis.y(), axis.z(), 0, -axis.x(), -axis.y(),
                                 axis.x(), 0).finished();
      const Eigen::Matrix3d R = Eigen::AngleAxisd(spin * t, axis).toRotationMatrix();
      Eigen::Vector3d dp;
      for (int i = 0; i < 3; ++i) dp[i] = a[i] + b[i] * f[i] * std::cos(f[i] * t + ph[i]);
      return Eigen::Vector3d(spin * K * R * c0 + dp);
    };
    const double expected = M_PI * r * r * curve_length(dc) + 4.0 / 3.0 * M_PI * r * r * r;
    const auto rep = run(text);
    CAPTURE(n, text, rep.to_json().dump(), expected);
    if (rep.ok()) {
      ++ok;
      CHECK(rep.volume_brep == Approx(expected).epsilon(1e-7));
      CHECK(rep.volume_divergence == Approx(expected).epsilon(1e-7));
    } else {
      // only the reach of the path may stop the build, and then it says so
      ++refused;
      const bool reach = rep.message.find("comes back within") != std::string::npos ||
                         rep.message.find("bends tighter") != std::string::npos;
      CHECK(reach);
    }
  }
  CHECK(ok >= 9);
}

TEST_CASE("Stage motions: the rotation minimising frame builds the same tube") {
  const sweep::Expr tr[3] = {sweep::Expr::parse("0", {"t"}), sweep::Expr::parse("0", {"t"}),
                             sweep::Expr::parse("6*t", {"t"})};
  const sweep::PathMotion spring(
      0, 1, tr, {sweep::PathRotation{{sweep::Expr::parse("0", {"t"}), sweep::Expr::parse("0", {"t"}),
                                      sweep::Expr::parse("1", {"t"})},
                                     sweep::Expr::parse("4*pi*t", {"t"})}});
  for (const bool rmf : {false, true}) {
    double err = 0;
    std::string why;
    const TopoDS_Shape s =
        sweep::occt::ball_path_sweep(Eigen::Vector3d(5, 0, 0), 1.0, spring, 1e-7, 12, &err, nullptr, &why, rmf);
    CAPTURE(rmf, why);
    REQUIRE_FALSE(s.IsNull());
    GProp_GProps g;
    BRepGProp::VolumeProperties(s, g);
    CHECK(g.Mass() == Approx(202.47883577450276).epsilon(1e-8));
    CHECK(err < 1e-7);
  }
}

TEST_CASE("Stage motions: paths that are one screw are swept and judged as their screw") {
  // a cylinder (r 0.5, h 2) slid 3 at 40 degrees to its axis, at a growing rate:
  // pi r^2 h + |d| (pi r^2 cos a + 2 r h sin a)
  const double a = 40 * M_PI / 180, r = 0.5, h = 2, d = 3;
  const auto slide = run(R"({"sweep": 1, "entity": {"kind": "cylinder", "base": [0, 0, 0], "axis": [0, 0, 1],
      "radius": 0.5, "height": 2}, "motion": {"kind": "path", "t": [0, 1],
      "translate": ["3*sin(40*pi/180)*t^2", "0", "3*cos(40*pi/180)*t^2"]}})");
  CAPTURE(slide.to_json().dump());
  REQUIRE(slide.ok());
  CHECK(slide.volume_brep == Approx(M_PI * r * r * h + d * (M_PI * r * r * std::cos(a) + 2 * r * h * std::sin(a))).epsilon(1e-9));
  // a box turned 200 degrees about the vertical axis through (1, 0.5): x -> c + R (x - c)
  const auto turn = run(R"J({"sweep": 1, "entity": {"kind": "box", "min": [2, -0.5, 0], "max": [3, 0.5, 1]},
      "motion": {"kind": "path", "t": [0, 1],
      "translate": ["1 - (cos(200*pi/180*t) - 0.5*sin(200*pi/180*t))", "0.5 - (sin(200*pi/180*t) + 0.5*cos(200*pi/180*t))", "0"],
      "rotate": {"axis": [0, 0, 1], "angle": "200*pi/180*t"}}})J");
  CAPTURE(turn.to_json().dump());
  REQUIRE(turn.ok());
  CHECK(turn.volume_brep == Approx(1 + 20 * M_PI / 9).epsilon(1e-9));
  // a ball of radius 0.3 at distance 1 turned more than once round: the solid torus 2 pi^2 R r^2
  const auto round = run(R"({"sweep": 1, "entity": {"kind": "sphere", "center": [1, 0, 0], "radius": 0.3},
      "motion": {"kind": "path", "t": [0, 7], "translate": ["0", "0", "0"], "rotate": {"axis": [0, 0, 1], "angle": "t"}}})");
  CAPTURE(round.to_json().dump());
  REQUIRE(round.ok());
  CHECK(round.volume_brep == Approx(2 * M_PI * M_PI * 0.09).epsilon(1e-9));
  // a box on a helix: the helical joint's solid
  const auto helix = run(R"({"sweep": 1, "entity": {"kind": "box", "min": [2, -0.5, 0], "max": [3, 0.5, 1]},
      "motion": {"kind": "path", "t": [0, 1], "translate": ["0", "0", "2*t"], "rotate": {"axis": [0, 0, 1], "angle": "pi*t"}}})");
  const auto joint = run(R"({"sweep": 1, "entity": {"kind": "box", "min": [2, -0.5, 0], "max": [3, 0.5, 1]},
      "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 4, "range": [0, 3.141592653589793]}})");
  CAPTURE(helix.to_json().dump(), joint.to_json().dump());
  REQUIRE(helix.ok());
  REQUIRE(joint.ok());
  CHECK(helix.volume_brep == Approx(joint.volume_brep).epsilon(1e-9));
}

TEST_CASE("Stage motions: what is not built yet or cannot be fails with its reason") {
  const auto cylinder = run(R"({"sweep": 1, "entity": {"kind": "cylinder", "base": [0, 0, -1], "axis": [0, 0, 1],
      "radius": 0.5, "height": 2}, "motion": {"kind": "path", "t": [0, 1], "translate": ["0", "4*t", "0"],
      "rotate": {"axis": [1, 0, 0], "angle": "pi*t"}}})");
  CHECK(cylinder.status == "failed");
  CHECK(cylinder.message.find("not supported yet") != std::string::npos);
  // a ball on a circle of radius 1 once round (and a little up and down, so that the path is no
  // screw): the path comes back onto itself
  const auto round = run(R"J({"sweep": 1, "entity": {"kind": "sphere", "center": [1, 0, 0], "radius": 0.3},
      "motion": {"kind": "path", "t": [0, 7], "translate": ["0", "0", "0.01*sin(t)"], "rotate": {"axis": [0, 0, 1], "angle": "t"}}})J");
  CHECK(round.status == "failed");
  CHECK(round.message.find("comes back within") != std::string::npos);
  // a path with a corner (abs) is refused rather than built as one smooth tube
  const auto corner = run(R"J({"sweep": 1, "entity": {"kind": "sphere", "center": [0, 0, 0], "radius": 0.5},
      "motion": {"kind": "path", "t": [-1, 1], "translate": ["2*t", "2*abs(t)", "0"]}})J");
  CHECK(corner.status == "failed");
  CHECK(corner.message.find("corner") != std::string::npos);
  // bending tighter than the radius
  const auto tight = run(R"J({"sweep": 1, "entity": {"kind": "sphere", "center": [0.5, 0, 0], "radius": 1},
      "motion": {"kind": "path", "t": [0, 2], "translate": ["0", "0", "0.01*sin(t)"], "rotate": {"axis": [0, 0, 1], "angle": "t"}}})J");
  CHECK(tight.status == "failed");
  CHECK(tight.message.find("bends tighter") != std::string::npos);
}

TEST_CASE("Stage motions: a point sweeps its path and a curve a surface") {
  // a point on a helix of radius 5 rising 6 over two turns: its length
  const sweep::Spec point = sweep::parse_spec(R"({"sweep": 1, "entity": {"kind": "point", "at": [5, 0, 0]},
      "motion": {"kind": "path", "t": [0, 1], "translate": ["0", "0", "6*t"],
                 "rotate": {"axis": [0, 0, 1], "angle": "4*pi*t"}}})", ".");
  const auto p = sweep::occt::run_sweep(point);
  CAPTURE(p.report.to_json().dump());
  REQUIRE(p.report.ok());
  CHECK(p.report.dimension == 1);
  GProp_GProps g;
  BRepGProp::LinearProperties(p.shape->shape, g);
  CHECK(g.Mass() == Approx(2 * std::sqrt(100 * M_PI * M_PI + 9)).epsilon(1e-9));
  // a segment from radius 1 to 3 screwed 1.5 rad while rising 5: a strip of a helicoid
  const sweep::Spec curve = sweep::parse_spec(R"({"sweep": 1,
      "entity": {"kind": "curve", "params": {"s": [0, 1]}, "xyz": ["1+2*s", "0", "0"]},
      "motion": {"kind": "path", "t": [0, 1], "translate": ["0", "0", "5*t"], "rotate": {"axis": [0, 0, 1], "angle": "1.5*t"}}})",
                                              ".");
  const auto c = sweep::occt::run_sweep(curve);
  CAPTURE(c.report.to_json().dump());
  REQUIRE(c.report.ok());
  CHECK(c.report.dimension == 2);
  const double h = 5 / 1.5;
  const auto F = [h](double r) { return 0.5 * (r * std::sqrt(r * r + h * h) + h * h * std::log(r + std::sqrt(r * r + h * h))); };
  CHECK(c.report.area == Approx(1.5 * (F(3) - F(1))).epsilon(1e-8));
}
