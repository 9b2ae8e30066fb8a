// One sweep per entity kind, each against a closed form.
#include <BRepAdaptor_Surface.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <sstream>

#include "base/internal.hpp"
#include "occt_bridge/sweeper.hpp"
#include "sweep/spec.hpp"
#include "util/random_one_joint.hpp"

namespace {

sweep::occt::Report run(const std::string& json) {
  sweep::Spec spec = sweep::parse_spec(json, ".");
  auto r = sweep::occt::run_sweep(spec);
  INFO(r.report.to_json().dump());
  return r.report;
}

/// The number of faces of each surface type (GeomAbs_SurfaceType) of a computed shape, read back
/// from the BREP file it is written to.
std::map<int, int> surface_types(const sweep::occt::RunResult& r, const std::string& name) {
  const std::string path = std::string(SWEEP_BINARY_DIR) + "/kinds_" + name + ".brep";
  sweep::occt::write_shape(*r.shape, path, 1e-3);
  TopoDS_Shape s;
  BRep_Builder b;
  BRepTools::Read(s, path.c_str(), b);
  std::map<int, int> n;
  for (TopExp_Explorer ex(s, TopAbs_FACE); ex.More(); ex.Next()) ++n[int(BRepAdaptor_Surface(TopoDS::Face(ex.Current())).GetType())];
  return n;
}

const char* quarter_turn_z = R"("motion": {"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0],
    "direction": [0, 0, 1], "range": [0, 90]}]})";

}  // namespace

TEST_CASE("Kinds: a point sweeps a curve, a curve sweeps a surface") {
  auto p = run(std::string(R"({"sweep": 1, "angles": "deg", "entity": {"kind": "point", "at": [2, 0, 0]}, )") +
               quarter_turn_z + "}");
  CHECK(p.status == "ok");
  CHECK(p.dimension == 1);
  CHECK(p.volume_brep == Approx(0.0).margin(1e-12));
  auto c = run(std::string(R"({"sweep": 1, "angles": "deg",
      "entity": {"kind": "curve", "params": {"s": [1, 2]}, "xyz": ["s", "0", "0"]}, )") +
               quarter_turn_z + "}");
  CHECK(c.status == "ok");
  CHECK(c.dimension == 2);
  CHECK(c.area == Approx(0.75 * M_PI).epsilon(1e-9));  // annulus sector 1..2 over a quarter turn
}

TEST_CASE("Kinds: a cone extruded along its axis") {
  auto r = run(R"({"sweep": 1,
      "entity": {"kind": "cone", "base": [0, 0, 0], "axis": [0, 0, 1], "radius1": 1, "radius2": 0.5, "height": 2},
      "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [0, 0, 1], "range": [0, 3]}]}})");
  CHECK(r.status == "ok");
  // radius-1 cylinder of length 3 below the last copy's frustum
  CHECK(r.volume_brep == Approx(3 * M_PI + 7 * M_PI / 6).epsilon(1e-9));
}

