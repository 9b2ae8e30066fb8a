// Orbit arcs where two faces swept along one joint's orbits cross (see orbit_section.hpp).
#include "faces/orbit_section.hpp"

#include <BRepAdaptor_Surface.hxx>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Geom_Surface.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Circle.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomAPI_ProjectPointOnCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "base/internal.hpp"
#include "faces/section_refit.hpp"

namespace sweep::occt {

namespace {

/// The joint's orbits: circles about a revolute joint's axis, lines along a prismatic joint's
/// direction, helices about a helical joint's axis. A point has two coordinates across the orbits
/// (its profile point: (r, z) about the axis; its projection on the plane through `p0` across the
/// direction; the point where its helix meets the plane through the axis point across the axis,
/// in that plane) and one along them (an angle about the axis; a distance along the direction; the
/// joint parameter that carries that point of the plane to it).
struct OrbitFrame {
  bool turning;  ///< circles (the coordinate along them is periodic)
  bool helix;    ///< helices (`h`: their advance per radian)
  double h;
  Eigen::Vector3d p0, w, e1, e2;
  explicit OrbitFrame(const ScrewJoint& j)
      : turning(j.type == JointType::Revolute),
        helix(j.type == JointType::Helical),
        h(j.type == JointType::Helical ? j.pitch : 0.0),
        p0(j.type != JointType::Prismatic ? j.point : Eigen::Vector3d::Zero()),
        w(j.direction.normalized()),
        e1(w.unitOrthogonal()),
        e2(w.cross(e1)) {}
  Eigen::Vector3d radial(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d d = x - p0;
    return d - w * w.dot(d);
  }
  /// The coordinate along the orbit through x.
  double along(const Eigen::Vector3d& x) const {
    if (helix) return w.dot(x - p0) / h;
    if (!turning) return w.dot(x - p0);
    const Eigen::Vector3d r = radial(x);
    return std::atan2(e2.dot(r), e1.dot(r));
  }
  /// x moved by s along its orbit.
  Eigen::Vector3d moved(const Eigen::Vector3d& x, double s) const {
    if (helix) return p0 + Eigen::AngleAxisd(s, w) * (x - p0) + w * (h * s);
    return turning ? Eigen::Vector3d(p0 + Eigen::AngleAxisd(s, w) * (x - p0)) : Eigen::Vector3d(x + s * w);
  }
  /// The profile point of x, and its derivative along dx.
  std::pair<Eigen::Vector2d, Eigen::Vector2d> across(const Eigen::Vector3d& x, const Eigen::Vector3d& dx) const {
    const Eigen::Vector3d d = x - p0;
    if (helix) {
      // back along the helix to the plane: y = R(-q) rho, dy = R(-q) drho - dq w x y
      const double q = w.dot(d) / h, dq = w.dot(dx) / h;
      const Eigen::AngleAxisd back(-q, w);
      const Eigen::Vector3d y = back * (d - w * w.dot(d));
      const Eigen::Vector3d dy = back * (dx - w * w.dot(dx)) - dq * w.cross(y);
      return {{e1.dot(y), e2.dot(y)}, {e1.dot(dy), e2.dot(dy)}};
    }
    if (!turning) return {{e1.dot(d), e2.dot(d)}, {e1.dot(dx), e2.dot(dx)}};
    const double z = w.dot(d), dz = w.dot(dx);
    const Eigen::Vector3d rho = d - w * z, drho = dx - w * dz;
    const double r = rho.norm();
    return {{r, z}, {r > 0 ? rho.dot(drho) / r : drho.norm(), dz}};
  }
  /// The point of the helix through profile point m at coordinate q along it, and its tangent.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> on_helix(const Eigen::Vector2d& m, double q) const {
    const Eigen::Vector3d y = Eigen::AngleAxisd(q, w) * (e1 * m(0) + e2 * m(1));
    return {p0 + y + w * (h * q), w.cross(y) + w * h};
  }
  /// The shortest piece of range overlap worth an edge, at profile point m.
  double min_length(const Eigen::Vector2d& m, double tol) const {
    if (helix) return tol / std::max(std::hypot(m.norm(), h), tol);
    return turning ? tol / std::max(m(0), tol) : tol;
  }
  /// The orbit arc at profile point m over [start, start + len] of the coordinate along it (none
  /// for helices: helix_section() makes those on the faces' own surfaces).
  std::optional<TopoDS_Edge> arc(const Eigen::Vector2d& m, double start, double len) const {
    if (helix) return std::nullopt;
    if (!turning) {
      const Eigen::Vector3d base = p0 + e1 * m(0) + e2 * m(1);
      BRepBuilderAPI_MakeEdge mk(to_pnt(base + w * start), to_pnt(base + w * (start + len)));
      if (!mk.IsDone()) return std::nullopt;
      return mk.Edge();
    }
    const Handle(Geom_Circle) circle = new Geom_Circle(gp_Ax2(to_pnt(p0 + w * m(1)), gp_Dir(to_vec(w)), gp_Dir(to_vec(e1))), m(0));
    const double lo = std::remainder(start, 2 * M_PI);
    BRepBuilderAPI_MakeEdge mk(circle, lo, lo + std::min(len, 2 * M_PI));
    if (!mk.IsDone()) return std::nullopt;
    return mk.Edge();
  }
};

/// A patch with an evaluator of its own (OCCT's surface adaptors cache and are not shared by threads).
struct Carried {
  const OrbitPatch& p;
  BRepAdaptor_Surface surface;
  double b0, b1;
  explicit Carried(const OrbitPatch& patch) : p(patch), surface(patch.face, false), b0(patch.b0), b1(patch.b1) {}
  /// The surface point at orbit parameter a and profile parameter b, and its derivative in b.
  void at(double a, double b, Eigen::Vector3d& x, Eigen::Vector3d& dx) const {
    gp_Pnt P;
    gp_Vec Du, Dv;
    if (p.orbit_is_u) surface.D1(a, b, P, Du, Dv);
    else surface.D1(b, a, P, Du, Dv);
    x = to_eigen(P);
    dx = to_eigen(p.orbit_is_u ? Dv : Du);
  }
};

/// A profile point and its derivative in the profile's parameter.
struct ProfilePoint {
  Eigen::Vector2d m, dm;
};

ProfilePoint profile(const Carried& p, const OrbitFrame& ax, double b) {
  Eigen::Vector3d x, dx;
  p.at(p.p.a0, b, x, dx);
  const auto [m, dm] = ax.across(x, dx);
  return {m, dm};
}

/// Samples of a profile for finding where it crosses: N + 1 points evenly spaced in its parameter.
constexpr int kSamples = Settings::orbit_profile_samples;

/// The profile's sample points, and the largest distance of a profile point halfway between two
/// samples from their chord (a bound on how far the polyline strays from the profile).
double sampled_profile(const Carried& p, const OrbitFrame& ax, std::vector<Eigen::Vector2d>& m) {
  m.resize(kSamples + 1);
  for (int k = 0; k <= kSamples; ++k) m[k] = profile(p, ax, p.b0 + (p.b1 - p.b0) * k / kSamples).m;
  double sag = 0;
  for (int k = 0; k < kSamples; ++k) {
    const Eigen::Vector2d mid = profile(p, ax, p.b0 + (p.b1 - p.b0) * (k + 0.5) / kSamples).m;
    sag = std::max(sag, (mid - 0.5 * (m[k] + m[k + 1])).norm());
  }
  return sag;
}

/// Closest points of segments [p, p + d] and [q, q + e] in the plane: (s, t) in [0, 1]^2.
std::pair<double, double> closest_on_segments(const Eigen::Vector2d& p, const Eigen::Vector2d& d,
                                              const Eigen::Vector2d& q, const Eigen::Vector2d& e) {
  const double dd = d.squaredNorm(), ee = e.squaredNorm(), de = d.dot(e);
  const Eigen::Vector2d r = p - q;
  const double den = dd * ee - de * de;
  double s = den > 1e-300 ? std::clamp((de * e.dot(r) - ee * d.dot(r)) / den, 0.0, 1.0) : 0.0;
  double t = ee > 0 ? std::clamp((e.dot(r) + de * s) / ee, 0.0, 1.0) : 0.0;
  s = dd > 0 ? std::clamp((de * t - d.dot(r)) / dd, 0.0, 1.0) : 0.0;
  return {s, t};
}

/// Where the profiles come closest near (ba, bb): a damped Gauss-Newton solve of ma(ba) = mb(bb)
/// in the parameter boxes. Returns the distance left.
double closest_profile_points(const Carried& a, const Carried& b, const OrbitFrame& ax, double& ba, double& bb) {
  ProfilePoint A = profile(a, ax, ba), B = profile(b, ax, bb);
  Eigen::Vector2d F = A.m - B.m;
  const double least_damping = Settings::profile_solve_damping;
  double lambda = least_damping;
  for (int it = 0; it < Settings::profile_solve_iterations && F.norm() > 0; ++it) {
    Eigen::Matrix2d J;
    J.col(0) = A.dm;
    J.col(1) = -B.dm;
    const Eigen::Matrix2d H = J.transpose() * J;
    const Eigen::Vector2d g = J.transpose() * F;
    const double scale = H.diagonal().maxCoeff();
    if (!(scale > 0)) break;
    const Eigen::Vector2d step = -(H + lambda * scale * Eigen::Matrix2d::Identity()).ldlt().solve(g);
    const double na = std::clamp(ba + step(0), std::min(a.b0, a.b1), std::max(a.b0, a.b1));
    const double nb = std::clamp(bb + step(1), std::min(b.b0, b.b1), std::max(b.b0, b.b1));
    const ProfilePoint A2 = profile(a, ax, na), B2 = profile(b, ax, nb);
    const Eigen::Vector2d F2 = A2.m - B2.m;
    if (F2.norm() < F.norm()) {
      const bool moved = std::abs(na - ba) > Settings::profile_solve_step * (1 + std::abs(ba)) ||
                         std::abs(nb - bb) > Settings::profile_solve_step * (1 + std::abs(bb));
      ba = na, bb = nb, A = A2, B = B2, F = F2;
      lambda = std::max(least_damping, lambda * 0.1);
      if (!moved) break;
    } else {
      lambda *= 10;
      if (lambda > Settings::profile_solve_max_damping) break;
    }
  }
  return F.norm();
}

/// The pieces (start, length) where ranges [sa, sa + la] and [sb, sb + lb] of the coordinate along
/// the orbits overlap (on the circle, for angles).
std::vector<std::pair<double, double>> overlapping_ranges(const OrbitFrame& ax, double sa, double la, double sb, double lb,
                                                          double min_len) {
  std::vector<std::pair<double, double>> out;
  if (!ax.turning) {
    const double lo = std::max(sa, sb), hi = std::min(sa + la, sb + lb);
    if (hi - lo > min_len) out.push_back({lo, hi - lo});
    return out;
  }
  const double full = 2 * M_PI;
  const bool whole_a = la >= full - Settings::angle_resolution, whole_b = lb >= full - Settings::angle_resolution;
  if (whole_a && whole_b) return {{0.0, full}};
  if (whole_a) return {{sb, lb}};
  if (whole_b) return {{sa, la}};
  for (double shift : {-full, 0.0, full}) {
    const double lo = std::max(sa, sb + shift), hi = std::min(sa + la, sb + shift + lb);
    if (hi - lo > min_len) out.push_back({lo, hi - lo});
  }
  return out;
}

/// Patch p's range along the orbits at profile parameter b: (start, length) with the length >= 0.
std::pair<double, double> orbit_range(const Carried& p, const OrbitFrame& ax, double b) {
  Eigen::Vector3d x, dx;
  p.at(p.p.a0, b, x, dx);
  const double s = ax.along(x);
  const double len = std::abs(p.p.rate) * (p.p.a1 - p.p.a0);
  return p.p.rate > 0 ? std::make_pair(s, len) : std::make_pair(s - len, len);
}

/// Whether the face's boundary is the four sides of its parameter box (one wire of iso-lines).
bool bounded_by_its_box(const TopoDS_Face& face, double u0, double u1, double v0, double v1) {
  int wires = 0;
  for (TopExp_Explorer wx(face, TopAbs_WIRE); wx.More(); wx.Next()) ++wires;
  if (wires != 1) return false;
  const double tu = Settings::box_side_resolution * (1 + std::abs(u0) + std::abs(u1));
  const double tv = Settings::box_side_resolution * (1 + std::abs(v0) + std::abs(v1));
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    double f, l;
    const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), face, f, l);
    if (pc.IsNull()) return false;
    bool on_u0 = true, on_u1 = true, on_v0 = true, on_v1 = true;
    for (double s : {f, 0.5 * (f + l), l}) {
      const gp_Pnt2d uv = pc->Value(s);
      on_u0 = on_u0 && std::abs(uv.X() - u0) <= tu;
      on_u1 = on_u1 && std::abs(uv.X() - u1) <= tu;
      on_v0 = on_v0 && std::abs(uv.Y() - v0) <= tv;
      on_v1 = on_v1 && std::abs(uv.Y() - v1) <= tv;
    }
    if (!(on_u0 || on_u1 || on_v0 || on_v1)) return false;
  }
  return true;
}

