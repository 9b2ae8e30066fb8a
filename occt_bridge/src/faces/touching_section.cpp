// Crossings of the sweep of a grazing curve with the face it lies on (touching_section.hpp):
// h(s, t) = (d(E(s, t)) - d(E(s, t*))) / (t - t*)^2 traced on a grid over the sweep's parameters,
// its chains cut to the copy face and fitted; and crossings with a face on a torus, the zero set of
// its exact distance over the other face's parameters.
#include "faces/touching_section.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>
#include <gp_Sphere.hxx>
#include <gp_Torus.hxx>
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "base/internal.hpp"
#include "sweep/contour.hpp"

namespace sweep::occt {
namespace {

using UV = Eigen::Vector2d;

/// A signed distance from the surface of a face: exact for planes, cylinders, spheres and tori,
/// within the meridian plane for cones, along the normal at the nearest point otherwise (that
/// point may jump between sheets: roots there are not on the surface, and the caller drops them).
std::function<double(const gp_Pnt&)> distance_function(const TopoDS_Face& face) {
  const BRepAdaptor_Surface S(face);
  auto local = [](const gp_Ax3& ax, const gp_Pnt& x) {
    const gp_Vec d(ax.Location(), x);
    return gp_XYZ(d.Dot(ax.XDirection()), d.Dot(ax.YDirection()), d.Dot(ax.Direction()));
  };
  switch (S.GetType()) {
    case GeomAbs_Plane: {
      const gp_Ax3 ax = S.Plane().Position();
      return [ax, local](const gp_Pnt& x) { return local(ax, x).Z(); };
    }
    case GeomAbs_Cylinder: {
      const gp_Cylinder c = S.Cylinder();
      return [c, local](const gp_Pnt& x) {
        const gp_XYZ p = local(c.Position(), x);
        return std::hypot(p.X(), p.Y()) - c.Radius();
      };
    }
    case GeomAbs_Cone: {
      const gp_Cone c = S.Cone();
      return [c, local](const gp_Pnt& x) {
        const gp_XYZ p = local(c.Position(), x);
        const double a = c.SemiAngle();
        return (std::hypot(p.X(), p.Y()) - c.RefRadius() - p.Z() * std::tan(a)) * std::cos(a);
      };
    }
    case GeomAbs_Sphere: {
      const gp_Sphere s = S.Sphere();
      return [s](const gp_Pnt& x) { return x.Distance(s.Location()) - s.Radius(); };
    }
    case GeomAbs_Torus: {
      const gp_Torus t = S.Torus();
      return [t, local](const gp_Pnt& x) {
        const gp_XYZ p = local(t.Position(), x);
        return std::hypot(std::hypot(p.X(), p.Y()) - t.MajorRadius(), p.Z()) - t.MinorRadius();
      };
    }
    default: {
      const auto projector = std::make_shared<ShapeAnalysis_Surface>(BRep_Tool::Surface(face));
      return [projector](const gp_Pnt& x) {
        const gp_Pnt2d uv = projector->ValueOfUV(x, Settings::surface_projection_precision);
        gp_Pnt p;
        gp_Vec du, dv;
        projector->Surface()->D1(uv.X(), uv.Y(), p, du, dv);
        const gp_Vec n = du.Crossed(dv);
        const double m = n.Magnitude();
        return m > 1e-300 ? gp_Vec(p, x).Dot(n) / m : x.Distance(p);
      };
    }
  }
}

/// Whether point x (on the face's surface) lies in the face: its parameters, brought into the
/// face's parameter box over periods, classified against the face's boundary.
class FaceMembership {
 public:
  explicit FaceMembership(const TopoDS_Face& f)
      : surf_(BRep_Tool::Surface(f)), projector_(surf_) {
    BRepTools::UVBounds(f, u0_, u1_, v0_, v1_);
    const double uvtol = Settings::parameter_resolution * std::max(u1_ - u0_, v1_ - v0_);
    cls_ = std::make_unique<BRepTopAdaptor_FClass2d>(f, uvtol);
  }
  bool contains(const gp_Pnt& x) {
    gp_Pnt2d uv = projector_.ValueOfUV(x, Settings::surface_projection_precision);
    double u = uv.X(), v = uv.Y();
    if (surf_->IsUPeriodic()) u = wrap(u, u0_, u1_, surf_->UPeriod());
    if (surf_->IsVPeriodic()) v = wrap(v, v0_, v1_, surf_->VPeriod());
    return cls_->Perform(gp_Pnt2d(u, v)) != TopAbs_OUT;
  }