TEST_CASE("Kinds: a torus extruded obliquely: OCCT's volume of its spline extrusions agrees with the independent ones") {
  // the grazing curves are splines, their extrusions surfaces of extrusion of splines, on which
  // OCCT's adaptive volume integral stopped 1.5e-5 off (depending on the point it integrates about)
  const std::string json = R"({"sweep": 1,
      "entity": {"kind": "torus", "center": [0.1, -0.2, 0.3], "axis": [0.3, -0.4, 0.8], "major": 0.9, "minor": 0.3},
      "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [1, 0.2, 0.6], "range": [0, 1.7]}]}})";
  const sweep::Spec spec = sweep::parse_spec(json, ".");
  const sweep::occt::RunResult r = sweep::occt::run_sweep(spec);
  INFO(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(surface_types(r, "torus_oblique")[int(GeomAbs_SurfaceOfExtrusion)] >= 2);
  double ref_err = 0;
  const double ref = sweep::testing::reference_volume(spec, 1e-8, &ref_err);
  CHECK(std::abs(r.report.volume_brep - r.report.volume_divergence) <= 1e-7 * ref);
  CHECK(std::abs(r.report.volume_brep - ref) <= 1e-7 * ref + 3 * ref_err);
}

TEST_CASE("Kinds: a ball screw-swept about an axis through it: the divergence volume agrees with OCCT's") {
  // The divergence quadrature cuts the spans of the fitted tube's surface and curves and takes x
  // about a point near the solid; cut evenly and about the origin it was 1.2e-5 off here, and the
  // right solid was reported failed (the orbit-space reference is 22.3284950079 +- 7.9e-8).
  const auto r = run(R"({"sweep": 1, "angles": "deg",
      "entity": {"kind": "sphere", "center": [0.962843, -0.245443, 0.480181], "radius": 1.164546},
      "motion": {"kind": "axes", "joints": [{"type": "helical", "point": [0.228847, -0.285592, 0.173050],
                 "direction": [0, 0, 1], "pitch": 1.201622, "range": [0, 312.196787]}]}})");
  REQUIRE(r.ok());
  CHECK(std::abs(r.volume_divergence - r.volume_brep) <= 1e-9 * r.volume_brep);
  CHECK(r.volume_brep == Approx(22.3284950079).epsilon(1e-7));
}

TEST_CASE("Kinds: a torus turned more than a full turn about its own axis is itself") {
  auto r = run(R"({"sweep": 1, "angles": "deg",
      "entity": {"kind": "torus", "center": [0, 0, 1], "axis": [0, 0, 1], "major": 3, "minor": 1},
      "motion": {"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1],
                 "range": [0, 400]}]}})");
  CHECK(r.status == "ok");
  CHECK(r.volume_brep == Approx(2 * M_PI * M_PI * 3).epsilon(1e-9));
}

TEST_CASE("Kinds: placement moves the entity before the motion") {
  auto r = run(R"({"sweep": 1,
      "entity": {"kind": "box", "min": [0, 0, 0], "max": [1, 1, 1], "placement": {"translate": [10, 0, 0]}},
      "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [1, 0, 0], "pitch": 0, "range": [0, 0.5]}})");
  CHECK(r.status == "ok");
  CHECK(r.bbox_min[0] == Approx(10.0).margin(1e-7));
  CHECK(r.bbox_max[0] == Approx(11.0).margin(1e-7));
}

TEST_CASE("Kinds: a surface extruded along a direction in which it is a graph, and across one in which it is not") {
  const std::string half_cylinder = R"js({"sweep": 1, "entity": {"kind": "surface",
      "params": {"u": [0, 3.141592653589793], "v": [0, 1]}, "xyz": ["cos(u)", "sin(u)", "v"]},
      "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": )js";
  // along y every line meets the half cylinder once: the solid between it and its copy 3 further,
  // 2 x 1 x 3, sewn from the face, its copy and the sweeps of its four edges (no arrangement)
  sweep::Spec graph = sweep::parse_spec(half_cylinder + R"([0, 1, 0], "range": [0, 3]}]}})", ".");
  auto g = sweep::occt::run_sweep(graph);
  INFO(g.report.to_json().dump());
  REQUIRE(g.report.ok());
  CHECK(g.report.volume_brep == Approx(6.0).epsilon(1e-7));
  CHECK(g.report.faces == 6);
  CHECK_FALSE(g.report.seconds.contains("arrangement"));
  // along x, n . d changes sign: the general arrangement, and the region swept by the half circle
  // along x has the area 3 + pi / 2 (a vertical slice at height y is [-s, s + 3], s = sqrt(1 - y^2))
  sweep::Spec across = sweep::parse_spec(half_cylinder + R"([1, 0, 0], "range": [0, 3]}]}})", ".");
  auto a = sweep::occt::run_sweep(across);
  INFO(a.report.to_json().dump());
  REQUIRE(a.report.ok());
  CHECK(a.report.volume_brep == Approx(3 + M_PI / 2).epsilon(1e-7));
  CHECK(a.report.seconds.contains("arrangement"));
}