/// Face p's parameters at profile parameter b and coordinate q along the orbits.
gp_Pnt2d patch_uv(const Carried& p, const OrbitFrame& ax, double b, double q) {
  Eigen::Vector3d x, dx;
  p.at(p.p.a0, b, x, dx);
  const double a = p.p.a0 + (q - ax.along(x)) / p.p.rate;
  return p.p.orbit_is_u ? gp_Pnt2d(a, b) : gp_Pnt2d(b, a);
}

/// The curve where patches a and b cross along the helix through profile point m (profile
/// parameters ba and bb) over [start, start + len]: points of the helix moved onto both faces'
/// surfaces (fitted ones stray from the helix by their fit error) and a B-spline through them,
/// within `tol` of both between its points. Nothing when a point does not converge or strays
/// more than `stray` from the helix. *err: the curve's largest distance from the crossing.
std::optional<TopoDS_Edge> helix_section(const Carried& a, const Carried& b, const OrbitFrame& ax, const Eigen::Vector2d& m,
                                         double ba, double bb, double start, double len, double tol, double stray,
                                         double* err) {
  auto crossing = [&](double q) -> std::optional<gp_Pnt> {
    const auto [x, t] = ax.on_helix(m, q);
    const auto p = point_on_both(a.surface, b.surface, to_pnt(x), to_vec(t.normalized()), patch_uv(a, ax, ba, q),
                                 patch_uv(b, ax, bb, q), tol);
    if (!p || !to_eigen(*p).allFinite() || (to_eigen(*p) - x).norm() > stray) return std::nullopt;
    return p;
  };
  const int quarter_turns = std::max(1, int(std::ceil(len / (0.5 * M_PI))));
  for (int n = Settings::helix_section_samples_first * quarter_turns;
       n <= Settings::helix_section_samples_last * quarter_turns; n *= 2) {
    TColgp_Array1OfPnt pts(1, n + 1);
    for (int k = 0; k <= n; ++k) {
      const auto p = crossing(start + len * k / n);
      if (!p) return std::nullopt;
      pts.SetValue(k + 1, *p);
    }
    GeomAPI_PointsToBSpline fit(pts, 3, 8, GeomAbs_C2, 0.1 * tol);
    if (!fit.IsDone()) continue;
    const Handle(Geom_BSplineCurve) curve = fit.Curve();
    double worst = 0;
    for (int k = 0; k < n; ++k) {
      const auto p = crossing(start + len * (k + 0.5) / n);
      if (!p) return std::nullopt;
      GeomAPI_ProjectPointOnCurve proj(*p, curve);
      if (proj.NbPoints() == 0) return std::nullopt;
      worst = std::max(worst, proj.LowerDistance());
    }
    if (worst > tol) continue;
    BRepBuilderAPI_MakeEdge mk(curve);
    if (!mk.IsDone()) return std::nullopt;
    *err = std::max(*err, worst);
    return mk.Edge();
  }
  return std::nullopt;
}

