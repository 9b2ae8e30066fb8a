// A face translated along a direction in which it is a graph. Each line parallel to d meets the
// face at most once when n . d keeps one sign on it and the boundary (seams and collapsed edges left
// out: they bound no region of the projection) projects onto a simple closed curve: an orientation-
// preserving immersion of a disk whose boundary runs once around a simple curve covers the curve's
// inside exactly once. The swept set is then the union of the segments from each point of the face
// to its translate: the region between the face and its translate, closed by the sweep of that
// boundary. These faces meet only along their edges, so they are sewn without an arrangement.
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Pnt2d.hxx>
#include <vector>

#include "base/internal.hpp"

namespace sweep::occt {
namespace {

/// Whether segments pq and rs cross or touch (2D).
bool segments_meet(const gp_Pnt2d& p, const gp_Pnt2d& q, const gp_Pnt2d& r, const gp_Pnt2d& s) {
  auto orient = [](const gp_Pnt2d& a, const gp_Pnt2d& b, const gp_Pnt2d& c) {
    return (b.X() - a.X()) * (c.Y() - a.Y()) - (b.Y() - a.Y()) * (c.X() - a.X());
  };
  const double d1 = orient(r, s, p), d2 = orient(r, s, q), d3 = orient(p, q, r), d4 = orient(p, q, s);
  return ((d1 > 0) != (d2 > 0) || d1 == 0 || d2 == 0) && ((d3 > 0) != (d4 > 0) || d3 == 0 || d4 == 0) &&
         std::max(std::min(p.X(), q.X()), std::min(r.X(), s.X())) <= std::min(std::max(p.X(), q.X()), std::max(r.X(), s.X())) &&
         std::max(std::min(p.Y(), q.Y()), std::min(r.Y(), s.Y())) <= std::min(std::max(p.Y(), q.Y()), std::max(r.Y(), s.Y()));
}

}  // namespace

TopoDS_Shape graph_extrusion(const TopoDS_Face& face, const ScrewJoint& j, double L, double size, double tol,
                             double* fit_err, std::vector<GraphExtrusionFace>* faces) {
  const Eigen::Vector3d d = j.direction;
  // one wire (no holes)
  int wires = 0;
  for (TopExp_Explorer wx(face, TopAbs_WIRE); wx.More(); wx.Next()) ++wires;
  if (wires != 1) return {};
  // n . d of one sign over a grid of points inside the face
  {
    BRepAdaptor_Surface S(face);
    double u0, u1, v0, v1;
    BRepTools::UVBounds(face, u0, u1, v0, v1);
    BRepTopAdaptor_FClass2d cls(face, 1e-9);
    const int n = 32;
    double lo = 1e300, hi = -1e300;
    for (int i = 0; i <= n; ++i)
      for (int k = 0; k <= n; ++k) {
        const double u = u0 + (u1 - u0) * i / n, v = v0 + (v1 - v0) * k / n;
        if (cls.Perform(gp_Pnt2d(u, v)) == TopAbs_OUT) continue;
        gp_Pnt p;
        gp_Vec Su, Sv;
        S.D1(u, v, p, Su, Sv);
        const gp_Vec nv = Su.Crossed(Sv);
        if (nv.Magnitude() <= 1e-12 * Su.Magnitude() * Sv.Magnitude() || nv.Magnitude() == 0) continue;  // a pole
        const double nd = nv.Normalized().Dot(to_vec(d));
        lo = std::min(lo, nd), hi = std::max(hi, nd);
      }
    // (a fitted surface's normal is tangent to d along a grazing border only up to its fitting error)
    if (!((lo >= -1e-6 && hi > 1e-3) || (hi <= 1e-6 && lo < -1e-3))) return {};
  }
  // the boundary without seams and collapsed edges, projected on the plane normal to d, must be
  // one simple closed polygon
  const Eigen::Vector3d e1 = d.unitOrthogonal(), e2 = d.cross(e1);
  const double gap = 1e-7 * size;
  std::vector<gp_Pnt2d> poly;
  std::vector<TopoDS_Edge> kept;
  TopoDS_Wire wire = BRepTools::OuterWire(face);
  for (BRepTools_WireExplorer we(wire, face); we.More(); we.Next()) {
    const TopoDS_Edge& e = we.Current();
    if (BRep_Tool::Degenerated(e) || BRep_Tool::IsClosed(e, face)) continue;
    BRepAdaptor_Curve c(e);
    const double f = c.FirstParameter(), l = c.LastParameter();
    const int m = 64;
    std::vector<gp_Pnt2d> pts;
    double spread = 0;
    for (int k = 0; k <= m; ++k) {
      const double t = e.Orientation() == TopAbs_REVERSED ? l - (l - f) * k / m : f + (l - f) * k / m;
      const Eigen::Vector3d x = to_eigen(c.Value(t));
      pts.emplace_back(x.dot(e1), x.dot(e2));
      spread = std::max(spread, pts.back().Distance(pts.front()));
    }
    if (spread < gap) continue;  // collapsed in projection
    kept.push_back(e);
    if (!poly.empty() && poly.back().Distance(pts.front()) > 10 * gap) return {};
    poly.insert(poly.end(), poly.empty() ? pts.begin() : pts.begin() + 1, pts.end());
  }
  if (kept.empty() || poly.size() < 4 || poly.back().Distance(poly.front()) > 10 * gap) return {};
  poly.pop_back();
  const std::size_t np = poly.size();
  for (std::size_t i = 0; i < np; ++i)
    for (std::size_t k = i + 2; k < np; ++k) {
      if (i == 0 && k == np - 1) continue;  // adjacent through the closing segment
      if (segments_meet(poly[i], poly[(i + 1) % np], poly[k], poly[(k + 1) % np])) return {};
    }
  // the faces: the face, its translate and the sweep of each kept edge
  const gp_Vec shift = to_vec(d * L);
  std::vector<GraphExtrusionFace> out;
  std::vector<TopoDS_Face> fs;
  out.push_back({face, -1, 0, 0});
  gp_Trsf tr;
  tr.SetTranslation(shift);
  out.push_back({TopoDS::Face(face.Moved(TopLoc_Location(tr))), -2, 0, 0});
  double err = *fit_err;
  for (std::size_t k = 0; k < kept.size(); ++k) {
    // exact surfaces where the edge is a line or a circle (a circle along its normal: a cylinder)
    double f, l;
    Handle(Geom_Curve) c = BRep_Tool::Curve(kept[k], f, l);
    if (c.IsNull()) return {};
    const double f0 = f, l0 = l;
    c = canonical_curve(c, f, l, std::max(1e-3 * tol, 1e-10 * size));
    const auto walls = sweep_curve(c, f, l, j, L, tol, &err);
    if (walls.empty()) return {};
    for (const auto& w : walls) out.push_back({w, int(k), f0, l0});
  }
  for (const auto& g : out) fs.push_back(g.face);
  TopoDS_Shape solid = sew_solid(fs, gap);
  if (solid.IsNull()) return {};
  *fit_err = err;
  if (faces) *faces = out;
  return solid;
}

}  // namespace sweep::occt
