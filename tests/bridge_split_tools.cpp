// Section curves made ready to split a face: ends that stop short of a curve are joined to it,
// and curves get their curves on the face's surface (against the surfaces' own equations).
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_Surface.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <gp_Ax3.hxx>
#include <gp_Circ.hxx>
#include <gp_Pln.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "arrangement/split_tools.hpp"
#include "base/internal.hpp"

namespace {

int faces_of(const TopoDS_Shape& s) {
  int n = 0;
  for (TopExp_Explorer ex(s, TopAbs_FACE); ex.More(); ex.Next()) ++n;
  return n;
}

/// The unit square z = 0 split by the segment x = 0.5 from y = 0 to y = 1 - gap.
int pieces_after(double gap, double max_gap, int* bridged) {
  const TopoDS_Face square = BRepBuilderAPI_MakeFace(gp_Pln(gp::XOY()), 0, 1, 0, 1).Face();
  const TopoDS_Edge cut = BRepBuilderAPI_MakeEdge(gp_Pnt(0.5, 0, 0), gp_Pnt(0.5, 1 - gap, 0)).Edge();
  // (the curve listed twice, as when two pairs of faces found it: it is not its own target)
  *bridged = sweep::occt::bridge_section_ends(square, {cut, cut}, max_gap);
  TopTools_ListOfShape tools;
  tools.Append(cut);
  const TopoDS_Shape split = sweep::occt::split_by_edges(square, tools, 1e-9, sweep::occt::SplitMode::NonDestructive);
  REQUIRE_FALSE(split.IsNull());
  return faces_of(split);
}

}  // namespace

TEST_CASE("Split tools: a section that stops short of the boundary by less than the gap splits the face") {
  int bridged = 0;
  CHECK(pieces_after(2e-6, 1e-5, &bridged) == 2);
  CHECK(bridged == 1);  // the end on the boundary is already joined
  // farther than the gap: left dangling (the face stays whole, with the curve inside it)
  CHECK(pieces_after(2e-5, 1e-5, &bridged) == 1);
  CHECK(bridged == 0);
  // reaching the boundary: nothing to bridge
  CHECK(pieces_after(0, 1e-5, &bridged) == 2);
  CHECK(bridged == 0);
}

TEST_CASE("Split tools: curves on a face follow its surface across the seam") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  // a torus and a cylinder about oblique axes, each with an arc of one of its circles that
  // crosses the seam of the angle parameter
  const gp_Ax3 frame(gp_Pnt(0.3, -0.2, 0.5), gp_Dir(1, 2, 2), gp_Dir(2, -1, 0));
  const double R = 2, r = 0.5;
  const Handle(Geom_Surface) torus = new Geom_ToroidalSurface(frame, R, r);
  const Handle(Geom_Surface) cylinder = new Geom_CylindricalSurface(frame, r);
  for (const Handle(Geom_Surface)& S : {torus, cylinder}) {
    const TopoDS_Face face = BRepBuilderAPI_MakeFace(S, 1e-9).Face();
    // the circle v = 0.7 on the torus, the circle at height 0.7 on the cylinder, from angle -0.4
    // to 0.9 (through the seam at 0)
    const double v = 0.7;
    const gp_Pnt centre = frame.Location().Translated(gp_Vec(frame.Direction()) * (S == torus ? r * std::sin(v) : v));
    const double radius = S == torus ? R + r * std::cos(v) : r;
    const gp_Circ circle(gp_Ax2(centre, frame.Direction(), frame.XDirection()), radius);
    const TopoDS_Edge arc = BRepBuilderAPI_MakeEdge(circle, -0.4, 0.9).Edge();
    double f, l;
    REQUIRE(BRep_Tool::CurveOnSurface(arc, face, f, l).IsNull());
    const double target = 1e-9;
    CHECK(sweep::occt::add_curves_on_face(face, {arc}, target, 1e-6) == 1);
    const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(arc, face, f, l);
    REQUIRE_FALSE(pc.IsNull());
    CHECK(BRep_Tool::Tolerance(arc) <= 1e-7 + 1e-12);  // the edge's own tolerance, not raised
    // the surface along the curve on it is the circle, point for point (same parameter), and its
    // angle runs on across the seam instead of jumping by a turn
    double worst = 0, jump = 0;
    gp_Pnt2d prev = pc->Value(f);
    for (int k = 0; k <= 200; ++k) {
      const double s = f + (l - f) * (k + unit(rng)) / 201;
      const gp_Pnt2d q = pc->Value(s);
      const gp_Pnt on_surface = S->Value(q.X(), q.Y());
      const gp_Pnt exact = centre.Translated(gp_Vec(frame.XDirection()) * (radius * std::cos(s)) +
                                             gp_Vec(frame.YDirection()) * (radius * std::sin(s)));
      worst = std::max(worst, on_surface.Distance(exact));
      jump = std::max(jump, std::abs(q.X() - prev.X()));
      prev = q;
    }
    CHECK(worst <= 10 * target);
    CHECK(jump <= 0.1);
  }
}