/// The pairs of profile parameters (ba < bb) where the patch's profile crosses itself at an angle
/// (two places of the profile, not one: a solve that slides together, as next to a cusp, is none).
std::vector<std::pair<double, double>> self_crossing_pairs(const Carried& p, const OrbitFrame& ax, double boundary_tol) {
  constexpr int N = kSamples;
  std::vector<Eigen::Vector2d> m;
  const double sag = sampled_profile(p, ax, m);
  // (one profile: its sag counted for both)
  const double near = 2 * Settings::orbit_near_sags * sag + Settings::orbit_near_tols * boundary_tol;
  const double step = (p.b1 - p.b0) / N;
  const double apart = Settings::self_crossing_apart * std::abs(p.b1 - p.b0);
  std::vector<std::pair<double, double>> out;
  for (int i = 0; i < N; ++i)
    for (int k = i + 2; k < N; ++k) {
      const auto [s, t] = closest_on_segments(m[i], m[i + 1] - m[i], m[k], m[k + 1] - m[k]);
      if ((m[i] + s * (m[i + 1] - m[i]) - m[k] - t * (m[k + 1] - m[k])).norm() > near) continue;
      double ba = p.b0 + step * (i + s), bb = p.b0 + step * (k + t);
      if (closest_profile_points(p, p, ax, ba, bb) > boundary_tol) continue;
      if (std::abs(bb - ba) < std::abs(step)) continue;
      const ProfilePoint A = profile(p, ax, ba), B = profile(p, ax, bb);
      const double sine = std::abs(A.dm(0) * B.dm(1) - A.dm(1) * B.dm(0)) / (A.dm.norm() * B.dm.norm());
      if (!(sine >= Settings::orbit_section_min_sine)) continue;
      if (ba > bb) std::swap(ba, bb);
      bool known = false;
      for (const auto& [x, y] : out) known = known || (std::abs(x - ba) < apart && std::abs(y - bb) < apart);
      if (!known) out.push_back({ba, bb});
    }
  return out;
}

