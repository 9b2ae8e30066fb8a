// Faces swept by a curve under one screw joint.
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <ShapeFix_Face.hxx>
#include <ShapeAnalysis_Edge.hxx>
#include <GeomProjLib.hxx>
#include <Geom2d_Curve.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BezierCurve.hxx>
#include <Geom_Ellipse.hxx>
#include <GeomConvert.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <Geom_SurfaceOfLinearExtrusion.hxx>
#include <Geom_SurfaceOfRevolution.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <ElCLib.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Line.hxx>
#include <Geom_Plane.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <gp_Circ.hxx>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "base/internal.hpp"
#include "sweep/error.hpp"
#include "sweep/settings.hpp"
#include "sweep/trig_bezier.hpp"

namespace sweep::occt {
namespace {

TopoDS_Face make_face(const Handle(Geom_Surface)& s, double u0, double u1, double v0, double v1, double tol) {
  BRepBuilderAPI_MakeFace mf(s, u0, u1, v0, v1, tol);
  if (!mf.IsDone()) throw ComputeError("could not build a swept face");
  return mf.Face();
}

/// True when the motion moves every point of the curve along the curve itself (its sweep is the
/// curve, with no area).
bool slides_along(const Handle(Geom_Curve)& c, double f, double l, const ScrewJoint& j) {
  const int n = Settings::curve_slide_samples;
  for (int k = 0; k <= n; ++k) {
    gp_Pnt p;
    gp_Vec d;
    c->D1(f + (l - f) * k / n, p, d);
    Eigen::Vector3d v = j.velocity(to_eigen(p)), t = to_eigen(d);
    if (t.norm() < 1e-300) continue;
    if (v.cross(t).norm() > Settings::parallel_angle * (v.norm() + 1e-300) * t.norm() &&
        v.norm() > Settings::still_speed)
      return false;
  }
  return true;
}

/// True when the curve lies within tol of a rotation joint's axis (sampled): its sweep is a tube of
/// radius at most tol, with no area to bound the swept set (and a thin tube stalls OCCT's
/// intersectors).
bool on_axis(const Handle(Geom_Curve)& c, double f, double l, const ScrewJoint& j, double tol) {
  if (!j.is_rotation()) return false;
  const int n = Settings::curve_on_axis_samples;
  for (int k = 0; k <= n; ++k) {
    const Eigen::Vector3d r = to_eigen(c->Value(f + (l - f) * k / n)) - j.point;
    if ((r - j.direction * j.direction.dot(r)).norm() > tol) return false;
  }
  return true;
}

/// Best-fit check: all samples of c within tol of the candidate.
bool matches(const Handle(Geom_Curve)& c, double f, double l, const Handle(Geom_Curve)& cand, double tol) {
  const int n = Settings::canonical_curve_samples;
  for (int k = 0; k <= n; ++k) {
    gp_Pnt p = c->Value(f + (l - f) * k / n);
    if (cand->IsKind(STANDARD_TYPE(Geom_Line))) {
      if (Handle(Geom_Line)::DownCast(cand)->Lin().Distance(p) > tol) return false;
    } else {
      if (Handle(Geom_Circle)::DownCast(cand)->Circ().Distance(p) > tol) return false;
    }
  }
  return true;
}

/// The planar region swept by a segment lying in a plane perpendicular to the rotation axis,
/// as faces bounded by the segment at both ends and the arcs of its end points. The segment is
/// split at the foot of the axis so each piece sweeps one-to-one.
std::vector<TopoDS_Face> planar_segment_sweep(const gp_Pnt& a, const gp_Pnt& b, const ScrewJoint& j, double T,
                                              double tol) {
  std::vector<TopoDS_Face> out;
  const gp_Ax1 axis(to_pnt(j.point), gp_Dir(to_vec(j.direction)));
  const gp_Lin seg(a, gp_Dir(gp_Vec(a, b)));
  // foot of the axis on the segment's line (closest point in the plane)
  gp_Pnt c = to_pnt(j.point + j.direction * j.direction.dot(to_eigen(a) - j.point));
  double s = ElCLib::Parameter(seg, c), len = a.Distance(b);
  std::vector<std::pair<gp_Pnt, gp_Pnt>> parts;
  if (s > tol && s < len - tol) {
    gp_Pnt f = ElCLib::Value(s, seg);
    parts.push_back({f, a});
    parts.push_back({f, b});
  } else {
    parts.push_back({a, b});
  }
  const int pieces = sweep_pieces(T);
  Handle(Geom_Plane) plane = new Geom_Plane(a, axis.Direction());
  for (auto [p, q] : parts) {
    for (int k = 0; k < pieces; ++k) {
      const double t0 = T * k / pieces, t1 = T * (k + 1) / pieces;
      gp_Trsf r0, r1;
      r0.SetRotation(axis, t0);
      r1.SetRotation(axis, t1);
      gp_Pnt p0 = p.Transformed(r0), q0 = q.Transformed(r0), p1 = p.Transformed(r1), q1 = q.Transformed(r1);
      BRepBuilderAPI_MakeWire w;
      w.Add(BRepBuilderAPI_MakeEdge(p0, q0).Edge());
      const TopoDS_Edge outer = path_edge(to_eigen(q0), j, 0.0, t1 - t0, tol);
      if (!outer.IsNull()) w.Add(outer);
      w.Add(BRepBuilderAPI_MakeEdge(q1, p1).Edge());
      const TopoDS_Edge inner = path_edge(to_eigen(p0), j, 0.0, t1 - t0, tol);  // null at the axis
      if (!inner.IsNull()) w.Add(inner);
      if (!w.IsDone()) throw ComputeError("could not build a planar swept face");
      BRepBuilderAPI_MakeFace mf(plane, w.Wire(), true);
      if (!mf.IsDone()) throw ComputeError("could not build a planar swept face");
      out.push_back(mf.Face());
    }
  }
  return out;
}

TopoDS_Edge edge_of(const Handle(Geom_Curve)& c, double first, double last) {
  BRepBuilderAPI_MakeEdge mk(c, first, last);
  if (!mk.IsDone())
    throw ComputeError("could not build an edge on a " + std::string(c->DynamicType()->Name()) + " from " +
                       std::to_string(first) + " to " + std::to_string(last) + " (error " +
                       std::to_string(int(mk.Error())) + ")");
  return mk.Edge();
}

/// The centre O of the sphere about a point of the rotation axis on which a circle lies (its axis
/// meets the rotation axis there), or false.
bool sphere_centre_on_axis(const gp_Circ& circ, const gp_Ax1& axis, double tol, gp_Pnt* centre) {
  const gp_Dir w = axis.Direction(), n = circ.Axis().Direction();
  // perpendicular to the axis: planar
  if (gp_Vec(n).Crossed(gp_Vec(w)).Magnitude() < Settings::parallel_angle) return false;
  // closest points of the circle's axis line C + s n and the rotation axis P + t w
  const gp_Pnt C = circ.Location(), P = axis.Location();
  const gp_Vec d(P, C);
  const double nw = gp_Vec(n).Dot(gp_Vec(w)), den = 1 - nw * nw;
  const double sn = (nw * d.Dot(gp_Vec(w)) - d.Dot(gp_Vec(n))) / den;
  const gp_Pnt onC = C.Translated(gp_Vec(n) * sn);
  const gp_Pnt O = P.Translated(gp_Vec(w) * gp_Vec(P, onC).Dot(gp_Vec(w)));
  // (a circle recognised from fitted points misses the axis by its fitting error)
  const double scale = 1 + circ.Radius() + d.Magnitude();
  if (onC.Distance(O) > std::max(Settings::circle_axis_rounding * scale, Settings::recognised_circle_slack * tol))
    return false;
  *centre = O;
  return true;
}

/// A circle whose axis meets the rotation axis at O lies on the sphere about O through it. A whole
/// turn of an arc of it (its axial coordinate monotonic) sweeps the zone of that sphere between
/// the latitudes of the arc's ends: returned as quarter-turn faces of one spherical surface, with
/// exact iso-parametric edges, instead of general surfaces of revolution (which the arrangement
/// intersects by marching). Empty when the circle lies on no such sphere.
std::vector<TopoDS_Face> sphere_zone(const gp_Circ& circ, const gp_Pnt& a, const gp_Pnt& b, const gp_Ax1& axis,
                                     double tol) {
  const gp_Dir w = axis.Direction();
  gp_Pnt O;
  if (!sphere_centre_on_axis(circ, axis, tol, &O)) return {};
  const double R = std::sqrt(circ.Radius() * circ.Radius() + circ.Location().SquareDistance(O));
  auto latitude = [&](const gp_Pnt& x) {
    return std::asin(std::clamp(gp_Vec(O, x).Dot(gp_Vec(w)) / R, -1.0, 1.0));
  };
  const double va = std::min(latitude(a), latitude(b)), vb = std::max(latitude(a), latitude(b));
  if (vb - va < Settings::sphere_latitude_span_min) return {};
  // a zone through a pole is left to the general revolve (merging faces around the poles of a
  // spherical surface loops in ShapeUpgrade_UnifySameDomain)
  if (va < -M_PI / 2 + Settings::sphere_pole_margin || vb > M_PI / 2 - Settings::sphere_pole_margin) return {};
  gp_Dir xd = w.IsParallel(gp::DX(), 1e-3) ? gp_Dir(gp_Vec(w).Crossed(gp::DY())) : gp_Dir(gp_Vec(w).Crossed(gp::DX()));
  std::vector<TopoDS_Face> out;
  for (int k = 0; k < 4; ++k) {
    // each quarter on its own copy of the sphere, turned to start at its u = 0: faces meeting
    // across a surface's seam come out of the arrangement with pcurves on the wrong side of it
    Handle(Geom_SphericalSurface) sphere =
        new Geom_SphericalSurface(gp_Ax3(O, w, xd.Rotated(gp_Ax1(O, w), k * M_PI / 2)), R);
    BRepBuilderAPI_MakeFace mf(sphere, 0, M_PI / 2, va, vb, tol);
    if (!mf.IsDone()) return {};
    out.push_back(mf.Face());
  }
  return out;
}

/// An arc of a circle in a plane through the rotation axis, its centre off the axis by more than
/// its radius, sweeps a piece of the torus about the axis through it: returned as one face of that
/// torus per piece of at most a quarter turn, bounded by iso-parametric lines (instead of general
/// surfaces of revolution, which the arrangement intersects by marching). Empty otherwise.
std::vector<TopoDS_Face> torus_piece(const Handle(Geom_Circle)& c, double first, double last, const ScrewJoint& j,
                                     double T, double tol) {
  const gp_Circ circ = c->Circ();
  const gp_Vec w = to_vec(j.direction).Normalized(), n(circ.Axis().Direction());
  const gp_Pnt P = to_pnt(j.point), C = circ.Location();
  // (a circle recognised from fitted points is off the plane by its fitting error)
  if (std::abs(n.Dot(w)) * circ.Radius() > Settings::recognised_circle_slack * tol ||
      std::abs(gp_Vec(P, C).Dot(n)) > Settings::recognised_circle_slack * tol)
    return {};
  const gp_Pnt foot = P.Translated(w * gp_Vec(P, C).Dot(w));
  const gp_Vec x(foot, C);
  const double major = x.Magnitude(), minor = circ.Radius();
  if (major <= minor + tol) return {};
  // torus angle v of a point of the circle: from the outward radial direction towards w
  const gp_Vec xd = x / major;
  auto angle = [&](const gp_Pnt& p) {
    const gp_Vec d(C, p);
    return std::atan2(d.Dot(w), d.Dot(xd));
  };
  double v0 = angle(c->Value(first));
  const double span = last - first;  // the arc's angle
  // direction of travel: v increases from xd towards w, counter-clockwise about xd x w; the
  // circle runs counter-clockwise about its normal n, so the two agree when n is along xd x w
  const bool along = gp_Vec(n).Dot(xd.Crossed(w)) > 0;
  double va = v0, vb = v0 + span;
  if (!along) {
    va = v0 - span;
    vb = v0;
  }
  const gp_Ax1 ax(foot, gp_Dir(w));
  auto torus = [&](double turn) {
    return new Geom_ToroidalSurface(gp_Ax3(foot, gp_Dir(w), gp_Dir(xd).Rotated(ax, turn)), major, minor);
  };
  if (torus(0)->Value(0, along ? vb : va).Distance(c->Value(last)) >
      Settings::recognised_circle_slack * tol + Settings::torus_end_rounding * (major + minor))
    return {};
  const int pieces = sweep_pieces(T);
  std::vector<TopoDS_Face> out;
  for (int k = 0; k < pieces; ++k) {
    // each piece on its own copy of the torus, turned to start at its u = 0 (see sphere_zone)
    BRepBuilderAPI_MakeFace mf(torus(T * k / pieces), 0, T / pieces, va, vb, tol);
    if (!mf.IsDone()) return {};
    out.push_back(mf.Face());
  }
  return out;
}

/// Less than a whole turn of an arc of a circle lying on a sphere about a point O of the rotation
/// axis (its axial coordinate monotonic, neither end on the axis) sweeps a patch of that sphere
/// bounded by the arc at both ends of each piece of the turn and the parallels of the arc's ends:
/// returned as one face of the sphere per piece of at most a quarter turn. Empty when the circle
/// lies on no such sphere or a face does not come out valid with the area of the patch
/// (R^2 dt (sin b - sin a) for latitudes a < b and a turn dt, whatever the arc's shape).
std::vector<TopoDS_Face> sphere_patch(const Handle(Geom_Circle)& c, double first, double last, const ScrewJoint& j,
                                      double T, double tol) {
  const gp_Ax1 axis(to_pnt(j.point), gp_Dir(to_vec(j.direction)));
  gp_Pnt O;
  if (!sphere_centre_on_axis(c->Circ(), axis, tol, &O)) return {};
  const gp_Dir w = axis.Direction();
  const gp_Pnt a = c->Value(first), b = c->Value(last), m = c->Value(0.5 * (first + last));
  const double R = O.Distance(a);
  auto latitude = [&](const gp_Pnt& x) { return std::asin(std::clamp(gp_Vec(O, x).Dot(gp_Vec(w)) / R, -1.0, 1.0)); };
  const double la = latitude(a), lb = latitude(b);
  if (std::abs(lb - la) < Settings::sphere_latitude_span_min) return {};
  if (std::max(std::abs(la), std::abs(lb)) > M_PI / 2 - Settings::sphere_pole_margin) return {};  // an end on the axis
  const int pieces = sweep_pieces(T);
  const TopoDS_Edge arc = edge_of(c, first, last);
  std::vector<TopoDS_Face> out;
  for (int k = 0; k < pieces; ++k) {
    const double t0 = T * k / pieces, t1 = T * (k + 1) / pieces;
    gp_Trsf r0, r1, rm;
    r0.SetRotation(axis, t0);
    r1.SetRotation(axis, t1);
    // the sphere's seam half a turn from the middle of the patch
    rm.SetRotation(axis, 0.5 * (t0 + t1) + M_PI);
    gp_Vec radial(O, m.Transformed(rm));
    radial -= gp_Vec(w) * radial.Dot(gp_Vec(w));
    if (radial.Magnitude() < Settings::on_axis_resolution * R) return {};
    Handle(Geom_SphericalSurface) sphere = new Geom_SphericalSurface(gp_Ax3(O, w, gp_Dir(radial)), R);
    const TopoDS_Edge e0 = TopoDS::Edge(BRepBuilderAPI_Transform(arc, r0, true).Shape());
    const TopoDS_Edge e1 = TopoDS::Edge(BRepBuilderAPI_Transform(arc, r1, true).Shape());
    const TopoDS_Edge pa = path_edge(to_eigen(a.Transformed(r0)), j, 0.0, t1 - t0, tol);
    const TopoDS_Edge pb = path_edge(to_eigen(b.Transformed(r0)), j, 0.0, t1 - t0, tol);
    if (pa.IsNull() || pb.IsNull()) return {};
    BRepBuilderAPI_MakeWire mw;
    mw.Add(e0);
    mw.Add(pb);
    mw.Add(TopoDS::Edge(e1.Reversed()));
    mw.Add(TopoDS::Edge(pa.Reversed()));
    if (!mw.IsDone()) return {};
    // the wire runs counter-clockwise about the sphere's normal or clockwise, as the arc runs
    // up or down: the orientation giving a positive area is kept
    TopoDS_Face f;
    GProp_GProps g;
    for (const TopoDS_Wire& wire : {mw.Wire(), TopoDS::Wire(mw.Wire().Reversed())}) {
      BRepBuilderAPI_MakeFace mf(sphere, wire, true);
      if (!mf.IsDone()) return {};
      ShapeFix_Face fix(mf.Face());
      fix.SetPrecision(tol);
      fix.Perform();
      f = fix.Face();
      g = GProp_GProps();
      BRepGProp::SurfaceProperties(f, g, Settings::sphere_patch_area_precision);
      if (g.Mass() > 0) break;
    }
    tighten_pcurves(f, std::max(tol, 1e-9));
    if (!BRepCheck_Analyzer(f).IsValid()) return {};
    const double area = R * R * (t1 - t0) * std::abs(std::sin(lb) - std::sin(la));
    if (std::abs(g.Mass() - area) > Settings::area_relative_tolerance * area) return {};
    out.push_back(f);
  }
  return out;
}

}  // namespace

namespace {
/// How far the edge's pcurve on the face strays from the edge: along it (against the 3-D curve)
/// and at its ends (against the vertices).
double pcurve_gap(const TopoDS_Edge& e, const TopoDS_Face& face, const Handle(Geom_Surface)& surface) {
  double dev = 0;
  ShapeAnalysis_Edge().CheckSameParameter(e, face, dev, Settings::pcurve_gap_samples);
  double f, l;
  const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, face, f, l);
  if (pc.IsNull()) return dev;
  for (TopExp_Explorer vx(e, TopAbs_VERTEX); vx.More(); vx.Next()) {
    const TopoDS_Vertex& v = TopoDS::Vertex(vx.Current());
    const gp_Pnt2d uv = pc->Value(BRep_Tool::Parameter(v, e, face));
    dev = std::max(dev, surface->Value(uv.X(), uv.Y()).Distance(BRep_Tool::Pnt(v)));
  }
  return dev;
}
}  // namespace

