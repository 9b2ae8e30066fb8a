// One stage built from its sweep boundary: which candidates on one surface are arranged by OCCT.
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <GProp_GProps.hxx>
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
  const auto member = sweep::occt::trajectory_membership(body, j, j.hi, sweep::Settings::resolution * size);
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