/// Whether profile parameters ba and bb (where the profiles of a and b meet) lie where the two
/// profiles run together into an end they share: the sweeps of two curves from one vertex of the
/// body, one a grazing curve, whose profiles touch there (the grazing curve's profile is the fold
/// of its face's, and the other curve's leaves it tangentially). A solver at such a touching point
/// stops short of the end, where the profiles are closer than `tol` but meet at no angle; the
/// profiles are then within `tol` all the way to the shared end. (Two arms of a profile's cusp at a
/// shared end also run together into it: a solver may find them touching, at no angle, within
/// the fit error of the end.)
bool in_shared_end_contact(const Carried& a, const Carried& b, const OrbitFrame& ax, double ba, double bb, double tol) {
  for (const double ea : {a.b0, a.b1})
    for (const double eb : {b.b0, b.b1}) {
      if ((profile(a, ax, ea).m - profile(b, ax, eb).m).norm() > tol) continue;
      bool together = true;
      for (const double f : {0.25, 0.5, 0.75}) {
        const Eigen::Vector2d pa = profile(a, ax, ba + f * (ea - ba)).m, pb = profile(b, ax, bb + f * (eb - bb)).m;
        together = together && (pa - pb).norm() <= tol;
      }
      if (together) return true;
    }
  return false;
}

