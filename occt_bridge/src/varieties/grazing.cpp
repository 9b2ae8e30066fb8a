// Grazing curves: where a motion's velocity field at one instant is tangent to a face, g = n . v = 0.
// The zero set is traced on a grid over the face's parameter domain (marching squares, every
// point an exact root of g on a grid line or a crossing point of two branches), densified with
// roots on lines across the chords, clipped to the face's trimmed domain (ending exactly on the
// roots of g along its boundary edges) and fitted by a B-spline curve whose distance from the exact
// curve is measured between the points.
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRep_Builder.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <ElCLib.hxx>
#include <GC_MakeCircle.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Line.hxx>
#include <gp_Circ.hxx>
#include <gp_Lin.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <cmath>
#include <optional>

#include "base/internal.hpp"
#include "sweep/contour.hpp"

namespace sweep::occt {
namespace {

using UV = Eigen::Vector2d;

struct Field {
  BRepAdaptor_Surface S;
  VelocityField velocity;
  double u0, u1, v0, v1;
  bool uper = false, vper = false;
  double uP = 0, vP = 0;

  Field(const TopoDS_Face& f, const VelocityField& v) : S(f), velocity(v) {}

  /// n . v with the unit normal and the velocity of the point; 0 where the normal is undefined.
  double g(const UV& p) const {
    gp_Pnt P;
    gp_Vec Du, Dv;
    S.D1(p.x(), p.y(), P, Du, Dv);
    gp_Vec N = Du.Crossed(Dv);
    double n = N.Magnitude();
    if (n < Settings::parametric_pole * (Du.Magnitude() + Dv.Magnitude() + 1e-300) || n < 1e-300) {
      // a pole of the parametrization: take the normal's limit from just inside the domain
      const double eu = Settings::pole_normal_offset * (u1 - u0) * (p.x() < 0.5 * (u0 + u1) ? 1 : -1);
      const double ev = Settings::pole_normal_offset * (v1 - v0) * (p.y() < 0.5 * (v0 + v1) ? 1 : -1);
      gp_Pnt Q;
      S.D1(p.x() + eu, p.y() + ev, Q, Du, Dv);
      N = Du.Crossed(Dv);
      n = N.Magnitude();
      if (n < 1e-300) return 0.0;
    }
    return N.Dot(to_vec(velocity.at(to_eigen(P)))) / n;
  }
  gp_Pnt point(const UV& p) const { return S.Value(p.x(), p.y()); }
};

/// The point of the grazing set near p: p projected onto the face's surface, then moved in the
/// parameter plane along the gradient of g to g = 0.
gp_Pnt grazing_point_near(const Field& F, ShapeAnalysis_Surface& projector, const gp_Pnt& p) {
  const double hu = Settings::grazing_gradient_step * (F.u1 - F.u0);
  const double hv = Settings::grazing_gradient_step * (F.v1 - F.v0);
  // (near a crossing of two branches the gradient vanishes: no step beyond Settings::grazing_point_step
  // of the domain)
  const double cap = Settings::grazing_point_step * std::max(F.u1 - F.u0, F.v1 - F.v0);
  const gp_Pnt2d uv0 = projector.ValueOfUV(p, Settings::surface_projection_precision);
  UV uv(uv0.X(), uv0.Y());
  for (int it = 0; it < 4; ++it) {
    const double g = F.g(uv);
    const UV grad((F.g(uv + UV(hu, 0)) - F.g(uv - UV(hu, 0))) / (2 * hu),
                  (F.g(uv + UV(0, hv)) - F.g(uv - UV(0, hv))) / (2 * hv));
    const double n2 = grad.squaredNorm();
    if (!(n2 > 0)) break;
    UV step = g / n2 * grad;
    if (step.norm() > cap) step *= cap / step.norm();
    uv -= step;
  }
  return F.point(uv);
}

/// The largest distance of curve c from the exact grazing curve, at eight points per knot span
/// (the distance to grazing_point_near bounds the true one from above).
double distance_from_grazing(const Field& F, ShapeAnalysis_Surface& projector, const Handle(Geom_BSplineCurve)& c) {
  double worst = 0;
  const int spans = c->NbKnots() - 1;
  for (int s = 1; s <= spans; ++s)
    for (int k = 0; k < 8; ++k) {
      const gp_Pnt p = c->Value(c->Knot(s) + (c->Knot(s + 1) - c->Knot(s)) * (k + 0.5) / 8);
      worst = std::max(worst, p.Distance(grazing_point_near(F, projector, p)));
    }
  return worst;
}

/// A B-spline through the exact points q of a grazing curve: approximated to a tenth of tol, or,
/// where that strays between the points (an approximation that cannot meet its tolerance ends in
/// wiggles), interpolated by a cubic; while that does not keep within tol, through twice the
/// points (up to three times). *error: the measured distance from the exact curve of the curve returned.
Handle(Geom_BSplineCurve) fitted_curve(const Field& F, ShapeAnalysis_Surface& projector, std::vector<gp_Pnt> q,
                                       double tol, double* error) {
  *error = 1e300;
  Handle(Geom_BSplineCurve) best;
  auto consider = [&](const Handle(Geom_BSplineCurve)& c) {
    if (c.IsNull()) return;
    const double e = distance_from_grazing(F, projector, c);
    if (e < *error) {
      best = c;
      *error = e;
    }
  };
  for (int round = 0; round < 4 && *error > tol; ++round) {
    if (round > 0) {
      std::vector<gp_Pnt> denser{q.front()};
      for (std::size_t k = 1; k < q.size(); ++k) {
        const gp_Pnt mid((q[k - 1].XYZ() + q[k].XYZ()) * 0.5);
        const gp_Pnt exact = grazing_point_near(F, projector, mid);
        // (a midpoint whose grazing point is not between its neighbours is left out)
        if (exact.Distance(mid) <= 0.5 * q[k - 1].Distance(q[k])) denser.push_back(exact);
        denser.push_back(q[k]);
      }
      q = std::move(denser);
    }
    TColgp_Array1OfPnt arr(1, int(q.size()));
    for (std::size_t k = 0; k < q.size(); ++k) arr.SetValue(int(k) + 1, q[k]);
    if (q.size() == 2) {
      GeomAPI_PointsToBSpline fit(arr, 1, 1, GeomAbs_C0, tol);
      if (fit.IsDone()) consider(fit.Curve());
      continue;
    }
    if (round == 0) {  // (with more points than this an approximation costs much and fails alike)
      GeomAPI_PointsToBSpline fit(arr, 3, 8, GeomAbs_C2, 0.1 * tol);
      if (fit.IsDone()) consider(fit.Curve());
      if (*error <= tol) break;
    }
    Handle(TColgp_HArray1OfPnt) pts = new TColgp_HArray1OfPnt(1, int(q.size()));
    for (std::size_t k = 0; k < q.size(); ++k) pts->SetValue(int(k) + 1, q[k]);
    GeomAPI_Interpolate interp(pts, false, Settings::grazing_interpolation_tolerance);
    interp.Perform();
    if (interp.IsDone()) consider(interp.Curve());
  }
  return best;
}

}  // namespace

/// The roots of g along the face's real boundary edges (not seams, not degenerate): exact ends of
/// the grazing chains that leave the face.
std::vector<gp_Pnt> boundary_roots_of(const TopoDS_Face& face, Field& F) {
  std::vector<gp_Pnt> boundary_roots;
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    TopoDS_Edge e = TopoDS::Edge(ex.Current());
    if (BRep_Tool::Degenerated(e) || BRep_Tool::IsClosed(e, face)) continue;
    double f, l;
    Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, face, f, l);
    if (pc.IsNull()) continue;
    const int n = Settings::grazing_boundary_samples;
    double gprev = 0;
    for (int k = 0; k <= n; ++k) {
      gp_Pnt2d q = pc->Value(f + (l - f) * k / n);
      UV cur(q.X(), q.Y());
      double gc = F.g(cur);
      if (k > 0 && (gc > 0) != (gprev > 0)) {
        double s = root_in_unit(
            [&](double t) {
              gp_Pnt2d r = pc->Value(f + (l - f) * (k - 1 + t) / n);
              return F.g(UV(r.X(), r.Y()));
            },
            gprev, gc);
        gp_Pnt2d r = pc->Value(f + (l - f) * (k - 1 + s) / n);
        boundary_roots.push_back(F.point(UV(r.X(), r.Y())));
      }
      gprev = gc;
    }
  }

  return boundary_roots;
}