void tighten_pcurves(const TopoDS_Face& face, double tol) {
  BRep_Builder bb;
  TopLoc_Location loc;
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(face, loc);
  if (!loc.IsIdentity()) return;
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    TopoDS_Edge e = TopoDS::Edge(ex.Current());
    if (BRep_Tool::Degenerated(e) || BRep_Tool::IsClosed(e, face)) continue;
    const double dev = pcurve_gap(e, face, surface);
    if (dev <= tol) continue;
    double f, l;
    TopLoc_Location cl;
    Handle(Geom_Curve) c = BRep_Tool::Curve(e, cl, f, l);
    if (c.IsNull() || !cl.IsIdentity()) continue;
    double achieved = tol;
    Handle(Geom2d_Curve) pc = GeomProjLib::Curve2d(c, f, l, surface, achieved);
    if (pc.IsNull()) continue;
    double pf, pl;
    const Handle(Geom2d_Curve) old = BRep_Tool::CurveOnSurface(e, face, pf, pl);
    const double edge_tol = BRep_Tool::Tolerance(e);
    bb.UpdateEdge(e, pc, face, edge_tol);
    bb.Range(e, face, f, l);
    const double dev2 = pcurve_gap(e, face, surface);
    if (dev2 < dev) {
      bb.UpdateEdge(e, std::max(Settings::edge_tolerance_margin * dev2, 1e-7));
    } else {  // the projection is no better: the old pcurve stays
      bb.UpdateEdge(e, old, face, edge_tol);
      bb.Range(e, face, pf, pl);
    }
  }
}

