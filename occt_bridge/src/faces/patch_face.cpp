#include "faces/patch_face.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomFill.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Plane.hxx>
#include <Geom_SphericalSurface.hxx>
#include <Geom_ToroidalSurface.hxx>
#include <ShapeFix_Face.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Circ.hxx>
#include <gp_Elips.hxx>
#include <Eigen/Eigenvalues>
#include <gp_Lin.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <cmath>

#include "base/internal.hpp"
#include "sweep/error.hpp"

namespace sweep::occt {
namespace {

gp_Dir to_dir(const Eigen::Vector3d& v) { return gp_Dir(v.x(), v.y(), v.z()); }

/// The elementary surface of a form, or null for a general one (or a cone of no slope).
Handle(Geom_Surface) form_surface(const PatchForm& f) {
  const gp_Ax3 frame(to_pnt(f.origin), to_dir(f.axis), to_dir(f.ref));
  switch (f.kind) {
    case PatchForm::Kind::Plane: return new Geom_Plane(frame);
    case PatchForm::Kind::Cylinder: return new Geom_CylindricalSurface(frame, f.radius);
    case PatchForm::Kind::Cone:
      if (!(std::abs(f.semi_angle) > Settings::angle_resolution && std::abs(f.semi_angle) < M_PI / 2)) return nullptr;
      return new Geom_ConicalSurface(frame, f.semi_angle, f.radius);
    case PatchForm::Kind::Sphere: return new Geom_SphericalSurface(frame, f.radius);
    case PatchForm::Kind::Torus: return new Geom_ToroidalSurface(frame, f.radius, f.minor);
    default: return nullptr;
  }
}

/// The sides that bound the patch (bounding_sides), counter-clockwise, as points.
std::vector<std::vector<gp_Pnt>> boundary_sides(const Patch& p, double tol) {
  const int n = Settings::patch_side_samples;
  std::vector<std::vector<gp_Pnt>> out;
  for (int k : bounding_sides(p, tol, n)) {
    out.emplace_back();
    for (int i = 0; i <= n; ++i) out.back().push_back(to_pnt(side_point(p, k, double(i) / n)));
  }
  return out;
}

/// The edge through the points of one side: a segment, a circle arc or a whole ellipse when every
/// point lies on it to rounding, else a fitted curve (a line or a circle when canonical_curve
/// finds one within tol).
TopoDS_Edge side_edge(const std::vector<gp_Pnt>& side, double tol) {
  const gp_Pnt &a = side.front(), &m = side[side.size() / 2], &b = side.back();
  double size = 0;
  for (const gp_Pnt& q : side) size = std::max(size, q.Distance(a));
  const double exact = Settings::patch_side_rounding * std::max(size, 1.0);
  const gp_Vec ab(a, b), am(a, m);
  if (ab.Magnitude() > exact && am.Crossed(ab).Magnitude() <= exact * ab.Magnitude()) {
    const gp_Lin line(a, gp_Dir(ab));
    if (std::all_of(side.begin(), side.end(), [&](const gp_Pnt& q) { return line.Distance(q) <= exact; }))
      return BRepBuilderAPI_MakeEdge(a, b).Edge();
  }
  // a circle through a, the point a third along and the point two thirds along (a closed side's
  // last point is its first)
  const gp_Pnt &p1 = side[side.size() / 3], &p2 = side[2 * side.size() / 3];
  const Eigen::Vector3d A = to_eigen(a), B = to_eigen(p1), C = to_eigen(p2);
  const Eigen::Vector3d n = (B - A).cross(C - A);
  if (n.norm() > exact * size) {
    const Eigen::Vector3d centre =
        A + ((C - A).squaredNorm() * n.cross(B - A) + (B - A).squaredNorm() * (C - A).cross(n)) / (2 * n.squaredNorm());
    const double r = (A - centre).norm();
    if (std::all_of(side.begin(), side.end(), [&](const gp_Pnt& q) {
          return std::abs((to_eigen(q) - centre).norm() - r) <= exact && std::abs((to_eigen(q) - centre).dot(n.normalized())) <= exact;
        })) {
      const Eigen::Vector3d x = (A - centre).normalized();
      const gp_Circ circ(gp_Ax2(to_pnt(centre), gp_Dir(n.x(), n.y(), n.z()), gp_Dir(x.x(), x.y(), x.z())), r);
      if (a.Distance(b) <= exact) return BRepBuilderAPI_MakeEdge(circ).Edge();
      return BRepBuilderAPI_MakeEdge(circ, a, b).Edge();
    }
  }
  if (a.Distance(b) <= exact && n.norm() > exact * size) {
    // a whole ellipse sampled uniformly in its angle: the points' mean is its centre and their
    // second moments are (a^2 X X^T + b^2 Y Y^T) / 2
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i + 1 < side.size(); ++i) centre += to_eigen(side[i]);
    centre /= double(side.size() - 1);
    Eigen::Matrix3d moments = Eigen::Matrix3d::Zero();
    for (std::size_t i = 0; i + 1 < side.size(); ++i) {
      const Eigen::Vector3d d = to_eigen(side[i]) - centre;
      moments += d * d.transpose();
    }
    moments *= 2.0 / double(side.size() - 1);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(moments);
    const double major = std::sqrt(std::max(eig.eigenvalues()[2], 0.0)), minor = std::sqrt(std::max(eig.eigenvalues()[1], 0.0));
    const Eigen::Vector3d X = eig.eigenvectors().col(2), Y = eig.eigenvectors().col(1), N = X.cross(Y);
    if (minor > exact && std::all_of(side.begin(), side.end(), [&](const gp_Pnt& q) {
          const Eigen::Vector3d d = to_eigen(q) - centre;
          return std::abs(d.dot(N)) <= exact && std::abs(std::hypot(d.dot(X) / major, d.dot(Y) / minor) - 1) * minor <= exact;
        }))
      return BRepBuilderAPI_MakeEdge(gp_Elips(gp_Ax2(to_pnt(centre), gp_Dir(N.x(), N.y(), N.z()), gp_Dir(X.x(), X.y(), X.z())),
                                              major, minor)).Edge();
  }
  TColgp_Array1OfPnt pts(1, int(side.size()));
  for (std::size_t i = 0; i < side.size(); ++i) pts.SetValue(int(i) + 1, side[i]);
  GeomAPI_PointsToBSpline fit(pts, 3, 8, GeomAbs_C2, 0.1 * tol);
  if (!fit.IsDone()) return {};
  double first = fit.Curve()->FirstParameter(), last = fit.Curve()->LastParameter();
  const Handle(Geom_Curve) c = canonical_curve(fit.Curve(), first, last, tol);
  return BRepBuilderAPI_MakeEdge(c, first, last).Edge();
}

/// The face of `surface` bounded by the patch's sides (each an exact line or circle when it is one).
TopoDS_Face bounded_face(const Handle(Geom_Surface)& surface, const Patch& p, double tol) {
  BRepBuilderAPI_MakeWire wire;
  for (const auto& side : boundary_sides(p, tol)) {
    const TopoDS_Edge e = side_edge(side, tol);
    if (e.IsNull()) return {};
    wire.Add(e);
    if (!wire.IsDone()) return {};
  }
  if (!wire.IsDone() || !wire.Wire().Closed()) return {};
  BRepBuilderAPI_MakeFace mf(surface, wire.Wire(), true);
  if (!mf.IsDone()) return {};
  ShapeFix_Face fix(mf.Face());  // pcurves, and the wire's orientation on the surface
  fix.Perform();
  return fix.Face();
}

/// The largest distance from a grid of patch points to the face's surface.
double measured_error(const Patch& p, const TopoDS_Face& face, bool own_parameters) {
  const Handle(Geom_Surface) s = BRep_Tool::Surface(face);
  const int n = Settings::patch_error_grid;
  double e = 0;
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= n; ++k) {
      const double u = p.lo(0) + (p.hi(0) - p.lo(0)) * i / n, v = p.lo(1) + (p.hi(1) - p.lo(1)) * k / n;
      const gp_Pnt x = to_pnt(p.eval(u, v).x);
      if (own_parameters) {
        const double sv = p.form().kind == PatchForm::Kind::Cone ? v / std::cos(p.form().semi_angle) : v;
        e = std::max(e, s->Value(u, sv).Distance(x));
      } else {
        GeomAPI_ProjectPointOnSurf proj(x, s);
        e = std::max(e, proj.NbPoints() > 0 ? proj.LowerDistance() : 1e300);
      }
    }
  return e;
}