/// The points as an exact line or circle when they lie on one within etol (the grazing curves of
/// planes, spheres, cylinders...: the points are roots of g to rounding, so three of them define
/// the curve); none otherwise.
std::optional<GrazingCurve> exact_line_or_circle(const std::vector<gp_Pnt>& q, double etol) {
  auto all_within = [&](auto dist) {
    for (const auto& p : q)
      if (dist(p) > etol) return false;
    return true;
  };
  const gp_Pnt a = q.front(), b = q.back();
  if (a.Distance(b) > etol) {
    gp_Lin lin(a, gp_Dir(gp_Vec(a, b)));
    if (all_within([&](const gp_Pnt& p) { return lin.Distance(p); })) {
      GrazingCurve gc;
      gc.curve = new Geom_Line(lin);
      gc.first = 0;
      gc.last = a.Distance(b);
      return gc;
    }
  }
  gp_Pnt m1 = q[q.size() / 3], m2 = q[(2 * q.size()) / 3];
  GC_MakeCircle mk(a, m1, m2);
  if (q.size() >= 6 && mk.IsDone()) {
    gp_Circ circ = mk.Value()->Circ();
    if (all_within([&](const gp_Pnt& p) { return circ.Distance(p); })) {
      // orient the circle so that its parameter follows the points
      double f = ElCLib::Parameter(circ, a), t1 = ElCLib::Parameter(circ, m1);
      if (std::remainder(t1 - f, 2 * M_PI) < 0) {
        gp_Ax2 ax = circ.Position();
        ax.SetDirection(ax.Direction().Reversed());
        circ = gp_Circ(ax, circ.Radius());
        f = ElCLib::Parameter(circ, a);
      }
      double l = ElCLib::Parameter(circ, b);
      while (l <= f + Settings::angle_resolution) l += 2 * M_PI;
      while (l > f + 2 * M_PI + Settings::angle_resolution) l -= 2 * M_PI;
      if (a.Distance(b) <= etol) l = f + 2 * M_PI;
      GrazingCurve gc;
      gc.curve = new Geom_Circle(circ);
      gc.first = f;
      gc.last = l;
      return gc;
    }
  }
  return std::nullopt;
}

