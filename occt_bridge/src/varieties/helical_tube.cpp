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
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Line.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
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
#include <optional>

#include "base/internal.hpp"
#include "base/stop.hpp"
#include "varieties/tube_fit.hpp"

namespace sweep::occt {
namespace {

/// The chord |c(s) - c(s + D)| of a helix of radius R rising b per radian.
double helix_chord(double R, double b, double D) { return std::sqrt(2 * R * R * (1 - std::cos(D)) + b * b * D * D); }

/// A lower bound of the chord |c(s) - c(s + D)| of a helix (radius R, rise b per radian) over D in
/// [D0, D1]: its least value on samples spaced Settings::helix_chord_spacing of r / speed apart,
/// less what it can drop between two samples (its slope is at most the helix speed).
double chord_lower_bound(double R, double b, double r, double D0, double D1) {
  auto chord = [&](double D) { return helix_chord(R, b, D); };
  const double speed = std::sqrt(R * R + b * b);
  const int n =
      std::max(Settings::helix_chord_samples, int(std::ceil((D1 - D0) / (Settings::helix_chord_spacing * r / speed))));
  const double h = (D1 - D0) / n;
  double lo = 1e300;
  for (int k = 0; k <= n; ++k) lo = std::min(lo, chord(D0 + h * k));
  return lo - h * speed;
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
  if (u1 - u0 < 2 * M_PI - Settings::whole_period_margin || v0 > -M_PI / 2 + Settings::whole_period_margin ||
      v1 < M_PI / 2 - Settings::whole_period_margin)
    return false;
  *centre = to_eigen(sph->Location());
  *radius = sph->Radius();
  return true;
}

bool helix_reach_exceeds(const ScrewJoint& j, const Eigen::Vector3d& c, double T, double r, double margin) {
  if (j.type != JointType::Helical || j.pitch == 0) return false;
  const Eigen::Vector3d w = j.direction;
  const Eigen::Vector3d d = (c - j.point) - w * w.dot(c - j.point);
  const double R = d.norm(), b = j.pitch;
  if (R <= Settings::on_axis_resolution * (r + std::abs(b))) return false;  // the centre on the axis: a straight path
  // local: the helix's radius of curvature (R^2 + b^2) / R
  if ((R * R + b * b) / R <= r + margin) return false;
  // global: chords |c(s) - c(s + D)|^2 = 2 R^2 (1 - cos D) + b^2 D^2 grow until the first zero D1 of
  // R^2 sin D + b^2 D; double normals (and the end pair) have D in [D1, T], and their half lengths
  // bound the reach from below.
  auto g = [&](double D) { return R * R * std::sin(D) + b * b * D; };
  double D1 = -1;
  {
    const int n = Settings::helix_turn_samples;
    double prev = M_PI;
    for (int k = 1; k <= n; ++k) {  // g > 0 on (0, pi]; its first zero lies in (pi, 2 pi]
      const double D = M_PI + M_PI * k / n;
      if (g(D) <= 0) {
        double lo = prev, hi = D;
        for (int it = 0; it < Settings::helix_turn_bisections; ++it)
          ((g(0.5 * (lo + hi)) > 0) ? lo : hi) = 0.5 * (lo + hi);
        D1 = lo;
        break;
      }
      prev = D;
    }
  }
  if (D1 < 0 || D1 >= T) return true;  // chords grow over the whole range
  return chord_lower_bound(R, b, r, D1, T) > 2 * (r + margin);
}

namespace {

/// The tube of a ball's screw sweep and its two half balls, as B-spline surfaces: the tube with u
/// along the motion ([0, T]) and v around the grazing circle ([0, 2 pi], starting at angle `phase`
/// from an arbitrary normal), the half balls with u from the rim (0) to the pole (pi / 2) and the
/// tube's v; their rims are the tube's end rows.
struct Tube {
  Handle(Geom_BSplineSurface) tube, back, front;
  double error = 0;  ///< distance bound between the tube and the true tube
  Eigen::Vector3d n0, b0, t0;  ///< the circle's frame at the start: v = 0 along n0, t0 the motion
};

bool build_tube(const Eigen::Vector3d& c, double r, const ScrewJoint& j, double T, double fit_tol, double phase,
                Tube* out) {
  const Eigen::Vector3d t0 = j.velocity(c).normalized();
  const Eigen::Vector3d m0 = t0.unitOrthogonal(), m1 = t0.cross(m0);
  const Eigen::Vector3d n0 = std::cos(phase) * m0 + std::sin(phase) * m1, b0 = t0.cross(n0);
  // Polynomial B-splines of degree 9 with uniform knots: smooth enough (C8) that plain Gauss
  // integration over a whole face (as OCCT's default mass properties do) stays accurate.
  const int p = 9;
  // the grazing circle, fitted once as a unit circle, within half the tolerance
  const Fit circle = fit_unit_circle(p, 0.5 * fit_tol / r);
  if (r * circle.error > 0.5 * fit_tol) return false;
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
  for (int spans = std::max(1, int(std::ceil(T / M_PI))); spans <= Settings::ball_tube_max_spans;
       spans += std::max(1, spans / 4)) {
    path = fit_bspline(helices, 3 * nc, T, p, spans, 1);
    if (path.error <= 0.5 * fit_tol) break;
  }
  if (path.error > 0.5 * fit_tol) return false;
  out->error = r * circle.error + path.error;
  out->n0 = n0;
  out->b0 = b0;
  out->t0 = t0;
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
  out->tube = new Geom_BSplineSurface(P, uk, vk, um, vm, p, p);
  // half balls on the tube's end rows (the exact images of the fitted circle)
  std::vector<Eigen::Vector3d> rim0(nc), rim1(nc);
  for (int k = 0; k < nc; ++k) {
    rim0[k] = to_eigen(P.Value(1, k + 1));
    rim1[k] = to_eigen(P.Value(np, k + 1));
  }
  const Eigen::Isometry3d MT = j.transform(T);
  out->back = half_ball(c, r, -t0, rim0, circle, p);
  out->front = half_ball(MT * c, r, MT.linear() * t0, rim1, circle, p);
  return true;
}

}  // namespace

TopoDS_Shape sew_solid(const std::vector<TopoDS_Face>& fs, double tol, const OutwardHint* hint) {
  BRepBuilderAPI_Sewing sew(tol);
  for (const auto& f : fs) sew.Add(f);
  sew.Perform(stop_range());
  check_stop();
  TopoDS_Shape sewn = sew.SewedShape();
  if (sewn.ShapeType() == TopAbs_FACE) {  // one face closed on itself (a sphere, a torus): its shell
    TopoDS_Shell one;
    BRep_Builder b;
    b.MakeShell(one);
    b.Add(one, sewn);
    one.Closed(BRep_Tool::IsClosed(one));
    sewn = one;
  }
  TopExp_Explorer sx(sewn, TopAbs_SHELL);
  if (!sx.More()) return {};
  const TopoDS_Shell shell = TopoDS::Shell(sx.Current());
  sx.Next();
  if (sx.More()) return {};
  BRepBuilderAPI_MakeSolid ms(shell);
  if (!ms.IsDone()) return {};
  TopoDS_Solid solid = ms.Solid();
  // the hinted face as sewn, with its orientation in the solid: its normal against `out`
  double side = 0;
  if (hint && hint->face < fs.size()) {
    const TopoDS_Shape sewn_face = sew.Modified(fs[hint->face]);
    for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More() && !sewn_face.IsNull(); ex.Next()) {
      if (!ex.Current().IsSame(sewn_face)) continue;
      const TopoDS_Face& f = TopoDS::Face(ex.Current());
      TopLoc_Location loc;
      const Handle(Geom_Surface) S = BRep_Tool::Surface(f, loc);
      if (S.IsNull()) break;
      gp_Pnt p;
      gp_Vec su, sv;
      S->D1(hint->u, hint->v, p, su, sv);
      gp_Vec n = su.Crossed(sv).Transformed(loc.Transformation());
      if (f.Orientation() == TopAbs_REVERSED) n.Reverse();
      const double m = n.Magnitude() * hint->out.Magnitude();
      if (m > 0) side = n.Dot(hint->out) / m;
      break;
    }
  }
  if (std::abs(side) > 0.1) {
    if (side < 0) solid.Reverse();
  } else {
    BRepLib::OrientClosedSolid(solid);
  }
  return solid;
}

TopoDS_Shape ball_screw_sweep(const Eigen::Vector3d& c, double r, const ScrewJoint& j, double T, double fit_tol,
                              double size, double* fit_err, std::vector<TopoDS_Face>* faces) {
  Tube tb;
  if (!build_tube(c, r, j, T, fit_tol, 0.0, &tb)) return {};
  *fit_err = std::max(*fit_err, tb.error);
  const double tol = Settings::resolution * size;
  std::vector<TopoDS_Face> fs;
  for (const Handle(Geom_BSplineSurface)& srf : {tb.tube, tb.back, tb.front}) {
    double a0, a1, b0_, b1;
    srf->Bounds(a0, a1, b0_, b1);
    BRepBuilderAPI_MakeFace mf(srf, a0, a1, b0_, b1, tol);
    if (!mf.IsDone()) return {};
    fs.push_back(mf.Face());
  }
  TopoDS_Shape solid = sew_solid(fs, tol);
  if (!solid.IsNull() && faces) *faces = fs;
  return solid;
}


namespace {

/// Root of a function increasing through zero on [a, b] (f(a) <= 0 <= f(b)), Illinois regula falsi.
double root_between(const std::function<double(double)>& f, double a, double b) {
  double fa = f(a), fb = f(b);
  if (fa >= 0) return a;
  if (fb <= 0) return b;
  for (int it = 0; it < Settings::helix_root_iterations && b - a > Settings::helix_root_precision * (1 + std::abs(a));
       ++it) {
    const double x = b - fb * (b - a) / (fb - fa);
    const double fx = f(x);
    if (fx == 0) return x;
    if (fx < 0) {
      a = x, fa = fx;
      fb *= 0.5;
    } else {
      b = x, fb = fx;
      fa *= 0.5;
    }
  }
  return 0.5 * (a + b);
}

/// The path of a point under a screw motion, c(s) = M(s) c, with its first two derivatives.
struct HelixPath {
  Eigen::Vector3d o, e1, e2, w;  ///< c(s) = o + cos s e1 + sin s e2 + b s w
  double b = 0;
  HelixPath(const ScrewJoint& j, const Eigen::Vector3d& c) : w(j.direction), b(j.pitch) {
    const Eigen::Vector3d d = c - j.point;
    e1 = d - w * w.dot(d);
    e2 = w.cross(e1);
    o = c - e1;
  }
  double radius() const { return e1.norm(); }
  Eigen::Vector3d pos(double s) const { return o + std::cos(s) * e1 + std::sin(s) * e2 + b * s * w; }
  Eigen::Vector3d d1(double s) const { return -std::sin(s) * e1 + std::cos(s) * e2 + b * w; }
  Eigen::Vector3d d2(double s) const { return -std::cos(s) * e1 - std::sin(s) * e2; }
  double chord(double D) const { return helix_chord(radius(), b, D); }
  /// min over s in [lo, hi] of |x - c(s)|^2, the minimiser in *arg (sampled, then Newton
  /// safeguarded by bisection on the derivative).
  double min_dist2(const Eigen::Vector3d& x, double lo, double hi, double* arg) const {
    const int n = Settings::helix_distance_samples;
    double best = 1e300;
    int kb = 0;
    for (int k = 0; k <= n; ++k) {
      const double d2 = (x - pos(lo + (hi - lo) * k / n)).squaredNorm();
      if (d2 < best) best = d2, kb = k;
    }
    auto g = [&](double s) { return -2 * (x - pos(s)).dot(d1(s)); };
    double a = lo + (hi - lo) * std::max(kb - 1, 0) / n, bb = lo + (hi - lo) * std::min(kb + 1, n) / n;
    double s = lo + (hi - lo) * kb / n;
    if (g(a) <= 0 && g(bb) >= 0) {
      for (int it = 0; it < Settings::helix_distance_iterations; ++it) {
        const Eigen::Vector3d y = pos(s), y1 = d1(s);
        const double gs = -2 * (x - y).dot(y1), hs = 2 * y1.squaredNorm() - 2 * (x - y).dot(d2(s));
        (gs < 0 ? a : bb) = s;
        double ns = s - gs / hs;
        if (!(hs > 0) || ns <= a || ns >= bb) ns = 0.5 * (a + bb);
        const bool done = std::abs(ns - s) <= Settings::helix_distance_precision * (1 + std::abs(s));
        s = ns;
        if (done || bb - a <= Settings::helix_distance_precision * (1 + std::abs(s))) break;
      }
      best = (x - pos(s)).squaredNorm();
    }
    if (arg) *arg = s;
    return best;
  }
  /// The root of |x - c(s)|^2 = r^2 between s0 (where it is below) and s1 (where it is above).
  double crossing(const Eigen::Vector3d& x, double r, double s0, double s1) const {
    auto h = [&](double s) { return (x - pos(s)).squaredNorm() - r * r; };
    if (s0 < s1) return root_between(h, s0, s1);
    return root_between([&](double s) { return -h(s); }, s1, s0);
  }
};

/// An edge on surface S along the 2D curve c over [a, b], with its 3D curve built from it.
TopoDS_Edge edge_on(const Handle(Geom_Surface)& S, const Handle(Geom2d_Curve)& c, double a, double b, double tol) {
  BRepBuilderAPI_MakeEdge me(c, S, a, b);
  if (!me.IsDone()) return {};
  TopoDS_Edge e = me.Edge();
  if (!BRepLib::BuildCurve3d(e, tol, GeomAbs_C1, Settings::tongue_edge_max_degree, Settings::tongue_edge_max_segments))
    return {};
  return e;
}

/// The straight edge from p to q in S's parameter plane.
TopoDS_Edge segment_on(const Handle(Geom_Surface)& S, const gp_Pnt2d& p, const gp_Pnt2d& q, double tol) {
  const double len = p.Distance(q);
  if (len <= 0) return {};
  Handle(Geom2d_Line) line = new Geom2d_Line(p, gp_Dir2d(q.X() - p.X(), q.Y() - p.Y()));
  return edge_on(S, line, 0.0, len, tol);
}

/// A B-spline curve in a parameter plane fitted to f on [0, pi] (rows (x, y, 0)), within `tol` in
/// that plane; null when no fit reaches it.
Handle(Geom2d_BSplineCurve) fit_pcurve(const std::function<Eigen::RowVectorXd(double)>& f, double tol, double* err) {
  const int p = 7;
  // the error falls like spans^-(p + 1): from the error at 8 spans, the number that should reach
  // tol (with a margin), then more if needed
  Fit fit;
  int spans = 8;
  for (int attempt = 0; attempt < 6 && spans <= Settings::tongue_fit_max_spans; ++attempt) {
    fit = fit_bspline(f, 3, M_PI, p, spans, 1);
    if (fit.error <= tol) break;
    const double grow = std::pow(fit.error / tol, 1.0 / (p + 1));
    spans = std::max(spans + 1, int(std::ceil(Settings::tongue_fit_span_margin * spans * grow)));
  }
  if (!(fit.error <= tol)) return {};
  *err = std::max(*err, fit.error);
  TColgp_Array1OfPnt2d poles(1, int(fit.poles.rows()));
  for (int i = 0; i < int(fit.poles.rows()); ++i) poles.SetValue(i + 1, gp_Pnt2d(fit.poles(i, 0), fit.poles(i, 1)));
  TColStd_Array1OfReal knots(1, int(fit.knots.size()));
  TColStd_Array1OfInteger mults(1, int(fit.knots.size()));
  knots_of(fit, knots, mults);
  return new Geom2d_BSplineCurve(poles, knots, mults, p);
}

}  // namespace

namespace {

/// A ball screw-swept over more than a turn and a half whose neighbouring turns meet, built in
/// steps that share what they find: the arcs of the start circle that the next and the previous
/// turn cover, the tube's tongues (where it leaves the set a neighbouring turn covers) and the half
/// balls' tongues, a guard that samples the covered set, and the faces.
class OverlapSweep {
 public:
  OverlapSweep(const Eigen::Vector3d& c, double r, const ScrewJoint& j, double T, double fit_tol, double size)
      : c_(c), r_(r), j_(j), T_(T), fit_tol_(fit_tol), size_(size), H_(j, c) {}

