// Faces swept by a curve under a screw: fitted B-spline faces, checked against exact points of the
// sweep that no fit produced.
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Line.hxx>
#include <Geom_OffsetCurve.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRep_Builder.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopoDS_Compound.hxx>
#include <catch2/catch.hpp>

#include <random>

#include "base/internal.hpp"
#include "sweep/stage_motion.hpp"

using namespace sweep;

namespace {

/// The largest distance from exact points T(q) c(s), at random (s, q), to the faces.
double largest_gap(const std::vector<TopoDS_Face>& faces, const Handle(Geom_Curve)& c, double f, double l,
                   const ScrewJoint& j, double T) {
  TopoDS_Compound all;
  BRep_Builder bb;
  bb.MakeCompound(all);
  for (const TopoDS_Face& face : faces) bb.Add(all, face);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  double gap = 0;
  for (int k = 0; k < 30; ++k) {
    const gp_Pnt p = c->Value(f + (l - f) * unit(rng));
    const Eigen::Vector3d x = j.transform(T * unit(rng)) * Eigen::Vector3d(p.X(), p.Y(), p.Z());
    BRepExtrema_DistShapeShape d(BRepBuilderAPI_MakeVertex(gp_Pnt(x.x(), x.y(), x.z())).Vertex(), all);
    REQUIRE(d.IsDone());
    gap = std::max(gap, d.Value());
  }
  return gap;
}

}  // namespace

TEST_CASE("Helical sweeps of curves: the grazing curves of a screwed cylinder sweep faces within the tolerance") {
  // a cylinder whose axis is oblique to the screw's, and one third of a turn (random case
  // cylinder_helical_50 of seed 41, whose fits between grid points once strayed 4e-3)
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = Eigen::Vector3d(-0.375912, -0.417794, -0.432983);
  j.direction = Eigen::Vector3d(0, 0, 1);
  j.pitch = 0.710984 / (2 * M_PI);
  const double T = 120.515719 * M_PI / 180, tol = 2.5e-8;
  const TopoDS_Shape body =
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0.429133, -0.504559, 0.410256), gp_Dir(-0.586627, 0.573952, 0.571356)),
                               0.384240, 1.223087).Shape();
  int swept = 0;
  for (TopExp_Explorer ex(body, TopAbs_FACE); ex.More(); ex.Next())
    for (const occt::GrazingCurve& g : occt::grazing_curves(TopoDS::Face(ex.Current()), VelocityField(j), tol, 2.0))
      for (const auto& [a, b] : {std::pair{0.0, 1.0}, std::pair{0.0, 0.8986}, std::pair{0.2377, 0.9732}}) {
        const double f = g.first + a * (g.last - g.first), l = g.first + b * (g.last - g.first);
        double err = 0;
        const std::vector<TopoDS_Face> faces = occt::sweep_curve(g.curve, f, l, j, T, tol, &err);
        CAPTURE(f, l, err);
        CHECK(err <= tol);
        CHECK(largest_gap(faces, g.curve, f, l, j, T) <= tol + 1e-9);
        ++swept;
      }
  CHECK(swept >= 3);
}

TEST_CASE("Helical sweeps of curves: a smooth curve sweeps one face per piece of at most a quarter turn") {
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = Eigen::Vector3d(0.1, 0.2, 0);
  j.direction = Eigen::Vector3d(0.2, -0.1, 1).normalized();
  j.pitch = 0.15;
  const double T = 2.5, tol = 1e-7;
  TColgp_Array1OfPnt pts(1, 5);
  for (int k = 0; k < 5; ++k) pts.SetValue(k + 1, gp_Pnt(1 + 0.2 * k, 0.1 * k * k, 0.3 * k));
  GeomAPI_PointsToBSpline fit(pts, 3, 3, GeomAbs_C2, 1e-12);
  REQUIRE(fit.IsDone());
  const Handle(Geom_BSplineCurve) c = fit.Curve();
  double err = 0;
  const std::vector<TopoDS_Face> faces =
      occt::sweep_curve(c, c->FirstParameter(), c->LastParameter(), j, T, tol, &err);
  CHECK(faces.size() == 2);  // (2.5 rad: two pieces)
  CHECK(err <= tol);
  CHECK(largest_gap(faces, c, c->FirstParameter(), c->LastParameter(), j, T) <= tol + 1e-9);
}