TEST_CASE("Kinds: a ball extruded along (1, 0, 1) (an arrangement that builds no cell at one fuzzy value)") {
  auto r = run(R"({"sweep": 1, "entity": {"kind": "sphere", "center": [0, 0, 0], "radius": 1},
      "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [1, 0, 1], "range": [0, 2]}]}})");
  CHECK(r.status == "ok");
  CHECK(r.volume_brep == Approx(4 * M_PI / 3 + 2 * M_PI).epsilon(1e-9));
}

TEST_CASE("Kinds: a parametric spherical cap is built as an exact sphere face") {
  // a cap of the sphere of radius 2 about (1, 0, 0) above z = 1 (rim radius sqrt 3), extruded 3
  // along z: the rim's disk times 3, 9 pi; with the cap a spherical face and its rim's sweep a
  // cylinder, only the rim's recognition from fitted points is inexact (about 1e-10)
  auto r = run(R"js({"sweep": 1, "entity": {"kind": "surface",
      "params": {"u": [0, 6.283185307179586], "v": [0, 1.0471975511965976]},
      "xyz": ["1 + 2*cos(u)*sin(v)", "2*sin(u)*sin(v)", "2*cos(v)"]},
      "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [0, 0, 1], "range": [0, 3]}]}})js");
  CHECK(r.status == "ok");
  CHECK(r.volume_brep == Approx(9 * M_PI).epsilon(1e-9));
  CHECK(r.faces == 3);
}

