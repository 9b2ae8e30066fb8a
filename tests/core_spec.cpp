#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sweep/error.hpp"
#include "sweep/spec.hpp"

using sweep::InputError;

namespace {

constexpr double kPi = 3.14159265358979323846;

const char* kSpecExample = R"({
  "sweep": 1,
  "name": "seed 000, section 4.4",
  "angles": "deg",
  "entity": { "kind": "point", "at": [0, 0, 0] },
  "motion": { "kind": "dh", "joints": [
      { "type": "revolute", "theta": "q", "d": 0, "a": 0,  "alpha": 90, "range": [0, 270] },
      { "type": "revolute", "theta": "q", "d": 0, "a": 10, "alpha": 0,  "range": [-120, 120] },
      { "type": "revolute", "theta": "q", "d": 0, "a": 5,  "alpha": 0,  "range": [-120, 120] } ] },
  "tolerance": 1e-6
})";

/// A spec document with the given entity and motion objects (JSON text), one field per line.
std::string doc(const std::string& entity, const std::string& motion, const std::string& extra = "") {
  return "{\n  \"sweep\": 1,\n" + extra + "  \"entity\": " + entity + ",\n  \"motion\": " + motion + "\n}\n";
}

const std::string kSphere = R"({"kind": "sphere", "center": [0, 0, 0], "radius": 1})";
const std::string kRevolute =
    R"({"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, 1]}]})";

/// Parses `text`, requires an InputError at `pointer`, and returns it.
InputError input_error(const std::string& text, const std::vector<std::string>& overrides = {},
                       const std::string& base_dir = ".") {
  try {
    sweep::parse_spec(text, base_dir, overrides);
  } catch (const InputError& e) {
    return e;
  }
  FAIL("no InputError for:\n" << text);
  throw std::logic_error("unreachable");
}

/// The error must be at `pointer`; when the pointer occurs in the text, line:column must be its position.
InputError expect_error(const std::string& text, const std::string& pointer,
                        const std::vector<std::string>& overrides = {}, const std::string& base_dir = ".") {
  const InputError e = input_error(text, overrides, base_dir);
  INFO(e.describe("spec.json"));
  CHECK(e.pointer() == pointer);
  const auto loc = sweep::locate_pointer(text, pointer);
  if (loc.first > 0 && overrides.empty()) {
    CHECK(e.line() == loc.first);
    CHECK(e.column() == loc.second);
    CHECK(e.line() > 0);
  }
  return e;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

Eigen::Isometry3d dh(double theta, double d, double a, double alpha) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.rotate(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()));
  T.translate(Eigen::Vector3d(0, 0, d));
  T.translate(Eigen::Vector3d(a, 0, 0));
  T.rotate(Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()));
  return T;
}

double max_diff(const Eigen::Isometry3d& A, const Eigen::Isometry3d& B) {
  return (A.matrix() - B.matrix()).cwiseAbs().maxCoeff();
}

// The shared contract cases, as copied into examples/cases.
std::string shared_case(const std::string& name) { return std::string(SWEEP_SOURCE_DIR) + "/examples/cases/" + name; }

}  // namespace

// ---------------------------------------------------------------------------------------------
// Valid specs

TEST_CASE("Spec: SPEC.md example", "[spec]") {
  const sweep::Spec s = sweep::parse_spec(kSpecExample, ".");
  CHECK(s.version == 1);
  CHECK(s.name == "seed 000, section 4.4");
  CHECK(s.degrees);
  CHECK(s.tolerance == Approx(1e-6).epsilon(1e-12));
  CHECK(s.entity.kind == sweep::EntityKind::Point);
  CHECK(s.entity.dimension() == 0);
  CHECK(s.entity.at.norm() == Approx(0.0).margin(1e-15));
  CHECK(s.motion.kind == sweep::MotionKind::Dh);
  REQUIRE(s.motion.dh.size() == 3);
  REQUIRE(s.motion.motion.dof() == 3);
  CHECK(s.motion.dh[0].lo == Approx(0.0).margin(1e-15));
  CHECK(s.motion.dh[0].hi == Approx(1.5 * kPi).epsilon(1e-14));
  CHECK(s.motion.dh[1].lo == Approx(-120 * kPi / 180).epsilon(1e-14));
  // theta = q, so the joint ranges are the q ranges in radians.
  CHECK(s.motion.motion.joints[0].hi == Approx(1.5 * kPi).epsilon(1e-12));
  CHECK(s.motion.motion.joints[2].lo == Approx(-120 * kPi / 180).epsilon(1e-12));
  CHECK(s.motion.dh[0].alpha.eval(std::vector<double>{0.0}) == Approx(kPi / 2).epsilon(1e-14));
  CHECK(s.json["tolerance"].get<double>() == Approx(1e-6).epsilon(1e-12));

  const std::vector<std::vector<double>> qs = {{0, 0, 0}, {0.3, -1.2, 2.0}, {4.5, 2.0, -2.0}, {1.0, 0.5, 0.25}};
  for (const auto& q : qs) {
    const Eigen::Isometry3d direct = dh(q[0], 0, 0, kPi / 2) * dh(q[1], 0, 10, 0) * dh(q[2], 0, 5, 0);
    CHECK(max_diff(s.motion.motion.transform(q), direct) < 1e-12);
  }
}