TEST_CASE("Split tools: a curve off the surface gets no curve on it") {
  const Handle(Geom_Surface) cylinder = new Geom_CylindricalSurface(gp::XOY(), 1);
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(cylinder, 0, 2 * M_PI, -1, 1, 1e-9).Face();
  // a circle of radius 1.2 about the axis: 0.2 off the cylinder everywhere
  const TopoDS_Edge off = BRepBuilderAPI_MakeEdge(gp_Circ(gp::XOY(), 1.2), 0.2, 1.5).Edge();
  CHECK(sweep::occt::add_curves_on_face(face, {off}, 1e-9, 1e-6) == 0);
  double f, l;
  CHECK(BRep_Tool::CurveOnSurface(off, face, f, l).IsNull());
}

TEST_CASE("Split tools: a curve running past the end of a bounded surface fails no run") {
  // the surface swept by the segment x = 1, 0 <= z <= 1 turned about the z axis (a spline
  // profile, as a grazing curve's); lines along it run past its end circle z = 1, where
  // projections stop at the end (points that project to one, which the interpolation refuses)
  TColgp_Array1OfPnt poles(1, 2);
  poles(1) = gp_Pnt(1, 0, 0);
  poles(2) = gp_Pnt(1, 0, 1);
  TColStd_Array1OfReal knots(1, 2);
  knots(1) = 0;
  knots(2) = 1;
  TColStd_Array1OfInteger mults(1, 2);
  mults.Init(2);
  const Handle(Geom_Curve) profile = new Geom_BSplineCurve(poles, knots, mults, 1);
  const Handle(Geom_Surface) S = new Geom_SurfaceOfRevolution(profile, gp::OZ());
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(S, 1e-9).Face();
  for (double past : {1e-7, 1e-3, 0.5}) {
    const TopoDS_Edge e = BRepBuilderAPI_MakeEdge(gp_Pnt(1, 0, 0.5), gp_Pnt(1, 0, 1 + past)).Edge();
    int added = -1;
    CHECK_NOTHROW(added = sweep::occt::add_curves_on_face(face, {e}, 1e-9, 1e-6));
    double f, l;
    const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, face, f, l);
    CHECK(added == int(!pc.IsNull()));
    if (pc.IsNull()) continue;
    // a curve given is on the surface within what it was accepted at, and the edge says so
    for (int k = 0; k <= 20; ++k) {
      const double s = f + (l - f) * k / 20;
      const gp_Pnt2d q = pc->Value(s);
      double cf, cl;
      const gp_Pnt on_edge = BRep_Tool::Curve(e, cf, cl)->Value(s);
      CHECK(S->Value(q.X(), q.Y()).Distance(on_edge) <= std::max(1e-6, BRep_Tool::Tolerance(e)) + 1e-12);
    }
    CHECK(BRep_Tool::Tolerance(e) <= 1e-6 + 1e-12);
  }
  // a line within it gets its curve
  const TopoDS_Edge within = BRepBuilderAPI_MakeEdge(gp_Pnt(1, 0, 0.25), gp_Pnt(1, 0, 0.75)).Edge();
  CHECK(sweep::occt::add_curves_on_face(face, {within}, 1e-9, 1e-6) == 1);
}

TEST_CASE("Split tools: a curve near the fold of an extrusion gets its curve on the sheet it lies on") {
  // a face of a torus extruded obliquely (the extrusion of its grazing curve, whose outline along
  // the direction has cusps, so that the surface folds back close to itself) and a section curve
  // on it that runs past the fold: projected from one point to the next, the curve's points
  // settled on the other sheet, up to 1e-4 away, and the splitter projected it instead, 1e-3 off
  TopoDS_Shape both;
  BRep_Builder builder;
  REQUIRE(BRepTools::Read(both, SWEEP_SOURCE_DIR "/tests/data/folded_extrusion_section.brep", builder));
  TopoDS_Face face;
  TopoDS_Edge section;
  for (TopoDS_Iterator it(both); it.More(); it.Next()) {
    if (it.Value().ShapeType() == TopAbs_FACE) face = TopoDS::Face(it.Value());
    if (it.Value().ShapeType() == TopAbs_EDGE) section = TopoDS::Edge(it.Value());
  }
  REQUIRE_FALSE(face.IsNull());
  REQUIRE_FALSE(section.IsNull());
  double f, l;
  REQUIRE(BRep_Tool::CurveOnSurface(section, face, f, l).IsNull());
  const double target = 3.4e-8, accept = 3.4e-6;  // the run's fit and requested tolerances
  CHECK(sweep::occt::add_curves_on_face(face, {section}, target, accept) == 1);
  const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(section, face, f, l);
  REQUIRE_FALSE(pc.IsNull());
  const Handle(Geom_Surface) S = BRep_Tool::Surface(face);
  double cf, cl;
  const Handle(Geom_Curve) c = BRep_Tool::Curve(section, cf, cl);
  double worst = 0;
  for (int k = 0; k <= 400; ++k) {
    const double s = f + (l - f) * k / 400;
    const gp_Pnt2d q = pc->Value(s);
    worst = std::max(worst, S->Value(q.X(), q.Y()).Distance(c->Value(s)));
  }
  CHECK(worst <= 10 * target);
  CHECK(BRep_Tool::Tolerance(section) <= accept);
}
