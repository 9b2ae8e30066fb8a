// The solid swept by a ball whose centre follows any smooth path c(t), built directly when the
// path's reach exceeds the radius: then the boundary of the union of the balls is the tube of the
// circles normal to the path (the grazing circles: n . c'(t) = 0) closed by the back half of the
// ball at the start and the front half at the end.
//
// The reach is checked on samples: the radius of curvature |c'|^3 / |c' x c''| above r, and every
// chord between points at least pi r apart along the path longer than 2 r (a chord between nearer
// points cannot be normal to the path at both ends while the curvature radius exceeds r). The tube
// is c(t) + r (x N1(t) + y N2(t)) over a fitted unit circle (x, y), with (N1, N2) the rotation
// minimising frame of the path (double reflection between samples), its pole rows fitted together
// along t as in the screw case (helical_tube.cpp).
#include <BRepBuilderAPI_MakeFace.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <algorithm>
#include <cmath>

#include "arrangement/stage_sweep.hpp"
#include "base/internal.hpp"
#include "base/stop.hpp"
#include "varieties/ball_path.hpp"
#include "varieties/tube_fit.hpp"

namespace sweep::occt {
namespace {

/// The centre's path sampled at n + 1 points with its rotation minimising frame.
struct SampledPath {
  double lo = 0, h = 0;
  std::vector<Eigen::Vector3d> c, tangent, n1, dn1;
  std::vector<Eigen::Vector3d> dtangent;  ///< the unit tangent's derivative in t
  std::vector<double> arc;  ///< arc length from the start
  bool use_reference = false;
  Eigen::Vector3d reference = Eigen::Vector3d::UnitZ();
};

Eigen::Vector3d centre_at(const StageMotion& m, const Eigen::Vector3d& c0, double t, Eigen::Vector3d* d1 = nullptr,
                          Eigen::Vector3d* d2 = nullptr) {
  const PoseJet P = m.pose(t);
  if (d1) *d1 = P.dR * c0 + P.dp;
  if (d2) *d2 = P.ddR * c0 + P.ddp;
  return P.R * c0 + P.p;
}

/// The frame N1 at t, normal to the unit tangent there. With a reference direction `a` that no
/// tangent comes near, the projection of a (smooth as the path). Otherwise the rotation
/// minimising frame, cubic Hermite between samples (its derivative -(N1 . T') T), made normal
/// and unit.
Eigen::Vector3d frame_at(const SampledPath& s, double t, const Eigen::Vector3d& tangent) {
  Eigen::Vector3d n;
  if (s.use_reference) {
    n = s.reference;
  } else {
    const double x = std::clamp((t - s.lo) / s.h, 0.0, double(s.c.size() - 1));
    const std::size_t k = std::min<std::size_t>(std::size_t(x), s.c.size() - 2);
    const double a = x - double(k), a2 = a * a, a3 = a2 * a;
    n = (2 * a3 - 3 * a2 + 1) * s.n1[k] + (a3 - 2 * a2 + a) * s.h * s.dn1[k] + (-2 * a3 + 3 * a2) * s.n1[k + 1] +
        (a3 - a2) * s.h * s.dn1[k + 1];
  }
  n -= tangent * tangent.dot(n);
  return n.normalized();
}

/// The direction among a spread of candidates that makes the largest least angle with the
/// tangents (as the sine of that angle).
std::pair<Eigen::Vector3d, double> reference_direction(const std::vector<Eigen::Vector3d>& tangents) {
  std::pair<Eigen::Vector3d, double> best{Eigen::Vector3d::UnitZ(), -1.0};
  const int m = 12;
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j < 2 * m; ++j) {
      const double th = M_PI / 2 * i / m, ph = M_PI * j / m;  // a hemisphere: a and -a are alike
      const Eigen::Vector3d a(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
      double least = 1.0;
      for (const auto& t : tangents) least = std::min(least, a.cross(t).norm());
      if (least > best.second) best = {a, least};
      if (i == 0) break;
    }
  return best;
}

}  // namespace

TopoDS_Shape ball_path_sweep(const Eigen::Vector3d& c0, double r, const StageMotion& m, double fit_tol,
                             double size, double* fit_err, std::vector<TopoDS_Face>* faces, std::string* why,
                             bool rotation_minimising) {
  const int n = 4096;
  SampledPath s;
  s.lo = m.lo();
  s.h = (m.hi() - m.lo()) / n;
  double vmax = 0, vmin = 1e300, rho_min = 1e300;
  for (int k = 0; k <= n; ++k) {
    Eigen::Vector3d d1, d2;
    s.c.push_back(centre_at(m, c0, s.lo + s.h * k, &d1, &d2));
    const double v = d1.norm();
    vmax = std::max(vmax, v);
    vmin = std::min(vmin, v);
    const Eigen::Vector3d tg = v > 0 ? Eigen::Vector3d(d1 / v) : Eigen::Vector3d::Zero();
    s.tangent.push_back(tg);
    s.dtangent.push_back(v > 0 ? Eigen::Vector3d((d2 - tg * tg.dot(d2)) / v) : Eigen::Vector3d::Zero());
    const double k_num = d1.cross(d2).norm();
    if (k_num > 0) rho_min = std::min(rho_min, v * v * v / k_num);
  }
  if (!(vmin > Settings::resolution * size / (m.hi() - m.lo()))) {
    *why = "the centre of the ball stops on its path (no normal circle there)";
    return {};
  }
  const double margin = 0.01 * r;
  if (!(rho_min > r + margin)) {
    *why = "the path of the ball's centre bends tighter than its radius (curvature radius " + std::to_string(rho_min) +
           " for radius " + std::to_string(r) + ")";
    return {};
  }
  s.arc.assign(n + 1, 0.0);
  for (int k = 1; k <= n; ++k) {
    s.arc[k] = s.arc[k - 1] + (s.c[k] - s.c[k - 1]).norm();
    // a tangent that turns between samples by more than that curvature allows: a corner (or a bend
    // the samples miss), where the union of the balls has more than the tube
    const double turn = std::acos(std::clamp(s.tangent[k - 1].dot(s.tangent[k]), -1.0, 1.0));
    if (turn > 2 * (s.arc[k] - s.arc[k - 1]) / (r + margin) + 1e-9) {
      *why = "the path of the ball's centre has a corner near t = " + std::to_string(s.lo + s.h * k);
      return {};
    }
  }
  // chords of points at least pi (r + margin) apart along the path; between samples a chord's
  // length changes by at most the speed bound times the spacing
  const double slack = vmax * s.h * 1.01, near = M_PI * (r + margin), need = 2 * (r + margin) + slack;
  for (int i = 0, j0 = 0; i <= n; ++i) {
    while (j0 <= n && s.arc[j0] - s.arc[i] < near) ++j0;
    for (int j = j0; j <= n; ++j)
      if ((s.c[j] - s.c[i]).squaredNorm() < need * need) {
        *why = "the path of the ball's centre comes back within its diameter (t = " + std::to_string(s.lo + s.h * i) +
               " and " + std::to_string(s.lo + s.h * j) + ")";
        return {};
      }
    if ((i & 255) == 0) check_stop();
  }
  const auto [reference, least_sine] = reference_direction(s.tangent);
  if (least_sine > 0.2 && !rotation_minimising) {
    s.use_reference = true;
    s.reference = reference;
  } else {
    // rotation minimising frame by double reflection (Wang, Juettler, Zheng, Liu 2008)
    s.n1.resize(n + 1);
    s.dn1.resize(n + 1);
    s.n1[0] = s.tangent[0].unitOrthogonal();
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d v1 = s.c[k + 1] - s.c[k];
      const double c1 = v1.squaredNorm();
      Eigen::Vector3d rL = s.n1[k], tL = s.tangent[k];
      if (c1 > 0) {
        rL -= (2 / c1) * v1.dot(rL) * v1;
        tL -= (2 / c1) * v1.dot(tL) * v1;
      }
      const Eigen::Vector3d v2 = s.tangent[k + 1] - tL;
      const double c2 = v2.squaredNorm();
      Eigen::Vector3d next = rL;
      if (c2 > 0) next -= (2 / c2) * v2.dot(rL) * v2;
      next -= s.tangent[k + 1] * s.tangent[k + 1].dot(next);
      s.n1[k + 1] = next.normalized();
    }
    for (int k = 0; k <= n; ++k) s.dn1[k] = -s.n1[k].dot(s.dtangent[k]) * s.tangent[k];
  }
  const int p = 9;
  const Fit circle = fit_unit_circle(p, 0.5 * fit_tol / r);
  if (r * circle.error > 0.5 * fit_tol) {
    *why = "the normal circle could not be fitted within the tolerance";
    return {};
  }
  const int nc = int(circle.poles.rows());
  const double L = m.hi() - m.lo();
  auto rows = [&](double u) {
    Eigen::Vector3d d1;
    const double t = std::min(m.lo() + u, m.hi());
    const Eigen::Vector3d c = centre_at(m, c0, t, &d1);
    const Eigen::Vector3d tg = d1.normalized();
    const Eigen::Vector3d a = frame_at(s, t, tg), b = tg.cross(a);
    Eigen::RowVectorXd row(3 * nc);
    for (int k = 0; k < nc; ++k) row.segment<3>(3 * k) = (c + r * (circle.poles(k, 0) * a + circle.poles(k, 1) * b)).transpose();
    return row;
  };
  // spans from the path's turning, then as the error of a degree-9 fit falls (as spans^-10)
  int spans = std::max(2, int(std::ceil(s.arc.back() / (2 * r))));
  Fit path;
  for (int attempt = 0; attempt < 8 && spans <= 1024; ++attempt) {
    check_stop();
    path = fit_bspline(rows, 3 * nc, L, p, spans, 1);
    if (path.error <= 0.5 * fit_tol) break;
    const double grow = std::pow(path.error / (0.5 * fit_tol), 0.1) * 1.25;
    spans = std::max(spans + 1, int(std::ceil(spans * std::min(grow, 4.0))));
  }
  if (!(path.error <= 0.5 * fit_tol)) {
    *why = "the tube could not be fitted within the tolerance (error " + std::to_string(path.error) + ")";
    return {};
  }
  const int np = int(path.poles.rows());
  TColgp_Array2OfPnt P(1, np, 1, nc);
  for (int i = 0; i < np; ++i)
    for (int k = 0; k < nc; ++k)
      P.SetValue(i + 1, k + 1, gp_Pnt(path.poles(i, 3 * k), path.poles(i, 3 * k + 1), path.poles(i, 3 * k + 2)));
  TColStd_Array1OfReal uk(1, int(path.knots.size())), vk(1, int(circle.knots.size()));
  TColStd_Array1OfInteger um(1, int(path.knots.size())), vm(1, int(circle.knots.size()));
  knots_of(path, uk, um);
  knots_of(circle, vk, vm);
  Handle(Geom_BSplineSurface) tube = new Geom_BSplineSurface(P, uk, vk, um, vm, p, p);
  std::vector<Eigen::Vector3d> rim0(nc), rim1(nc);
  for (int k = 0; k < nc; ++k) {
    rim0[k] = to_eigen(P.Value(1, k + 1));
    rim1[k] = to_eigen(P.Value(np, k + 1));
  }
  const Handle(Geom_BSplineSurface) back = half_ball(s.c.front(), r, -s.tangent.front(), rim0, circle, p);
  const Handle(Geom_BSplineSurface) front = half_ball(s.c.back(), r, s.tangent.back(), rim1, circle, p);
  const double tol = Settings::resolution * size;
  std::vector<TopoDS_Face> fs;
  for (const Handle(Geom_BSplineSurface)& srf : {tube, back, front}) {
    double a0, a1, b0, b1;
    srf->Bounds(a0, a1, b0, b1);
    BRepBuilderAPI_MakeFace mf(srf, a0, a1, b0, b1, tol);
    if (!mf.IsDone()) {
      *why = "a face of the tube could not be made";
      return {};
    }
    fs.push_back(mf.Face());
  }
  TopoDS_Shape solid = sew_solid(fs, tol);
  if (solid.IsNull() || !valid_and_closed(solid)) {
    *why = "the tube and its two half balls do not make a valid closed solid";
    return {};
  }
  *fit_err = std::max(*fit_err, r * circle.error + path.error);
  if (faces) *faces = fs;
  return solid;
}

}  // namespace sweep::occt