/// The crossing through a meeting point of two faces' profiles (profile parameters ba of a and bb
/// of b, at m across the orbits): an arc, segment or helix over each range along the orbits that
/// both faces hold there, appended to `out`. False when one is not placed; the fit error grows
/// with each helix fitted.
bool meeting_point_arcs(const Carried& a, const Carried& b, const OrbitFrame& ax, const Eigen::Vector2d& m, double ba,
                        double bb, double boundary_tol, double* fit_err, std::vector<TopoDS_Edge>& out) {
  const auto [sa, la] = orbit_range(a, ax, ba);
  const auto [sb, lb] = orbit_range(b, ax, bb);
  for (const auto& [start, len] : overlapping_ranges(ax, sa, la, sb, lb, ax.min_length(m, boundary_tol))) {
    double err = 0;
    const std::optional<TopoDS_Edge> e =
        ax.helix ? helix_section(a, b, ax, m, ba, bb, start, len, 0.1 * boundary_tol, boundary_tol, &err)
                 : ax.arc(m, start, len);
    if (fit_err) *fit_err = std::max(*fit_err, err);
    if (!e) return false;
    out.push_back(*e);
  }
  return true;
}

/// Where two faces swept from one curve (pieces of one sweep, their profiles the same, or the
/// same reversed) cross: where the profile crosses itself, a line of the one may cross a line of
/// the other (two turns of one screwed curve's sweep), over the range along the orbits both hold
/// there. Nothing when a crossing is not placed.
std::optional<std::vector<TopoDS_Edge>> same_profile_crossings(const Carried& a, const Carried& b, const OrbitFrame& ax,
                                                               bool reversed, double boundary_tol, double* fit_err) {
  std::vector<TopoDS_Edge> out;
  for (const auto& [x1, x2] : self_crossing_pairs(a, ax, boundary_tol))
    for (const auto& [xa, xb] : {std::pair{x1, x2}, std::pair{x2, x1}}) {
      const double f = (xb - a.b0) / (a.b1 - a.b0);
      double ba = xa, bb = b.b0 + (b.b1 - b.b0) * (reversed ? 1 - f : f);
      if (closest_profile_points(a, b, ax, ba, bb) > boundary_tol) return std::nullopt;
      if (!meeting_point_arcs(a, b, ax, profile(a, ax, ba).m, ba, bb, boundary_tol, fit_err, out)) return std::nullopt;
    }
  return out;
}