/// The parameter (0 or 1) along which the patch runs straight (a ruled sheet: a line of a face, or a
/// straight edge, carried by a motion), to within `eps`; -1 when neither does.
int straight_parameter(const Patch& p, double eps) {
  for (int k = 0; k < 2; ++k) {
    bool straight = true;
    for (int i = 0; i <= 8 && straight; ++i) {
      const double w = p.lo(1 - k) + (p.hi(1 - k) - p.lo(1 - k)) * i / 8;
      auto at = [&](double f) {
        const double s = p.lo(k) + (p.hi(k) - p.lo(k)) * f;
        return k == 0 ? p.eval(s, w).x : p.eval(w, s).x;
      };
      const Eigen::Vector3d a = at(0), b = at(1);
      const Eigen::Vector3d d = b - a;
      if (!(d.norm() > eps)) continue;  // (a side that collapses to a point)
      for (double f : {0.25, 0.5, 0.75}) straight = straight && (at(f) - a).cross(d).norm() <= eps * d.norm();
    }
    if (straight) return k;
  }
  return -1;
}

/// The two sides of a ruled patch across its straight parameter k, fitted over one parameter f in
/// [0, 1]: the other parameter at f is lo + (hi - lo) (1 - cos pi f) / 2, closer near both ends,
/// where a grazing line's ends can move fast as it enters or leaves a face. False when a side does
/// not fit.
bool ruled_sides(const Patch& p, int k, double tol, int samples, Handle(Geom_BSplineCurve) sides[2]) {
  TColStd_Array1OfReal params(1, samples + 1);
  for (int i = 0; i <= samples; ++i) params.SetValue(i + 1, double(i) / samples);
  for (int e = 0; e < 2; ++e) {
    TColgp_Array1OfPnt pts(1, samples + 1);
    const double s = e == 0 ? p.lo(k) : p.hi(k);
    for (int i = 0; i <= samples; ++i) {
      const double w = p.lo(1 - k) + (p.hi(1 - k) - p.lo(1 - k)) * 0.5 * (1 - std::cos(M_PI * i / samples));
      pts.SetValue(i + 1, to_pnt(k == 0 ? p.eval(s, w).x : p.eval(w, s).x));
    }
    GeomAPI_PointsToBSpline fit(pts, params, 3, 8, GeomAbs_C2, 0.1 * tol);
    if (!fit.IsDone()) return false;
    sides[e] = fit.Curve();
  }
  return true;
}

