// Volume by the divergence theorem, V = 1/3 sum_F integral_F x . n dA, each face integral reduced
// by Green's theorem to its boundary in the parameter domain:
//   integral_D f du dv = loop_{dD} P dv,   P(u, v) = integral_{u_a}^{u} f(s, v) ds,
// with f = S . (S_u x S_v) and Gauss-Legendre quadrature on both levels.
#include <BRepAdaptor_Curve2d.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepTools.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <cmath>
#include <utility>

#include "base/internal.hpp"

namespace sweep::occt {
namespace {

constexpr int kGauss = 8;
constexpr double kX[kGauss] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                               0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
constexpr double kW[kGauss] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                               0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

/// The integrals of x . n (volume, times 3) and of 1 (area) over the face, both with the face's
/// parametrization's orientation (the first signed, the second not).
std::pair<double, double> face_integrals(const TopoDS_Face& face) {
  BRepAdaptor_Surface S(face, false);
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  const double hu = (u1 - u0) / 12.0;
  // P(u, v) = integral from u0 to u of f(s, v) ds, for both integrands at once
  auto P = [&](double u, double v) -> std::pair<double, double> {
    const double len = u - u0;
    if (len == 0) return {0.0, 0.0};
    const int m = std::max(1, int(std::ceil(std::abs(len) / hu)));
    const double h = len / m;
    double s = 0, a = 0;
    for (int k = 0; k < m; ++k) {
      const double c = u0 + (k + 0.5) * h;
      for (int i = 0; i < kGauss; ++i) {
        gp_Pnt p;
        gp_Vec du, dv;
        S.D1(c + 0.5 * h * kX[i], v, p, du, dv);
        const gp_Vec n = du.Crossed(dv);
        s += kW[i] * gp_Vec(p.XYZ()).Dot(n);
        a += kW[i] * n.Magnitude();
      }
    }
    return {s * 0.5 * h, a * 0.5 * h};
  };
  double total = 0, area = 0;
  TopoDS_Face fwd = TopoDS::Face(face.Oriented(TopAbs_FORWARD));
  for (TopExp_Explorer ex(fwd, TopAbs_EDGE); ex.More(); ex.Next()) {
    TopoDS_Edge e = TopoDS::Edge(ex.Current());
    // an edge inside the face (or outside it) has the face on both sides: its two passes cancel
    if (e.Orientation() == TopAbs_INTERNAL || e.Orientation() == TopAbs_EXTERNAL) continue;
    BRepAdaptor_Curve2d c(e, fwd);
    double a = c.FirstParameter(), b = c.LastParameter();
    const double sign = e.Orientation() == TopAbs_REVERSED ? -1.0 : 1.0;
    const int m = 16;
    const double h = (b - a) / m;
    double s = 0, sa = 0;
    for (int k = 0; k < m; ++k) {
      const double mid = a + (k + 0.5) * h;
      for (int i = 0; i < kGauss; ++i) {
        gp_Pnt2d q;
        gp_Vec2d d;
        c.D1(mid + 0.5 * h * kX[i], q, d);
        if (d.Y() == 0) continue;
        const auto [pv, pa] = P(q.X(), q.Y());
        s += kW[i] * pv * d.Y();
        sa += kW[i] * pa * d.Y();
      }
    }
    total += sign * s * 0.5 * h;
    area += sign * sa * 0.5 * h;
  }
  return {total, std::abs(area)};
}

}  // namespace

std::pair<double, double> face_divergence_and_area(const TopoDS_Face& f) {
  const auto [i, a] = face_integrals(f);
  return {(f.Orientation() == TopAbs_REVERSED ? -i : i) / 3.0, a};
}

double face_divergence(const TopoDS_Face& f) {
  const double i = face_integrals(f).first;
  return (f.Orientation() == TopAbs_REVERSED ? -i : i) / 3.0;
}

double face_area(const TopoDS_Face& f) { return face_integrals(f).second; }

}  // namespace sweep::occt