TEST_CASE("Kinds: a joint that slides a curve along itself extends its parameter range") {
  // an arc of radius 2 turned about its own axis: the longer arc, then extruded 3 along the axis
  const std::string head = R"js({"sweep": 1, "angles": "deg",
      "entity": {"kind": "curve", "params": {"t": [0, 1.5707963267948966]}, "xyz": ["2*cos(t)", "2*sin(t)", "0"]},
      "motion": {"kind": "axes", "joints": [
        {"type": "prismatic", "direction": [0, 0, 1], "range": [0, 3]},
        {"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": )js";
  auto half = run(head + "[0, 90]}]}}");
  CHECK(half.status == "ok");
  CHECK(half.dimension == 2);
  CHECK(half.area == Approx(2 * M_PI * 3).epsilon(1e-7));  // half a cylinder of radius 2, height 3
  // beyond a whole turn the arc closes into the circle, covered once
  auto whole = run(head + "[0, 400]}]}}");
  CHECK(whole.status == "ok");
  CHECK(whole.area == Approx(4 * M_PI * 3).epsilon(1e-7));
}

TEST_CASE("Kinds: circles turned about an axis in their plane or through their axis sweep tori and spheres") {
  // A ball of radius 1 whose centre is 3 from the axis, a quarter turn: the tube between its two
  // halves is one exact torus face (Pappus: pi r^2 * 3 * pi / 2, plus the ball).
  auto ball = sweep::occt::run_sweep(sweep::parse_spec(
      std::string(R"({"sweep": 1, "angles": "deg", "entity": {"kind": "sphere", "center": [3, 0, 0], "radius": 1}, )") +
          quarter_turn_z + "}",
      "."));
  INFO(ball.report.to_json().dump());
  REQUIRE(ball.report.ok());
  CHECK(ball.report.volume_brep == Approx(1.5 * M_PI * M_PI + 4 * M_PI / 3).epsilon(1e-12));
  CHECK(ball.report.faces == 3);
  auto types = surface_types(ball, "ball_quarter");
  CHECK(types[GeomAbs_Torus] == 1);
  CHECK(types[GeomAbs_Sphere] == 2);
  CHECK(types[GeomAbs_SurfaceOfRevolution] == 0);
  // A circle of radius 1 in the plane through the axis (a parametric curve, recognised as a circle
  // from fitted points): the torus of radii 3 and 1 over a quarter turn, area 2 pi * 3 * pi / 2.
  auto ring = sweep::occt::run_sweep(sweep::parse_spec(
      std::string(R"js({"sweep": 1, "angles": "deg",
      "entity": {"kind": "curve", "params": {"t": [0, 6.283185307179586]}, "xyz": ["3 + cos(t)", "0", "sin(t)"]}, )js") +
          quarter_turn_z + "}",
      "."));
  INFO(ring.report.to_json().dump());
  REQUIRE(ring.report.ok());
  CHECK(ring.report.area == Approx(3 * M_PI * M_PI).epsilon(1e-8));
  types = surface_types(ring, "ring_quarter");
  CHECK(types[GeomAbs_Torus] >= 1);
  CHECK(types.size() == 1);
  // A half circle of radius 1 about the x axis at x = 3 (its axis meets the rotation axis): it lies
  // on the sphere of radius sqrt 10 about the origin, and a quarter turn sweeps the patch of it
  // between the latitudes +-asin(1 / sqrt 10): area 10 (pi / 2) (2 / sqrt 10) = pi sqrt 10.
  auto rim = sweep::occt::run_sweep(sweep::parse_spec(
      std::string(R"js({"sweep": 1, "angles": "deg",
      "entity": {"kind": "curve", "params": {"t": [-1.5707963267948966, 1.5707963267948966]},
      "xyz": ["3", "cos(t)", "sin(t)"]}, )js") +
          quarter_turn_z + "}",
      "."));
  INFO(rim.report.to_json().dump());
  REQUIRE(rim.report.ok());
  CHECK(rim.report.area == Approx(M_PI * std::sqrt(10.0)).epsilon(1e-8));
  types = surface_types(rim, "rim_quarter");
  CHECK(types[GeomAbs_Sphere] >= 1);
  CHECK(types.size() == 1);
  // The whole circle: its two halves sweep overlapping patches, counted once. At height z the
  // circle's points (3, +-sqrt(1 - z^2), z) sweep the longitudes [-g, g + pi / 2], g = atan(sqrt(1 -
  // z^2) / 3), so the area is sqrt 10 * int (pi / 2 + 2 g) dz = pi (20 - 5 sqrt 10) (with
  // int_0^1 atan(a sqrt(1 - z^2)) dz = (pi / 2)(sqrt(1 + a^2) - 1) / a).
  auto full = run(std::string(R"js({"sweep": 1, "angles": "deg",
      "entity": {"kind": "curve", "params": {"t": [0, 6.283185307179586]}, "xyz": ["3", "cos(t)", "sin(t)"]}, )js") +
                  quarter_turn_z + "}");
  REQUIRE(full.status == "ok");
  CHECK(full.area == Approx(M_PI * (20 - 5 * std::sqrt(10.0))).epsilon(1e-6));
}

TEST_CASE("Elliptic cylinders: the entity, and swept by a prismatic and a revolute joint against closed forms") {
  // the twisted entity keeps its sections' area: volume pi a b h
  {
    const sweep::Spec s = sweep::parse_spec(R"({"sweep": 1, "entity": {"kind": "elliptic_cylinder", "base": [0.5, 0, 0],
        "axis": [0, 1, 1], "a": 1.0, "b": 0.4, "height": 3, "twist": "1.5*u"},
        "motion": {"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 0, "range": [0, 1]}})", ".");
    double err = 0;
    const TopoDS_Shape body = sweep::occt::entity_shape(s.entity, 1e-7, &err);
    GProp_GProps g;
    BRepGProp::VolumeProperties(body, g);
    CHECK(std::abs(g.Mass()) == Approx(M_PI * 1.0 * 0.4 * 3).epsilon(1e-6));
    CHECK(err < 1e-6);
  }
  const std::string entity = R"({"kind": "elliptic_cylinder", "base": [0, 0, 0], "axis": [0, 0, 1], "a": 1.5, "b": 0.7, "height": 2})";
  // translated 3 along its a axis: the ellipse plus a 3 x 2b rectangle, times the height
  const auto slide = sweep::occt::run_sweep(sweep::parse_spec(R"({"sweep": 1, "entity": )" + entity + R"(,
      "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [1, 0, 0], "range": [0, 3]}]}})", "."));
  CAPTURE(slide.report.to_json().dump());
  CHECK(slide.report.ok());
  CHECK(slide.report.volume_brep == Approx((M_PI * 1.5 * 0.7 + 3 * 1.4) * 2).epsilon(1e-9));
  // turned 1.2 rad about its own axis: at radius rho in [b, a] the section covers two arcs of half
  // angle alpha(rho) (sin^2 alpha = (1/rho^2 - 1/a^2) / (1/b^2 - 1/a^2)), each lengthened by the turn
  const auto turn = sweep::occt::run_sweep(sweep::parse_spec(R"({"sweep": 1, "entity": )" + entity + R"(,
      "motion": {"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, 1.2]}]}})", "."));
  CAPTURE(turn.report.to_json().dump());
  CHECK(turn.report.ok());
  const double a = 1.5, b = 0.7, th = 1.2;
  // Gauss-Legendre on [b, a] in the variable s = sqrt(a - rho) (smooth where the arcs vanish), split where the arcs meet
  const auto covered = [&](double rho) {
    const double s2 = std::clamp((1 / (rho * rho) - 1 / (a * a)) / (1 / (b * b) - 1 / (a * a)), 0.0, 1.0);
    return std::min(2 * M_PI, 2 * (2 * std::asin(std::sqrt(s2)) + th));
  };
  // the arcs meet where 2 alpha + th = pi
  const double s2m = std::pow(std::sin(0.5 * (M_PI - th)), 2);
  const double rho_m = 1 / std::sqrt(s2m * (1 / (b * b) - 1 / (a * a)) + 1 / (a * a));
  const double x[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  const double w[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                       0.2369268850561891};
  double area = M_PI * rho_m * rho_m;  // every angle covered below rho_m
  const int n = 400;
  const double smax = std::sqrt(a - rho_m);
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 5; ++i) {
      const double s = smax * (k + 0.5 + 0.5 * x[i]) / n, rho = a - s * s;
      area += w[i] * 0.5 * smax / n * rho * covered(rho) * 2 * s;
    }
  CHECK(turn.report.volume_brep == Approx(area * 2).epsilon(1e-9));
}

TEST_CASE("Kinds: placed balls along random prismatic joints are capsules, built directly and by the general pipeline") {
  // the first one: a ball placed and turned, moved along -y, whose general build once stalled in
  // OCCT's face merging (two halves of its cylinder, one on a left-handed frame)
  std::vector<std::string> specs = {R"({"sweep": 1, "angles": "deg",
      "entity": {"kind": "sphere", "center": [-0.0903, -1.6495, 0.9854], "radius": 1.7704,
                 "placement": {"translate": [0.7682, 3.5503, -0.8804], "rotate": {"axis": [0, -1, 0], "angle": -26.054}}},
      "motion": {"kind": "axes", "joints": [{"type": "prismatic", "point": [0, 0, 0], "direction": [0, -1, 0],
                                              "range": [-0.9726, 8.2267]}]}})"};
  std::vector<double> exact = {M_PI * 1.7704 * 1.7704 * (8.2267 + 0.9726) + 4 * M_PI / 3 * std::pow(1.7704, 3)};
  std::mt19937_64 rng(38);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto num = [](double x) {
    std::ostringstream o;
    o.precision(17);
    o << x;
    return o.str();
  };
  for (int k = 0; k < 6; ++k) {
    const double r = 0.2 + std::abs(u(rng)), lo = u(rng), hi = lo + 0.1 + 3 * std::abs(u(rng));
    const double cx = u(rng), cy = u(rng), cz = u(rng), ax = u(rng), ay = u(rng), angle = 3 * u(rng);
    const Eigen::Vector3d d(u(rng), u(rng), u(rng));  // the joint's direction (normalised by the spec)
    specs.push_back(R"({"sweep": 1, "entity": {"kind": "sphere", "center": [)" + num(cx) + ", " + num(cy) + ", " +
                    num(cz) + R"(], "radius": )" + num(r) +
                    R"(, "placement": {"translate": [0.3, -0.5, 0.2], "rotate": {"axis": [)" + num(ax) + ", " +
                    num(ay) + R"(, 1], "angle": )" + num(angle) +
                    R"(}}}, "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [)" +
                    num(d.x()) + ", " + num(d.y()) + ", " + num(d.z()) + R"(], "range": [)" + num(lo) + ", " + num(hi) +
                    "]}]}}");
    exact.push_back(M_PI * r * r * (hi - lo) + 4 * M_PI / 3 * r * r * r);
  }
  for (std::size_t k = 0; k < specs.size(); ++k)
    for (const bool direct : {true, false}) {
      INFO(specs[k] << (direct ? " (direct)" : " (general pipeline)"));
      const sweep::Spec spec = sweep::parse_spec(specs[k], ".");
      sweep::occt::RunOptions opt;
      opt.direct_builds = direct;
      opt.stop = sweep::occt::stop_after(60);
      const auto r = sweep::occt::run_sweep(spec, opt);
      INFO(r.report.to_json().dump());
      CHECK(r.report.status == "ok");
      CHECK(r.report.volume_brep == Approx(exact[k]).epsilon(1e-9));
      if (direct) CHECK(r.report.faces == 3);  // one cylinder, two half balls
    }
}

TEST_CASE("Kinds: a spec without a tolerance takes Settings::default_tolerance of the model size", "[kinds]") {
  // a unit box turned a quarter turn about the z axis: model size from its reach
  const sweep::Spec spec = sweep::parse_spec(
      R"({"sweep": 1, "entity": {"kind": "box", "min": [0, 0, 0], "max": [1, 1, 1]},
          "motion": {"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1],
                                                  "range": [0, 1.5707963267948966]}]}})",
      ".");
  sweep::occt::RunOptions fine, coarse;
  coarse.settings.default_tolerance = 1e-5;
  const auto a = sweep::occt::run_sweep(spec, fine).report, b = sweep::occt::run_sweep(spec, coarse).report;
  INFO(a.to_json().dump() << "\n" << b.to_json().dump());
  REQUIRE(a.ok());
  REQUIRE(b.ok());
  CHECK(a.tol_requested > 0);
  CHECK(std::abs(b.tol_requested / a.tol_requested - 10) < 1e-12);
  // the swept square: half of each end copy and the quarter of the disc of radius sqrt(2) between
  CHECK(std::abs(a.volume_brep - (1 + M_PI / 2)) <= a.area * a.tol_requested);
  CHECK(std::abs(b.volume_brep - (1 + M_PI / 2)) <= b.area * b.tol_requested);
}

