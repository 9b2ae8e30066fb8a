// The solid swept by a ball under a screw motion, built directly when the path of its centre (a
// helix arc) has a reach larger than the radius: then every point of the boundary of the union of
// the balls has one nearest point on the path, and the boundary is exactly the tube of the normal
// circles (the grazing circles carried by the motion) closed by the back half of the ball at the
// start and the front half at the end. No arrangement is needed.
//
// The tube is a tensor-product B-spline: the grazing circle is fitted once (degree 9, uniform
// knots, within half the fitting tolerance); along the motion each of its control points moves on a
// helix, and these helices are fitted together (same knots, end points exact). The surface is a
// convex combination of the fitted helices, so its distance to the true tube is at most the circle
// error plus the largest helix error. The two half balls are rational surfaces (an exact quarter
// circle from rim to pole) on the tube's end rows, so the end circles are shared exactly. Uniform
// knots keep every face smooth (C8) inside: plain Gauss integration over a whole face, which OCCT's
// default mass properties use (and FreeCAD's Shape.Volume with them), stays accurate; a rational
// circle with its C1 knots was 0.45 % off there.
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <ShapeAnalysis_Shell.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>

#include "internal.hpp"

namespace sweep::occt {
namespace {

/// Values of the p+1 non-zero B-spline basis functions at x (span index `span`, The NURBS Book A2.2).
void basis_funs(int span, double x, int p, const std::vector<double>& U, double* N) {
  std::vector<double> left(p + 1), right(p + 1);
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = x - U[span + 1 - j];
    right[j] = U[span + j] - x;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double tmp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * tmp;
      saved = left[j - r] * tmp;
    }
    N[j] = saved;
  }
}

/// The clamped uniform knot vector's span containing x (last span for x at the end).
int find_span(double x, int p, int npoles, const std::vector<double>& U) {
  if (x >= U[npoles]) return npoles - 1;
  int lo = p, hi = npoles;
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (x < U[mid] ? hi : lo) = mid;
  }
  return lo;
}

/// A clamped B-spline of degree p with `spans` uniform spans on [0, L] (interior knots of
/// multiplicity `mult`) fitted by least squares to samples of f (a row of D values), its end
/// poles the exact end values.
struct Fit {
  std::vector<double> knots;  ///< distinct knots
  std::vector<int> mults;     ///< their multiplicities
  Eigen::MatrixXd poles;      ///< one row per pole
  double error = 0;           ///< largest distance measured (per group of three values)
};

Fit fit_bspline(const std::function<Eigen::RowVectorXd(double)>& f, int D, double L, int p, int spans, int mult) {
  Fit out;
  const int np = p + 1 + (spans - 1) * mult;
  std::vector<double> U;
  for (int i = 0; i <= p; ++i) U.push_back(0.0);
  for (int i = 1; i < spans; ++i)
    for (int k = 0; k < mult; ++k) U.push_back(L * i / spans);
  for (int i = 0; i <= p; ++i) U.push_back(L);
  out.knots.push_back(0.0);
  out.mults.push_back(p + 1);
  for (int i = 1; i < spans; ++i) {
    out.knots.push_back(L * i / spans);
    out.mults.push_back(mult);
  }
  out.knots.push_back(L);
  out.mults.push_back(p + 1);
  const int m = 4 * np + 8 * spans;  // samples, both ends included
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, np - 2);
  Eigen::MatrixXd Y(m, D);
  const Eigen::RowVectorXd first = f(0.0), last = f(L);
  std::vector<double> N(p + 1);
  for (int s = 0; s < m; ++s) {
    const double x = L * s / (m - 1);
    const int span = find_span(x, p, np, U);
    basis_funs(span, x, p, U, N.data());
    double n0 = 0, n1 = 0;
    for (int r = 0; r <= p; ++r) {
      const int i = span - p + r;
      if (i == 0) n0 = N[r];
      else if (i == np - 1) n1 = N[r];
      else A(s, i - 1) = N[r];
    }
    Y.row(s) = f(x) - n0 * first - n1 * last;
  }
  out.poles.resize(np, D);
  out.poles.row(0) = first;
  out.poles.row(np - 1) = last;
  out.poles.middleRows(1, np - 2) = A.colPivHouseholderQr().solve(Y);
  // error between the samples (8 points per span)
  const int ne = 8 * spans;
  for (int s = 0; s < ne; ++s) {
    const double x = L * (s + 0.5) / ne;
    const int span = find_span(x, p, np, U);
    basis_funs(span, x, p, U, N.data());
    Eigen::RowVectorXd v = Eigen::RowVectorXd::Zero(D);
    for (int r = 0; r <= p; ++r) v += out.poles.row(span - p + r) * N[r];
    const Eigen::RowVectorXd d = v - f(x);
    for (int g = 0; g + 3 <= D; g += 3) out.error = std::max(out.error, d.segment<3>(g).norm());
  }
  return out;
}