TEST_CASE("Spec: shared case box_quarter_turn", "[spec]") {
  const sweep::Spec s = sweep::load_spec(shared_case("box_quarter_turn.json"));
  CHECK(s.degrees);
  CHECK(s.entity.kind == sweep::EntityKind::Box);
  CHECK(s.entity.dimension() == 3);
  CHECK(s.entity.min.x() == Approx(1.0).margin(1e-15));
  CHECK(s.entity.max.y() == Approx(1.0).margin(1e-15));
  CHECK(s.motion.kind == sweep::MotionKind::Axes);
  REQUIRE(s.motion.motion.joints.size() == 1);
  const auto& j = s.motion.motion.joints[0];
  CHECK(j.type == sweep::JointType::Revolute);
  CHECK(j.lo == Approx(0.0).margin(1e-15));
  CHECK(j.hi == Approx(kPi / 2).epsilon(1e-14));
  CHECK((j.direction - Eigen::Vector3d::UnitZ()).norm() < 1e-15);
  CHECK(max_diff(s.motion.motion.home, Eigen::Isometry3d::Identity()) < 1e-15);
  CHECK(s.json.contains("_expected_volume"));
  CHECK(s.tolerance == 0.0);
}

TEST_CASE("Spec: shared case capsule", "[spec]") {
  const sweep::Spec s = sweep::load_spec(shared_case("capsule.json"));
  CHECK_FALSE(s.degrees);
  CHECK(s.entity.kind == sweep::EntityKind::Sphere);
  CHECK(s.entity.radius == Approx(1.0).epsilon(1e-15));
  REQUIRE(s.motion.motion.joints.size() == 1);
  const auto& j = s.motion.motion.joints[0];
  CHECK(j.type == sweep::JointType::Prismatic);
  CHECK((j.direction - Eigen::Vector3d(1, 1, 1).normalized()).norm() < 1e-15);
  CHECK(j.lo == Approx(0.0).margin(1e-15));
  CHECK(j.hi == Approx(5.0).epsilon(1e-15));
}

TEST_CASE("Spec: shared case cylinder_through_axis", "[spec]") {
  const sweep::Spec s = sweep::load_spec(shared_case("cylinder_through_axis.json"));
  CHECK(s.entity.kind == sweep::EntityKind::Cylinder);
  CHECK(s.entity.base.z() == Approx(-1.0).epsilon(1e-15));
  CHECK((s.entity.axis - Eigen::Vector3d::UnitZ()).norm() < 1e-15);
  CHECK(s.entity.height == Approx(2.0).epsilon(1e-15));
  REQUIRE(s.motion.motion.joints.size() == 1);
  CHECK(s.motion.motion.joints[0].hi == Approx(kPi).epsilon(1e-14));
  CHECK((s.motion.motion.joints[0].direction - Eigen::Vector3d::UnitX()).norm() < 1e-15);
}

TEST_CASE("Spec: shared case spring_open", "[spec]") {
  const sweep::Spec s = sweep::load_spec(shared_case("spring_open.json"));
  CHECK(s.motion.kind == sweep::MotionKind::Screw);
  REQUIRE(s.motion.motion.joints.size() == 1);
  const auto& j = s.motion.motion.joints[0];
  CHECK(j.type == sweep::JointType::Helical);
  CHECK(j.pitch == Approx(3.0 / (2 * kPi)).epsilon(1e-14));
  CHECK(j.hi == Approx(4 * kPi).epsilon(1e-14));
  // Two turns rise by two pitches.
  const Eigen::Isometry3d T = s.motion.motion.transform({4 * kPi});
  CHECK((T * s.entity.center - Eigen::Vector3d(5, 0, 6)).norm() < 1e-12);
}

TEST_CASE("Spec: shared case torus_sector", "[spec]") {
  const sweep::Spec s = sweep::load_spec(shared_case("torus_sector.json"));
  CHECK(s.entity.kind == sweep::EntityKind::Surface);
  CHECK(s.entity.dimension() == 2);
  REQUIRE(s.entity.params.size() == 2);
  // Document order is kept: r first, then p.
  CHECK(s.entity.params[0].name == "r");
  CHECK(s.entity.params[1].name == "p");
  CHECK(s.entity.params[1].hi == Approx(2 * kPi).epsilon(1e-15));
  const std::vector<double> rp = {0.5, kPi / 2};
  CHECK(s.entity.xyz[0].eval(rp) == Approx(3.0).epsilon(1e-14));
  CHECK(s.entity.xyz[1].eval(rp) == Approx(0.0).margin(1e-15));
  CHECK(s.entity.xyz[2].eval(rp) == Approx(0.5).epsilon(1e-14));
  CHECK(s.motion.motion.joints.at(0).hi == Approx(1.5 * kPi).epsilon(1e-14));
}