  /// The seam's angle on the start circle when the sweep is one this builds: the tube smooth, only
  /// neighbouring turns meeting, each covering one arc of the start circle, the two apart.
  std::optional<double> seam_phase() const;
  /// The tube from `phase`, the covered arcs in its v, and the tongues of the tube and of the half
  /// balls fitted; false when a step does not reach its tolerance.
  bool tongues(double phase);
  /// The faces sewn into the solid while the guard runs; null when either fails.
  TopoDS_Shape solid(std::vector<TopoDS_Face>* faces, std::vector<int>* roles);
  /// The tube's bound on its distance from the true tube, and the fits' errors carried to space.
  double error() const { return err_; }

 private:
  /// The tolerance of the faces' edges, built from their parameter-plane curves.
  double edge_tol() const { return std::max(Settings::resolution * size_, 0.1 * fit_tol_); }
  double covered_up(const Eigen::Vector3d& x) const { return H_.min_dist2(x, up_lo, up_hi, nullptr) - r_ * r_; }
  double covered_dn(const Eigen::Vector3d& x) const { return H_.min_dist2(x, dn_lo, dn_hi, nullptr) - r_ * r_; }
  Eigen::Vector3d start_row(double v) const { return to_eigen(tb_.tube->Value(0.0, v)); }
  bool arc(int which, double* v1, double* v2) const;
  double tongue_time(double v, bool up, bool end = false) const;
  Eigen::Vector3d tube_point(double v, bool up, bool end = false) const {
    return to_eigen(tb_.tube->Value(tongue_time(v, up, end), v));
  }
  Handle(Geom2d_BSplineCurve) tube_tongue(double vs, double ve, bool up, double* e2d) const;
  double on_ball(const Handle(Geom_BSplineSurface)& ball, const Eigen::Isometry3d& M, const Eigen::Vector3d& pole,
                 const Eigen::Vector3d& y, double* u, double* v) const;
  Handle(Geom2d_BSplineCurve) ball_tongue(const Handle(Geom_BSplineSurface)& ball, const Eigen::Isometry3d& M,
                                          const Eigen::Vector3d& pole, double vs, double ve, double ts, double te,
                                          bool up, double* umax, double* proj_err, double* e2d) const;
  bool guard(std::size_t part) const;
  bool tube_face(double vlo, double vhi, std::vector<TopoDS_Face>& fs, std::vector<int>& rl) const;
  bool ball_faces(const Handle(Geom_BSplineSurface)& ball, const Handle(Geom2d_BSplineCurve)& tongue, double v1,
                  double v2, double umax, int role, std::vector<TopoDS_Face>& fs, std::vector<int>& rl) const;