void knots_of(const Fit& fit, TColStd_Array1OfReal& knots, TColStd_Array1OfInteger& mults) {
  for (int i = 0; i < int(fit.knots.size()); ++i) {
    knots.SetValue(i + 1, fit.knots[i]);
    mults.SetValue(i + 1, fit.mults[i]);
  }
}

/// Half of a ball (centre c, radius r, pole in direction t) bounded by the closed curve `rim`
/// (points c + r C(v) with C a fitted unit circle perpendicular to t, its poles given): the
/// surface c + r (x(u) C(v) + z(u) t), with (x, z) the exact rational quarter circle from the rim
/// (u = 0) to the pole (u = pi / 2). Its first row is the rim itself.
Handle(Geom_BSplineSurface) half_ball(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& t,
                                     const std::vector<Eigen::Vector3d>& rim, const Fit& circle, int p) {
  const int nc = int(rim.size());
  // rows: rim, its corner above (weight 1/sqrt 2), the pole
  const std::vector<double> weight{1.0, std::sqrt(0.5), 1.0};
  const int rows = int(weight.size());
  TColgp_Array2OfPnt P(1, rows, 1, nc);
  TColStd_Array2OfReal W(1, rows, 1, nc);
  for (int l = 0; l < rows; ++l)
    for (int k = 0; k < nc; ++k) {
      P.SetValue(l + 1, k + 1, to_pnt(l == 0 ? rim[k] : l == 1 ? Eigen::Vector3d(rim[k] + r * t) : Eigen::Vector3d(c + r * t)));
      W.SetValue(l + 1, k + 1, weight[l]);
    }
  TColStd_Array1OfReal uk(1, 2), vk(1, int(circle.knots.size()));
  TColStd_Array1OfInteger um(1, 2), vm(1, int(circle.knots.size()));
  uk.SetValue(1, 0.0);
  uk.SetValue(2, M_PI / 2);
  um.Init(3);
  knots_of(circle, vk, vm);
  return new Geom_BSplineSurface(P, W, uk, vk, um, vm, 2, p);
}

}  // namespace

bool sphere_of(const TopoDS_Shape& body, Eigen::Vector3d* centre, double* radius) {
  TopExp_Explorer ex(body, TopAbs_FACE);
  if (!ex.More()) return false;
  const TopoDS_Face face = TopoDS::Face(ex.Current());
  ex.Next();
  if (ex.More()) return false;
  Handle(Geom_Surface) s = BRep_Tool::Surface(face);
  while (s->IsKind(STANDARD_TYPE(Geom_RectangularTrimmedSurface)))
    s = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)->BasisSurface();
  Handle(Geom_SphericalSurface) sph = Handle(Geom_SphericalSurface)::DownCast(s);
  if (sph.IsNull()) return false;
  // the whole sphere: its face spans the full parameter ranges
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  if (u1 - u0 < 2 * M_PI - 1e-9 || v0 > -M_PI / 2 + 1e-9 || v1 < M_PI / 2 - 1e-9) return false;
  *centre = to_eigen(sph->Location());
  *radius = sph->Radius();
  return true;
}

bool helix_reach_exceeds(const ScrewJoint& j, const Eigen::Vector3d& c, double T, double r, double margin) {
  if (j.type != JointType::Helical || j.pitch == 0) return false;
  const Eigen::Vector3d w = j.direction;
  const Eigen::Vector3d d = (c - j.point) - w * w.dot(c - j.point);
  const double R = d.norm(), b = j.pitch;
  if (R <= 1e-9 * (r + std::abs(b))) return false;  // the centre on the axis: a straight path
  // local: the helix's radius of curvature (R^2 + b^2) / R
  if ((R * R + b * b) / R <= r + margin) return false;
  // global: chords |c(s) - c(s + D)|^2 = 2 R^2 (1 - cos D) + b^2 D^2 grow until the first zero D1 of
  // R^2 sin D + b^2 D; double normals (and the end pair) have D in [D1, T], and their half lengths
  // bound the reach from below.
  auto chord = [&](double D) { return std::sqrt(2 * R * R * (1 - std::cos(D)) + b * b * D * D); };
  auto g = [&](double D) { return R * R * std::sin(D) + b * b * D; };
  double D1 = -1;
  {
    const int n = 256;
    double prev = M_PI;
    for (int k = 1; k <= n; ++k) {  // g > 0 on (0, pi]; its first zero lies in (pi, 2 pi]
      const double D = M_PI + M_PI * k / n;
      if (g(D) <= 0) {
        double lo = prev, hi = D;
        for (int it = 0; it < 60; ++it) ((g(0.5 * (lo + hi)) > 0) ? lo : hi) = 0.5 * (lo + hi);
        D1 = lo;
        break;
      }
      prev = D;
    }
  }
  if (D1 < 0 || D1 >= T) return true;  // chords grow over the whole range
  // min of the chord over [D1, T], sampled with a bound on the chord's slope (the helix speed)
  const double speed = std::sqrt(R * R + b * b);
  const int n = std::max(64, int(std::ceil((T - D1) / (0.01 * r / speed))));
  const double h = (T - D1) / n;
  double lo = 1e300;
  for (int k = 0; k <= n; ++k) lo = std::min(lo, chord(D1 + h * k));
  return lo - h * speed > 2 * (r + margin);
}