TEST_CASE("Spec: every entity kind parses", "[spec]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "sweep_core_spec_files";
  fs::create_directories(dir);
  { std::ofstream(dir / "part.step") << "ISO-10303-21;\n"; }
  { std::ofstream(dir / "part.stl") << "solid x\nendsolid x\n"; }

  struct Case {
    std::string entity;
    sweep::EntityKind kind;
    int dim;
  };
  const std::vector<Case> cases = {
      {R"({"kind": "point", "at": [1, 2, 3]})", sweep::EntityKind::Point, 0},
      {R"({"kind": "curve", "params": {"t": [0, 1]}, "xyz": ["t", "t^2", 0]})", sweep::EntityKind::Curve, 1},
      {R"({"kind": "surface", "params": {"u": [0, 1], "v": [0, 1]}, "xyz": ["u", "v", "u*v"]})",
       sweep::EntityKind::Surface, 2},
      {R"({"kind": "cylinder", "base": [0, 0, 0], "axis": [0, 0, 2], "radius": 1, "height": 2})",
       sweep::EntityKind::Cylinder, 3},
      {R"({"kind": "cone", "base": [0, 0, 0], "axis": [0, 0, 1], "radius1": 1, "radius2": 0, "height": 2})",
       sweep::EntityKind::Cone, 3},
      {R"({"kind": "torus", "center": [0, 0, 0], "axis": [0, 0, 1], "major": 3, "minor": 1})",
       sweep::EntityKind::Torus, 3},
      {R"({"kind": "elliptic_cylinder", "base": [0, 0, 0], "axis": [0, 0, 1], "a": 2, "b": 1, "height": 3,
           "twist": "pi*u"})",
       sweep::EntityKind::EllipticCylinder, 3},
      {R"({"kind": "implicit", "inequalities": ["x^2+y^2+z^2-1", "-z"],
           "bounds": {"min": [-1, -1, -1], "max": [1, 1, 1]}})",
       sweep::EntityKind::Implicit, 3},
      {R"({"kind": "brep", "file": "part.step"})", sweep::EntityKind::Brep, 3},
      {R"({"kind": "mesh", "file": "part.stl"})", sweep::EntityKind::Mesh, 3},
      {R"({"kind": "tube", "spine": {"kind": "curve", "params": {"s": [0, 1]}, "xyz": ["s", 0, 0]},
           "radius": "0.1+0.05*s"})",
       sweep::EntityKind::Tube, 3},
  };
  for (const auto& c : cases) {
    INFO(c.entity);
    const sweep::Spec s = sweep::parse_spec(doc(c.entity, kRevolute), dir.string());
    CHECK(s.entity.kind == c.kind);
    CHECK(s.entity.dimension() == c.dim);
    CHECK(std::string(sweep::to_string(c.kind)) == s.json["entity"]["kind"].get<std::string>());
  }
  const sweep::Spec cyl = sweep::parse_spec(doc(cases[3].entity, kRevolute), ".");
  CHECK((cyl.entity.axis - Eigen::Vector3d::UnitZ()).norm() < 1e-15);  // normalized
  const sweep::Spec mesh = sweep::parse_spec(doc(cases[9].entity, kRevolute), dir.string());
  CHECK(fs::equivalent(mesh.entity.file, dir / "part.stl"));
  const sweep::Spec tube = sweep::parse_spec(doc(cases[10].entity, kRevolute), ".");
  REQUIRE(tube.entity.spine);
  CHECK(tube.entity.spine->kind == sweep::EntityKind::Curve);
  CHECK(tube.entity.tube_radius->eval(std::vector<double>{1.0}) == Approx(0.15).epsilon(1e-14));
  const sweep::Spec impl = sweep::parse_spec(doc(cases[7].entity, kRevolute), ".");
  CHECK(impl.entity.inequalities.size() == 2);
  CHECK(impl.entity.max.z() == Approx(1.0).epsilon(1e-15));
  fs::remove_all(dir);
}

TEST_CASE("Spec: placements", "[spec]") {
  const std::string e1 =
      R"({"kind": "sphere", "center": [1, 0, 0], "radius": 1,
          "placement": {"translate": [0, 0, 5], "rotate": {"axis": [0, 0, 3], "angle": 90}}})";
  const sweep::Spec s = sweep::parse_spec(doc(e1, kRevolute, "  \"angles\": \"deg\",\n"), ".");
  CHECK((s.entity.placement * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(0, 1, 5)).norm() < 1e-14);

  const std::string e2 =
      R"({"kind": "sphere", "center": [1, 0, 0], "radius": 1,
          "placement": {"matrix": [[0, -1, 0, 1], [1, 0, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]}})";
  const sweep::Spec m = sweep::parse_spec(doc(e2, kRevolute), ".");
  CHECK((m.entity.placement * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(1, 3, 3)).norm() < 1e-14);

  const std::string bad =
      R"({"kind": "sphere", "center": [1, 0, 0], "radius": 1,
          "placement": {"matrix": [[2, 0, 0, 1], [0, 1, 0, 2], [0, 0, 1, 3], [0, 0, 0, 1]]}})";
  expect_error(doc(bad, kRevolute), "/entity/placement/matrix");
  const std::string last =
      R"({"kind": "sphere", "center": [1, 0, 0], "radius": 1,
          "placement": {"matrix": [[1, 0, 0, 1], [0, 1, 0, 2], [0, 0, 1, 3], [0, 0, 1, 1]]}})";
  expect_error(doc(last, kRevolute), "/entity/placement/matrix/3");
}

