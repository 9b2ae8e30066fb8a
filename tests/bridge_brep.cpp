// A `brep` entity read from a STEP file the test writes: a box with a cylindrical through hole; the
// entity the engine makes of it (faces, edges, distance bound).
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <random>

#include "base/internal.hpp"
#include "entity/brep_entity.hpp"
#include "occt_bridge/sweeper.hpp"
#include "sweep/candidate_patches.hpp"
#include "sweep/membership.hpp"
#include "arrangement/stage_sweep.hpp"
#include "sweep/error.hpp"
#include "sweep/spec.hpp"
#include "util/box_hole.hpp"
#include "util/cases.hpp"

TEST_CASE("Brep entity: box with a hole from STEP, extruded along the hole") {
  REQUIRE(sweep_test::write_box_with_hole(SWEEP_BINARY_DIR "/box_hole.step"));
  // The example spec, with its relative file name resolved in the build tree.
  const std::string text = sweep_test::read_text(SWEEP_SOURCE_DIR "/examples/brep_box_hole.json");
  sweep::Spec spec = sweep::parse_spec(text, SWEEP_BINARY_DIR);
  const double expected = 16.0 - M_PI;
  REQUIRE(spec.json["_expected_volume"].get<double>() == Approx(expected).epsilon(1e-15));
  auto r = sweep::occt::run_sweep(spec);
  CAPTURE(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(r.report.valid);
  CHECK(r.report.closed);
  CHECK(r.report.volume_brep == Approx(expected).epsilon(1e-6));
  CHECK(r.report.volume_divergence == Approx(expected).epsilon(1e-6));
  // the pieces of each surface merged: the box's six faces and the hole's cylinder
  CHECK(r.report.faces == 7);
  const std::string out = SWEEP_BINARY_DIR "/box_hole_swept.step";
  sweep::occt::write_shape(*r.shape, out, 1e-3);
  CHECK(sweep::occt::file_volume(out) == Approx(expected).epsilon(1e-6));
}

TEST_CASE("Brep entity: unreadable STEP is an input error naming /entity/file") {
  const std::string junk = SWEEP_BINARY_DIR "/junk.step";
  std::ofstream(junk) << "this is not a STEP file\n";
  sweep::Spec spec = sweep::parse_spec(
      R"({"sweep": 1, "entity": {"kind": "brep", "file": "junk.step"},
          "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [0, 0, 1], "range": [0, 1]}]}})",
      SWEEP_BINARY_DIR);
  try {
    sweep::occt::run_sweep(spec);
    FAIL("no error for an unreadable STEP file");
  } catch (const sweep::InputError& e) {
    CHECK(e.pointer() == "/entity/file");
  }
}

namespace {

/// The box with its hole as the run reads it (STEP written, read back, placed) and its entity. Each
/// test writes a file of its own (`name`): tests run side by side.
struct BoxHoleEntity {
  TopoDS_Shape shape;
  sweep::EntityPtr entity;
  explicit BoxHoleEntity(const std::string& name) {
    const std::string file = SWEEP_BINARY_DIR "/" + name + ".step";
    REQUIRE(sweep_test::write_box_with_hole(file));
    sweep::EntitySpec spec;
    spec.kind = sweep::EntityKind::Brep;
    spec.file = file;
    shape = sweep::occt::entity_shape(spec, 0.0, nullptr);
    entity = sweep::occt::brep_entity(shape);
  }
};

double exact_distance(const TopoDS_Shape& shape, const Eigen::Vector3d& p) {
  TopoDS_Shell shell;
  for (TopExp_Explorer ex(shape, TopAbs_SHELL); ex.More(); ex.Next()) shell = TopoDS::Shell(ex.Current());
  BRepExtrema_DistShapeShape d(BRepBuilderAPI_MakeVertex(sweep::occt::to_pnt(p)).Vertex(), shell);
  REQUIRE(d.IsDone());
  return d.Value();
}

bool exactly_inside(const TopoDS_Shape& shape, const Eigen::Vector3d& p) {
  BRepClass3d_SolidClassifier c(shape, sweep::occt::to_pnt(p), 1e-9);
  return c.State() == TopAbs_IN;
}

}  // namespace

TEST_CASE("Brep entity: faces and edges as patches on their exact surfaces and curves") {
  const BoxHoleEntity b("brep_entity_patches");
  const sweep::Entity& e = *b.entity;
  CHECK(e.kind() == sweep::EntityKind::Brep);
  CHECK(e.dimension() == 3);
  CHECK(e.box().min().isApprox(Eigen::Vector3d(-1, -1, 0), 1e-9));
  CHECK(e.box().max().isApprox(Eigen::Vector3d(1, 1, 1), 1e-9));
  // six planes and the hole's cylinder; the box's twelve edges and the hole's two circles (its
  // seam is no crease)
  REQUIRE(e.faces().size() == 7);
  int planes = 0, cylinders = 0, circles = 0, lines = 0;
  for (const sweep::PatchPtr& f : e.faces()) {
    CHECK(f->trimmed);
    planes += f->form().kind == sweep::PatchForm::Kind::Plane;
    if (f->form().kind == sweep::PatchForm::Kind::Cylinder) {
      ++cylinders;
      CHECK(f->form().radius == Approx(0.5).epsilon(1e-12));
      CHECK(std::abs(f->form().axis.z()) == Approx(1).epsilon(1e-12));
    }
    // derivatives against central differences, at a point inside the parameter box
    const double u = 0.3 * f->lo(0) + 0.7 * f->hi(0), v = 0.6 * f->lo(1) + 0.4 * f->hi(1), h = 1e-6;
    const sweep::PatchPoint p = f->eval(u, v);
    CHECK((p.xu - (f->eval(u + h, v).x - f->eval(u - h, v).x) / (2 * h)).norm() < 1e-6);
    CHECK((p.xv - (f->eval(u, v + h).x - f->eval(u, v - h).x) / (2 * h)).norm() < 1e-6);
  }
  CHECK(planes == 6);
  CHECK(cylinders == 1);
  for (const sweep::PatchPtr& c : e.edges()) {
    circles += c->form().kind == sweep::PatchForm::Kind::Circle;
    lines += c->form().kind == sweep::PatchForm::Kind::Line;
  }
  CHECK(lines == 12);
  CHECK(circles == 2);
  CHECK(e.edges().size() == 14);
  // the face patches' outward normals: xu x xv times the orientation points away from the box's
  // centre on the planes, towards the hole's axis on the cylinder
  for (const sweep::PatchPtr& f : e.faces()) {
    const double u = 0.5 * (f->lo(0) + f->hi(0)), v = 0.5 * (f->lo(1) + f->hi(1));
    const sweep::PatchPoint p = f->eval(u, v);
    const Eigen::Vector3d n = f->orientation() * p.xu.cross(p.xv);
    if (f->form().kind == sweep::PatchForm::Kind::Cylinder) {
      CHECK(n.dot(Eigen::Vector3d(p.x.x(), p.x.y(), 0)) < 0);
    } else {
      CHECK(n.dot(p.x - Eigen::Vector3d(0, 0, 0.5)) > 0);
    }
  }
}

TEST_CASE("Brep entity: the distance bound against OCCT's exact distance") {
  const BoxHoleEntity b("brep_entity_distance");
  const sweep::Entity& e = *b.entity;
  REQUIRE(e.has_distance_bound());
  CHECK_FALSE(e.tight_distance());
  const std::unique_ptr<sweep::SignedDistance> sd = e.distance_bound();
  REQUIRE(sd);
  const double slack = sd->slack();
  CHECK(slack > 0);
  CHECK(slack < 1e-3);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(-1.4, 1.4);
  int inside = 0, near = 0;
  for (int k = 0; k < 400; ++k) {
    // every other point near a face, where the bound cannot give the side
    Eigen::Vector3d p(uni(rng), uni(rng), 0.5 + 0.5 * uni(rng));
    if (k % 2) p.x() = (k % 4 == 1 ? 1.0 : 0.5) + 0.4 * slack * uni(rng);
    const double exact = exact_distance(b.shape, p);
    const bool in = exactly_inside(b.shape, p);
    const double d = (*sd)(p);
    CAPTURE(p.transpose(), exact, in, d, slack);
    CHECK(std::abs(d) <= exact + 1e-12);
    CHECK(e.inside(p) == in);
    if (d < 0) {
      CHECK(in);
      ++inside;
    } else if (exact > slack) {
      // away from the faces: the side is known, and the bound is the distance less the slack
      CHECK(in == false);
      CHECK(d >= exact - slack - 1e-12);
    } else {
      ++near;
    }
    if (exact > slack) CHECK(std::abs(d) >= exact - slack - 1e-12);
    // the bound below a limit: negative inside (a bound too), the same where it is in [0, limit),
    // at least the limit elsewhere
    const double limit = 0.05;
    const double db = sd->below(p, limit);
    if (d < 0) {
      CHECK(db < 0);
      CHECK(-db <= exact + 1e-12);
    } else if (d < limit) {
      CHECK(db == Approx(d).margin(1e-12));
    } else {
      CHECK(db >= limit);
    }
  }
  CHECK(inside > 20);
  CHECK(near > 20);
}

TEST_CASE("Brep entity: the general engine refuses its trimmed faces") {
  const BoxHoleEntity b("brep_entity_general");
  sweep::ScrewJoint j;
  j.type = sweep::JointType::Prismatic;
  j.direction = Eigen::Vector3d::UnitX();
  j.hi = 1;
  const auto motion = sweep::occt::screw_stage_motion(j, 1.0);
  CHECK_THROWS_AS(sweep::candidate_patches(*b.entity, motion), sweep::ComputeError);
}