/// Whether a face on a surface of this type can be swept along the joint's orbits: surfaces of
/// revolution under a revolute joint, extrusions and planes under a prismatic one, cylinders under
/// either, and under a helical joint the B-splines its sweeps are fitted as.
bool may_follow_orbits(GeomAbs_SurfaceType type, JointType joint) {
  switch (type) {
    case GeomAbs_SurfaceOfRevolution:
    case GeomAbs_Cone:
    case GeomAbs_Sphere:
    case GeomAbs_Torus:
      return joint == JointType::Revolute;
    case GeomAbs_SurfaceOfExtrusion:
    case GeomAbs_Plane:
      return joint == JointType::Prismatic;
    case GeomAbs_Cylinder:
      return joint != JointType::Helical;
    case GeomAbs_BSplineSurface:
      return joint == JointType::Helical;
    default:
      return false;
  }
}

}  // namespace

std::optional<OrbitPatch> orbit_patch(const TopoDS_Face& face, const ScrewJoint& j, double eps, double helix_tol) {
  const bool helix = j.type == JointType::Helical;
  if (helix && !(helix_tol > 0 && std::abs(j.pitch) > 0)) return std::nullopt;
  if (helix) eps = helix_tol;
  const bool turning = j.type == JointType::Revolute;
  const BRepAdaptor_Surface surface(face, false);
  if (!may_follow_orbits(surface.GetType(), j.type)) return std::nullopt;
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  if (!(u1 - u0 > 0) || !(v1 - v0 > 0)) return std::nullopt;
  if (!bounded_by_its_box(face, u0, u1, v0, v1)) return std::nullopt;
  const OrbitFrame ax(j);
  // the parameter along the orbits: u for surfaces turned about the axis, either for extrusions
  for (const bool orbit_is_u : {true, false}) {
    if (turning && !orbit_is_u) break;
    OrbitPatch p;
    p.face = face;
    p.orbit_is_u = orbit_is_u;
    p.a0 = orbit_is_u ? u0 : v0, p.a1 = orbit_is_u ? u1 : v1;
    p.b0 = orbit_is_u ? v0 : u0, p.b1 = orbit_is_u ? v1 : u1;
    const double da = p.a1 - p.a0;
    if (turning && da > 2 * M_PI + Settings::whole_period_margin) return std::nullopt;
    auto point = [&](double a, double b) { return to_eigen(orbit_is_u ? surface.Value(a, b) : surface.Value(b, a)); };
    // whether moving by `rate` per unit of the orbit parameter follows the surface at sample points
    bool off_axis = false;
    auto follows = [&](double rate) {
      for (double fb : {0.2, 0.5, 0.8}) {
        const double b = p.b0 + fb * (p.b1 - p.b0);
        const Eigen::Vector3d x0 = point(p.a0, b);
        if (ax.radial(x0).norm() > Settings::orbit_patch_extent * eps) off_axis = true;
        for (double fa : {0.25, 0.5, 1.0})
          if ((ax.moved(x0, rate * fa * da) - point(p.a0 + fa * da, b)).norm() > eps) return false;
      }
      return true;
    };
    if (turning) {
      const bool plus = follows(1.0), minus = follows(-1.0);
      if (plus == minus || !off_axis) return std::nullopt;  // neither, or on the axis
      p.rate = plus ? 1.0 : -1.0;
      return p;
    }
    const double b = 0.5 * (p.b0 + p.b1);
    const double rate = (ax.along(point(p.a1, b)) - ax.along(point(p.a0, b))) / da;
    if (std::abs(rate) * da > (helix ? Settings::orbit_patch_min_turn : Settings::orbit_patch_extent * eps) &&
        follows(rate)) {
      p.rate = rate;
      return p;
    }
  }
  return std::nullopt;
}

