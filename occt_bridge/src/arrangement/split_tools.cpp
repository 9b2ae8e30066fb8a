// Section curves made ready to split a face.
#include "arrangement/split_tools.hpp"

#include <BRepBndLib.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Geom2dAPI_Interpolate.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <Precision.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_HArray1OfPnt2d.hxx>
#include <TopLoc_Location.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Vertex.hxx>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sweep/settings.hpp"

namespace sweep::occt {

namespace {

/// An edge another curve may end on, with its box.
struct Target {
  TopoDS_Edge edge;
  Bnd_Box box;
};

Target target_of(const TopoDS_Edge& e, double gap) {
  Target t{e, {}};
  BRepBndLib::Add(e, t.box);
  t.box.Enlarge(gap);
  return t;
}

/// The distance from v to e, less the tolerances that already join them (negative: joined).
double open_gap(const TopoDS_Vertex& v, const Target& t) {
  BRepExtrema_DistShapeShape dist(v, t.edge);
  if (!dist.IsDone() || dist.NbSolution() == 0) return std::numeric_limits<double>::infinity();
  return dist.Value() - BRep_Tool::Tolerance(v) - BRep_Tool::Tolerance(t.edge);
}

}  // namespace

int bridge_section_ends(const TopoDS_Face& face, const std::vector<TopoDS_Edge>& tools, double max_gap) {
  std::vector<Target> targets;
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
    if (!BRep_Tool::Degenerated(e)) targets.push_back(target_of(e, max_gap));
  }
  for (const auto& e : tools) targets.push_back(target_of(e, max_gap));
  BRep_Builder bb;
  int bridged = 0;
  for (std::size_t k = 0; k < tools.size(); ++k) {
    TopoDS_Vertex ends[2];
    TopExp::Vertices(tools[k], ends[0], ends[1]);
    for (const TopoDS_Vertex& v : ends) {
      if (v.IsNull()) continue;
      const gp_Pnt p = BRep_Tool::Pnt(v);
      double nearest = std::numeric_limits<double>::infinity();
      double reach = 0;  // the vertex tolerance that joins the nearest edge
      for (std::size_t m = 0; m < targets.size(); ++m) {
        // (not the curve itself, which a face's list of curves can hold twice)
        if (targets[m].edge.IsSame(tools[k]) || targets[m].box.IsOut(p)) continue;
        const double gap = open_gap(v, targets[m]);
        if (gap <= 0) {  // already on a curve
          nearest = gap;
          break;
        }
        if (gap < nearest) {
          nearest = gap;
          reach = BRep_Tool::Tolerance(v) + gap * 1.01;
        }
      }
      if (nearest > 0 && nearest <= max_gap) {
        bb.UpdateVertex(v, reach);
        ++bridged;
      }
    }
  }
  return bridged;
}

namespace {

/// q moved by whole periods of S to lie nearest to `prev`.
gp_Pnt2d nearest_turn(const Handle(Geom_Surface)& S, gp_Pnt2d q, const gp_Pnt2d& prev) {
  if (S->IsUPeriodic()) q.SetX(q.X() + S->UPeriod() * std::round((prev.X() - q.X()) / S->UPeriod()));
  if (S->IsVPeriodic()) q.SetY(q.Y() + S->VPeriod() * std::round((prev.Y() - q.Y()) / S->VPeriod()));
  return q;
}

/// The point of S nearest to p, by a search over all of S: where S folds back close to itself (an
/// extrusion of a curve that turns back), the projection from the previous point of a curve can
/// settle on the wrong sheet. *uv is kept when the search finds nothing closer than `gap`.
void nearest_on_surface(const Handle(Geom_Surface)& S, const gp_Pnt& p, double gap, gp_Pnt2d* uv) {
  try {
    GeomAPI_ProjectPointOnSurf search(p, S);
    if (search.NbPoints() == 0 || !(search.LowerDistance() < gap)) return;
    double u, v;
    search.LowerDistanceParameters(u, v);
    uv->SetCoord(u, v);
  } catch (const Standard_Failure&) {
  }
}

/// The curve of `e` on surface S, its parameters those of the edge's curve: points of the curve
/// projected onto S (following the periodic surfaces' turns) and interpolated, on finer samples
/// until the surface at the fitted curve lies within `target` of the edge's curve at the points
/// between the samples; else the closest of the fits. *dev: its largest distance found.
Handle(Geom2d_Curve) fitted_curve_on(const TopoDS_Edge& e, const Handle(Geom_Surface)& S, double target, double* dev) {
  double f, l;
  const Handle(Geom_Curve) c = BRep_Tool::Curve(e, f, l);
  if (c.IsNull() || !(l > f)) return nullptr;
  ShapeAnalysis_Surface sas(S);
  const double prec = 0.01 * target;
  Handle(Geom2d_Curve) best;
  *dev = std::numeric_limits<double>::infinity();
  for (int n = 16; n <= Settings::curve_on_face_max_samples; n *= 2) {
    Handle(TColgp_HArray1OfPnt2d) uv = new TColgp_HArray1OfPnt2d(1, n + 1);
    Handle(TColStd_HArray1OfReal) params = new TColStd_HArray1OfReal(1, n + 1);
    for (int k = 0; k <= n; ++k) {
      const double s = f + (l - f) * k / n;
      const gp_Pnt p = c->Value(s);
      gp_Pnt2d q = k == 0 ? sas.ValueOfUV(p, prec) : sas.NextValueOfUV(uv->Value(k), p, prec);
      if (sas.Gap() > target) nearest_on_surface(S, p, sas.Gap(), &q);
      if (k > 0) q = nearest_turn(S, q, uv->Value(k));
      uv->SetValue(k + 1, q);
      params->SetValue(k + 1, s);
    }
    // (the interpolation refuses two points that project to one, as points past the end of a
    // bounded surface do)
    Handle(Geom2d_BSplineCurve) pc;
    try {
      Geom2dAPI_Interpolate fit(uv, params, false, Precision::PConfusion());
      fit.Perform();
      if (fit.IsDone()) pc = fit.Curve();
    } catch (const Standard_Failure&) {
    }
    if (pc.IsNull()) continue;
    double worst = 0;
    for (int k = 0; k < 2 * n; ++k) {
      const double s = f + (l - f) * (k + 0.5) / (2 * n);
      const gp_Pnt2d q = pc->Value(s);
      worst = std::max(worst, S->Value(q.X(), q.Y()).Distance(c->Value(s)));
    }
    if (worst < *dev) {
      *dev = worst;
      best = pc;
    }
    if (worst <= target) break;
  }
  return best;
}

}  // namespace

int add_curves_on_face(const TopoDS_Face& face, const std::vector<TopoDS_Edge>& tools, double target, double accept) {
  int added = 0;
  TopLoc_Location loc;
  const Handle(Geom_Surface) S = BRep_Tool::Surface(face, loc);
  const Handle(Geom_Surface) placed = BRep_Tool::Surface(face);
  BRep_Builder bb;
  for (const auto& e : tools) {
    double f, l;
    if (!BRep_Tool::CurveOnSurface(e, face, f, l).IsNull()) continue;
    double dev = 0;
    const Handle(Geom2d_Curve) pc = fitted_curve_on(e, placed, target, &dev);
    if (pc.IsNull() || dev > accept) continue;  // the splitter projects it
    bb.UpdateEdge(e, pc, S, loc, std::max(BRep_Tool::Tolerance(e), dev));
    ++added;
  }
  return added;
}

}  // namespace sweep::occt