Handle(Geom_Curve) canonical_curve(const Handle(Geom_Curve)& c0, double& first, double& last, double tol) {
  Handle(Geom_Curve) c = c0;
  while (c->IsKind(STANDARD_TYPE(Geom_TrimmedCurve))) c = Handle(Geom_TrimmedCurve)::DownCast(c)->BasisCurve();
  if (c->IsKind(STANDARD_TYPE(Geom_Line)) || c->IsKind(STANDARD_TYPE(Geom_Circle))) return c;
  gp_Pnt a = c->Value(first), m = c->Value(0.5 * (first + last)), b = c->Value(last);
  gp_Pnt q = c->Value(first + 0.25 * (last - first));
  if (a.Distance(b) > tol) {
    Handle(Geom_Line) line = new Geom_Line(a, gp_Dir(gp_Vec(a, b)));
    if (matches(c, first, last, line, tol)) {
      double f = ElCLib::Parameter(line->Lin(), a), l = ElCLib::Parameter(line->Lin(), b);
      first = f;
      last = l;
      return line;
    }
  }
  // circle through three points (a, q, m) or (a, m, b)
  for (auto tri : {std::array<gp_Pnt, 3>{a, q, m}, std::array<gp_Pnt, 3>{a, m, b}}) {
    GC_MakeArcOfCircle mk(tri[0], tri[1], tri[2]);
    if (!mk.IsDone()) continue;
    Handle(Geom_Circle) circ = Handle(Geom_Circle)::DownCast(mk.Value()->BasisCurve());
    if (circ.IsNull() || !matches(c, first, last, circ, tol)) continue;
    // parameters: follow the direction of travel of c
    double f = ElCLib::Parameter(circ->Circ(), a);
    double mid = ElCLib::Parameter(circ->Circ(), m);
    double l = ElCLib::Parameter(circ->Circ(), b);
    if (mid < f) mid += 2 * M_PI;
    if (l <= f + Settings::angle_resolution) l += 2 * M_PI;
    if (mid > l) {  // travel is clockwise: reverse the circle's axis
      gp_Circ cc = circ->Circ();
      gp_Ax2 ax = cc.Position();
      ax.SetDirection(ax.Direction().Reversed());
      circ = new Geom_Circle(gp_Circ(ax, cc.Radius()));
      f = ElCLib::Parameter(circ->Circ(), a);
      l = ElCLib::Parameter(circ->Circ(), b);
      if (l <= f + Settings::angle_resolution) l += 2 * M_PI;
    }
    if (a.Distance(b) <= tol) l = f + 2 * M_PI;
    first = f;
    last = l;
    return circ;
  }
  return c0;
}