TEST_CASE("Spec: DH conversion matches the direct DH product", "[spec]") {
  // Revolute with an offset expression, prismatic with a scaled variable, helical; in degrees, with a base.
  const std::string motion = R"({"kind": "dh",
    "base": {"translate": [1, 2, 3], "rotate": {"axis": [1, 1, 0], "angle": 30}},
    "joints": [
      {"type": "revolute", "theta": "q-90", "d": 0.5, "a": 2, "alpha": 90, "range": [0, 270]},
      {"type": "prismatic", "theta": 30, "d": "2*q", "a": 1, "alpha": -45, "range": [-1, 2]},
      {"type": "helical", "theta": "q", "d": 0.25, "a": 0.5, "alpha": "45/2", "pitch": 3, "range": [-90, 180]}
    ]})";
  const sweep::Spec s = sweep::parse_spec(doc(kSphere, motion, "  \"angles\": \"deg\",\n"), ".");
  const auto& M = s.motion.motion;
  REQUIRE(M.dof() == 3);
  const double deg = kPi / 180;
  // Joint variable intervals: theta = q - 90 over [0, 270] deg; d = 2 q over [-1, 2]; theta = q.
  CHECK(M.joints[0].lo == Approx(-90 * deg).epsilon(1e-12));
  CHECK(M.joints[0].hi == Approx(180 * deg).epsilon(1e-12));
  CHECK(M.joints[1].type == sweep::JointType::Prismatic);
  CHECK(M.joints[1].lo == Approx(-2.0).epsilon(1e-12));
  CHECK(M.joints[1].hi == Approx(4.0).epsilon(1e-12));
  CHECK(M.joints[2].pitch == Approx(3.0 / (2 * kPi)).epsilon(1e-14));
  CHECK(s.motion.dh[0].lo == Approx(0.0).margin(1e-15));
  CHECK(s.motion.dh[0].hi == Approx(270 * deg).epsilon(1e-14));
  CHECK(s.motion.dh[1].hi == Approx(2.0).epsilon(1e-15));
  // DhRow expressions take q in radians and return radians.
  CHECK(s.motion.dh[0].theta.eval(std::vector<double>{kPi}) == Approx(kPi / 2).epsilon(1e-14));

  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
  base.translation() = Eigen::Vector3d(1, 2, 3);
  base.linear() = Eigen::AngleAxisd(30 * deg, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  const std::vector<std::vector<double>> qs = {
      {0, -1, -90}, {45, 0, 0}, {270, 2, 180}, {123.4, 0.7, -12.5}, {90, -0.3, 33}};
  for (const auto& q : qs) {
    const double th1 = (q[0] - 90) * deg, d2 = 2 * q[1], th3 = q[2] * deg;
    const Eigen::Isometry3d direct = base * dh(th1, 0.5, 2, 90 * deg) * dh(30 * deg, d2, 1, -45 * deg) *
                                     dh(th3, 0.25 + 3.0 / (2 * kPi) * th3, 0.5, 22.5 * deg);
    // Motion variables are the DH joint variables (theta or d), not q.
    const Eigen::Isometry3d T = M.transform({th1, d2, th3});
    INFO("q = " << q[0] << ", " << q[1] << ", " << q[2]);
    CHECK(max_diff(T, direct) < 1e-12);
  }
}

TEST_CASE("Spec: DH conversion in radians", "[spec]") {
  const std::string motion = R"({"kind": "dh", "joints": [
      {"type": "revolute", "theta": "q", "d": 1, "a": 0, "alpha": "pi/2", "range": [-1, 1]},
      {"type": "revolute", "theta": "q+pi/4", "d": 0, "a": 3, "alpha": 0, "range": [0, 2]}]})";
  const sweep::Spec s = sweep::parse_spec(doc(kSphere, motion), ".");
  for (const auto& q : std::vector<std::vector<double>>{{0, 0}, {0.5, 1.5}, {-1, 2}, {0.25, 0.125}}) {
    const double th2 = q[1] + kPi / 4;
    const Eigen::Isometry3d direct = dh(q[0], 1, 0, kPi / 2) * dh(th2, 0, 3, 0);
    CHECK(max_diff(s.motion.motion.transform({q[0], th2}), direct) < 1e-12);
  }
  CHECK(s.motion.motion.joints[1].lo == Approx(kPi / 4).epsilon(1e-12));
  CHECK(s.motion.motion.joints[1].hi == Approx(2 + kPi / 4).epsilon(1e-12));
}