std::vector<GrazingCurve> grazing_curves(const TopoDS_Face& face, const VelocityField& velocity, double tol,
                                         double size) {
  Field F(face, velocity);
  BRepTools::UVBounds(face, F.u0, F.u1, F.v0, F.v1);
  ShapeAnalysis_Surface projector(BRep_Tool::Surface(face));
  // Periodic directions: trace over a window shifted by an irrational fraction of the period,
  // so that no grazing line sits on the window's border.
  double ua = F.u0, ub = F.u1, va = F.v0, vb = F.v1;
  if (F.S.IsUPeriodic() && std::abs((F.u1 - F.u0) - F.S.UPeriod()) < Settings::whole_period_margin) {
    F.uper = true;
    F.uP = F.S.UPeriod();
    ua += 0.3819660112501051 * F.uP * 0.1;
    ub = ua + F.uP;
  }
  if (F.S.IsVPeriodic() && std::abs((F.v1 - F.v0) - F.S.VPeriod()) < Settings::whole_period_margin) {
    F.vper = true;
    F.vP = F.S.VPeriod();
    va += 0.3819660112501051 * F.vP * 0.1;
    vb = va + F.vP;
  }
  const double vscale = size + velocity.reach();
  const ContourFunction g = [&F](const UV& p) { return F.g(p); };
  auto chains = contour_chains(g, ua, ub, va, vb, Settings::grazing_curve_grid_u, Settings::grazing_curve_grid_v,
                               Settings::grazing_curve_flat * vscale);
  if (chains.empty()) return {};  // none: the face slides within itself

  // Trimmed domain: keep the parts inside the face.
  const double uvtol = Settings::parameter_resolution * std::max(ub - ua, vb - va);
  BRepTopAdaptor_FClass2d cls(face, uvtol);
  auto wrap = [&](UV p) {
    if (F.uper && p.x() > F.u1) p.x() -= F.uP;
    if (F.vper && p.y() > F.v1) p.y() -= F.vP;
    return p;
  };
  auto state = [&](const UV& p) { return cls.Perform(gp_Pnt2d(wrap(p).x(), wrap(p).y())); };

  // exact ends of the chains that leave the face
  const std::vector<gp_Pnt> boundary_roots = boundary_roots_of(face, F);

  std::vector<GrazingCurve> out;
  for (auto& chain : chains) {
    // drop chains lying on the face boundary: the sweeps of the boundary edges cover them
    bool all_on = true;
    for (const auto& p : chain)
      if (state(p) != TopAbs_ON) { all_on = false; break; }
    if (all_on) {
      // On a seam the face lies on both sides: the chain is interior after all.
      const UV m = chain[chain.size() / 2];
      const double eu = Settings::seam_probe_offset * (ub - ua), ev = Settings::seam_probe_offset * (vb - va);
      auto inside = [&](UV q) {
        if (F.uper && q.x() < F.u0) q.x() += F.uP;
        if (F.vper && q.y() < F.v0) q.y() += F.vP;
        return state(q) == TopAbs_IN;
      };
      const bool seam = (inside(m + UV(eu, 0)) && inside(m - UV(eu, 0))) ||
                        (inside(m + UV(0, ev)) && inside(m - UV(0, ev)));
      if (!seam) continue;
    }
    // split into runs inside the face
    std::vector<std::vector<gp_Pnt>> runs;
    std::vector<UV> run;
    auto snap = [&](const UV& in, const UV& out_) {
      UV a = in, b = out_;
      for (int it = 0; it < Settings::grazing_boundary_bisections; ++it) {
        UV m = 0.5 * (a + b);
        (state(m) == TopAbs_OUT ? b : a) = m;
      }
      gp_Pnt p = F.point(a);
      double reach = F.point(in).Distance(F.point(out_)) * 2 + 1e-9;
      double best = reach;
      gp_Pnt snapped = p;
      for (const auto& r : boundary_roots)
        if (r.Distance(p) < best) { best = r.Distance(p); snapped = r; }
      return snapped;
    };
    std::vector<gp_Pnt> cur;
    std::vector<UV> dense = densified(g, densified(g, chain));
    for (std::size_t k = 0; k < dense.size(); ++k) {
      bool in = state(dense[k]) != TopAbs_OUT;
      if (in) {
        if (cur.empty() && k > 0) cur.push_back(snap(dense[k], dense[k - 1]));
        cur.push_back(F.point(dense[k]));
      } else if (!cur.empty()) {
        cur.push_back(snap(dense[k - 1], dense[k]));
        runs.push_back(cur);
        cur.clear();
      }
    }
    if (!cur.empty()) runs.push_back(cur);
    for (auto& pts : runs) {
      // remove near-duplicate points
      std::vector<gp_Pnt> q;
      for (const auto& p : pts)
        if (q.empty() || q.back().Distance(p) > Settings::resolution * size) q.push_back(p);
      if (q.size() < 2) continue;
      double len = 0;
      for (std::size_t k = 1; k < q.size(); ++k) len += q[k].Distance(q[k - 1]);
      if (len < Settings::grazing_curve_min_length * size) continue;
      if (const auto exact = exact_line_or_circle(q, Settings::canonical_curve_rounding * size)) {
        out.push_back(*exact);
        continue;
      }
      double error = 0;
      const Handle(Geom_BSplineCurve) c = fitted_curve(F, projector, q, tol, &error);
      if (c.IsNull()) continue;
      GrazingCurve gc;
      gc.curve = c;
      gc.first = c->FirstParameter();
      gc.last = c->LastParameter();
      gc.error = error;
      out.push_back(gc);
    }
  }
  return out;
}

