// One engine for every motion (arrangement/stage_sweep.hpp): a stage takes a StageMotion, finds
// the screw a joint's motion is, and reaches the screw engine's closed forms only through it. The
// same stage run as a general motion (its screw withheld, cells kept by the search over t) gives
// the screw engine's solid. How a motion meets a face (arrangement/facing.hpp) is one test for
// both engines.
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "arrangement/facing.hpp"
#include "arrangement/stage_sweep.hpp"
#include "base/internal.hpp"
#include "occt_bridge/sweeper.hpp"
#include "run/run_steps.hpp"
#include "sweep/error.hpp"
#include "sweep/spec.hpp"
#include "sweep/stage_membership.hpp"
#include "util/core_entities.hpp"

namespace {

using sweep::occt::Facing;

/// The facing of each face of the box [0,1]^3 by the normal it points along: "+x", "-x", ...
std::map<std::string, Facing> box_facings(const sweep::VelocityField& field) {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), gp_Pnt(1, 1, 1)).Shape();
  std::map<std::string, Facing> out;
  for (TopExp_Explorer ex(box, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face f = TopoDS::Face(ex.Current());
    const auto samples = sweep::occt::face_samples(f, 7);
    REQUIRE(samples.size() == 49);
    const gp_Vec n = samples.front().n;
    const char* axis = std::abs(n.X()) > 0.5 ? "x" : std::abs(n.Y()) > 0.5 ? "y" : "z";
    const double sign = n.X() + n.Y() + n.Z();
    out[std::string(sign > 0 ? "+" : "-") + axis] = sweep::occt::facing_of(f, field, 1.0);
  }
  return out;
}

double volume_of(const TopoDS_Shape& s) {
  GProp_GProps g;
  BRepGProp::VolumeProperties(s, g);
  return g.Mass();
}

/// The box's stage under `joint_json` as a general motion: its screw withheld, its candidates the
/// core's patches, its cells kept by the search over t.
double general_engine_volume(const std::string& box_json, const std::string& joint_json, double size) {
  const sweep::Spec spec = sweep::parse_spec(R"({"sweep": 1, "entity": )" + box_json +
                                                 R"(, "motion": {"kind": "axes", "joints": [)" + joint_json + "]}}",
                                             ".");
  const sweep::occt::RunEntity entity(spec.entity);
  double fit_err = 0;
  const TopoDS_Shape body = sweep::occt::entity_shape(spec.entity, 1e-9, &fit_err, entity.core.get());
  const auto motion = std::make_shared<sweep::ScrewStage>(spec.motion.motion.joints[0]);
  const double tol = 1e-6 * size;
  sweep::occt::StageInput in(body, 3, motion, 1.0, size, tol, 0.1 * tol, 1, 1);
  REQUIRE(in.screw);
  in.screw.reset();
  REQUIRE_THROWS_AS(in.j(), sweep::InternalError);
  in.core = entity.core.get();
  const auto sd = entity.sd;
  const sweep::occt::MemberTestMaker search = [sd, motion, size]() -> sweep::occt::MemberTest {
    auto set = std::make_shared<sweep::StageSweptSet>(*sd, *motion, 1e-9 * size, 20000);
    return [set](const Eigen::Vector3d& x) { return (*set)(x); };
  };
  in.member = sweep::occt::decided_or_failed(search, "a cell the search over t does not decide");
  sweep::occt::StageRecord record;
  sweep::occt::Candidates cand;
  const TopoDS_Shape solid = sweep::occt::solid_sweep(in, fit_err, record, &cand, false, nullptr, false);
  CHECK(record.cells >= 1);
  return volume_of(solid);
}

}  // namespace

