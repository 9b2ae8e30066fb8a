// The sweeps of points and curves: a curve and a surface, with no volume.
#include <BRepAlgoAPI_BuilderAlgo.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <cmath>

#include "run/run_steps.hpp"
#include "verdict/solid_checks.hpp"
#include "base/stop.hpp"
#include "sweep/error.hpp"

namespace sweep::occt {

TopoDS_Shape point_sweep(const TopoDS_Shape& body, const ScrewJoint& j, double T, double tol, double size) {
  TopoDS_Compound comp;
  BRep_Builder bb;
  bb.MakeCompound(comp);
  int n = 0;
  for (TopExp_Explorer ex(body, TopAbs_VERTEX); ex.More(); ex.Next()) {
    Eigen::Vector3d x = to_eigen(BRep_Tool::Pnt(TopoDS::Vertex(ex.Current())));
    if (j.type != JointType::Helical) {
      const TopoDS_Edge e = path_edge(x, j, 0.0, T, 1e-12 * size);
      if (e.IsNull()) continue;
      bb.Add(comp, e);
    } else {
      const int m = std::max(16, int(std::ceil(T / (M_PI / 32))));
      TColgp_Array1OfPnt pts(1, m + 1);
      for (int k = 0; k <= m; ++k) pts.SetValue(k + 1, to_pnt(j.transform(T * k / m) * x));
      GeomAPI_PointsToBSpline fit(pts, 3, 8, GeomAbs_C2, tol);
      Handle(Geom_Curve) c(fit.Curve().get());
      bb.Add(comp, BRepBuilderAPI_MakeEdge(c).Edge());
    }
    ++n;
  }
  if (n == 0) throw ComputeError("the point lies on the joint axis: its sweep is a point");
  return comp;
}

TopoDS_Shape curve_sweep(const TopoDS_Shape& body, const ScrewJoint& j, double T, double tol, double fit_tol,
                         double size, double* fit_err) {
  TopoDS_Compound comp;
  BRep_Builder bb;
  bb.MakeCompound(comp);
  int n = 0;
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(body, TopAbs_EDGE, edges);
  for (int k = 1; k <= edges.Extent(); ++k) {
    TopoDS_Edge e = TopoDS::Edge(edges(k));
    if (BRep_Tool::Degenerated(e)) continue;
    double f, l;
    Handle(Geom_Curve) c = BRep_Tool::Curve(e, f, l);
    if (c.IsNull()) continue;
    c = canonical_curve(c, f, l, fit_tol);
    gp_Pln plane;
    const bool planar = keeps_plane_of(c, f, l, j, size, &plane);
    for (const auto& face : planar ? planar_curve_sweep(c, f, l, j, T, plane, size) : sweep_curve(c, f, l, j, T, tol, fit_err)) {
      bb.Add(comp, face);
      ++n;
    }
  }
  if (n == 0) throw ComputeError("the curve slides along itself: its sweep is a curve");
  return comp;
}

TopoDS_Shape finish_curve_or_surface(const TopoDS_Shape& shape, int dim, double size, double fit_err, bool verify,
                                     Report& rep) {
  TopoDS_Shape result = shape;
  if (dim == 2) {
    TopTools_ListOfShape faces;
    for (TopExp_Explorer ex(result, TopAbs_FACE); ex.More(); ex.Next()) faces.Append(ex.Current());
    if (faces.Extent() > 1) {
      BRepAlgoAPI_BuilderAlgo gf;
      gf.SetArguments(faces);
      gf.SetRunParallel(true);
      gf.SetFuzzyValue(Settings::resolution * size);
      gf.SetNonDestructive(true);
      gf.Build(stop_range());
      check_stop();
      if (gf.IsDone() && !gf.HasErrors()) {
        TopTools_IndexedMapOfShape unique;
        TopExp::MapShapes(gf.Shape(), TopAbs_FACE, unique);
        TopoDS_Compound comp;
        BRep_Builder bb;
        bb.MakeCompound(comp);
        for (int k = 1; k <= unique.Extent(); ++k) bb.Add(comp, unique(k));
        result = comp;
      }
    }
  }
  BRepCheck_Analyzer check(result);
  rep.valid = check.IsValid();
  rep.closed = false;
  for (TopExp_Explorer ex(result, TopAbs_FACE); ex.More(); ex.Next()) ++rep.faces;
  GProp_GProps g;
  if (dim == 2) BRepGProp::SurfaceProperties(result, g, 1e-10);
  else BRepGProp::LinearProperties(result, g);
  rep.area = dim == 2 ? g.Mass() : 0.0;
  set_centroid_and_box(rep, g.CentreOfMass(), shape_box(result));
  rep.tol_achieved = std::max(fit_err, max_tolerance(result));
  rep.status = rep.valid ? "ok" : "failed";
  rep.message = std::string(rep.valid ? "" : "the result is not valid (BRepCheck); ") + "the swept set is a " +
                (dim == 2 ? "surface" : "curve") + ": it has no volume";
  if (verify) rep.message += "; --verify applies to solids only";
  return result;
}

}  // namespace sweep::occt