/// The largest distance from patch points (an n x n grid, off the sides' samples) to the segment
/// between the fitted sides at the same parameter: the ruled surface's error, measured without
/// projecting onto it (which strays where the sides meet).
double ruled_error(const Patch& p, int k, const Handle(Geom_BSplineCurve) sides[2], int n) {
  double worst = 0;
  for (int i = 0; i <= n; ++i) {
    const double g = (i + 0.37) / (n + 1);  // (between the sides' samples)
    const double w = p.lo(1 - k) + (p.hi(1 - k) - p.lo(1 - k)) * g;
    const double f = std::acos(std::clamp(1 - 2 * g, -1.0, 1.0)) / M_PI;
    const Eigen::Vector3d a = to_eigen(sides[0]->Value(f)), b = to_eigen(sides[1]->Value(f));
    for (int j = 0; j <= n; ++j) {
      const double s = p.lo(k) + (p.hi(k) - p.lo(k)) * j / n;
      const Eigen::Vector3d x = k == 0 ? p.eval(s, w).x : p.eval(w, s).x;
      const Eigen::Vector3d d = b - a;
      const double along = d.squaredNorm() > 0 ? std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
      worst = std::max(worst, (x - (a + along * d)).norm());
    }
  }
  return worst;
}

/// The face of a ruled patch within tol, with its measured error; null when none is.
TopoDS_Face ruled_face(const Patch& p, double tol, double* error) {
  const int k = straight_parameter(p, Settings::ruled_straightness * tol);
  if (k < 0) return {};
  const int n = Settings::ruled_side_samples;
  for (int samples : {n, 4 * n, 16 * n}) {
    Handle(Geom_BSplineCurve) sides[2];
    if (!ruled_sides(p, k, tol, samples, sides)) return {};
    const double e = ruled_error(p, k, sides, Settings::ruled_error_grid);
    if (!(e <= tol)) continue;
    BRepBuilderAPI_MakeFace mf(GeomFill::Surface(sides[0], sides[1]), Settings::ruled_face_degenerate * tol);
    if (!mf.IsDone()) return {};
    *error = e;
    return mf.Face();
  }
  return {};
}

/// Turns the face so that its normal agrees with the patch's outward one at the patch's middle.
TopoDS_Face oriented(const TopoDS_Face& face, const Patch& p) {
  const PatchPoint m = p.eval(0.5 * (p.lo(0) + p.hi(0)), 0.5 * (p.lo(1) + p.hi(1)));
  const Eigen::Vector3d out = p.orientation() * m.xu.cross(m.xv);
  GeomAPI_ProjectPointOnSurf proj(to_pnt(m.x), BRep_Tool::Surface(face));
  if (proj.NbPoints() == 0) return face;
  double u, v;
  proj.LowerDistanceParameters(u, v);
  BRepLProp_SLProps props(BRepAdaptor_Surface(face, false), u, v, 1, Settings::normal_resolution);
  if (!props.IsNormalDefined()) return face;
  Eigen::Vector3d n = to_eigen(gp_Vec(props.Normal()));
  if (face.Orientation() == TopAbs_REVERSED) n = -n;
  return n.dot(out) < 0 ? TopoDS::Face(face.Reversed()) : face;
}

}  // namespace