TEST_CASE("Kinds: a saddle patch placed and swept by each joint kind is judged ok", "[kinds]") {
  // (judged by each point's trajectory against the patch alone, the verdict called points just
  // inside the swept set not swept at 1 to 8 of 512 probes: where a trajectory misses the patch,
  // the search over joint and surface parameters is asked too)
  const std::string entity = R"json({"kind": "surface", "params": {"u": [-1, 1], "v": [-1, 1]},
      "xyz": ["u", "v", "0.3*u*v + 0.2*u*u"],
      "placement": {"translate": [0.3, -0.2, 0.5], "rotate": {"axis": [1, 2, 0.5], "angle": 0.7}}})json";
  for (const std::string joint :
       {R"({"type": "revolute", "point": [2, 0.5, 0], "direction": [0.2, 0.3, 1], "range": [0, 1.3]})",
        R"({"type": "prismatic", "direction": [0.3, -0.5, 1], "range": [0, 1.7]})",
        R"({"type": "helical", "point": [1.5, 0.5, 0], "direction": [0.2, 0.3, 1], "pitch": 0.4, "range": [0, 2.5]})"}) {
    const auto r = run(R"({"sweep": 1, "entity": )" + entity + R"(, "motion": {"kind": "axes", "joints": [)" + joint + "]}}");
    INFO(r.to_json().dump());
    CHECK(r.ok());
    CHECK(r.volume_brep > 5);
    CHECK(std::abs(r.volume_brep - r.volume_divergence) <= 1e-9 * r.volume_brep + r.tol_requested * r.area);
  }
}