std::vector<double> axial_breaks(const Handle(Geom_Curve)& c, double first, double last, const ScrewJoint& j) {
  const gp_Vec w = to_vec(j.direction);
  auto da = [&](double u) {
    gp_Pnt p;
    gp_Vec d;
    c->D1(u, p, d);
    return d.Dot(w);
  };
  const int n = Settings::profile_cut_samples;
  std::vector<double> cuts;
  double amin = 1e300, amax = -1e300;
  for (int k = 0; k <= n; ++k) {
    double a = gp_Vec(c->Value(first + (last - first) * k / n).XYZ()).Dot(w);
    amin = std::min(amin, a);
    amax = std::max(amax, a);
  }
  if (amax - amin <= Settings::profile_axial_flat * (1 + std::abs(amax))) return cuts;
  std::vector<double> u(n + 1), d(n + 1);
  double dmax = 0;
  for (int k = 0; k <= n; ++k) {
    u[k] = first + (last - first) * k / n;
    d[k] = da(u[k]);
    dmax = std::max(dmax, std::abs(d[k]));
  }
  const double zero = Settings::profile_slope_zero * dmax;
  for (int k = 1; k <= n; ++k) {
    if (k < n && std::abs(d[k]) <= zero) {
      cuts.push_back(u[k]);
      continue;
    }
    if (std::abs(d[k - 1]) <= zero || std::abs(d[k]) <= zero || (d[k - 1] > 0) == (d[k] > 0)) continue;
    double lo = u[k - 1], hi = u[k], flo = d[k - 1];
    for (int it = 0; it < Settings::profile_cut_bisections; ++it) {
      double m = 0.5 * (lo + hi), fm = da(m);
      if ((fm > 0) == (flo > 0)) { lo = m; flo = fm; } else hi = m;
    }
    const double cut = 0.5 * (lo + hi);
    // an axial turn at an end (within rounding of the sampled derivative) makes no piece
    if (cut - first > Settings::profile_cut_end * (last - first) &&
        last - cut > Settings::profile_cut_end * (last - first))
      cuts.push_back(cut);
  }
  return cuts;
}