TopoDS_Shape ball_screw_sweep(const Eigen::Vector3d& c, double r, const ScrewJoint& j, double T, double fit_tol,
                              double size, double* fit_err, std::vector<TopoDS_Face>* faces) {
  const Eigen::Vector3d t0 = j.velocity(c).normalized();
  const Eigen::Vector3d n0 = t0.unitOrthogonal(), b0 = t0.cross(n0);
  // Polynomial B-splines of degree 9 with uniform knots: smooth enough (C8) that plain Gauss
  // integration over a whole face (as OCCT's default mass properties do) stays accurate.
  const int p = 9;
  // the grazing circle, fitted once as a unit circle, within half the tolerance
  Fit circle;
  for (int spans = 4; spans <= 256; spans += std::max(1, spans / 4)) {
    circle = fit_bspline([](double a) { return Eigen::RowVector3d(std::cos(a), std::sin(a), 0.0); }, 3, 2 * M_PI,
                         p, spans, 1);
    if (r * circle.error <= 0.5 * fit_tol) break;
  }
  if (r * circle.error > 0.5 * fit_tol) return {};
  const int nc = int(circle.poles.rows());
  std::vector<Eigen::Vector3d> Q(nc);
  for (int k = 0; k < nc; ++k) Q[k] = c + r * (circle.poles(k, 0) * n0 + circle.poles(k, 1) * b0);
  // the helices of its poles, fitted together within the other half
  auto helices = [&](double q) {
    const Eigen::Isometry3d M = j.transform(q);
    Eigen::RowVectorXd row(3 * nc);
    for (int k = 0; k < nc; ++k) row.segment<3>(3 * k) = (M * Q[k]).transpose();
    return row;
  };
  Fit path;
  for (int spans = std::max(1, int(std::ceil(T / M_PI))); spans <= 512; spans += std::max(1, spans / 4)) {
    path = fit_bspline(helices, 3 * nc, T, p, spans, 1);
    if (path.error <= 0.5 * fit_tol) break;
  }
  if (path.error > 0.5 * fit_tol) return {};
  *fit_err = std::max(*fit_err, r * circle.error + path.error);
  const int np = int(path.poles.rows());
  // tube: u along the motion, v around the circle
  TColgp_Array2OfPnt P(1, np, 1, nc);
  for (int i = 0; i < np; ++i)
    for (int k = 0; k < nc; ++k)
      P.SetValue(i + 1, k + 1, gp_Pnt(path.poles(i, 3 * k), path.poles(i, 3 * k + 1), path.poles(i, 3 * k + 2)));
  TColStd_Array1OfReal uk(1, int(path.knots.size())), vk(1, int(circle.knots.size()));
  TColStd_Array1OfInteger um(1, int(path.knots.size())), vm(1, int(circle.knots.size()));
  knots_of(path, uk, um);
  knots_of(circle, vk, vm);
  Handle(Geom_BSplineSurface) tube = new Geom_BSplineSurface(P, uk, vk, um, vm, p, p);
  // half balls on the tube's end rows (the exact images of the fitted circle)
  std::vector<Eigen::Vector3d> rim0(nc), rim1(nc);
  for (int k = 0; k < nc; ++k) {
    rim0[k] = to_eigen(P.Value(1, k + 1));
    rim1[k] = to_eigen(P.Value(np, k + 1));
  }
  const Eigen::Isometry3d MT = j.transform(T);
  Handle(Geom_BSplineSurface) back = half_ball(c, r, -t0, rim0, circle, p);
  Handle(Geom_BSplineSurface) front = half_ball(MT * c, r, MT.linear() * t0, rim1, circle, p);
  const double tol = 1e-9 * size;
  BRepBuilderAPI_Sewing sew(tol);
  std::vector<TopoDS_Face> fs;
  for (const Handle(Geom_BSplineSurface)& srf : {tube, back, front}) {
    double a0, a1, b0_, b1;
    srf->Bounds(a0, a1, b0_, b1);
    BRepBuilderAPI_MakeFace mf(srf, a0, a1, b0_, b1, tol);
    if (!mf.IsDone()) return {};
    fs.push_back(mf.Face());
    sew.Add(mf.Face());
  }
  sew.Perform();
  TopoDS_Shape sewn = sew.SewedShape();
  TopExp_Explorer sx(sewn, TopAbs_SHELL);
  if (!sx.More()) return {};
  BRepBuilderAPI_MakeSolid ms(TopoDS::Shell(sx.Current()));
  if (!ms.IsDone()) return {};
  TopoDS_Solid solid = ms.Solid();
  BRepLib::OrientClosedSolid(solid);
  if (faces) *faces = fs;
  return solid;
}

}  // namespace sweep::occt