TEST_CASE("Spec: DH interval of a non-monotone joint expression", "[spec]") {
  const std::string motion = R"J({"kind": "dh", "joints": [
      {"type": "revolute", "theta": "sin(q)", "d": 0, "a": 1, "alpha": 0, "range": [0, 3.141592653589793]}]})J";
  const sweep::Spec s = sweep::parse_spec(doc(kSphere, motion), ".");
  CHECK(s.motion.motion.joints[0].lo == Approx(0.0).margin(1e-12));
  CHECK(s.motion.motion.joints[0].hi == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("Spec: overrides", "[spec]") {
  const std::string text = doc(kSphere, kRevolute, "  \"angles\": \"deg\",\n");
  const sweep::Spec s =
      sweep::parse_spec(text, ".", {"/motion/joints/0/range=[0,90]", "/name=hello world", "/entity/radius=2.5"});
  CHECK(s.motion.motion.joints[0].hi == Approx(kPi / 2).epsilon(1e-14));
  CHECK(s.name == "hello world");
  CHECK(s.entity.radius == Approx(2.5).epsilon(1e-15));
  CHECK(s.json["motion"]["joints"][0]["range"][1].get<double>() == Approx(90.0).epsilon(1e-15));

  // A value from --set that fails validation names the pointer but has no position in the file.
  const InputError e = input_error(text, {"/entity/radius=-1"});
  CHECK(e.pointer() == "/entity/radius");
  CHECK(e.line() == 0);
  CHECK(contains(e.what(), "got -1"));
}

TEST_CASE("Spec: locate_pointer", "[spec]") {
  const std::string text = "{\n  \"a\": [1, {\"b/c\": \"x\\\"y\", \"t~\": true}],\n  \"\\u00e9\": {\"k\": null}\n}";
  CHECK(sweep::locate_pointer(text, "") == std::make_pair(1, 1));
  CHECK(sweep::locate_pointer(text, "/a") == std::make_pair(2, 8));
  CHECK(sweep::locate_pointer(text, "/a/0") == std::make_pair(2, 9));
  CHECK(sweep::locate_pointer(text, "/a/1") == std::make_pair(2, 12));
  CHECK(sweep::locate_pointer(text, "/a/1/b~1c") == std::make_pair(2, 20));
  CHECK(sweep::locate_pointer(text, "/a/1/t~0") == std::make_pair(2, 34));
  CHECK(sweep::locate_pointer(text, "/\xc3\xa9/k") == std::make_pair(3, 19));
  CHECK(sweep::locate_pointer(text, "/a/2") == std::make_pair(0, 0));
  CHECK(sweep::locate_pointer(text, "/zz") == std::make_pair(0, 0));
  CHECK(sweep::locate_pointer("{\"a\": ", "/a") == std::make_pair(0, 0));
  // A UTF-8 byte order mark is not a column.
  CHECK(sweep::locate_pointer("\xEF\xBB\xBF{\"a\": 1}", "/a") == std::make_pair(1, 7));
}

// ---------------------------------------------------------------------------------------------
// Errors

TEST_CASE("Spec: malformed JSON", "[spec]") {
  const InputError e = input_error("{\n  \"sweep\": 1,\n  \"entity\": }\n");
  CHECK(e.pointer() == "");
  CHECK(e.line() == 3);
  CHECK(e.column() == 13);
  CHECK(contains(e.what(), "malformed JSON"));

  const InputError eof = input_error("{\"sweep\": 1");
  CHECK(eof.line() == 1);
  CHECK(eof.column() == 12);
}

TEST_CASE("Spec: unknown entity kind", "[spec]") {
  const InputError e = expect_error(doc(R"({"kind": "blob", "radius": 1})", kRevolute), "/entity/kind");
  CHECK(contains(e.what(), "unknown entity kind 'blob'"));
  CHECK(contains(e.what(), "sphere"));
}

TEST_CASE("Spec: unknown motion kind", "[spec]") {
  const InputError e = expect_error(doc(kSphere, R"({"kind": "wobble"})"), "/motion/kind");
  CHECK(contains(e.what(), "unknown motion kind 'wobble'"));
  CHECK(contains(e.what(), "screw"));
  const InputError later = expect_error(doc(kSphere, R"({"kind": "polyscrew", "screws": []})"), "/motion/kind");
  CHECK(std::string(later.what()) == "motion kind 'polyscrew' is not supported yet");
}

TEST_CASE("Spec: missing field", "[spec]") {
  const std::string text = doc(R"({"kind": "sphere", "center": [0, 0, 0]})", kRevolute);
  const InputError e = expect_error(text, "/entity/radius");
  CHECK(std::string(e.what()) == "missing required field 'radius'");
  // Positioned at the nearest existing parent.
  CHECK(std::make_pair(e.line(), e.column()) == sweep::locate_pointer(text, "/entity"));
  CHECK(e.line() > 0);

  const InputError top = expect_error("{\"sweep\": 1, \"entity\": " + kSphere + "}", "/motion");
  CHECK(top.line() == 1);
  expect_error(doc(kSphere, R"({"kind": "axes", "joints": [{"type": "revolute", "direction": [0, 0, 1],
                                "range": [0, 1]}]})"),
               "/motion/joints/0/point");
}

TEST_CASE("Spec: extra field", "[spec]") {
  const InputError e =
      expect_error(doc(R"({"kind": "sphere", "center": [0, 0, 0], "radius": 1, "raduis": 2})", kRevolute),
                   "/entity/raduis");
  CHECK(contains(e.what(), "unknown field 'raduis'"));
  CHECK(e.line() > 0);
  expect_error(doc(kSphere, kRevolute, "  \"tolerence\": 1e-6,\n"), "/tolerence");
  expect_error(doc(kSphere, R"({"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0],
                               "direction": [0, 0, 1], "range": [0, 1], "pitch": 2}]})"),
               "/motion/joints/0/pitch");
  // Comments are accepted anywhere.
  CHECK_NOTHROW(sweep::parse_spec(
      doc(R"({"kind": "sphere", "_c": 1, "center": [0, 0, 0], "radius": 1})",
          R"({"kind": "axes", "_why": "x", "joints": [{"_j": 0, "type": "prismatic", "direction": [1, 0, 0],
              "range": [0, 1]}]})",
          "  \"_comment\": {\"anything\": true},\n"),
      "."));
}

