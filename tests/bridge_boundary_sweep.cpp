// One stage built from its sweep boundary: which candidates on one surface are arranged by OCCT.
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <GProp_GProps.hxx>
#include <BRep_Tool.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>
#include <catch2/catch.hpp>

#include <cmath>

#include "arrangement/boundary_sweep.hpp"
#include "arrangement/stage_sweep.hpp"
#include "sweep/orbit.hpp"

namespace {

/// The stage of `body` under j over [0, j.hi], its membership from each point's trajectory.
sweep::occt::BoundarySweep stage_of(const TopoDS_Shape& body, const sweep::ScrewJoint& j, double size) {
  const sweep::Settings settings;
  const double tol = settings.default_tolerance * size;
  const auto member = sweep::occt::trajectory_membership(body, sweep::occt::screw_stage_motion(j, j.hi),
                                                         sweep::Settings::resolution * size);
  return sweep::occt::boundary_sweep(body, j, j.hi, member, size, tol, settings, 1, 1);
}

double volume_of(const TopoDS_Shape& s) {
  GProp_GProps g;
  BRepGProp::VolumeProperties(s, g);
  return g.Mass();
}

}  // namespace

TEST_CASE("Boundary sweep: the pieces of one copy on one surface are kept as they are, overlapping regions arranged") {
  SECTION("a torus turned about a skew axis: each copy split at its grazing curves is one group, not arranged") {
    const TopoDS_Shape torus = BRepPrimAPI_MakeTorus(gp_Ax2(gp::Origin(), gp_Dir(0, 0, 1)), 1.0, 0.3).Shape();
    sweep::ScrewJoint j;
    j.type = sweep::JointType::Revolute;
    j.point = Eigen::Vector3d(0.4, 2.2, 0.1);
    j.direction = Eigen::Vector3d(1, 0.3, 0.2).normalized();
    j.hi = 1.0;
    const sweep::occt::BoundarySweep b = stage_of(torus, j, 4.0);
    INFO(b.failure);
    REQUIRE(!b.solid.IsNull());
    CHECK(b.copy_groups >= 2);  // the start and the end copy
    CHECK(b.arranged_groups == 0);
    // the volume integrated over the joint's orbits, which does not use the boundary
    double err = 0;
    const double orbits =
        sweep::joint_sweep_volume(*sweep::orbit_torus(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), 1.0, 0.3), j,
                                  j.hi, 1e-9, &err);
    CHECK(std::abs(volume_of(b.solid) - orbits) <= 1e-6 * orbits + 3 * err);
  }
  SECTION("a box slid along one of its edges: each face the motion slides within is arranged with its copies") {
    const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), gp_Pnt(1, 1, 1)).Shape();
    sweep::ScrewJoint j;
    j.type = sweep::JointType::Prismatic;
    j.direction = Eigen::Vector3d::UnitX();
    j.hi = 0.5;
    const sweep::occt::BoundarySweep b = stage_of(box, j, 2.0);
    INFO(b.failure);
    REQUIRE(!b.solid.IsNull());
    CHECK(b.arranged_groups >= 4);  // the faces y = 0, y = 1, z = 0 and z = 1
    CHECK(std::abs(volume_of(b.solid) - 1.5) <= 1e-9);
  }
}

TEST_CASE("Boundary sweep: a cone's grazing curve that ends at its apex splits the copies without widening their edges") {
  // a pointed cone turned about a skew axis: one of its grazing curves ends at the apex, where the
  // splitter's own projection of it onto the cone widened the copies' edges to 0.015; the
  // boundary did not close, and the cells' solid failed on its geometric error (4e-4)
  const Eigen::Vector3d base(-0.866471, 0.645637, -0.291712), axis = Eigen::Vector3d(-0.385517, 0.789747, 0.477155).normalized();
  const double r1 = 0.569264, h = 1.842732;
  const TopoDS_Shape cone =
      BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(base.x(), base.y(), base.z()), gp_Dir(axis.x(), axis.y(), axis.z())), r1, 0, h)
          .Shape();
  sweep::ScrewJoint j;
  j.type = sweep::JointType::Revolute;
  j.point = Eigen::Vector3d(-1.346904, -0.620114, 0.664015);
  j.direction = Eigen::Vector3d(0.668559, 0.537262, 0.514177).normalized();
  j.hi = 106.055017 * M_PI / 180;
  const double size = 4.0, tol = sweep::Settings().default_tolerance * size;
  const sweep::occt::BoundarySweep b = stage_of(cone, j, size);
  INFO(b.failure);
  REQUIRE(!b.solid.IsNull());
  double widest = 0;
  for (TopExp_Explorer ex(b.solid, TopAbs_EDGE); ex.More(); ex.Next())
    widest = std::max(widest, BRep_Tool::Tolerance(TopoDS::Edge(ex.Current())));
  CHECK(widest <= tol);
  double err = 0;
  const double orbits = sweep::joint_sweep_volume(*sweep::orbit_cone(base, axis, r1, 0, h), j, j.hi, 1e-9, &err);
  CHECK(std::abs(volume_of(b.solid) - orbits) <= 1e-6 * orbits + 3 * err);
}
