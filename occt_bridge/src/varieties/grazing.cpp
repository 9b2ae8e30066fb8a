// Grazing curves: where the velocity of a screw motion is tangent to a face, g = n . v = 0.
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
#include <map>

#include "base/internal.hpp"

namespace sweep::occt {
namespace {

using UV = Eigen::Vector2d;

struct Field {
  BRepAdaptor_Surface S;
  ScrewJoint joint;
  double u0, u1, v0, v1;
  bool uper = false, vper = false;
  double uP = 0, vP = 0;

  explicit Field(const TopoDS_Face& f, const ScrewJoint& j) : S(f), joint(j) {}

  /// n . v with the unit normal and the velocity of the point; 0 where the normal is undefined.
  double g(const UV& p) const {
    gp_Pnt P;
    gp_Vec Du, Dv;
    S.D1(p.x(), p.y(), P, Du, Dv);
    gp_Vec N = Du.Crossed(Dv);
    double n = N.Magnitude();
    if (n < 1e-12 * (Du.Magnitude() + Dv.Magnitude() + 1e-300) || n < 1e-300) {
      // a pole of the parametrization: take the normal's limit from just inside the domain
      const double eu = 1e-7 * (u1 - u0) * (p.x() < 0.5 * (u0 + u1) ? 1 : -1);
      const double ev = 1e-7 * (v1 - v0) * (p.y() < 0.5 * (v0 + v1) ? 1 : -1);
      gp_Pnt Q;
      S.D1(p.x() + eu, p.y() + ev, Q, Du, Dv);
      N = Du.Crossed(Dv);
      n = N.Magnitude();
      if (n < 1e-300) return 0.0;
    }
    return N.Dot(to_vec(joint.velocity(to_eigen(P)))) / n;
  }
  gp_Pnt point(const UV& p) const { return S.Value(p.x(), p.y()); }
};

/// Root of f on [0,1] given f(0), f(1) of opposite signs (Illinois false position + bisection).
template <class F>
double root01(F f, double fa, double fb) {
  double a = 0, b = 1;
  if (fa == 0) return 0;
  if (fb == 0) return 1;
  int side = 0;
  for (int it = 0; it < 100; ++it) {
    double c = (a * fb - b * fa) / (fb - fa);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    double fc = f(c);
    if (fc == 0 || b - a < 1e-15) return c;
    if ((fc > 0) == (fb > 0)) {
      b = c; fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      a = c; fa = fc;
      if (side == 1) fb *= 0.5;
      side = 1;
    }
    if (b - a < 1e-15) break;
  }
  return 0.5 * (a + b);
}

/// Root of g on the segment p..q (signs differ at the ends).
UV root_on_segment(const Field& F, const UV& p, const UV& q, double gp, double gq) {
  double s = root01([&](double t) { return F.g(p + t * (q - p)); }, gp, gq);
  return p + s * (q - p);
}

struct Graph {
  std::vector<UV> pts;
  std::vector<std::vector<int>> adj;
  int add(const UV& p) {
    pts.push_back(p);
    adj.emplace_back();
    return int(pts.size()) - 1;
  }
  void link(int a, int b) {
    if (a == b) return;
    adj[a].push_back(b);
    adj[b].push_back(a);
  }
};

/// Traces g = 0 on an nu x nv grid over the window, returns chains of points (exact roots).
std::vector<std::vector<UV>> trace(const Field& F, double ua, double ub, double va, double vb, int nu,
                                   int nv, double gscale) {
  std::vector<double> G((nu + 1) * (nv + 1));
  auto node = [&](int i, int j) { return UV(ua + (ub - ua) * i / nu, va + (vb - va) * j / nv); };
  double gmax = 0;
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      G[i * (nv + 1) + j] = F.g(node(i, j));
      gmax = std::max(gmax, std::abs(G[i * (nv + 1) + j]));
    }
  if (gmax <= 1e-9 * gscale) return {};  // the whole face slides within itself
  auto val = [&](int i, int j) { return G[i * (nv + 1) + j]; };
  auto pos = [&](double g) { return g > 0; };
  Graph gr;
  std::map<long, int> edge_pt;  // grid edge -> graph node
  auto edge_node = [&](int i0, int j0, int i1, int j1) -> int {
    long key = (long(i0) * (nv + 1) + j0) * 2 + (i1 != i0 ? 0 : 1);
    auto it = edge_pt.find(key);
    if (it != edge_pt.end()) return it->second;
    UV p = root_on_segment(F, node(i0, j0), node(i1, j1), val(i0, j0), val(i1, j1));
    int id = gr.add(p);
    edge_pt[key] = id;
    return id;
  };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      // corners in order: (i,j) (i+1,j) (i+1,j+1) (i,j+1); edges e0..e3 between them
      int ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
      int crossing[4], nc = 0;
      for (int e = 0; e < 4; ++e) {
        int a = e, b = (e + 1) % 4;
        if (pos(val(ci[a], cj[a])) != pos(val(ci[b], cj[b]))) {
          int i0 = std::min(ci[a], ci[b]), j0 = std::min(cj[a], cj[b]);
          int i1 = std::max(ci[a], ci[b]), j1 = std::max(cj[a], cj[b]);
          crossing[nc++] = edge_node(i0, j0, i1, j1);
        }
      }
      if (nc == 2) {
        gr.link(crossing[0], crossing[1]);
      } else if (nc == 4) {
        // Two branches cross (or pass close): locate the saddle of g in the cell by Newton on
        // grad g = 0 (central differences); if g vanishes there, all four meet at it.
        UV c = 0.5 * (node(i, j) + node(i + 1, j + 1));
        const double hu = (ub - ua) / nu * 1e-3, hv = (vb - va) / nv * 1e-3;
        bool ok = false;
        for (int it = 0; it < 30; ++it) {
          double g0 = F.g(c);
          double gpu = F.g(c + UV(hu, 0)), gmu = F.g(c - UV(hu, 0));
          double gpv = F.g(c + UV(0, hv)), gmv = F.g(c - UV(0, hv));
          double gu = (gpu - gmu) / (2 * hu), gv = (gpv - gmv) / (2 * hv);
          double guu = (gpu - 2 * g0 + gmu) / (hu * hu), gvv = (gpv - 2 * g0 + gmv) / (hv * hv);
          double guv = (F.g(c + UV(hu, hv)) - F.g(c + UV(hu, -hv)) - F.g(c + UV(-hu, hv)) + F.g(c - UV(hu, hv))) /
                       (4 * hu * hv);
          double det = guu * gvv - guv * guv;
          if (std::abs(det) < 1e-300) break;
          UV d((gvv * gu - guv * gv) / det, (guu * gv - guv * gu) / det);
          c -= d;
          if (d.norm() < 1e-13 * (1 + c.norm())) { ok = true; break; }
        }
        bool inside = c.x() >= node(i, j).x() && c.x() <= node(i + 1, j).x() && c.y() >= node(i, j).y() &&
                      c.y() <= node(i, j + 1).y();
        if (ok && inside && std::abs(F.g(c)) < 1e-7 * gscale) {
          int s = gr.add(c);
          for (int k = 0; k < 4; ++k) gr.link(crossing[k], s);
        } else {
          double gc = F.g(0.5 * (node(i, j) + node(i + 1, j + 1)));
          // resolve the ambiguous cell by the sign at its centre
          if (pos(gc) == pos(val(i, j))) {
            gr.link(crossing[0], crossing[1]);
            gr.link(crossing[2], crossing[3]);
          } else {
            gr.link(crossing[1], crossing[2]);
            gr.link(crossing[3], crossing[0]);
          }
        }
      }
    }
  // Chains between nodes of degree != 2, and closed loops.
  std::vector<std::vector<UV>> chains;
  std::vector<std::vector<bool>> used(gr.pts.size());
  for (std::size_t k = 0; k < gr.pts.size(); ++k) used[k].assign(gr.adj[k].size(), false);
  auto mark = [&](int a, int b) {
    for (std::size_t m = 0; m < gr.adj[a].size(); ++m)
      if (gr.adj[a][m] == b && !used[a][m]) { used[a][m] = true; break; }
    for (std::size_t m = 0; m < gr.adj[b].size(); ++m)
      if (gr.adj[b][m] == a && !used[b][m]) { used[b][m] = true; break; }
  };
  auto walk = [&](int start, std::size_t slot) {
    std::vector<UV> chain{gr.pts[start]};
    int cur = gr.adj[start][slot];
    mark(start, cur);
    chain.push_back(gr.pts[cur]);
    while (gr.adj[cur].size() == 2 && cur != start) {
      int nxt = -1;
      for (std::size_t m = 0; m < 2; ++m)
        if (!used[cur][m]) { nxt = gr.adj[cur][m]; break; }
      if (nxt < 0) break;
      mark(cur, nxt);
      cur = nxt;
      chain.push_back(gr.pts[cur]);
    }
    chains.push_back(chain);
  };
  for (std::size_t k = 0; k < gr.pts.size(); ++k)
    if (gr.adj[k].size() != 2)
      for (std::size_t m = 0; m < gr.adj[k].size(); ++m)
        if (!used[k][m]) walk(int(k), m);
  for (std::size_t k = 0; k < gr.pts.size(); ++k)
    for (std::size_t m = 0; m < gr.adj[k].size(); ++m)
      if (!used[k][m]) walk(int(k), m);
  return chains;
}