TEST_CASE("One engine: how a motion meets a face, in a screw's field and in a twist's") {
  SECTION("a translation along x: the motion moves into +x, leaves -x behind, slides within the others") {
    sweep::ScrewJoint slide;
    slide.type = sweep::JointType::Prismatic;
    slide.direction = Eigen::Vector3d::UnitX();
    const auto f = box_facings(sweep::VelocityField(slide));
    CHECK(f.at("+x") == Facing::Front);
    CHECK(f.at("-x") == Facing::Back);
    for (const char* k : {"+y", "-y", "+z", "-z"}) CHECK(f.at(k) == Facing::Slides);
  }
  SECTION("a turn about the box's vertical middle line: each side face both ways, top and bottom slide") {
    sweep::Twist turn;
    turn.omega = Eigen::Vector3d::UnitZ();
    turn.v = -turn.omega.cross(Eigen::Vector3d(0.5, 0.5, 0));
    const auto f = box_facings(sweep::VelocityField(turn));
    for (const char* k : {"+x", "-x", "+y", "-y"}) CHECK(f.at(k) == Facing::Mixed);
    CHECK(f.at("+z") == Facing::Slides);
    CHECK(f.at("-z") == Facing::Slides);
  }
  SECTION("a turn about an axis beside the box: the sides across the axis face one way each") {
    sweep::Twist turn;
    turn.omega = Eigen::Vector3d::UnitZ();
    turn.v = -turn.omega.cross(Eigen::Vector3d(3, 0.5, 0));  // the points move along -y, faster farther off
    const auto f = box_facings(sweep::VelocityField(turn));
    CHECK(f.at("-y") == Facing::Front);
    CHECK(f.at("+y") == Facing::Back);
    CHECK(f.at("+x") == Facing::Mixed);  // (its points on y = 0.5 move straight along it)
    CHECK(f.at("+z") == Facing::Slides);
  }
}

TEST_CASE("One engine: a stage finds the screw its motion is, and a path that is no screw has none") {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), gp_Pnt(1, 1, 1)).Shape();
  sweep::ScrewJoint j;
  j.type = sweep::JointType::Helical;
  j.point = Eigen::Vector3d(2, 0, 0);
  j.direction = Eigen::Vector3d(0, 0.6, 0.8);
  j.pitch = 0.3;
  j.lo = 0.4;
  j.hi = 2.9;
  const sweep::occt::StageInput screw(box, 3, sweep::occt::screw_stage_motion(j, j.hi - j.lo), 1, 5, 1e-6, 1e-7, 1, 1);
  REQUIRE(screw.screw);
  CHECK(screw.j().type == sweep::JointType::Helical);
  CHECK(screw.j().pitch == Approx(0.3).margin(1e-15));
  CHECK(screw.T() == Approx(2.5).margin(1e-15));
  CHECK((screw.screw->start.matrix() - Eigen::Matrix4d::Identity()).norm() < 1e-15);
  CHECK_FALSE(screw.full_turn());

  const auto path = std::make_shared<sweep::PathMotion>(sweep_test::wandering_path());
  const sweep::occt::StageInput general(box, 3, path, 1, 5, 1e-6, 1e-7, 1, 1);
  CHECK_FALSE(general.screw);
  CHECK_FALSE(general.full_turn());
  CHECK_THROWS_AS(general.j(), sweep::InternalError);
}

TEST_CASE("One engine: a box's stage run as a general motion gives the screw engine's solid") {
  const std::string box = R"({"kind": "box", "min": [-0.3, -0.2, -0.5], "max": [0.3, 0.2, 0.5]})";
  // a turn about a vertical axis beside the box, and a slide along an oblique direction
  for (const std::string joint :
       {R"({"type": "revolute", "point": [1.5, 0.2, 0], "direction": [0, 0, 1], "range": [0, 1.2]})",
        R"({"type": "prismatic", "point": [0, 0, 0], "direction": [1, 0.4, 0.3], "range": [0, 1.5]})"}) {
    CAPTURE(joint);
    const sweep::Spec spec = sweep::parse_spec(
        R"({"sweep": 1, "entity": )" + box + R"(, "motion": {"kind": "axes", "joints": [)" + joint + "]}}", ".");
    const sweep::occt::RunResult screw = sweep::occt::run_sweep(spec);
    REQUIRE(screw.report.status == "ok");
    const double v = general_engine_volume(box, joint, 3.0);
    CHECK(std::abs(v - screw.report.volume_brep) < 1e-6 * screw.report.volume_brep);
  }
}
