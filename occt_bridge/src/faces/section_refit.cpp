// Section curves refitted onto both surfaces (see section_refit.hpp).
#include "faces/section_refit.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Curve.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TColgp_Array1OfPnt.hxx>

#include <Eigen/Dense>
#include <algorithm>
#include <optional>
#include <vector>

#include "base/internal.hpp"

namespace sweep::occt {

std::optional<gp_Pnt> point_on_both(const BRepAdaptor_Surface& A, const BRepAdaptor_Surface& B, const gp_Pnt& p,
                              const gp_Vec& t, gp_Pnt2d uva, gp_Pnt2d uvb, double tol) {
  Eigen::Vector4d x(uva.X(), uva.Y(), uvb.X(), uvb.Y());
  const Eigen::Vector3d tt = to_eigen(t), pp = to_eigen(p);
  for (int it = 0; it < Settings::point_on_both_iterations; ++it) {
    gp_Pnt Pa, Pb;
    gp_Vec Au, Av, Bu, Bv;
    A.D1(x(0), x(1), Pa, Au, Av);
    B.D1(x(2), x(3), Pb, Bu, Bv);
    const Eigen::Vector3d a = to_eigen(Pa), b = to_eigen(Pb);
    Eigen::Vector4d F;
    F.head<3>() = a - b;
    F(3) = tt.dot(a - pp);
    if (F.head<3>().norm() <= Settings::section_point_precision * tol &&
        std::abs(F(3)) <= Settings::section_point_precision * tol)
      return Pa;
    Eigen::Matrix4d J = Eigen::Matrix4d::Zero();
    J.block<3, 1>(0, 0) = to_eigen(Au);
    J.block<3, 1>(0, 1) = to_eigen(Av);
    J.block<3, 1>(0, 2) = -to_eigen(Bu);
    J.block<3, 1>(0, 3) = -to_eigen(Bv);
    J(3, 0) = tt.dot(to_eigen(Au));
    J(3, 1) = tt.dot(to_eigen(Av));
    const Eigen::FullPivLU<Eigen::Matrix4d> lu(J);
    if (lu.rank() < 4) return std::nullopt;
    x -= lu.solve(F);
  }
  return std::nullopt;
}

TopoDS_Edge refitted_section_edge(const TopoDS_Edge& e, const TopoDS_Face& a, const TopoDS_Face& b, double tol,
                                  double above, double* err) {
  *err = 0;
  if (BRep_Tool::Tolerance(e) <= above) return e;
  double f, l, fa, la, fb, lb;
  const Handle(Geom_Curve) c = BRep_Tool::Curve(e, f, l);
  const Handle(Geom2d_Curve) pa = BRep_Tool::CurveOnSurface(e, a, fa, la);
  const Handle(Geom2d_Curve) pb = BRep_Tool::CurveOnSurface(e, b, fb, lb);
  const double r = Settings::refit_range_resolution;
  if (c.IsNull() || pa.IsNull() || pb.IsNull() || std::abs(fa - f) > r * (1 + std::abs(f)) ||
      std::abs(fb - f) > r * (1 + std::abs(f)) || std::abs(la - l) > r * (1 + std::abs(l)) ||
      std::abs(lb - l) > r * (1 + std::abs(l)))
    return e;
  const BRepAdaptor_Surface A(a), B(b);
  ShapeAnalysis_Surface on_a(BRep_Tool::Surface(a)), on_b(BRep_Tool::Surface(b));
  const double stray = Settings::refit_stray_tolerances * BRep_Tool::Tolerance(e);
  auto refined = [&](double s) -> std::optional<gp_Pnt> {
    gp_Pnt p;
    gp_Vec t;
    c->D1(s, p, t);
    if (t.Magnitude() == 0) return std::nullopt;
    const auto q = point_on_both(A, B, p, t.Normalized(), pa->Value(s), pb->Value(s), tol);
    if (!q || q->Distance(p) > stray) return std::nullopt;
    return q;
  };
  for (int m = Settings::refit_samples_first; m <= Settings::refit_samples_last; m *= 2) {
    TColgp_Array1OfPnt pts(1, m + 1);
    bool ok = true;
    for (int k = 0; k <= m && ok; ++k) {
      const auto q = refined(f + (l - f) * k / m);
      if (q) pts.SetValue(k + 1, *q);
      ok = bool(q);
    }
    if (!ok) return e;
    GeomAPI_PointsToBSpline fit(pts, 3, 8, GeomAbs_C2, 0.1 * tol);
    if (!fit.IsDone()) continue;
    const Handle(Geom_BSplineCurve) curve = fit.Curve();
    // how far the fit strays between its points: from the true crossing, or where the surfaces
    // are so near tangent that a point within the tolerance of both lies farther from it than
    // that (the crossing is then ill-conditioned along them), from the two surfaces
    double worst = 0;
    for (int k = 0; k < m && ok; ++k) {
      const auto q = refined(f + (l - f) * (k + 0.5) / m);
      if (!q) return e;
      GeomAPI_ProjectPointOnCurve proj(*q, curve);
      if (proj.NbPoints() == 0) {
        ok = false;
        break;
      }
      double stray_here = proj.LowerDistance();
      if (stray_here > tol) {
        const gp_Pnt x = proj.NearestPoint();
        stray_here = std::max(on_a.Value(on_a.ValueOfUV(x, Settings::section_point_precision * tol)).Distance(x),
                              on_b.Value(on_b.ValueOfUV(x, Settings::section_point_precision * tol)).Distance(x));
      }
      worst = std::max(worst, stray_here);
    }
    if (!ok || worst > tol) continue;
    BRepBuilderAPI_MakeEdge mk(curve);
    if (!mk.IsDone()) return e;
    *err = worst;
    TopoDS_Edge out = mk.Edge();
    out.Orientation(e.Orientation());
    return out;
  }
  return e;
}

}  // namespace sweep::occt