/// Inserts a root of g between consecutive points: on the line through the chord's midpoint,
/// perpendicular to the chord.
std::vector<UV> densify(const Field& F, const std::vector<UV>& c) {
  std::vector<UV> out{c.front()};
  for (std::size_t k = 0; k + 1 < c.size(); ++k) {
    UV a = c[k], b = c[k + 1], m = 0.5 * (a + b), d = b - a;
    UV n(-d.y(), d.x());
    UV p = m - n, q = m + n;
    double gp = F.g(p), gq = F.g(q);
    if ((gp > 0) != (gq > 0)) out.push_back(root_on_segment(F, p, q, gp, gq));
    out.push_back(b);
  }
  return out;
}

/// The point of the grazing set near p: p projected onto the face's surface, then moved in the
/// parameter plane along the gradient of g to g = 0.
gp_Pnt grazing_point_near(const Field& F, ShapeAnalysis_Surface& projector, const gp_Pnt& p) {
  const double hu = 1e-7 * (F.u1 - F.u0), hv = 1e-7 * (F.v1 - F.v0);
  // (near a crossing of two branches the gradient vanishes: no step beyond a hundredth of the domain)
  const double cap = 0.01 * std::max(F.u1 - F.u0, F.v1 - F.v0);
  const gp_Pnt2d uv0 = projector.ValueOfUV(p, 1e-12);
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
    GeomAPI_Interpolate interp(pts, false, 1e-12);
    interp.Perform();
    if (interp.IsDone()) consider(interp.Curve());
  }
  return best;
}

}  // namespace