 private:
  static double wrap(double u, double lo, double hi, double period) {
    const double mid = 0.5 * (lo + hi);
    return u + period * std::round((mid - u) / period);
  }
  Handle(Geom_Surface) surf_;
  ShapeAnalysis_Surface projector_;
  std::unique_ptr<BRepTopAdaptor_FClass2d> cls_;
  double u0_ = 0, u1_ = 0, v0_ = 0, v1_ = 0;
};

/// A root of h near p, on the line through p across the chord direction d (p when h does not
/// change sign within the chord's length of it).
UV root_across(const ContourFunction& h, const UV& p, const UV& d) {
  const UV n = UV(-d.y(), d.x());
  const double hp = h(p);
  if (hp == 0) return p;
  for (double s : {0.05, 0.2, 0.5}) {
    const UV a = p - s * n, b = p + s * n;
    const double ha = h(a), hb = h(b);
    if ((ha > 0) != (hb > 0)) return root_on_segment(h, a, b, ha, hb);
  }
  return p;
}

/// A B-spline through the points of a run, checked at the roots between them: within `tol` or
/// nothing (*err: the largest distance measured).
Handle(Geom_BSplineCurve) fitted_run(const std::vector<gp_Pnt>& on, const std::vector<gp_Pnt>& between, double tol,
                                     double* err) {
  TColgp_Array1OfPnt pts(1, int(on.size()));
  for (std::size_t k = 0; k < on.size(); ++k) pts.SetValue(int(k) + 1, on[k]);
  GeomAPI_PointsToBSpline fit(pts, 2, 8, GeomAbs_C2, 0.1 * tol);
  if (!fit.IsDone()) return nullptr;
  const Handle(Geom_BSplineCurve) c = fit.Curve();
  double worst = 0;
  for (const gp_Pnt& p : between) {
    GeomAPI_ProjectPointOnCurve proj(p, c);
    if (proj.NbPoints() == 0) return nullptr;
    worst = std::max(worst, proj.LowerDistance());
  }
  *err = worst;
  return worst <= tol ? c : nullptr;
}

/// The runs of a traced chain's points (densified) where `good` holds, each ending exactly where
/// it stops holding: that crossing is bisected along the contour, each point of the chord first
/// put on the contour across it (a point bisected on the chord and only then put on the contour
/// would leave a face's boundary by the chord's sagitta, and its section would stop short of the
/// boundary it must split the face at).
std::vector<std::vector<UV>> runs_where(const ContourFunction& h, const std::vector<UV>& dense,
                                        const std::function<bool(const UV&)>& good) {
  std::vector<std::vector<UV>> runs;
  std::vector<UV> run;
  auto ends_run = [&]() {
    if (run.size() >= 2) runs.push_back(run);
    run.clear();
  };
  bool prev_in = false;
  for (std::size_t k = 0; k < dense.size(); ++k) {
    const bool in = good(dense[k]);
    if (in != prev_in && k > 0) {
      const UV d = dense[k] - dense[k - 1];
      auto on_contour = [&](double lambda) { return root_across(h, dense[k - 1] + lambda * d, d); };
      double a = 0, b = 1;
      for (int it = 0; it < Settings::traced_run_bisections; ++it) {
        const double m = 0.5 * (a + b);
        (good(on_contour(m)) == prev_in ? a : b) = m;
      }
      run.push_back(on_contour(prev_in ? a : b));
      if (prev_in) ends_run();
    }
    if (in) run.push_back(dense[k]);
    prev_in = in;
  }
  ends_run();
  return runs;
}

/// Run r (roots of h over (s, t)) cut where it crosses the times in `breaks`, each piece ending on
/// the contour at that time.
std::vector<std::vector<UV>> cut_at_times(const ContourFunction& h, const std::vector<UV>& r,
                                          const std::vector<double>& breaks) {
  std::vector<std::vector<UV>> pieces{{r.front()}};
  for (std::size_t k = 0; k + 1 < r.size(); ++k) {
    const UV d = r[k + 1] - r[k];
    std::vector<double> along = breaks;  // in the order the segment meets them
    std::sort(along.begin(), along.end());
    if (d.y() < 0) std::reverse(along.begin(), along.end());
    for (const double tb : along) {
      if (!((r[k].y() - tb) * (r[k + 1].y() - tb) < 0)) continue;
      auto on_contour = [&](double lambda) { return root_across(h, r[k] + lambda * d, d); };
      const bool below = r[k].y() < tb;
      double a = 0, b = 1;
      for (int it = 0; it < Settings::traced_run_bisections; ++it) {
        const double m = 0.5 * (a + b);
        ((on_contour(m).y() < tb) == below ? a : b) = m;
      }
      const UV cut = on_contour(0.5 * (a + b));
      pieces.back().push_back(cut);
      pieces.push_back({cut});
    }
    pieces.back().push_back(r[k + 1]);
    // (a point of the run on a break, as where the contour's grid has a line there)
    bool on_break = false;
    for (const double tb : breaks)
      on_break = on_break || std::abs(r[k + 1].y() - tb) <= Settings::traced_break_rounding * (1 + std::abs(tb));
    if (on_break && k + 2 < r.size()) pieces.push_back({r[k + 1]});
  }
  return pieces;
}

/// Edges through a run of roots of h (points at(p)), each checked at the roots between its points;
/// a run reaching less than `min_reach` from its first point makes none. With `depth` > 0, where a
/// fit does not hold, the run is densified by those roots, and where that fit does not hold
/// either, halved (at most `depth` times). False when a part does not fit.
bool fitted_edges(std::vector<UV> r, const ContourFunction& h, const std::function<gp_Pnt(const UV&)>& at, double tol,
                  double size, double min_reach, int depth, std::vector<TopoDS_Edge>& edges, double* fit_err) {
  for (int pass = 0; pass < (depth > 0 ? 2 : 1); ++pass) {
    std::vector<gp_Pnt> on;
    for (const UV& p : r)
      if (on.empty() || on.back().Distance(at(p)) > Settings::resolution * size) on.push_back(at(p));
    if (on.size() < 2) return true;
    double reach = 0;
    for (const gp_Pnt& p : on) reach = std::max(reach, p.Distance(on.front()));
    if (reach < min_reach) return true;
    std::vector<UV> mids;
    std::vector<gp_Pnt> between;
    for (std::size_t k = 0; k + 1 < r.size(); ++k) {
      mids.push_back(root_across(h, 0.5 * (r[k] + r[k + 1]), r[k + 1] - r[k]));
      between.push_back(at(mids.back()));
    }
    double err = 0;
    const Handle(Geom_BSplineCurve) c = fitted_run(on, between, tol, &err);
    if (!c.IsNull()) {
      BRepBuilderAPI_MakeEdge mk(c);
      if (!mk.IsDone()) return false;
      *fit_err = std::max(*fit_err, err);
      edges.push_back(mk.Edge());
      return true;
    }
    if (pass == 1) break;
    std::vector<UV> denser;
    for (std::size_t k = 0; k < r.size(); ++k) {
      denser.push_back(r[k]);
      if (k < mids.size()) denser.push_back(mids[k]);
    }
    r = std::move(denser);
  }
  if (depth <= 0 || r.size() < 8) return false;
  const std::size_t m = r.size() / 2;
  return fitted_edges(std::vector<UV>(r.begin(), r.begin() + std::ptrdiff_t(m) + 1), h, at, tol, size, min_reach,
                      depth - 1, edges, fit_err) &&
         fitted_edges(std::vector<UV>(r.begin() + std::ptrdiff_t(m), r.end()), h, at, tol, size, min_reach, depth - 1,
                      edges, fit_err);
}

}  // namespace

std::optional<std::vector<TopoDS_Edge>> touching_section(const TouchingSweep& sw, double t_touch,
                                                         const TopoDS_Face& copy, double tol, double size,
                                                         double* fit_err) {
  if (sw.T <= 0) return std::nullopt;
  const auto dist = distance_function(copy);
  auto at = [&](double s, double t) { return to_pnt(sw.joint.transform(t) * to_eigen(sw.curve->Value(s))); };
  const std::function<gp_Pnt(const UV&)> at_uv = [&](const UV& p) { return at(p.x(), p.y()); };
  auto d = [&](double s, double t) { return dist(at(s, t)); };
  // h = (d(s, t) - d(s, t*)) / (t - t*)^2; within tau of t* it is interpolated between its limit
  // at t* (extrapolated from tau and 2 tau) and its value at tau, where rounding would dominate.
  const double tau = Settings::touching_time_band * sw.T, side = t_touch > 0.5 * sw.T ? -1.0 : 1.0;
  auto h_raw = [&](double s, double dt) { return (d(s, t_touch + side * dt) - d(s, t_touch)) / (dt * dt); };
  const ContourFunction h = [&](const UV& p) {
    const double dt = std::abs(p.y() - t_touch);
    if (dt >= tau) return h_raw(p.x(), dt);
    const double h1 = h_raw(p.x(), tau), h0 = 2 * h1 - h_raw(p.x(), 2 * tau);
    return h0 + (h1 - h0) * dt / tau;
  };
  const int grid = Settings::traced_section_grid;
  const auto chains = contour_chains(h, sw.first, sw.last, 0, sw.T, grid, grid, Settings::traced_section_flat * size);
  FaceMembership member(copy);
  const double stray = Settings::traced_section_stray * size;
  std::vector<TopoDS_Edge> edges;
  for (const auto& chain : chains) {
    const std::vector<UV> dense = densified(h, chain);
    // runs of points on both the sweep and the copy face
    auto good = [&](const UV& p) {
      return std::abs(d(p.x(), p.y()) - d(p.x(), t_touch)) <= stray && member.contains(at(p.x(), p.y()));
    };
    // (a run within Settings::touching_run_min_reach of the size is a point where the curve meets
    // the joint's axis: its orbit is that point, on the copy at every t)
    for (const std::vector<UV>& r : runs_where(h, dense, good)) {
      double reach = 0;
      for (const UV& p : r) reach = std::max(reach, at_uv(p).Distance(at_uv(r.front())));
      if (reach < Settings::touching_run_min_reach * size) continue;
      for (const std::vector<UV>& piece : cut_at_times(h, r, sw.breaks))
        if (!fitted_edges(piece, h, at_uv, tol, size, 0, 0, edges, fit_err)) return std::nullopt;
    }
  }
  return edges;
}

namespace {

/// The curves where face `a` crosses face `b`: the zero set of b's signed distance over a's
/// parameters, cut to both faces and fitted to within `tol`.
std::optional<std::vector<TopoDS_Edge>> section_by_distance(const TopoDS_Face& a, const TopoDS_Face& b, double tol,
                                                            double size, double* fit_err) {
  const auto dist = distance_function(b);
  const BRepAdaptor_Surface S(a);
  double u0, u1, v0, v1;
  BRepTools::UVBounds(a, u0, u1, v0, v1);
  if (!(u1 > u0) || !(v1 > v0)) return std::nullopt;
  const std::function<gp_Pnt(const UV&)> at = [&](const UV& p) { return S.Value(p.x(), p.y()); };
  const ContourFunction h = [&](const UV& p) { return dist(at(p)); };
  const int grid = Settings::traced_section_grid;
  const auto chains = contour_chains(h, u0, u1, v0, v1, grid, grid, Settings::traced_section_flat * size);
  BRepTopAdaptor_FClass2d in_a(a, Settings::parameter_resolution * std::max(u1 - u0, v1 - v0));
  FaceMembership in_b(b);
  const double stray = Settings::traced_section_stray * size;
  auto good = [&](const UV& p) {
    return std::abs(h(p)) <= stray && in_a.Perform(gp_Pnt2d(p.x(), p.y())) != TopAbs_OUT && in_b.contains(at(p));
  };
  std::vector<TopoDS_Edge> edges;
  for (const auto& chain : chains) {
    const std::vector<UV> dense = densified(h, chain);
    for (const std::vector<UV>& r : runs_where(h, dense, good))
      if (!fitted_edges(r, h, at, tol, size, 0.0, 4, edges, fit_err)) return std::nullopt;
  }
  return edges;
}

/// Whether an edge of face `a` lies on the surface of `b` (at five of its points, within `eps`).
bool has_edge_on(const TopoDS_Face& a, const TopoDS_Face& b, double eps) {
  const auto dist = distance_function(b);
  for (TopExp_Explorer ex(a, TopAbs_EDGE); ex.More(); ex.Next()) {
    double f, l;
    const Handle(Geom_Curve) c = BRep_Tool::Curve(TopoDS::Edge(ex.Current()), f, l);
    if (c.IsNull()) continue;
    bool on = true;
    for (int k = 0; k <= 4 && on; ++k) on = std::abs(dist(c->Value(f + (l - f) * k / 4))) <= eps;
    if (on) return true;
  }
  return false;
}

}  // namespace

std::optional<std::vector<TopoDS_Edge>> torus_section(const TopoDS_Face& a, const TopoDS_Face& b, double tol,
                                                      double size, double* fit_err) {
  if (BRepAdaptor_Surface(b).GetType() != GeomAbs_Torus) return std::nullopt;
  return section_by_distance(a, b, tol, size, fit_err);
}

std::optional<std::vector<TopoDS_Edge>> spline_section(const TopoDS_Face& a, const TopoDS_Face& b, double tol,
                                                       double size, double* fit_err) {
  if (BRepAdaptor_Surface(a).GetType() != GeomAbs_BSplineSurface) return std::nullopt;
  switch (BRepAdaptor_Surface(b).GetType()) {
    case GeomAbs_Plane:
    case GeomAbs_Cylinder:
    case GeomAbs_Cone:
    case GeomAbs_Sphere:
    case GeomAbs_Torus:
      break;
    default:
      return std::nullopt;
  }
  // (a side of a on b's surface, as where a curve's sweep starts on the face it bounds: the
  // distance vanishes along it, and its zero set there is no crossing)
  if (has_edge_on(a, b, Settings::traced_section_side_on * size)) return std::nullopt;
  return section_by_distance(a, b, tol, size, fit_err);
}

}  // namespace sweep::occt