  static constexpr double up_lo = M_PI, up_hi = 3 * M_PI, dn_lo = -3 * M_PI, dn_hi = -M_PI;
  Eigen::Vector3d c_;
  double r_;
  const ScrewJoint& j_;
  double T_, fit_tol_, size_;
  HelixPath H_;
  Tube tb_;
  double err_ = 0;
  double a1_ = 0, a2_ = 0, b1_ = 0, b2_ = 0;  ///< the arcs in the tube's v: [a1, a2] covered from above, [b1, b2] from below
  double speed_ = 0;
  Handle(Geom2d_BSplineCurve) tongue_up_, tongue_dn_, back_tongue_, front_tongue_;
  double Ua1_ = 0, Ua2_ = 0, Ub1_ = 0, Ub2_ = 0, umax_back_ = 0, umax_front_ = 0, e2d_ = 0;
};

std::optional<double> OverlapSweep::seam_phase() const {
  const double R = H_.radius(), b = j_.pitch, margin = Settings::overlap_margin * r_;
  if (R <= Settings::on_axis_resolution * (r_ + std::abs(b))) return std::nullopt;
  // the tube is smooth (radius of curvature above r), a whole turn and a half is swept, balls
  // half a turn apart or two turns and more apart are disjoint: only the neighbouring turns meet
  if ((R * R + b * b) / R <= r_ + margin || T_ < 3 * M_PI) return std::nullopt;
  if (H_.chord(M_PI) <= 2 * (r_ + margin)) return std::nullopt;
  if (chord_lower_bound(R, b, r_, 3 * M_PI, T_) <= 2 * (r_ + margin)) return std::nullopt;
  // Points of the grazing circle at the start covered by the next turn (sigma in (pi, 3 pi)) and
  // by the previous one (sigma in (-3 pi, -pi)): each must be one arc, the two disjoint.
  const Eigen::Vector3d t0 = j_.velocity(c_).normalized();
  const Eigen::Vector3d m0 = t0.unitOrthogonal(), m1 = t0.cross(m0);
  const int N = Settings::overlap_circle_samples;
  std::vector<int> state(N);  // 1: covered from above, 2: from below
  for (int k = 0; k < N; ++k) {
    const double th = 2 * M_PI * k / N;
    const Eigen::Vector3d x = c_ + r_ * (std::cos(th) * m0 + std::sin(th) * m1);
    // and no ball within half a turn reaches it (the local tube is the boundary there)
    if (H_.min_dist2(x, Settings::overlap_local_gap, M_PI, nullptr) <= r_ * r_ ||
        H_.min_dist2(x, -M_PI, -Settings::overlap_local_gap, nullptr) <= r_ * r_)
      return std::nullopt;
    const bool u = covered_up(x) < 0, d = covered_dn(x) < 0;
    if (u && d) return std::nullopt;
    state[k] = u ? 1 : d ? 2 : 0;
  }
  // one arc of each kind, separated by uncovered samples; the seam goes in the middle of the
  // longer gap
  int changes = 0, gap_start = -1, gap_len = 0;
  for (int k = 0; k < N; ++k)
    if (state[k] != state[(k + N - 1) % N]) ++changes;
  if (changes != 4) return std::nullopt;
  for (int k = 0; k < N; ++k) {
    if (state[k] != 0 || state[(k + N - 1) % N] == 0) continue;
    int len = 0;
    while (state[(k + len) % N] == 0) ++len;
    if (len > gap_len) gap_len = len, gap_start = k;
  }
  if (gap_start < 0 || gap_len < 4) return std::nullopt;
  return 2 * M_PI * (gap_start + 0.5 * gap_len) / N;
}

bool OverlapSweep::arc(int which, double* v1, double* v2) const {
  auto f = [&](double v) { return which == 1 ? covered_up(start_row(v)) : covered_dn(start_row(v)); };
  const int M = Settings::overlap_arc_samples;
  int first = -1, last = -1;
  for (int k = 1; k < M; ++k) {
    const bool in = f(2 * M_PI * k / M) < 0;
    if (in && first < 0) first = k;
    if (in) last = k;
  }
  if (first <= 1 || last >= M - 1) return false;
  const double h = 2 * M_PI / M;
  *v1 = root_between([&](double v) { return -f(v); }, h * (first - 1), h * first);
  *v2 = root_between(f, h * last, h * (last + 1));
  return *v2 > *v1;
}

// Where the tube leaves the set covered by a neighbouring turn: for v in [a1, a2] the points at
// u <= T - a+(v) lie in the next turn (a+ the first time its ball reaches the start point), for
// v in [b1, b2] those at u >= -b-(v) in the previous one. At the arc ends the two crossing times
// meet (`end`: there they are the time of least distance).
double OverlapSweep::tongue_time(double v, bool up, bool end) const {
  const Eigen::Vector3d x = start_row(v);
  double sm;
  const double d2 = up ? H_.min_dist2(x, up_lo, up_hi, &sm) : H_.min_dist2(x, dn_lo, dn_hi, &sm);
  if (end || d2 >= r_ * r_) return up ? T_ - sm : -sm;
  return up ? T_ - H_.crossing(x, r_, sm, up_lo) : -H_.crossing(x, r_, sm, dn_hi);
}

// v = v1 + (v2 - v1)(1 - cos phi) / 2 makes the curve smooth in phi at the arc's ends.
Handle(Geom2d_BSplineCurve) OverlapSweep::tube_tongue(double vs, double ve, bool up, double* e2d) const {
  const double ptol = 0.5 * fit_tol_ / speed_;
  return fit_pcurve(
      [&](double ph) {
        const double v = vs + (ve - vs) * 0.5 * (1 - std::cos(ph));
        return Eigen::RowVector3d(tongue_time(v, up, ph == 0 || ph == M_PI), v, 0.0);
      },
      ptol, e2d);
}

double OverlapSweep::on_ball(const Handle(Geom_BSplineSurface)& ball, const Eigen::Isometry3d& M,
                             const Eigen::Vector3d& pole, const Eigen::Vector3d& y, double* u, double* v) const {
  // start from the angles about the ball's centre, then Gauss-Newton on the surface
  const Eigen::Vector3d d = M.inverse() * y - c_;
  const double z = d.dot(pole);
  *v = std::atan2(d.dot(tb_.b0), d.dot(tb_.n0));
  if (*v < 0) *v += 2 * M_PI;
  *u = std::atan2(z, (d - z * pole).norm());
  for (int it = 0; it < Settings::ball_projection_iterations; ++it) {
    gp_Pnt P;
    gp_Vec Su, Sv;
    ball->D1(*u, *v, P, Su, Sv);
    const Eigen::Vector3d e = to_eigen(P) - y, a = to_eigen(Su), bb = to_eigen(Sv);
    Eigen::Matrix2d A;
    A << a.dot(a), a.dot(bb), a.dot(bb), bb.dot(bb);
    const Eigen::Vector2d step = A.ldlt().solve(Eigen::Vector2d(a.dot(e), bb.dot(e)));
    *u -= step(0);
    *v -= step(1);
    if (step.norm() < Settings::ball_projection_step) break;
  }
  return (to_eigen(ball->Value(*u, *v)) - y).norm();
}

// On the half balls the part inside the neighbouring turn is bounded by the same curve as the
// tube's tongue (the ball meets that turn's tube there); its points are projected on the ball. The
// ball's tongue runs from the rim point at v = vs to the one at ve, along the tube's tongue (from
// tube v = ts to te, `up` for the tongue of the next turn).
Handle(Geom2d_BSplineCurve) OverlapSweep::ball_tongue(const Handle(Geom_BSplineSurface)& ball,
                                                      const Eigen::Isometry3d& M, const Eigen::Vector3d& pole,
                                                      double vs, double ve, double ts, double te, bool up,
                                                      double* umax, double* proj_err, double* e2d) const {
  // which end of the tube's tongue is the rim point at vs
  const Eigen::Vector3d rs = to_eigen(ball->Value(0.0, vs));
  if ((tube_point(te, up, true) - rs).norm() < (tube_point(ts, up, true) - rs).norm()) std::swap(ts, te);
  // the projections meet the rim points within the fitting error: that difference is spread
  // linearly along the curve so that its ends are the rim points
  double bu, bv;
  on_ball(ball, M, pole, tube_point(ts, up, true), &bu, &bv);
  const Eigen::Vector2d d0 = Eigen::Vector2d(0.0, vs) - Eigen::Vector2d(bu, bv);
  on_ball(ball, M, pole, tube_point(te, up, true), &bu, &bv);
  const Eigen::Vector2d d1 = Eigen::Vector2d(0.0, ve) - Eigen::Vector2d(bu, bv);
  *umax = 0;
  return fit_pcurve(
      [&](double ph) {
        const double v = ts + (te - ts) * 0.5 * (1 - std::cos(ph));
        double pu, pv;
        *proj_err = std::max(*proj_err, on_ball(ball, M, pole, tube_point(v, up, ph == 0 || ph == M_PI), &pu, &pv));
        const Eigen::Vector2d uv = Eigen::Vector2d(pu, pv) + d0 * (1 - ph / M_PI) + d1 * (ph / M_PI);
        *umax = std::max(*umax, uv(0));
        return Eigen::RowVector3d(uv(0), uv(1), 0.0);
      },
      0.5 * fit_tol_ / (2 * r_), e2d);
}

bool OverlapSweep::tongues(double phase) {
  if (!build_tube(c_, r_, j_, T_, fit_tol_, phase, &tb_)) return false;
  err_ = tb_.error;
  if (!arc(1, &a1_, &a2_) || !arc(2, &b1_, &b2_)) return false;
  if (!(a2_ < b1_ || b2_ < a1_)) return false;
  speed_ = std::sqrt(H_.radius() * H_.radius() + j_.pitch * j_.pitch) + 2 * r_;
  // Each pair of independent fits below runs on two threads (they only read the surfaces and
  // the helix); each keeps its own errors.
  double e2d_of[4] = {0, 0, 0, 0};
  parallel_for(2, [&]() -> std::function<void(std::size_t)> {
    return [&](std::size_t k) {
      if (k == 0) tongue_up_ = tube_tongue(a2_, a1_, true, &e2d_of[0]);
      else tongue_dn_ = tube_tongue(b1_, b2_, false, &e2d_of[1]);
    };
  });
  if (tongue_up_.IsNull() || tongue_dn_.IsNull()) return false;
  Ua1_ = tongue_time(a1_, true, true), Ua2_ = tongue_time(a2_, true, true);
  Ub1_ = tongue_time(b1_, false, true), Ub2_ = tongue_time(b2_, false, true);
  if (!(Ua1_ > 0 && Ua2_ > 0 && Ub1_ < T_ && Ub2_ < T_)) return false;
  const Eigen::Isometry3d MT = j_.transform(T_);
  double proj_err_of[2] = {0, 0};
  // the start ball is covered by the next turn: the tube's tongue over [b1, b2] lies on it
  parallel_for(2, [&]() -> std::function<void(std::size_t)> {
    return [&](std::size_t k) {
      if (k == 0)
        back_tongue_ = ball_tongue(tb_.back, Eigen::Isometry3d::Identity(), -tb_.t0, a2_, a1_, b1_, b2_, false,
                                   &umax_back_, &proj_err_of[0], &e2d_of[2]);
      else
        front_tongue_ = ball_tongue(tb_.front, MT, tb_.t0, b2_, b1_, a1_, a2_, true, &umax_front_, &proj_err_of[1],
                                    &e2d_of[3]);
    };
  });
  if (back_tongue_.IsNull() || front_tongue_.IsNull()) return false;
  const double proj_err = std::max(proj_err_of[0], proj_err_of[1]);
  const double umax = Settings::ball_tongue_latitude_max * M_PI;
  if (proj_err > Settings::fit_error_margin * tb_.error + Settings::ball_projection_rounding * size_ ||
      umax_back_ >= umax || umax_front_ >= umax)
    return false;
  e2d_ = *std::max_element(e2d_of, e2d_of + 4);
  err_ += e2d_ * speed_;
  return true;
}

// On grids over the tube and the half balls, the points that other balls of the sweep cover are
// those the tongues cut away (points close to a tongue's curve are not compared). In four parts:
// the tube's grid in two halves, each half ball.
bool OverlapSweep::guard(std::size_t part) const {
  const double band = Settings::overlap_guard_band * r_ * r_;
  const int nu = Settings::overlap_guard_grid_u, nv = Settings::overlap_guard_grid_v;
  auto cover = [&](const Eigen::Vector3d& x, double lo1, double hi1, double lo2, double hi2) {
    double d = 1e300;
    if (hi1 > lo1) d = std::min(d, H_.min_dist2(x, lo1, hi1, nullptr));
    if (hi2 > lo2) d = std::min(d, H_.min_dist2(x, lo2, hi2, nullptr));
    return d - r_ * r_;
  };
  auto check_tube = [&](int iu0, int iu1) {
    for (int iu = iu0; iu <= iu1; ++iu)
      for (int iv = 0; iv < nv; ++iv) {
        const double U = T_ * iu / nu, v = 2 * M_PI * (iv + 0.5) / nv;
        const double k = cover(to_eigen(tb_.tube->Value(U, v)), std::max(0.0, U + M_PI), std::min(T_, U + 3 * M_PI),
                               std::max(0.0, U - 3 * M_PI), std::min(T_, U - M_PI));
        if (std::abs(k) < band) continue;
        const bool cut = (v > a1_ && v < a2_ && U < tongue_time(v, true)) ||
                         (v > b1_ && v < b2_ && U > tongue_time(v, false));
        if ((k < 0) != cut) return false;
      }
    return true;
  };
  auto inside = [](const std::vector<gp_Pnt2d>& poly, double x, double y) {
    bool in = false;
    for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
      const gp_Pnt2d& p = poly[i];
      const gp_Pnt2d& q = poly[(i + 1) % n];
      if ((p.Y() > y) != (q.Y() > y) && x < p.X() + (y - p.Y()) * (q.X() - p.X()) / (q.Y() - p.Y())) in = !in;
    }
    return in;
  };
  auto check_ball = [&](const Handle(Geom_BSplineSurface)& ball, const Handle(Geom2d_BSplineCurve)& tongue,
                        double lo, double hi) {
    std::vector<gp_Pnt2d> poly;
    const int np = Settings::overlap_guard_polygon, nr = Settings::overlap_guard_ball_rings;
    for (int i = 0; i <= np; ++i) poly.push_back(tongue->Value(M_PI * i / np));  // closed by the rim
    for (int iu = 1; iu <= nr; ++iu)
      for (int iv = 0; iv < nv; ++iv) {
        const double u = 0.5 * M_PI * iu / nr, v = 2 * M_PI * (iv + 0.5) / nv;
        const double k = cover(to_eigen(ball->Value(u, v)), lo, hi, 0, 0);
        if (std::abs(k) < band) continue;
        if ((k < 0) != inside(poly, u, v)) return false;
      }
    return true;
  };
  switch (part) {
    case 0: return check_tube(0, nu / 2);
    case 1: return check_tube(nu / 2 + 1, nu);
    case 2: return check_ball(tb_.back, back_tongue_, up_lo, up_hi);
    default: return check_ball(tb_.front, front_tongue_, T_ + dn_lo, T_ + dn_hi);
  }
}

/// A face on S bounded by `edges` (built on it from their parameter-plane curves) into fs.
bool face_from_edges(const Handle(Geom_Surface)& S, const std::vector<TopoDS_Edge>& edges,
                     std::vector<TopoDS_Face>& fs) {
  BRepBuilderAPI_MakeWire mw;
  for (const auto& e : edges) {
    if (e.IsNull()) return false;
    mw.Add(e);
    if (!mw.IsDone()) return false;
  }
  BRepBuilderAPI_MakeFace mf(S, mw.Wire(), true);
  if (!mf.IsDone()) return false;
  fs.push_back(mf.Face());
  return true;
}

// The tube: its parameter rectangle [0, T] x [0, 2 pi] without the two tongues, in two faces split
// along v between the arcs (away from the seam), so that each line where the tube meets its next
// turn joins two different faces. Each face's boundary runs counterclockwise in (time, angle);
// OCCT's face maker turns the wire round where the exchanged parameters below mirror it. The faces'
// surface has the tube's parameters exchanged (u around the circle, v along the motion): OCCT's face
// integration runs an inner Gauss integral along u, from the face's lowest u to each point of the
// boundary lines along which v varies; this way those inner integrals cross the few spans of the
// circle instead of the many along the motion.
bool OverlapSweep::tube_face(double vlo, double vhi, std::vector<TopoDS_Face>& fs, std::vector<int>& rl) const {
  const double etol = edge_tol();
  auto Q = [](double x, double y) { return gp_Pnt2d(y, x); };
  auto exchanged = [](const Handle(Geom2d_BSplineCurve)& cv) {
    Handle(Geom2d_BSplineCurve) e = Handle(Geom2d_BSplineCurve)::DownCast(cv->Copy());
    for (int i = 1; i <= e->NbPoles(); ++i) {
      const gp_Pnt2d p = e->Pole(i);
      e->SetPole(i, gp_Pnt2d(p.Y(), p.X()));
    }
    return e;
  };
  // a surface of its own: the faces share edges whose parameter lines differ (v = a2 here is v =
  // b1 there), and edges with two parameter lines on one surface would read as seams
  const Handle(Geom_BSplineSurface) tx = Handle(Geom_BSplineSurface)::DownCast(tb_.tube->Copy());
  tx->ExchangeUV();
  const Handle(Geom_Surface) tube(tx);
  std::vector<TopoDS_Edge> es{segment_on(tube, Q(0, vlo), Q(T_, vlo), etol)};
  double v = vlo;
  if (b1_ > vlo && b2_ < vhi) {  // the previous turn's tongue hangs from u = T
    es.push_back(segment_on(tube, Q(T_, v), Q(T_, b1_), etol));
    es.push_back(segment_on(tube, Q(T_, b1_), Q(Ub1_, b1_), etol));
    es.push_back(edge_on(tube, exchanged(tongue_dn_), 0, M_PI, etol));
    es.push_back(segment_on(tube, Q(Ub2_, b2_), Q(T_, b2_), etol));
    v = b2_;
  }
  es.push_back(segment_on(tube, Q(T_, v), Q(T_, vhi), etol));
  es.push_back(segment_on(tube, Q(T_, vhi), Q(0, vhi), etol));
  v = vhi;
  if (a1_ > vlo && a2_ < vhi) {  // the next turn's tongue stands on u = 0
    es.push_back(segment_on(tube, Q(0, v), Q(0, a2_), etol));
    es.push_back(segment_on(tube, Q(0, a2_), Q(Ua2_, a2_), etol));
    es.push_back(edge_on(tube, exchanged(tongue_up_), 0, M_PI, etol));
    es.push_back(segment_on(tube, Q(Ua1_, a1_), Q(0, a1_), etol));
    v = a1_;
  }
  es.push_back(segment_on(tube, Q(0, v), Q(0, vlo), etol));
  if (!face_from_edges(tube, es, fs)) return false;
  rl.push_back(0);
  return true;
}

// Each half ball: a band from the rim to u_cut without its tongue, and the cap beyond.
bool OverlapSweep::ball_faces(const Handle(Geom_BSplineSurface)& ball, const Handle(Geom2d_BSplineCurve)& tongue,
                              double v1, double v2, double umax, int role, std::vector<TopoDS_Face>& fs,
                              std::vector<int>& rl) const {
  const double etol = edge_tol();
  auto P = [](double x, double y) { return gp_Pnt2d(x, y); };
  const double V = 2 * M_PI;
  const double uc = umax + 0.5 * (0.5 * M_PI - umax);
  const Handle(Geom_Surface) S(ball);
  if (!face_from_edges(S,
                       {segment_on(S, P(0, 0), P(uc, 0), etol), segment_on(S, P(uc, 0), P(uc, V), etol),
                        segment_on(S, P(uc, V), P(0, V), etol), segment_on(S, P(0, V), P(0, v2), etol),
                        edge_on(S, tongue, 0, M_PI, etol), segment_on(S, P(0, v1), P(0, 0), etol)},
                       fs))
    return false;
  rl.push_back(role);
  BRepBuilderAPI_MakeFace cap(S, uc, 0.5 * M_PI, 0, V, Settings::resolution * size_);
  if (!cap.IsDone()) return false;
  fs.push_back(cap.Face());
  rl.push_back(role);
  return true;
}

TopoDS_Shape OverlapSweep::solid(std::vector<TopoDS_Face>* faces, std::vector<int>* roles) {
  std::vector<TopoDS_Face> fs;
  std::vector<int> rl;
  const double vm = a2_ < b1_ ? 0.5 * (a2_ + b1_) : 0.5 * (b2_ + a1_);
  // Outwards on the first tube face: at mid-time, on the arc of the circle before both tongues'
  // arcs (v = 0 is the middle of the gap between them), away from the centre's helix.
  OutwardHint out;
  out.face = 0;
  out.u = 0.5 * std::min(a1_, b1_);
  out.v = 0.5 * T_;
  const Eigen::Vector3d away = to_eigen(tb_.tube->Value(out.v, out.u)) - H_.pos(out.v);
  out.out = gp_Vec(away.x(), away.y(), away.z());
  // The faces and their sewing on one thread, the guard's parts on the other.
  TopoDS_Shape sewn;
  char guard_ok[4] = {0, 0, 0, 0};
  parallel_for(5, [&]() -> std::function<void(std::size_t)> {
    return [&](std::size_t task) {
      if (task > 0) {
        guard_ok[task - 1] = guard(task - 1);
      } else if (tube_face(0, vm, fs, rl) && tube_face(vm, 2 * M_PI, fs, rl) &&
                 ball_faces(tb_.back, back_tongue_, a1_, a2_, umax_back_, 1, fs, rl) &&
                 ball_faces(tb_.front, front_tongue_, b1_, b2_, umax_front_, 2, fs, rl)) {
        sewn = sew_solid(fs, std::max(Settings::sewing_gap * size_, Settings::overlap_sewing_fit_errors * err_), &out);
      }
    };
  });
  if (sewn.IsNull() || !std::all_of(guard_ok, guard_ok + 4, [](char ok) { return ok != 0; })) return {};
  if (faces) *faces = fs;
  if (roles) *roles = rl;
  return sewn;
}

}  // namespace

TopoDS_Shape ball_screw_sweep_overlap(const Eigen::Vector3d& c, double r, const ScrewJoint& j, double T,
                                      double fit_tol, double size, double* fit_err, std::vector<TopoDS_Face>* faces,
                                      std::vector<int>* roles) {
  if (j.type != JointType::Helical || j.pitch == 0) return {};
  OverlapSweep sweep(c, r, j, T, fit_tol, size);
  const std::optional<double> phase = sweep.seam_phase();
  if (!phase || !sweep.tongues(*phase)) return {};
  const TopoDS_Shape solid = sweep.solid(faces, roles);
  if (solid.IsNull()) return {};
  *fit_err = std::max(*fit_err, sweep.error());
  return solid;
}

}  // namespace sweep::occt