namespace {

/// The largest distance from face f's surface of curve c on [first, last], at
/// Settings::grazing_edge_samples points.
double distance_from_surface(const Handle(Geom_Curve)& c, double first, double last, const TopoDS_Face& f) {
  TopLoc_Location loc;
  const Handle(Geom_Surface) surf = BRep_Tool::Surface(f, loc);
  if (surf.IsNull()) return 0.0;
  ShapeAnalysis_Surface sas(surf);
  double worst = 0;
  const int n = Settings::grazing_edge_samples;
  for (int k = 0; k <= n; ++k) {
    const gp_Pnt p = c->Value(first + (last - first) * k / n).Transformed(loc.Transformation().Inverted());
    const gp_Pnt2d uv = sas.ValueOfUV(p, Settings::surface_projection_precision);
    worst = std::max(worst, p.Distance(surf->Value(uv.X(), uv.Y())));
  }
  return worst;
}

}  // namespace

GrazingEdge grazing_edge(const GrazingCurve& g, const TopoDS_Face& face, double tol) {
  GrazingEdge out;
  out.first = g.first;
  out.last = g.last;
  out.curve = canonical_curve(g.curve, out.first, out.last, tol);
  out.edge = BRepBuilderAPI_MakeEdge(out.curve, out.first, out.last).Edge();
  const double off = distance_from_surface(out.curve, out.first, out.last, face);
  if (off > BRep_Tool::Tolerance(out.edge)) BRep_Builder().UpdateEdge(out.edge, Settings::edge_tolerance_margin * off);
  return out;
}

}  // namespace sweep::occt