/// The parameters inside (first, last) where the curve meets the joint's axis (within `tol`): a
/// revolution cannot carry a curve across its axis, the pieces on either side sweep separately.
std::vector<double> axis_crossings(const Handle(Geom_Curve)& c, double first, double last, const ScrewJoint& j,
                                   double tol) {
  const gp_Vec w = to_vec(j.direction);
  const gp_Pnt p0 = to_pnt(j.point);
  auto radial = [&](const gp_Vec& v) { return v - w * v.Dot(w); };
  auto dist = [&](double u) { return radial(gp_Vec(p0, c->Value(u))).Magnitude(); };
  // the derivative of the squared distance to the axis: minima where it turns from - to +
  auto slope = [&](double u) {
    gp_Pnt p;
    gp_Vec d;
    c->D1(u, p, d);
    return radial(gp_Vec(p0, p)).Dot(radial(d));
  };
  const int n = Settings::profile_cut_samples;
  std::vector<double> cuts;
  std::vector<double> u(n + 1), g(n + 1);
  for (int k = 0; k <= n; ++k) u[k] = first + (last - first) * k / n, g[k] = slope(u[k]);
  for (int k = 1; k <= n; ++k) {
    if (!(g[k - 1] < 0 && g[k] >= 0)) continue;
    double lo = u[k - 1], hi = u[k];
    for (int it = 0; it < Settings::profile_cut_bisections; ++it) {
      const double m = 0.5 * (lo + hi);
      (slope(m) < 0 ? lo : hi) = m;
    }
    const double at = 0.5 * (lo + hi);
    if (dist(at) > tol) continue;
    if (at - first > Settings::profile_cut_end * (last - first) &&
        last - at > Settings::profile_cut_end * (last - first))
      cuts.push_back(at);
  }
  return cuts;
}

