// The checks of a solid that use its own boundary (see solid_checks.hpp).
#include <BRepAdaptor_Surface.hxx>
#include <BRepTools.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Standard_Failure.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepGProp_Domain.hxx>
#include <BRepGProp_Face.hxx>
#include <BRepGProp_Vinert.hxx>
#include <BRep_Tool.hxx>
#include <ShapeAnalysis_Shell.hxx>
#include <ShapeFix_Shape.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "base/internal.hpp"
#include "verdict/solid_checks.hpp"

namespace sweep::occt {

namespace {

/// The face on an exact B-spline form of its surface when that is an extrusion of a curve other than
/// a line, circle or conic (the same parameters, so its curves on the surface hold as they are);
/// the face itself otherwise. OCCT's adaptive volume integral takes an extrusion's basis curve as
/// one smooth span and can stop on a wrong value (1.5e-5 of a torus extruded, depending on the
/// point integrated about); on the B-spline form it integrates span by span.
TopoDS_Face integrable_face(const TopoDS_Face& f) {
  const BRepAdaptor_Surface S(f, false);
  if (S.GetType() != GeomAbs_SurfaceOfExtrusion) return f;
  const GeomAbs_CurveType basis = S.BasisCurve()->GetType();
  if (basis != GeomAbs_BSplineCurve && basis != GeomAbs_BezierCurve && basis != GeomAbs_OtherCurve) return f;
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  TopLoc_Location loc;
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(f, loc);
  try {
    const double du = Settings::bspline_form_curve_margin * (u1 - u0);
    const double dv = Settings::bspline_form_extrusion_margin * (v1 - v0) + Settings::bspline_form_extrusion_floor;
    const Handle(Geom_BSplineSurface) b = GeomConvert::SurfaceToBSplineSurface(new Geom_RectangularTrimmedSurface(
        surface, std::max(u0 - du, S.FirstUParameter()), std::min(u1 + du, S.LastUParameter()), v0 - dv, v1 + dv));
    // the same parameters: points agree to rounding
    for (double a : {0.0, 0.3, 0.7, 1.0})
      for (double c : {0.0, 0.6, 1.0}) {
        const double u = u0 + a * (u1 - u0), v = v0 + c * (v1 - v0);
        const gp_Pnt p = surface->Value(u, v);
        if (p.Distance(b->Value(u, v)) > Settings::bspline_form_rounding * (1 + p.XYZ().Modulus())) return f;
      }
    return face_on_surface(f, b);
  } catch (const Standard_Failure&) {
    return f;
  }
}

/// OCCT's volume integral of oriented faces, each about P (BRepGProp's adaptive Gauss integration,
/// face by face as BRepGProp::VolumeProperties does, extrusions of splines on their B-spline form):
/// the volume and the first moment about the origin add to those of the other faces taken about
/// the same P.
void occt_volume_of_faces(const std::vector<TopoDS_Face>& faces, const gp_Pnt& P, double eps, double* volume,
                          gp_XYZ* moment) {
  BRepGProp_Face BF;
  BRepGProp_Domain BD;
  BRepGProp_Vinert G;
  G.SetLocation(P);
  for (const TopoDS_Face& f : faces) {
    if (f.Orientation() != TopAbs_FORWARD && f.Orientation() != TopAbs_REVERSED) continue;
    TopLoc_Location loc;
    if (BRep_Tool::Surface(f, loc).IsNull()) continue;
    const TopoDS_Face h = integrable_face(f);
    BF.Load(h);
    if (h.NbChildren() == 0) {
      G.Perform(BF, eps);
    } else {
      BD.Init(h);
      G.Perform(BF, BD, eps);
    }
    *volume += G.Mass();
    *moment += G.CentreOfMass().XYZ() * G.Mass();
  }
}

}  // namespace

TopoDS_Shape healed(const TopoDS_Shape& s) {
  ShapeFix_Shape fix(s);
  fix.Perform();
  const TopoDS_Shape h = fix.Shape();
  if (h.IsNull() || !BRepCheck_Analyzer(h).IsValid()) return {};
  return h;
}

bool closed_solids(const TopoDS_Shape& shape) {
  int nsolids = 0;
  for (TopExp_Explorer ex(shape, TopAbs_SOLID); ex.More(); ex.Next()) {
    ++nsolids;
    ShapeAnalysis_Shell sas;
    sas.LoadShells(ex.Current());
    if (sas.CheckOrientedShells(ex.Current(), true) || sas.HasFreeEdges()) return false;
  }
  return nsolids > 0;
}

SolidChecks check_solid(const TopoDS_Shape& result) {
  SolidChecks c;
  // OCCT's volume integral is a sum over the faces: they are shared out between two parts of
  // about equal cost (large B-spline faces dominate), integrated on two threads about one point.
  std::vector<std::pair<double, TopoDS_Face>> faces;
  for (TopExp_Explorer ex(result, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& f = TopoDS::Face(ex.Current());
    const BRepAdaptor_Surface S(f, false);
    double cost = 1;
    if (S.GetType() == GeomAbs_BSplineSurface)
      cost = double(S.NbUKnots() * S.NbVKnots()) * (S.UDegree() + 1) * (S.VDegree() + 1);
    faces.push_back({cost, f});
  }
  std::stable_sort(faces.begin(), faces.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<TopoDS_Face> part[2];
  double load[2] = {0, 0};
  for (const auto& [cost, f] : faces) {
    const int k = load[0] <= load[1] ? 0 : 1;
    part[k].push_back(f);
    load[k] += cost;
  }
  gp_XYZ P(0, 0, 0);  // the mean of the vertices, near the solid
  int nv = 0;
  for (TopExp_Explorer ex(result, TopAbs_VERTEX); ex.More(); ex.Next(), ++nv)
    P += BRep_Tool::Pnt(TopoDS::Vertex(ex.Current())).XYZ();
  if (nv > 0) P /= nv;
  double volume[2] = {0, 0};
  gp_XYZ moment[2] = {gp_XYZ(0, 0, 0), gp_XYZ(0, 0, 0)};
  // Tasks, the long ones first so that the short ones fill in behind them: OCCT's integral of the
  // two parts, the box, validity and closedness, then the divergence integral face by face (the
  // costliest faces first).
  const std::size_t nf = faces.size();
  std::vector<std::pair<double, double>> div_area(nf);
  parallel_for(nf + 4, [&]() -> std::function<void(std::size_t)> {
    return [&](std::size_t task) {
      if (task < 2) {
        occt_volume_of_faces(part[task], gp_Pnt(P), Settings::brep_volume_precision, &volume[task], &moment[task]);
      } else if (task >= 4) {
        div_area[task - 4] = face_divergence_and_area(faces[task - 4].second, P);
      } else if (task == 2) {
        c.box = shape_box(result);
      } else {
        c.valid = BRepCheck_Analyzer(result).IsValid();
        c.closed = closed_solids(result);
      }
    };
  });
  for (const auto& [v, a] : div_area) {
    c.volume_divergence += v;
    c.area += a;
  }
  c.volume_brep = volume[0] + volume[1];
  // (no volume, no centroid: the point integrated about stands in, a finite number for the report)
  c.centroid = c.volume_brep != 0 ? gp_Pnt((moment[0] + moment[1]) / c.volume_brep) : gp_Pnt(P);
  return c;
}

int separate_parts(const std::vector<TopoDS_Shape>& parts, double gap) {
  const int n = int(parts.size());
  std::vector<int> group(n);
  std::iota(group.begin(), group.end(), 0);
  std::function<int(int)> root = [&](int x) { return group[x] == x ? x : group[x] = root(group[x]); };
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      if (root(a) == root(b)) continue;
      BRepExtrema_DistShapeShape dist(parts[a], parts[b]);
      if (dist.IsDone() && dist.Value() <= gap) group[root(b)] = root(a);
    }
  int groups = 0;
  for (int k = 0; k < n; ++k) groups += root(k) == k;
  return groups;
}

double max_tolerance(const TopoDS_Shape& s) {
  double t = 0;
  for (TopExp_Explorer ex(s, TopAbs_VERTEX); ex.More(); ex.Next())
    t = std::max(t, BRep_Tool::Tolerance(TopoDS::Vertex(ex.Current())));
  for (TopExp_Explorer ex(s, TopAbs_EDGE); ex.More(); ex.Next())
    t = std::max(t, BRep_Tool::Tolerance(TopoDS::Edge(ex.Current())));
  return t;
}

void set_centroid_and_box(Report& rep, const gp_Pnt& c, const Bnd_Box& bb) {
  rep.centroid[0] = c.X();
  rep.centroid[1] = c.Y();
  rep.centroid[2] = c.Z();
  bb.Get(rep.bbox_min[0], rep.bbox_min[1], rep.bbox_min[2], rep.bbox_max[0], rep.bbox_max[1], rep.bbox_max[2]);
}

}  // namespace sweep::occt