std::vector<double> profile_self_crossings(const OrbitPatch& patch, const ScrewJoint& j, double boundary_tol) {
  const OrbitFrame ax(j);
  const Carried p(patch);
  std::vector<double> cuts;
  for (const auto& [ba, bb] : self_crossing_pairs(p, ax, boundary_tol)) {
    // where the two sheets meet over a common range of the orbits
    const auto [sa, la] = orbit_range(p, ax, ba);
    const auto [sb, lb] = orbit_range(p, ax, bb);
    if (overlapping_ranges(ax, sa, la, sb, lb, ax.min_length(profile(p, ax, ba).m, boundary_tol)).empty()) continue;
    // (and halfway between: a piece from ba to bb would begin and end on one line)
    for (double c : {ba, 0.5 * (ba + bb), bb}) {
      const double apart = Settings::self_crossing_apart * std::abs(p.b1 - p.b0);
      bool known = std::abs(c - p.b0) < apart || std::abs(c - p.b1) < apart;
      for (double x : cuts) known = known || std::abs(x - c) < apart;
      if (!known) cuts.push_back(c);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  return cuts;
}

std::vector<PatchPiece> patch_pieces(const OrbitPatch& patch, const std::vector<double>& cuts) {
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(patch.face);
  std::vector<double> at{std::min(patch.b0, patch.b1)};
  for (double c : cuts) at.push_back(c);
  at.push_back(std::max(patch.b0, patch.b1));
  std::vector<PatchPiece> out;
  for (std::size_t k = 0; k + 1 < at.size(); ++k) {
    const double degen = Settings::profile_piece_degenerate;
    BRepBuilderAPI_MakeFace mk =
        patch.orbit_is_u ? BRepBuilderAPI_MakeFace(surface, patch.a0, patch.a1, at[k], at[k + 1], degen)
                         : BRepBuilderAPI_MakeFace(surface, at[k], at[k + 1], patch.a0, patch.a1, degen);
    if (!mk.IsDone()) return {};
    TopoDS_Face f = mk.Face();
    if (patch.face.Orientation() == TopAbs_REVERSED) f.Reverse();
    out.push_back({f, new Geom_RectangularTrimmedSurface(surface, at[k], at[k + 1], !patch.orbit_is_u)});
  }
  return out;
}

TopoDS_Face on_own_sheet(const TopoDS_Face& piece, const Handle(Geom_Surface)& sheet) {
  return face_on_surface(piece, sheet);
}

std::optional<std::vector<TopoDS_Edge>> orbit_section(const OrbitPatch& patch_a, const OrbitPatch& patch_b,
                                                      const ScrewJoint& j, double boundary_tol, double* fit_err,
                                                      double contact_band) {
  const OrbitFrame ax(j);
  const Carried a(patch_a), b(patch_b);
  constexpr int N = kSamples;
  std::vector<Eigen::Vector2d> ma, mb;
  const double sag_a = sampled_profile(a, ax, ma), sag_b = sampled_profile(b, ax, mb);
  const double near = Settings::orbit_near_sags * (sag_a + sag_b) + Settings::orbit_near_tols * boundary_tol;

  // One profile (pieces of one curve's sweep): the faces meet along an edge across the orbits at most.
  bool same = true, reversed = true;
  for (int k = 0; k <= N && (same || reversed); ++k) {
    same = same && (ma[k] - mb[k]).norm() <= boundary_tol;
    reversed = reversed && (ma[k] - mb[N - k]).norm() <= boundary_tol;
  }
  if (same || reversed) {
    const double v = 0.5 * (a.b0 + a.b1);
    const Eigen::Vector2d m = profile(a, ax, v).m;
    const auto [sa, la] = orbit_range(a, ax, v);
    const auto [sb, lb] = orbit_range(b, ax, 0.5 * (b.b0 + b.b1));  // (the middle sample of both)
    if (!overlapping_ranges(ax, sa, la, sb, lb, ax.min_length(m, boundary_tol)).empty()) return std::nullopt;
    return same_profile_crossings(a, b, ax, reversed && !same, boundary_tol, fit_err);
  }

  // Where the profiles meet: from every pair of sample segments that come near each other.
  struct Root {
    double ba, bb;
    Eigen::Vector2d m;
  };
  std::vector<Root> interior;
  std::vector<Eigen::Vector2d> touches;  // all meeting points, interior or on a boundary
  const Eigen::Vector2d amin = [&] { Eigen::Vector2d x = ma[0]; for (auto& p : ma) x = x.cwiseMin(p); return x; }();
  const Eigen::Vector2d amax = [&] { Eigen::Vector2d x = ma[0]; for (auto& p : ma) x = x.cwiseMax(p); return x; }();
  const Eigen::Vector2d bmin = [&] { Eigen::Vector2d x = mb[0]; for (auto& p : mb) x = x.cwiseMin(p); return x; }();
  const Eigen::Vector2d bmax = [&] { Eigen::Vector2d x = mb[0]; for (auto& p : mb) x = x.cwiseMax(p); return x; }();
  if ((amin.array() > bmax.array() + near).any() || (bmin.array() > amax.array() + near).any())
    return std::vector<TopoDS_Edge>{};
  for (int i = 0; i < N; ++i) {
    const Eigen::Vector2d p = ma[i], d = ma[i + 1] - ma[i];
    const Eigen::Vector2d plo = p.cwiseMin(ma[i + 1]).array() - near, phi = p.cwiseMax(ma[i + 1]).array() + near;
    for (int k = 0; k < N; ++k) {
      const Eigen::Vector2d q = mb[k], e = mb[k + 1] - mb[k];
      if ((q.cwiseMax(mb[k + 1]).array() < plo.array()).any() || (q.cwiseMin(mb[k + 1]).array() > phi.array()).any())
        continue;
      const auto [s, t] = closest_on_segments(p, d, q, e);
      const double gap = (p + s * d - q - t * e).norm();
      if (gap > near) continue;
      // skip a start near a meeting point already found
      const Eigen::Vector2d here = p + s * d;
      bool known = false;
      for (const auto& x : touches) known = known || (x - here).norm() <= near;
      if (known) continue;
      double ba = a.b0 + (a.b1 - a.b0) * (i + s) / N, bb = b.b0 + (b.b1 - b.b0) * (k + t) / N;
      const double dist = closest_profile_points(a, b, ax, ba, bb);
      if (dist > boundary_tol) {
        // the polylines cross but no crossing was found
        if (gap <= Settings::polyline_crossing_rounding * (1 + p.norm())) return std::nullopt;
        continue;  // they pass near each other
      }
      const ProfilePoint A = profile(a, ax, ba), B = profile(b, ax, bb);
      // (a solve from a start farther than `near` from the first may find the same crossing again)
      bool again = false;
      for (const auto& r : interior)
        again = again || (std::abs(r.ba - ba) <= Settings::crossing_found_again * std::abs(a.b1 - a.b0) &&
                          std::abs(r.bb - bb) <= Settings::crossing_found_again * std::abs(b.b1 - b.b0));
      if (again) continue;
      touches.push_back(A.m);
      auto at_end = [&](const Carried& pp, const Eigen::Vector2d& x) {
        return (profile(pp, ax, pp.b0).m - x).norm() <= boundary_tol || (profile(pp, ax, pp.b1).m - x).norm() <= boundary_tol;
      };
      if (at_end(a, A.m) || at_end(b, A.m)) continue;      // on a boundary
      if (in_shared_end_contact(a, b, ax, ba, bb, boundary_tol)) continue;
      if (ax.turning && A.m(0) <= boundary_tol) continue;  // on the axis
      const double sine = std::abs(A.dm(0) * B.dm(1) - A.dm(1) * B.dm(0)) / (A.dm.norm() * B.dm.norm());
      if (!(sine >= Settings::orbit_section_min_sine)) {
        // touching within the tolerance of an end both share: that end, no crossing of its own
        if (contact_band > boundary_tol && in_shared_end_contact(a, b, ax, ba, bb, contact_band)) continue;
        return std::nullopt;  // tangent or nearly so
      }
      interior.push_back({ba, bb, A.m});
    }
  }

  std::vector<TopoDS_Edge> out;
  for (const auto& root : interior)
    if (!meeting_point_arcs(a, b, ax, root.m, root.ba, root.bb, boundary_tol, fit_err, out)) return std::nullopt;
  return out;
}

}  // namespace sweep::occt
