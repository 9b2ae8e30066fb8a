// Volume by the divergence theorem, V = 1/3 sum_F integral_F x . n dA, each face integral reduced
// by Green's theorem to its boundary in the parameter domain:
//   integral_D f du dv = loop_{dD} P dv,   P(u, v) = integral_{u_a}^{u} f(s, v) ds,
// with f = S . (S_u x S_v) and Gauss-Legendre quadrature on both levels.
#include <BRepAdaptor_Curve2d.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepTools.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <cmath>
#include <algorithm>
#include <utility>
#include <vector>

#include "base/internal.hpp"

namespace sweep::occt {
namespace {

constexpr int kGauss = 8;
constexpr double kX[kGauss] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                               0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
constexpr double kW[kGauss] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                               0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

/// The points that cut [a, b] into `pieces` equal parts and at every break of continuity `breaks`
/// lists inside it: Gauss-Legendre quadrature on each part integrates one polynomial span.
std::vector<double> cuts_of(double a, double b, int pieces, const TColStd_Array1OfReal& breaks) {
  std::vector<double> at;
  for (int k = 0; k <= pieces; ++k) at.push_back(a + (b - a) * k / pieces);
  const double lo = std::min(a, b), hi = std::max(a, b), eps = 1e-12 * (hi - lo);
  for (int k = breaks.Lower(); k <= breaks.Upper(); ++k)
    if (breaks(k) > lo + eps && breaks(k) < hi - eps) at.push_back(breaks(k));
  std::sort(at.begin(), at.end());
  at.erase(std::unique(at.begin(), at.end(), [eps](double x, double y) { return y - x <= eps; }), at.end());
  return at;
}

/// The integrals of x . n (volume, times 3) and of 1 (area) over the face, both with the face's
/// parametrization's orientation (the first signed, the second not), x taken from `origin`. Both
/// levels cut at the surface's and the curves' spans as well as evenly.
std::pair<double, double> face_integrals(const TopoDS_Face& face, const gp_XYZ& origin) {
  BRepAdaptor_Surface S(face, false);
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  TColStd_Array1OfReal ubreaks(1, S.NbUIntervals(GeomAbs_C2) + 1);
  S.UIntervals(ubreaks, GeomAbs_C2);
  const std::vector<double> ucuts = cuts_of(u0, u1, 12, ubreaks);
  // f over [a, b] at v, for both integrands at once
  auto piece = [&](double a, double b, double v, double& s, double& ar) {
    const double c = 0.5 * (a + b), h = b - a;
    for (int i = 0; i < kGauss; ++i) {
      gp_Pnt p;
      gp_Vec du, dv;
      S.D1(c + 0.5 * h * kX[i], v, p, du, dv);
      const gp_Vec n = du.Crossed(dv);
      s += 0.5 * h * kW[i] * gp_Vec(p.XYZ() - origin).Dot(n);
      ar += 0.5 * h * kW[i] * n.Magnitude();
    }
  };
  // P(u, v) = integral from u0 to u of f(s, v) ds
  auto P = [&](double u, double v) -> std::pair<double, double> {
    double s = 0, a = 0;
    for (std::size_t k = 0; k + 1 < ucuts.size() && ucuts[k] < u; ++k) piece(ucuts[k], std::min(u, ucuts[k + 1]), v, s, a);
    return {s, a};
  };
  double total = 0, area = 0;
  TopoDS_Face fwd = TopoDS::Face(face.Oriented(TopAbs_FORWARD));
  for (TopExp_Explorer ex(fwd, TopAbs_EDGE); ex.More(); ex.Next()) {
    TopoDS_Edge e = TopoDS::Edge(ex.Current());
    // an edge inside the face (or outside it) has the face on both sides: its two passes cancel
    if (e.Orientation() == TopAbs_INTERNAL || e.Orientation() == TopAbs_EXTERNAL) continue;
    BRepAdaptor_Curve2d c(e, fwd);
    TColStd_Array1OfReal cbreaks(1, c.NbIntervals(GeomAbs_C2) + 1);
    c.Intervals(cbreaks, GeomAbs_C2);
    const std::vector<double> at = cuts_of(c.FirstParameter(), c.LastParameter(), 16, cbreaks);
    const double sign = e.Orientation() == TopAbs_REVERSED ? -1.0 : 1.0;
    double s = 0, sa = 0;
    for (std::size_t k = 0; k + 1 < at.size(); ++k) {
      const double mid = 0.5 * (at[k] + at[k + 1]), h = at[k + 1] - at[k];
      for (int i = 0; i < kGauss; ++i) {
        gp_Pnt2d q;
        gp_Vec2d d;
        c.D1(mid + 0.5 * h * kX[i], q, d);
        if (d.Y() == 0) continue;
        const auto [pv, pa] = P(q.X(), q.Y());
        s += 0.5 * h * kW[i] * pv * d.Y();
        sa += 0.5 * h * kW[i] * pa * d.Y();
      }
    }
    total += sign * s;
    area += sign * sa;
  }
  return {total, std::abs(area)};
}

}  // namespace

std::pair<double, double> face_divergence_and_area(const TopoDS_Face& f, const gp_XYZ& origin) {
  const auto [i, a] = face_integrals(f, origin);
  return {(f.Orientation() == TopAbs_REVERSED ? -i : i) / 3.0, a};
}

double face_divergence(const TopoDS_Face& f, const gp_XYZ& origin) {
  const double i = face_integrals(f, origin).first;
  return (f.Orientation() == TopAbs_REVERSED ? -i : i) / 3.0;
}

double face_area(const TopoDS_Face& f) { return face_integrals(f, gp_XYZ(0, 0, 0)).second; }

}  // namespace sweep::occt