TEST_CASE("Spec: NaN and infinity", "[spec]") {
  const InputError n =
      expect_error(doc(R"({"kind": "sphere", "center": [0, 0, 0], "radius": "nan"})", kRevolute), "/entity/radius");
  CHECK(contains(n.what(), "must be a positive finite number"));
  const std::string text = doc(R"({"kind": "sphere", "center": [0, 0, 1e999], "radius": 1})", kRevolute);
  const InputError i = expect_error(text, "/entity/center/2");
  CHECK(contains(i.what(), "finite"));
  CHECK(i.line() == 3);
  CHECK(i.line() > 0);
  const InputError s = expect_error(doc(kSphere, kRevolute), "/tolerance", {"/tolerance=-1e999"});
  CHECK(s.line() == 0);
}

TEST_CASE("Spec: inverted range", "[spec]") {
  const InputError e = expect_error(
      doc(kSphere, R"({"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1],
                       "range": [2, 1]}]})"),
      "/motion/joints/0/range");
  CHECK(contains(e.what(), "inverted range"));
}

TEST_CASE("Spec: empty range", "[spec]") {
  const InputError e = expect_error(
      doc(kSphere, R"({"kind": "screw", "point": [0, 0, 0], "direction": [0, 0, 1], "pitch": 1, "range": [1, 1]})"),
      "/motion/range");
  CHECK(contains(e.what(), "empty range"));
  expect_error(doc(R"({"kind": "curve", "params": {"t": [0, 0]}, "xyz": ["t", 0, 0]})", kRevolute),
               "/entity/params/t");
}

TEST_CASE("Spec: zero-length axis or direction", "[spec]") {
  const InputError e = expect_error(
      doc(kSphere, R"({"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 0],
                       "range": [0, 1]}]})"),
      "/motion/joints/0/direction");
  CHECK(contains(e.what(), "nonzero"));
  expect_error(doc(R"({"kind": "cylinder", "base": [0, 0, 0], "axis": [0, 0, 0], "radius": 1, "height": 1})",
                   kRevolute),
               "/entity/axis");
}

TEST_CASE("Spec: zero radius", "[spec]") {
  const InputError e =
      expect_error(doc(R"({"kind": "sphere", "center": [0, 0, 0], "radius": 0})", kRevolute), "/entity/radius");
  CHECK(std::string(e.what()) == "must be a positive finite number (got 0)");
}

TEST_CASE("Spec: negative radius", "[spec]") {
  const InputError e =
      expect_error(doc(R"({"kind": "sphere", "center": [0, 0, 0], "radius": -1})", kRevolute), "/entity/radius");
  CHECK(std::string(e.what()) == "must be a positive finite number (got -1)");
  CHECK(e.describe("spec.json") == "spec.json:3:63: /entity/radius: must be a positive finite number (got -1)");
}

TEST_CASE("Spec: expression syntax error", "[spec]") {
  const InputError e =
      expect_error(doc(R"({"kind": "curve", "params": {"t": [0, 1]}, "xyz": ["t", "2*(t+", 0]})", kRevolute),
                   "/entity/xyz/1");
  CHECK(contains(e.what(), "\"2*(t+\""));
  CHECK(contains(e.what(), "column"));
}

TEST_CASE("Spec: unknown variable in expression", "[spec]") {
  const InputError e =
      expect_error(doc(R"({"kind": "curve", "params": {"t": [0, 1]}, "xyz": ["3*s", "t", 0]})", kRevolute),
                   "/entity/xyz/0");
  CHECK(contains(e.what(), "\"3*s\""));
  CHECK(contains(e.what(), "column 3"));
  // In a DH table the only variable is q.
  expect_error(doc(kSphere, R"({"kind": "dh", "joints": [
      {"type": "revolute", "theta": "t", "d": 0, "a": 1, "alpha": 0, "range": [0, 1]}]})"),
               "/motion/joints/0/theta");
}

TEST_CASE("Spec: DH joint variable in the wrong field", "[spec]") {
  expect_error(doc(kSphere, R"({"kind": "dh", "joints": [
      {"type": "revolute", "theta": 0, "d": "q", "a": 1, "alpha": 0, "range": [0, 1]}]})"),
               "/motion/joints/0/theta");
  expect_error(doc(kSphere, R"({"kind": "dh", "joints": [
      {"type": "prismatic", "theta": 0, "d": "q", "a": "q", "alpha": 0, "range": [0, 1]}]})"),
               "/motion/joints/0/a");
  expect_error(doc(kSphere, R"({"kind": "dh", "joints": [
      {"type": "helical", "theta": "q", "d": 0, "a": 1, "alpha": 0, "range": [0, 1]}]})"),
               "/motion/joints/0/pitch");
}

