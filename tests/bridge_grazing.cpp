// Grazing curves of tori (B-spline fits, the only grazing curves that are not lines or circles):
// their distance from the exact grazing curve, measured here independently of the fitter, stays
// within the error the fitter reports, and that error within the tolerance.
#include <BRepPrimAPI_MakeTorus.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <string>

#include "base/internal.hpp"

namespace {

using sweep::JointType;
using sweep::ScrewJoint;

struct Torus {
  Eigen::Vector3d centre, axis;
  double major, minor;
};

sweep::Expr texpr(const std::string& text) { return sweep::Expr::parse(text, {"t"}); }

/// Distance of x from the torus surface, exactly.
double surface_distance(const Torus& t, const Eigen::Vector3d& x) {
  const Eigen::Vector3d d = x - t.centre;
  const double z = d.dot(t.axis), rho = (d - z * t.axis).norm();
  return std::abs(std::hypot(rho - t.major, z) - t.minor);
}

/// The torus's outward unit normal at (near) x.
Eigen::Vector3d normal(const Torus& t, const Eigen::Vector3d& x) {
  const Eigen::Vector3d d = x - t.centre;
  const double z = d.dot(t.axis);
  const Eigen::Vector3d radial = (d - z * t.axis).normalized();
  return (d - t.major * radial).normalized();
}

/// The largest of (distance from the surface, distance from n . v = 0 along the surface) at 400
/// points of every curve, and the largest error the fitter reported.
void worst_errors(const Torus& t, const ScrewJoint& j, double tol, double* measured, double* reported) {
  const gp_Ax2 ax(sweep::occt::to_pnt(t.centre), gp_Dir(sweep::occt::to_vec(t.axis)));
  const TopoDS_Shape solid = BRepPrimAPI_MakeTorus(ax, t.major, t.minor).Shape();
  *measured = 0;
  *reported = 0;
  int curves = 0;
  for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next()) {
    for (const auto& g : sweep::occt::grazing_curves(TopoDS::Face(ex.Current()), sweep::VelocityField(j), tol, 4.0)) {
      ++curves;
      *reported = std::max(*reported, g.error);
      for (int k = 0; k <= 400; ++k) {
        const Eigen::Vector3d x = sweep::occt::to_eigen(g.curve->Value(g.first + (g.last - g.first) * k / 400));
        const Eigen::Vector3d v = j.velocity(x);
        // |n . v| / |v|, the sine of the angle off grazing, times the minor radius: the distance
        // along the surface where the normal turns at the rate of the tighter curvature
        const double off_grazing = std::abs(normal(t, x).dot(v)) / v.norm() * t.minor;
        *measured = std::max({*measured, surface_distance(t, x), off_grazing});
      }
    }
  }
  CHECK(curves > 0);
}

}  // namespace

TEST_CASE("Grazing curves of tori: the fitted curves keep within the measured error of the exact ones", "[grazing]") {
  // a torus and a rotation about an axis beside it, where the least-squares fit to a tenth of a
  // tight tolerance used to end in wiggles of 6e-4 between its points
  const Torus t{{-0.724362, 0.891383, 0.946454}, Eigen::Vector3d(0.702565, -0.701949, 0.116920).normalized(), 0.529030,
                0.214537};
  ScrewJoint j;
  j.type = JointType::Revolute;
  j.point = {1.078405, 1.058095, 0.899718};
  j.direction = Eigen::Vector3d(0.115482, -0.210020, 0.970853).normalized();
  j.hi = 2.65;
  const double tol = 5e-8;
  double measured = 0, reported = 0;
  worst_errors(t, j, tol, &measured, &reported);
  CHECK(reported <= tol);
  CHECK(measured <= 2 * tol);
}

TEST_CASE("Grazing curves of random tori under the three joint types: reported errors are honest", "[grazing]") {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> uni(-1, 1);
  for (int i = 0; i < 12; ++i) {
    Torus t;
    t.centre = {uni(rng), uni(rng), uni(rng)};
    t.axis = Eigen::Vector3d(uni(rng), uni(rng), uni(rng)).normalized();
    t.minor = 0.15 + 0.35 * std::abs(uni(rng));
    t.major = t.minor + 0.3 + 0.9 * std::abs(uni(rng));
    ScrewJoint j;
    j.type = i % 3 == 0 ? JointType::Revolute : i % 3 == 1 ? JointType::Prismatic : JointType::Helical;
    j.point = 2.0 * Eigen::Vector3d(uni(rng), uni(rng), uni(rng));
    j.direction = Eigen::Vector3d(uni(rng), uni(rng), uni(rng)).normalized();
    j.pitch = j.type == JointType::Helical ? 0.3 : 0.0;
    j.hi = 1.0;
    const double tol = 5e-8;
    double measured = 0, reported = 0;
    worst_errors(t, j, tol, &measured, &reported);
    INFO("case " << i << ": measured " << measured << ", reported " << reported);
    // the reported error bounds what is measured here (up to the curvature factor's slack), and a
    // curve off by more than the tolerance says so
    CHECK(measured <= 2 * std::max(reported, tol));
    CHECK(reported <= 20 * tol);
  }
}