namespace {

/// The face swept by c on [s0, s1] under the screw for q in [q0, q1], fitted on a grid of exact
/// points; a span that no grid fits to `tol` is halved and each half fitted on its own.
void helical_piece(const Handle(Geom_Curve)& c, double s0, double s1, const ScrewJoint& j, double q0, double q1,
                   double tol, int depth, std::vector<TopoDS_Face>& out, double* fit_error) {
  // (the grid runs through q at fixed s: the curve point is evaluated once per s)
  double last_fs = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector3d p;
  auto exact = [&](double fs, double fq) {
    if (fs != last_fs) p = to_eigen(c->Value(s0 + (s1 - s0) * fs)), last_fs = fs;
    return to_pnt(j.transform(q0 + (q1 - q0) * fq) * p);
  };
  double err = 0;
  const Handle(Geom_BSplineSurface) best =
      fit_grid_surface(exact, tol, Settings::helical_fit_approx * tol, Settings::helical_fit_grid_first,
                       Settings::helical_fit_grid_last, &err);
  if ((best.IsNull() || err > tol) && depth < Settings::helical_fit_splits) {
    const double mid = 0.5 * (s0 + s1);
    helical_piece(c, s0, mid, j, q0, q1, tol, depth + 1, out, fit_error);
    helical_piece(c, mid, s1, j, q0, q1, tol, depth + 1, out, fit_error);
    return;
  }
  if (best.IsNull()) throw ComputeError("could not fit a helical swept face");
  *fit_error = std::max(*fit_error, err);
  double a0, a1, b0, b1;
  best->Bounds(a0, a1, b0, b1);
  out.push_back(make_face(best, a0, a1, b0, b1, tol));
}

}  // namespace