TEST_CASE("Spec: missing file", "[spec]") {
  const InputError e = expect_error(doc(R"({"kind": "mesh", "file": "no_such_part.stl"})", kRevolute),
                                    "/entity/file", {}, "/nonexistent_dir");
  CHECK(contains(e.what(), "cannot read file '/nonexistent_dir/no_such_part.stl'"));
  const InputError ext = expect_error(doc(R"({"kind": "brep", "file": "part.obj"})", kRevolute), "/entity/file");
  CHECK(contains(ext.what(), ".step"));
  const InputError spec = input_error("");
  CHECK(spec.pointer() == "");
  try {
    sweep::load_spec("/nonexistent_dir/spec.json");
    FAIL("no error");
  } catch (const InputError& l) {
    CHECK(l.pointer() == "");
    CHECK(contains(l.what(), "cannot read spec file '/nonexistent_dir/spec.json'"));
  }
}

TEST_CASE("Spec: bad --set pointer", "[spec]") {
  const std::string text = doc(kSphere, kRevolute);
  const InputError e = input_error(text, {"/x/y=3"});
  CHECK(e.pointer() == "/x/y");
  CHECK(contains(e.what(), "no such field"));
  CHECK(contains(e.what(), "--set /x/y"));
  CHECK(input_error(text, {"/motion/joints/5/range=[0,1]"}).pointer() == "/motion/joints/5/range");
  CHECK(input_error(text, {"/motion/joints/3=1"}).pointer() == "/motion/joints/3");
  CHECK(input_error(text, {"entity/radius=1"}).pointer() == "entity/radius");
  // A new field in an existing object is allowed by --set, then rejected by validation.
  const InputError typo = input_error(text, {"/entity/raduis=2"});
  CHECK(typo.pointer() == "/entity/raduis");
  CHECK(typo.line() == 0);
}

TEST_CASE("Spec: wrong sweep version", "[spec]") {
  const std::string text = "{\n  \"sweep\": 2,\n  \"entity\": " + kSphere + ",\n  \"motion\": " + kRevolute + "\n}";
  const InputError e = expect_error(text, "/sweep");
  CHECK(e.line() == 2);
  CHECK(e.column() == 12);
  CHECK(contains(e.what(), "version 2"));
  expect_error("{\"sweep\": \"1\", \"entity\": " + kSphere + ", \"motion\": " + kRevolute + "}", "/sweep");
  expect_error("{\"entity\": " + kSphere + ", \"motion\": " + kRevolute + "}", "/sweep");
}

TEST_CASE("Spec: other validation errors", "[spec]") {
  expect_error(doc(kSphere, kRevolute, "  \"angles\": \"grad\",\n"), "/angles");
  expect_error(doc(kSphere, kRevolute, "  \"tolerance\": 0,\n"), "/tolerance");
  expect_error(doc(kSphere, kRevolute, "  \"name\": 5,\n"), "/name");
  expect_error(doc(R"({"kind": "box", "min": [0, 0, 0], "max": [1, 0, 1]})", kRevolute), "/entity/max");
  expect_error(doc(R"({"kind": "torus", "center": [0, 0, 0], "axis": [0, 0, 1], "major": 1, "minor": 2})",
                   kRevolute),
               "/entity/minor");
  expect_error(doc(R"({"kind": "cone", "base": [0, 0, 0], "axis": [0, 0, 1], "radius1": 0, "radius2": 0,
                      "height": 1})",
                   kRevolute),
               "/entity/radius2");
  expect_error(doc(R"({"kind": "surface", "params": {"u": [0, 1]}, "xyz": ["u", 0, 0]})", kRevolute),
               "/entity/params");
  expect_error(doc(R"({"kind": "tube", "spine": {"kind": "sphere", "center": [0, 0, 0], "radius": 1},
                      "radius": 1})",
                   kRevolute),
               "/entity/spine/kind");
  expect_error(doc(R"({"kind": "tube", "spine": {"kind": "curve", "params": {"s": [0, 1]}, "xyz": ["s", 0, 0]},
                      "radius": "s-0.5"})",
                   kRevolute),
               "/entity/radius");
  expect_error(doc(R"({"kind": "implicit", "inequalities": [], "bounds": {"min": [0, 0, 0], "max": [1, 1, 1]}})",
                   kRevolute),
               "/entity/inequalities");
  expect_error(doc(R"({"kind": "point", "at": [0, 0]})", kRevolute), "/entity/at");
  expect_error(doc(kSphere, R"({"kind": "axes", "joints": []})"), "/motion/joints");
  expect_error(doc(kSphere, R"({"kind": "axes", "joints": [{"type": "spherical", "point": [0, 0, 0],
                               "direction": [0, 0, 1], "range": [0, 1]}]})"),
               "/motion/joints/0/type");
  expect_error(doc(kSphere, R"({"kind": "axes", "joints": [{"type": "helical", "point": [0, 0, 0],
                               "direction": [0, 0, 1], "pitch": 0, "range": [0, 1]}]})"),
               "/motion/joints/0/pitch");
  expect_error("[1, 2]", "");
}