TEST_CASE("Grazing curves under a path at one instant: a torus at its pose at t grazes where n . v(t) = 0",
          "[grazing]") {
  // A path that is no screw (it slides along a parabola while turning about a tilted axis): the
  // velocity field at t is the twist at t. The torus, placed at its pose at t, grazes where the
  // field is tangent to it; every point of the traced curves is checked against the exact torus and
  // the twist, independently of the tracer.
  const sweep::Expr translate[3] = {texpr("2*t"), texpr("t^2"), texpr("0.5*t")};
  const sweep::PathMotion path(0, 1, translate,
                               {sweep::PathRotation{{texpr("0.3"), texpr("0.2"), texpr("1")}, texpr("1.5*t")}});
  REQUIRE_FALSE(path.as_screw(2.0));
  const Torus at_rest{Eigen::Vector3d(0.2, -0.1, 0.3), Eigen::Vector3d(0.3, -0.5, 0.8).normalized(), 1.2, 0.4};
  for (double t : {0.25, 0.6}) {
    const Eigen::Isometry3d M = path.transform(t);
    const Torus placed{M * at_rest.centre, M.linear() * at_rest.axis, at_rest.major, at_rest.minor};
    const TopoDS_Shape solid =
        BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(placed.centre.x(), placed.centre.y(), placed.centre.z()),
                                     gp_Dir(placed.axis.x(), placed.axis.y(), placed.axis.z())),
                              placed.major, placed.minor)
            .Shape();
    const sweep::VelocityField field(path, t, 2.0);
    const sweep::Twist twist = path.twist(t);
    const double tol = 1e-7;
    int points = 0;
    for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next())
      for (const auto& g : sweep::occt::grazing_curves(TopoDS::Face(ex.Current()), field, tol, 4.0)) {
        for (int k = 0; k <= 100; ++k) {
          const gp_Pnt p = g.curve->Value(g.first + (g.last - g.first) * k / 100);
          const Eigen::Vector3d x(p.X(), p.Y(), p.Z()), v = twist.at(x);
          CHECK(surface_distance(placed, x) < 10 * tol);
          // n . v / |v| vanishes to first order in the distance along the surface
          CHECK(std::abs(normal(placed, x).dot(v.normalized())) < 1e-5);
          ++points;
        }
      }
    CHECK(points > 100);
  }
}

TEST_CASE("Velocity fields: a joint's is its own, a screw stage's is the joint's, a path's is its twist",
          "[grazing]") {
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = Eigen::Vector3d(1, 2, -1);
  j.direction = Eigen::Vector3d(0, 0.6, 0.8);
  j.pitch = 0.3;
  j.lo = 0;
  j.hi = 2;
  const Eigen::Vector3d x(0.4, -1.3, 2.2);
  CHECK((sweep::VelocityField(j).at(x) - j.velocity(x)).norm() == 0);
  CHECK((sweep::VelocityField(sweep::ScrewStage(j), 1.0, 3.0).at(x) - j.velocity(x)).norm() == 0);
  CHECK(sweep::VelocityField(j).reach() == Approx(0.3 + std::sqrt(6.0)).epsilon(1e-15));
  const sweep::Expr translate[3] = {texpr("t"), texpr("t^2"), texpr("0")};
  const sweep::PathMotion path(0, 1, translate, {sweep::PathRotation{{texpr("0"), texpr("0"), texpr("1")}, texpr("t")}});
  const sweep::VelocityField field(path, 0.5, 1.0);
  CHECK((field.at(x) - path.twist(0.5).at(x)).norm() < 1e-12);
  // its twist at t = 0.5: omega = z, v = dp - omega x p = (1, 1, 0) - (-0.25, 0.5, 0) with
  // p = (0.5, 0.25, 0): the axis passes omega x v = (-0.5, 1.25, 0) from the origin, without pitch
  CHECK(field.reach() == Approx(std::hypot(0.5, 1.25)).epsilon(1e-9));
}