std::vector<TopoDS_Face> sweep_curve(const Handle(Geom_Curve)& c, double first, double last,
                                     const ScrewJoint& j, double T, double tol, double* fit_error,
                                     HelicalFaces helical) {
  std::vector<TopoDS_Face> out;
  if (slides_along(c, first, last, j) || on_axis(c, first, last, j, tol)) return out;
  if (c->IsKind(STANDARD_TYPE(Geom_Line)) && j.type == JointType::Revolute) {
    gp_Pnt a = c->Value(first), b = c->Value(last);
    gp_Vec d(a, b);
    if (std::abs(d.Normalized().Dot(to_vec(j.direction))) < Settings::planar_segment_cosine)
      return planar_segment_sweep(a, b, j, T, tol);
  }
  auto faces_of = [&](const TopoDS_Shape& sh) {
    for (TopExp_Explorer ex(sh, TopAbs_FACE); ex.More(); ex.Next()) out.push_back(TopoDS::Face(ex.Current()));
  };
  if (j.type == JointType::Prismatic) {
    // BRepSweep gives exact planes and cylinders where the curve is a line or a circle.
    TopoDS_Edge e = edge_of(c, first, last);
    BRepPrimAPI_MakePrism mk(e, to_vec(j.direction) * T);
    if (!mk.IsDone()) throw ComputeError("could not extrude a curve");
    faces_of(mk.Shape());
    return out;
  }
  const bool screw = j.type == JointType::Helical && std::abs(j.pitch) > 0;
  // Pieces of at most a quarter turn never overlap themselves.
  const int pieces = sweep_pieces(T);
  if (!screw) {
    // Two points of one curve at the same axial height and radius would sweep the same circle:
    // split the curve where its axial coordinate turns, so each piece sweeps one-to-one.
    std::vector<double> cuts = axial_breaks(c, first, last, j);
    if (cuts.empty()) cuts = axis_crossings(c, first, last, j, std::max(tol, 1e-7));
    if (!cuts.empty()) {
      double a = first;
      cuts.push_back(last);
      for (double b : cuts) {
        auto part = sweep_curve(c, a, b, j, T, tol, fit_error, helical);
        out.insert(out.end(), part.begin(), part.end());
        a = b;
      }
      return out;
    }
    const gp_Ax1 axis(to_pnt(j.point), gp_Dir(to_vec(j.direction)));
    if (const Handle(Geom_Circle) circle = Handle(Geom_Circle)::DownCast(c); !circle.IsNull()) {
      // exact spheres and tori where the circle lies on one about the axis
      const bool whole = T >= 2 * M_PI - Settings::angle_resolution;
      auto exact = whole ? sphere_zone(circle->Circ(), c->Value(first), c->Value(last), axis, tol)
                         : std::vector<TopoDS_Face>{};
      if (exact.empty()) exact = torus_piece(circle, first, last, j, T, tol);
      if (exact.empty() && !whole) exact = sphere_patch(circle, first, last, j, T, tol);
      if (!exact.empty()) return exact;
    }
    TopoDS_Edge e = edge_of(c, first, last);
    for (int k = 0; k < pieces; ++k) {
      gp_Trsf r;
      r.SetRotation(axis, T * k / pieces);
      TopoDS_Shape ek = BRepBuilderAPI_Transform(e, r, true).Shape();
      BRepPrimAPI_MakeRevol mk(ek, axis, T / pieces);
      if (!mk.IsDone()) {
        gp_Pnt a = c->Value(first), b = c->Value(last);
        throw ComputeError("could not revolve a " + std::string(c->DynamicType()->Name()) + " from (" +
                           std::to_string(a.X()) + ", " + std::to_string(a.Y()) + ", " + std::to_string(a.Z()) + ") to (" +
                           std::to_string(b.X()) + ", " + std::to_string(b.Y()) + ", " + std::to_string(b.Z()) + ")");
      }
      faces_of(mk.Shape());
    }
    return out;
  }
  // Helical: each piece a tensor-product spline of the curve's poles' helices, or fitted to
  // tolerance on a grid of exact points T(q) c(s). (Copies of the first piece carried by the screw
  // would save the work, but OCCT's mesher leaves their triangulation open and the verdict falls
  // back to the slow classifier.)
  for (int k = 0; k < pieces; ++k) {
    const double q0 = T * k / pieces, q1 = T * (k + 1) / pieces;
    double err = 0;
    const Handle(Geom_BSplineSurface) s =
        helical == HelicalFaces::Spline ? helical_spline_surface(c, first, last, j, q0, q1, tol, &err) : nullptr;
    if (!s.IsNull() && err <= tol) {
      *fit_error = std::max(*fit_error, err);
      double a0, a1, b0, b1;
      s->Bounds(a0, a1, b0, b1);
      out.push_back(make_face(s, a0, a1, b0, b1, tol));
      continue;
    }
    helical_piece(c, first, last, j, q0, q1, tol, 0, out, fit_error);
  }
  return out;
}

