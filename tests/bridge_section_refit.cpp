// Section curves refitted onto both surfaces, against the surfaces themselves.
#include <BRepAlgoAPI_Section.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <catch2/catch.hpp>

#include "faces/section_refit.hpp"

using sweep::occt::refitted_section_edge;

TEST_CASE("Section refit: the refitted curve of two crossing cylinders lies on both within the tolerance") {
  // a cylinder of radius 1 about z and one of radius 0.7 about x, crossing in two closed curves
  const Handle(Geom_CylindricalSurface) s1 = new Geom_CylindricalSurface(gp_Ax3(gp::Origin(), gp::DZ()), 1.0);
  const Handle(Geom_CylindricalSurface) s2 =
      new Geom_CylindricalSurface(gp_Ax3(gp_Pnt(-2, 0, 0.2), gp::DX(), gp::DY()), 0.7);
  const TopoDS_Face a = BRepBuilderAPI_MakeFace(s1, 0, 2 * M_PI, -2, 2, 1e-7).Face();
  const TopoDS_Face b = BRepBuilderAPI_MakeFace(s2, 0, 2 * M_PI, 0, 4, 1e-7).Face();
  BRepAlgoAPI_Section sec(a, b, false);
  sec.Approximation(true);
  sec.ComputePCurveOn1(true);
  sec.ComputePCurveOn2(true);
  sec.Build();
  REQUIRE(sec.IsDone());
  const double tol = 1e-9;
  int edges = 0, refitted = 0;
  for (TopExp_Explorer ex(sec.Shape(), TopAbs_EDGE); ex.More(); ex.Next(), ++edges) {
    const TopoDS_Edge e = TopoDS::Edge(ex.Current());
    double err = -1;
    // kept as it is when its tolerance is below the threshold
    CHECK(refitted_section_edge(e, a, b, tol, 1.0, &err).IsSame(e));
    CHECK(err == 0);
    // refitted when asked for more than OCCT's approximation gives
    const TopoDS_Edge r = refitted_section_edge(e, a, b, tol, 0.0, &err);
    if (r.IsSame(e)) continue;
    ++refitted;
    CHECK(err <= tol);
    double f, l;
    const Handle(Geom_Curve) c = BRep_Tool::Curve(r, f, l);
    for (int k = 0; k <= 50; ++k) {
      const gp_Pnt p = c->Value(f + (l - f) * k / 50);
      CHECK(std::abs(std::hypot(p.X(), p.Y()) - 1.0) <= 2 * tol);
      CHECK(std::abs(std::hypot(p.Y(), p.Z() - 0.2) - 0.7) <= 2 * tol);
    }
  }
  CHECK(edges >= 2);
  CHECK(refitted == edges);
}