std::vector<GrazingCurve> grazing_curves(const TopoDS_Face& face, const ScrewJoint& joint, double tol,
                                         double size) {
  Field F(face, joint);
  BRepTools::UVBounds(face, F.u0, F.u1, F.v0, F.v1);
  ShapeAnalysis_Surface projector(BRep_Tool::Surface(face));
  // Periodic directions: trace over a window shifted by an irrational fraction of the period,
  // so that no grazing line sits on the window's border.
  double ua = F.u0, ub = F.u1, va = F.v0, vb = F.v1;
  if (F.S.IsUPeriodic() && std::abs((F.u1 - F.u0) - F.S.UPeriod()) < 1e-9) {
    F.uper = true;
    F.uP = F.S.UPeriod();
    ua += 0.3819660112501051 * F.uP * 0.1;
    ub = ua + F.uP;
  }
  if (F.S.IsVPeriodic() && std::abs((F.v1 - F.v0) - F.S.VPeriod()) < 1e-9) {
    F.vper = true;
    F.vP = F.S.VPeriod();
    va += 0.3819660112501051 * F.vP * 0.1;
    vb = va + F.vP;
  }
  const double vscale = size + std::abs(joint.pitch) + joint.point.norm();
  auto chains = trace(F, ua, ub, va, vb, 61, 59, vscale);
  if (chains.empty()) return {};

  // Trimmed domain: keep the parts inside the face.
  const double uvtol = 1e-9 * std::max(ub - ua, vb - va);
  BRepTopAdaptor_FClass2d cls(face, uvtol);
  auto wrap = [&](UV p) {
    if (F.uper && p.x() > F.u1) p.x() -= F.uP;
    if (F.vper && p.y() > F.v1) p.y() -= F.vP;
    return p;
  };
  auto state = [&](const UV& p) { return cls.Perform(gp_Pnt2d(wrap(p).x(), wrap(p).y())); };

  // Roots of g along the real boundary edges (not seams, not degenerate): exact chain ends.
  std::vector<gp_Pnt> boundary_roots;
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    TopoDS_Edge e = TopoDS::Edge(ex.Current());
    if (BRep_Tool::Degenerated(e) || BRep_Tool::IsClosed(e, face)) continue;
    double f, l;
    Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, face, f, l);
    if (pc.IsNull()) continue;
    const int n = 400;
    double gprev = 0;
    for (int k = 0; k <= n; ++k) {
      gp_Pnt2d q = pc->Value(f + (l - f) * k / n);
      UV cur(q.X(), q.Y());
      double gc = F.g(cur);
      if (k > 0 && (gc > 0) != (gprev > 0)) {
        double s = root01(
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

  std::vector<GrazingCurve> out;
  for (auto& chain : chains) {
    // drop chains lying on the face boundary: the sweeps of the boundary edges cover them
    bool all_on = true;
    for (const auto& p : chain)
      if (state(p) != TopAbs_ON) { all_on = false; break; }
    if (all_on) {
      // On a seam the face lies on both sides: the chain is interior after all.
      const UV m = chain[chain.size() / 2];
      const double eu = 1e-6 * (ub - ua), ev = 1e-6 * (vb - va);
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
      for (int it = 0; it < 60; ++it) {
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
    std::vector<UV> dense = densify(F, densify(F, chain));
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
        if (q.empty() || q.back().Distance(p) > 1e-9 * size) q.push_back(p);
      if (q.size() < 2) continue;
      double len = 0;
      for (std::size_t k = 1; k < q.size(); ++k) len += q[k].Distance(q[k - 1]);
      if (len < 1e-7 * size) continue;
      // Lines and circles (grazing curves of planes, spheres, cylinders...) are kept exact: the
      // points are roots of g to rounding, so three of them define the curve.
      {
        const double etol = 1e-10 * size;
        auto all_within = [&](auto dist) {
          for (const auto& p : q)
            if (dist(p) > etol) return false;
          return true;
        };
        gp_Pnt a = q.front(), b = q.back(), m = q[q.size() / 2];
        if (a.Distance(b) > etol) {
          gp_Lin lin(a, gp_Dir(gp_Vec(a, b)));
          if (all_within([&](const gp_Pnt& p) { return lin.Distance(p); })) {
            GrazingCurve gc;
            gc.curve = new Geom_Line(lin);
            gc.first = 0;
            gc.last = a.Distance(b);
            out.push_back(gc);
            continue;
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
            while (l <= f + 1e-12) l += 2 * M_PI;
            while (l > f + 2 * M_PI + 1e-12) l -= 2 * M_PI;
            if (a.Distance(b) <= etol) l = f + 2 * M_PI;
            (void)m;
            GrazingCurve gc;
            gc.curve = new Geom_Circle(circ);
            gc.first = f;
            gc.last = l;
            out.push_back(gc);
            continue;
          }
        }
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

/// The largest distance from face f's surface of curve c on [first, last], at 64 points.
double distance_from_surface(const Handle(Geom_Curve)& c, double first, double last, const TopoDS_Face& f) {
  TopLoc_Location loc;
  const Handle(Geom_Surface) surf = BRep_Tool::Surface(f, loc);
  if (surf.IsNull()) return 0.0;
  ShapeAnalysis_Surface sas(surf);
  double worst = 0;
  for (int k = 0; k <= 64; ++k) {
    const gp_Pnt p = c->Value(first + (last - first) * k / 64).Transformed(loc.Transformation().Inverted());
    const gp_Pnt2d uv = sas.ValueOfUV(p, 1e-12);
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
  if (off > BRep_Tool::Tolerance(out.edge)) BRep_Builder().UpdateEdge(out.edge, 1.5 * off);
  return out;
}

}  // namespace sweep::occt