Handle(Geom_BSplineSurface) helical_spline_surface(const Handle(Geom_Curve)& c, double s0, double s1,
                                                   const ScrewJoint& j, double q0, double q1, double tol,
                                                   double* err) {
  Handle(Geom_Curve) basis = c;
  while (const Handle(Geom_TrimmedCurve) tc = Handle(Geom_TrimmedCurve)::DownCast(basis)) basis = tc->BasisCurve();
  if (!basis->IsKind(STANDARD_TYPE(Geom_Line)) && !basis->IsKind(STANDARD_TYPE(Geom_Circle)) &&
      !basis->IsKind(STANDARD_TYPE(Geom_Ellipse)) && !basis->IsKind(STANDARD_TYPE(Geom_BSplineCurve)) &&
      !basis->IsKind(STANDARD_TYPE(Geom_BezierCurve)))
    return nullptr;
  const Handle(Geom_BSplineCurve) b = GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(basis, s0, s1));
  if (b.IsNull()) return nullptr;
  if (b->IsPeriodic()) b->SetNotPeriodic();
  // each pole split along the axis and across it, the across part's quarter turn ahead beside it
  const Eigen::Vector3d p = j.point, d = j.direction;
  const int nu = b->NbPoles();
  std::vector<Eigen::Vector3d> along(nu), across(nu), ahead(nu);
  double reach = 0;
  for (int i = 0; i < nu; ++i) {
    const Eigen::Vector3d y = to_eigen(b->Pole(i + 1)) - p;
    along[i] = p + d * y.dot(d);
    across[i] = y - d * y.dot(d);
    ahead[i] = d.cross(across[i]);
    reach = std::max(reach, across[i].norm());
  }
  if (reach <= 0) return nullptr;
  const TrigBezier trig = trig_bezier(q0, q1, Settings::helical_spline_share * tol / reach);
  const int nv = int(trig.cos.size());
  TColgp_Array2OfPnt poles(1, nu, 1, nv);
  TColStd_Array2OfReal weights(1, nu, 1, nv);
  for (int i = 0; i < nu; ++i)
    for (int k = 0; k < nv; ++k) {
      const double q = q0 + (q1 - q0) * k / (nv - 1);  // (q itself is linear in the Bernstein basis)
      poles.SetValue(i + 1, k + 1,
                     to_pnt(along[i] + trig.cos[k] * across[i] + trig.sin[k] * ahead[i] + d * (j.pitch * q)));
      weights.SetValue(i + 1, k + 1, b->Weight(i + 1));
    }
  TColStd_Array1OfReal uknots(1, b->NbKnots()), vknots(1, 2);
  TColStd_Array1OfInteger umults(1, b->NbKnots()), vmults(1, 2);
  b->Knots(uknots);
  b->Multiplicities(umults);
  vknots.SetValue(1, q0), vknots.SetValue(2, q1);
  vmults.SetValue(1, nv), vmults.SetValue(2, nv);
  const Handle(Geom_BSplineSurface) s =
      new Geom_BSplineSurface(poles, weights, uknots, vknots, umults, vmults, b->Degree(), nv - 1, false, false);
  // the bound, and what a grid of exact points measures (which also holds the construction to it)
  double measured = 0;
  const int n = 8;
  for (int a = 0; a <= n; ++a)
    for (int k = 0; k <= n; ++k) {
      const double u = b->FirstParameter() + (b->LastParameter() - b->FirstParameter()) * a / n;
      const double q = q0 + (q1 - q0) * k / n;
      const gp_Pnt exact = to_pnt(j.transform(q) * to_eigen(b->Value(u)));
      measured = std::max(measured, s->Value(u, q).Distance(exact));
    }
  *err = std::max(trig.error * reach, measured);
  return s;
}

Handle(Geom_BSplineSurface) fit_grid_surface(const std::function<gp_Pnt(double, double)>& exact, double tol,
                                             double approx_tol, int n0, int nmax, double* err) {
  Handle(Geom_BSplineSurface) best;
  double best_err = std::numeric_limits<double>::infinity();
  for (int n = n0; n <= nmax; n *= 2) {
    TColgp_Array2OfPnt pts(1, n + 1, 1, n + 1);
    for (int a = 0; a <= n; ++a)
      for (int b = 0; b <= n; ++b) pts.SetValue(a + 1, b + 1, exact(double(a) / n, double(b) / n));
    GeomAPI_PointsToBSplineSurface fit;
    fit.Init(pts, Approx_IsoParametric, 3, 8, GeomAbs_C2, approx_tol);
    if (!fit.IsDone()) continue;
    Handle(Geom_BSplineSurface) s = fit.Surface();
    double a0, a1, b0, b1;
    s->Bounds(a0, a1, b0, b1);
    const GeomAdaptor_Surface fitted(s);  // (evaluates through a cache of the span's polynomial)
    double e = 0;
    for (int a = 0; a < 2 * n; ++a)
      for (int b = 0; b < 2 * n; ++b) {
        const double fu = (a + 0.5) / (2 * n), fv = (b + 0.5) / (2 * n);
        e = std::max(e, fitted.Value(a0 + (a1 - a0) * fu, b0 + (b1 - b0) * fv).Distance(exact(fu, fv)));
      }
    if (e < best_err) best = s, best_err = e;
    if (e <= tol) break;
  }
  if (!best.IsNull()) *err = best_err;
  return best;
}

}  // namespace sweep::occt