TEST_CASE("Helical sweeps of curves: lines, circles, ellipses and splines sweep tensor-product faces within the tolerance") {
  // each curve's poles carried along polynomial helices: the faces hold the exact sweep to well
  // within the tolerance at random points, and the error they report is what a grid measures
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = Eigen::Vector3d(0.3, -0.2, 0.1);
  j.direction = Eigen::Vector3d(0.4, 0.45, 0.79).normalized();
  j.pitch = 0.634 / (2 * M_PI);
  const double T = 346.9 * M_PI / 180, tol = 2.7e-6;
  TColgp_Array1OfPnt pts(1, 6);
  for (int k = 0; k < 6; ++k) pts.SetValue(k + 1, gp_Pnt(0.5 + 0.2 * k, 0.1 * k * k - 0.3, 0.3 * k - 0.4));
  GeomAPI_PointsToBSpline fit(pts, 3, 5, GeomAbs_C2, 1e-12);
  REQUIRE(fit.IsDone());
  const gp_Ax2 frame(gp_Pnt(-0.4, 0.7, 0.2), gp_Dir(0.3, -0.5, 0.8));
  const std::vector<std::pair<const char*, Handle(Geom_Curve)>> curves = {
      {"line", new Geom_Line(gp_Pnt(-0.8, -0.05, 0.2), gp_Dir(0, 1, 0))},
      {"circle", new Geom_Circle(frame, 0.37)},
      {"ellipse", new Geom_Ellipse(frame, 0.6, 0.25)},
      {"spline", fit.Curve()}};
  for (const auto& [name, c] : curves) {
    const double f = c->IsKind(STANDARD_TYPE(Geom_Line)) ? 0.0 : c->FirstParameter();
    const double l = c->IsKind(STANDARD_TYPE(Geom_Line)) ? 0.8 : c->LastParameter();
    double err = 0;
    const std::vector<TopoDS_Face> faces = occt::sweep_curve(c, f, l, j, T, tol, &err);
    CAPTURE(name, err);
    CHECK(faces.size() == 4);  // (346.9 degrees: four quarter turns at most)
    CHECK(err <= 0.02 * tol);  // (the polynomials' share of the tolerance)
    CHECK(largest_gap(faces, c, f, l, j, T) <= 0.02 * tol + 1e-12);
    for (const TopoDS_Face& face : faces) CHECK(BRepCheck_Analyzer(face).IsValid());
    // each quarter turn on its own: the reported error bounds what a finer grid measures
    for (int k = 0; k < 4; ++k) {
      const double q0 = T * k / 4, q1 = T * (k + 1) / 4;
      double piece_err = 0;
      const Handle(Geom_BSplineSurface) s = occt::helical_spline_surface(c, f, l, j, q0, q1, tol, &piece_err);
      REQUIRE(!s.IsNull());
      double u0, u1, v0, v1;
      s->Bounds(u0, u1, v0, v1);
      CHECK(v0 == Approx(q0).margin(1e-15));
      CHECK(v1 == Approx(q1).margin(1e-15));
      const Handle(Geom_Curve) on = new Geom_TrimmedCurve(c, f, l);
      const Handle(Geom_BSplineCurve) b = GeomConvert::CurveToBSplineCurve(on);
      double worst = 0;
      for (int a = 0; a <= 40; ++a)
        for (int q = 0; q <= 40; ++q) {
          const double u = u0 + (u1 - u0) * a / 40, v = q0 + (q1 - q0) * q / 40;
          const gp_Pnt p = b->Value(u);
          const Eigen::Vector3d x = j.transform(v) * Eigen::Vector3d(p.X(), p.Y(), p.Z());
          worst = std::max(worst, s->Value(u, v).Distance(gp_Pnt(x.x(), x.y(), x.z())));
        }
      CHECK(worst <= 1.1 * piece_err + 1e-14);
    }
  }
}

TEST_CASE("Helical sweeps of curves: a curve of another kind is fitted, and the fits are still there on request") {
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = Eigen::Vector3d(0, 0, 0);
  j.direction = Eigen::Vector3d(0, 0, 1);
  j.pitch = 0.1;
  const double tol = 1e-6;
  const Handle(Geom_Curve) offset =
      new Geom_OffsetCurve(new Geom_Circle(gp_Ax2(gp_Pnt(1, 0, 0), gp_Dir(0, 1, 0)), 0.3), 0.05, gp_Dir(0, 1, 0));
  double err = 0;
  CHECK(occt::helical_spline_surface(offset, 0, 1, j, 0, 1, tol, &err).IsNull());
  const std::vector<TopoDS_Face> faces = occt::sweep_curve(offset, 0, 1, j, 1.0, tol, &err);
  CHECK(faces.size() == 1);
  CHECK(err <= tol);
  CHECK(largest_gap(faces, offset, 0, 1, j, 1.0) <= tol + 1e-9);
  const Handle(Geom_Curve) line = new Geom_Line(gp_Pnt(1, 0, 0), gp_Dir(0, 1, 1));
  double fitted_err = 0;
  const std::vector<TopoDS_Face> fitted = occt::sweep_curve(line, 0, 1, j, 1.0, tol, &fitted_err, occt::HelicalFaces::Fitted);
  CHECK(fitted.size() == 1);
  CHECK(fitted_err <= tol);
  CHECK(largest_gap(fitted, line, 0, 1, j, 1.0) <= tol + 1e-9);
}