TEST_CASE("Spec: a path motion and its bad input by field", "[spec]") {
  const sweep::Spec s = sweep::parse_spec(
      doc(kSphere, R"({"kind": "path", "t": [0, 2], "translate": ["t", 0, "t^2"],
                       "rotate": [{"axis": [1, 0, 0], "angle": "90*t"}, {"axis": ["1", "t", 0], "angle": 10}]})",
          "  \"angles\": \"deg\",\n"),
      ".");
  REQUIRE(s.motion.stage);
  CHECK(s.motion.kind == sweep::MotionKind::Path);
  CHECK(s.motion.stage->lo() == 0.0);
  CHECK(s.motion.stage->hi() == 2.0);
  // x goes to translate(t) + R_x(90 t deg) R_(1,t,0)(10 deg) x
  const double t = 1.5;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 2 * t, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                            Eigen::AngleAxisd(M_PI / 18, Eigen::Vector3d(1, t, 0).normalized()).toRotationMatrix();
  const Eigen::Vector3d x(0.3, -1, 2);
  CHECK((s.motion.stage->transform(t) * x - (Eigen::Vector3d(t, 0, t * t) + R * x)).norm() < 1e-12);

  const std::string ok_translate = R"("translate": ["t", 0, 0])";
  expect_error(doc(kSphere, R"({"kind": "path", "t": [1, 1], )" + ok_translate + "}"), "/motion/t");
  const InputError var = expect_error(doc(kSphere, R"({"kind": "path", "t": [0, 1], "translate": ["t", "s", 0]})"),
                                      "/motion/translate/1");
  CHECK(contains(var.what(), "s"));
  expect_error(doc(kSphere, R"({"kind": "path", "t": [0, 1], "translate": ["t", 0]})"), "/motion/translate");
  expect_error(doc(kSphere, R"J({"kind": "path", "t": [0, 1], "translate": ["log(t-1)", 0, 0]})J"),
               "/motion/translate/0");
  const InputError axis = expect_error(
      doc(kSphere, R"({"kind": "path", "t": [0, 2], )" + ok_translate + R"(, "rotate": {"axis": ["1-t", 0, 0], "angle": "t"}})"),
      "/motion/rotate/axis");
  CHECK(contains(axis.what(), "vanishes at t = 1"));
  expect_error(doc(kSphere, R"({"kind": "path", "t": [0, 2], )" + ok_translate +
                                R"(, "rotate": [{"axis": [0, 0, 1], "angle": "t"}, {"axis": [0, 0, 1]}]})"),
               "/motion/rotate/1/angle");
  expect_error(doc(kSphere, R"({"kind": "path", "t": [0, 2], )" + ok_translate + R"(, "speed": 3})"), "/motion/speed");
}

TEST_CASE("Spec: a keyframes motion and its bad input by field", "[spec]") {
  const sweep::Spec s = sweep::parse_spec(
      doc(kSphere, R"({"kind": "keyframes", "interpolation": "linear", "poses": [
            {"t": 0, "translate": [0, 0, 0]},
            {"t": 1, "translate": [1, 0, 0], "rotate": {"axis": [0, 0, 1], "angle": 90}},
            {"t": 3, "matrix": [[1, 0, 0, 2], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]}]})",
          "  \"angles\": \"deg\",\n"),
      ".");
  REQUIRE(s.motion.stage);
  CHECK(s.motion.kind == sweep::MotionKind::Keyframes);
  CHECK(s.motion.stage->hi() == 3.0);
  const Eigen::Isometry3d M = s.motion.stage->transform(1.0);
  CHECK((M.translation() - Eigen::Vector3d(1, 0, 0)).norm() < 1e-12);
  CHECK((M.linear() * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm() < 1e-12);
  CHECK((s.motion.stage->transform(3.0).translation() - Eigen::Vector3d(2, 0, 0)).norm() < 1e-12);
  // screw interpolation is the default
  const sweep::Spec d = sweep::parse_spec(
      doc(kSphere, R"({"kind": "keyframes", "poses": [{"t": 0}, {"t": 1, "translate": [0, 0, 1]}]})"), ".");
  REQUIRE(dynamic_cast<const sweep::KeyframeMotion*>(d.motion.stage.get()));
  CHECK(dynamic_cast<const sweep::KeyframeMotion*>(d.motion.stage.get())->interpolation() ==
        sweep::KeyframeMotion::Interpolation::Screw);

  const InputError order = expect_error(
      doc(kSphere, R"({"kind": "keyframes", "poses": [{"t": 0}, {"t": 2}, {"t": 1}]})"), "/motion/poses/2/t");
  CHECK(contains(order.what(), "increase"));
  expect_error(doc(kSphere, R"({"kind": "keyframes", "poses": [{"t": 0}]})"), "/motion/poses");
  expect_error(doc(kSphere, R"({"kind": "keyframes", "poses": [{"t": 0}, {"translate": [1, 0, 0]}]})"),
               "/motion/poses/1/t");
  expect_error(doc(kSphere, R"({"kind": "keyframes", "interpolation": "cubic", "poses": [{"t": 0}, {"t": 1}]})"),
               "/motion/interpolation");
  expect_error(doc(kSphere, R"({"kind": "keyframes", "poses": [{"t": 0}, {"t": 1, "rotate": {"axis": [0, 0, 0], "angle": 1}}]})"),
               "/motion/poses/1/rotate/axis");
  expect_error(doc(kSphere, R"({"kind": "keyframes", "poses": [{"t": 0}, {"t": 1, "scale": 2}]})"),
               "/motion/poses/1/scale");
}