PatchFace patch_face(const Patch& p, double tol) {
  if (p.dim() != 2) throw ComputeError("patch_face: '" + p.what() + "' is not a surface patch");
  PatchFace out;
  try {
    const Handle(Geom_Surface) surface = form_surface(p.form());
    if (!surface.IsNull() && p.form().surface_parameters) {
      const double scale = p.form().kind == PatchForm::Kind::Cone ? 1 / std::cos(p.form().semi_angle) : 1.0;
      // (an iso shorter than tol is a pole: a degenerate edge)
      BRepBuilderAPI_MakeFace mf(surface, p.lo(0), p.hi(0), scale * p.lo(1), scale * p.hi(1), tol);
      if (mf.IsDone()) {
        out.face = mf.Face();
        out.error = measured_error(p, out.face, true);
        out.exact = true;
      }
    } else if (!surface.IsNull()) {
      try {
        out.face = bounded_face(surface, p, tol);
      } catch (const Standard_Failure&) {  // a side OCCT cannot make an edge of: fitted below
        out.face.Nullify();
      }
      if (!out.face.IsNull()) {
        out.error = measured_error(p, out.face, false);
        out.exact = true;
      }
    }
    if (out.face.IsNull() || out.error > tol) {
      double err = 0;
      const TopoDS_Face ruled = ruled_face(p, tol, &err);
      if (!ruled.IsNull()) {
        out.face = ruled;
        out.error = err;
        out.exact = false;
      }
    }
    if (out.face.IsNull() || out.error > tol) {
      auto exact = [&p](double fu, double fv) {
        return to_pnt(p.eval(p.lo(0) + (p.hi(0) - p.lo(0)) * fu, p.lo(1) + (p.hi(1) - p.lo(1)) * fv).x);
      };
      double err = 0;
      const Handle(Geom_BSplineSurface) fitted =
          fit_grid_surface(exact, tol, Settings::patch_fit_approx * tol, Settings::patch_fit_grid_first,
                           Settings::patch_fit_grid_last, &err);
      if (fitted.IsNull()) throw ComputeError("no B-spline fits '" + p.what() + "'");
      BRepBuilderAPI_MakeFace mf(fitted, std::max(err, Settings::patch_face_min_tolerance * tol));
      if (!mf.IsDone()) throw ComputeError("no face on the B-spline of '" + p.what() + "'");
      out.face = mf.Face();
      out.exact = false;
      out.error = std::max(err, measured_error(p, out.face, false));
    }
  } catch (const Standard_Failure& f) {
    throw ComputeError("no face for '" + p.what() + "': " + (f.GetMessageString() ? f.GetMessageString() : "OCCT error"));
  }
  out.face = oriented(out.face, p);
  return out;
}

namespace {

void collect_faces(const PatchPtr& p, double tol, int splits_left, std::vector<PatchFace>& out) {
  PatchFace f = patch_face(*p, tol);
  if (f.error <= tol || f.exact || splits_left <= 0) {
    out.push_back(std::move(f));
    return;
  }
  // halve across the side that is longer in space (measured along the domain's middle lines)
  const double mu = 0.5 * (p->lo(0) + p->hi(0)), mv = 0.5 * (p->lo(1) + p->hi(1));
  const double lu = (p->eval(p->hi(0), mv).x - p->eval(mu, mv).x).norm() + (p->eval(mu, mv).x - p->eval(p->lo(0), mv).x).norm();
  const double lv = (p->eval(mu, p->hi(1)).x - p->eval(mu, mv).x).norm() + (p->eval(mu, mv).x - p->eval(mu, p->lo(1)).x).norm();
  const int k = lu >= lv ? 0 : 1;
  const double mid = k == 0 ? mu : mv;
  std::vector<double> lo{p->lo(0), p->lo(1)}, hi{p->hi(0), p->hi(1)};
  std::vector<double> hi_a = hi, lo_b = lo;
  hi_a[std::size_t(k)] = mid;
  lo_b[std::size_t(k)] = mid;
  collect_faces(patch_part(p, lo, hi_a), tol, splits_left - 1, out);
  collect_faces(patch_part(p, lo_b, hi), tol, splits_left - 1, out);
}

}  // namespace

std::vector<PatchFace> patch_faces(const Patch& patch, double tol, int max_splits) {
  if (patch.dim() != 2) throw ComputeError("patch_faces: '" + patch.what() + "' is not a surface patch");
  // the caller keeps the patch for the whole call; its parts refer to it
  const PatchPtr whole(&patch, [](const Patch*) {});
  std::vector<PatchFace> out;
  collect_faces(whole, tol, max_splits, out);
  return out;
}

}  // namespace sweep::occt
