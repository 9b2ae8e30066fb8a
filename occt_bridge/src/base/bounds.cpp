// The axis-aligned box of a shape: the edges' boxes from OCCT's optimisation along each curve,
// and inside each face the extremes of each coordinate, found on a grid of points the face's
// boundary classifies inside and refined by Newton's method on the surface. Points outside a
// trimmed face never count, so the box is that of the shape itself (OCCT's optimal box of a face
// covers its surface over the face's whole parameter rectangle, and searches it more slowly).
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <BndLib_Add3dCurve.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <Eigen/Dense>
#include <vector>

#include "base/internal.hpp"

namespace sweep::occt {
namespace {

void add_face(const TopoDS_Face& f, Bnd_Box& box) {
  BRepAdaptor_Surface S(f, false);
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  if (!(u1 > u0) || !(v1 > v0)) return;
  BRepTopAdaptor_FClass2d cls(f, 1e-9);
  const int n = 24;
  auto at = [&](int i, int k) { return gp_Pnt2d(u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * k / n); };
  std::vector<gp_Pnt> P((n + 1) * (n + 1));
  std::vector<char> in((n + 1) * (n + 1));
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= n; ++k) {
      const gp_Pnt2d uv = at(i, k);
      in[i * (n + 1) + k] = cls.Perform(uv) == TopAbs_IN;
      if (!in[i * (n + 1) + k]) continue;
      P[i * (n + 1) + k] = S.Value(uv.X(), uv.Y());
      box.Add(P[i * (n + 1) + k]);
    }
  const double du = u1 - u0, dv = v1 - v0;
  for (int d = 1; d <= 3; ++d)
    for (double sign : {-1.0, 1.0}) {
      auto w = [&](int idx) { return sign * P[idx].Coord(d); };
      for (int i = 0; i <= n; ++i)
        for (int k = 0; k <= n; ++k) {
          const int idx = i * (n + 1) + k;
          if (!in[idx]) continue;
          bool peak = true;  // no neighbour inside the face is higher
          for (int a = -1; a <= 1 && peak; ++a)
            for (int b = -1; b <= 1 && peak; ++b) {
              const int ii = i + a, kk = k + b;
              if ((a || b) && ii >= 0 && ii <= n && kk >= 0 && kk <= n && in[ii * (n + 1) + kk] &&
                  w(ii * (n + 1) + kk) > w(idx))
                peak = false;
            }
          if (!peak) continue;
          // Newton's method on the gradient of the coordinate; an interior maximum only
          gp_Pnt2d uv = at(i, k);
          bool converged = false;
          for (int it = 0; it < 20; ++it) {
            gp_Pnt p;
            gp_Vec Su, Sv, Suu, Svv, Suv;
            S.D2(uv.X(), uv.Y(), p, Su, Sv, Suu, Svv, Suv);
            const Eigen::Vector2d g(sign * Su.Coord(d), sign * Sv.Coord(d));
            Eigen::Matrix2d H;
            H << sign * Suu.Coord(d), sign * Suv.Coord(d), sign * Suv.Coord(d), sign * Svv.Coord(d);
            if (!(H(0, 0) < 0 && H.determinant() > 0)) break;
            const Eigen::Vector2d step = -H.inverse() * g;
            uv.SetCoord(uv.X() + step(0), uv.Y() + step(1));
            if (uv.X() < u0 || uv.X() > u1 || uv.Y() < v0 || uv.Y() > v1) break;
            if (std::abs(step(0)) <= 1e-13 * du && std::abs(step(1)) <= 1e-13 * dv) {
              converged = true;
              break;
            }
          }
          if (converged && cls.Perform(uv) == TopAbs_IN) box.Add(S.Value(uv.X(), uv.Y()));
        }
    }
}

}  // namespace

Bnd_Box shape_box(const TopoDS_Shape& s) {
  Bnd_Box box;
  for (TopExp_Explorer ex(s, TopAbs_VERTEX); ex.More(); ex.Next()) box.Add(BRep_Tool::Pnt(TopoDS::Vertex(ex.Current())));
  for (TopExp_Explorer ex(s, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
    if (BRep_Tool::Degenerated(e) || !BRep_Tool::IsGeometric(e)) continue;
    BndLib_Add3dCurve::AddOptimal(BRepAdaptor_Curve(e), 0.0, box);
  }
  for (TopExp_Explorer ex(s, TopAbs_FACE); ex.More(); ex.Next()) add_face(TopoDS::Face(ex.Current()), box);
  return box;
}

Eigen::AlignedBox3d box_of(const TopoDS_Shape& s) {
  const Bnd_Box b = shape_box(s);
  if (b.IsVoid()) return Eigen::AlignedBox3d();
  double x0, y0, z0, x1, y1, z1;
  b.Get(x0, y0, z0, x1, y1, z1);
  return Eigen::AlignedBox3d(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
}

double radius_of(const TopoDS_Shape& s) {
  const Eigen::AlignedBox3d box = box_of(s);
  if (box.isEmpty()) return 0;
  double r = 0;
  for (int k = 0; k < 8; ++k) r = std::max(r, box.corner(Eigen::AlignedBox3d::CornerType(k)).norm());
  return r;
}

}  // namespace sweep::occt
