// Circles where two faces turned about one axis cross (see revolution_section.hpp).
#include "revolution_section.hpp"

#include <BRepAdaptor_Surface.hxx>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Circle.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "internal.hpp"

namespace sweep::occt {

namespace {

/// The joint's axis with a frame for angles about it.
struct AxisFrame {
  Eigen::Vector3d p0, w, e1, e2;
  explicit AxisFrame(const ScrewJoint& j)
      : p0(j.point), w(j.direction.normalized()), e1(w.unitOrthogonal()), e2(w.cross(e1)) {}
  Eigen::Vector3d radial(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d d = x - p0;
    return d - w * w.dot(d);
  }
  double angle(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d r = radial(x);
    return std::atan2(e2.dot(r), e1.dot(r));
  }
  Eigen::Vector3d turned(const Eigen::Vector3d& x, double a) const {
    return p0 + Eigen::AngleAxisd(a, w) * (x - p0);
  }
};

/// A patch with an evaluator of its own (OCCT's surface adaptors cache and are not shared by threads).
struct Turned {
  const RevolutionPatch& p;
  BRepAdaptor_Surface surface;
  double u0, u1, v0, v1;
  int sense;
  explicit Turned(const RevolutionPatch& patch)
      : p(patch), surface(patch.face, false), u0(patch.u0), u1(patch.u1), v0(patch.v0), v1(patch.v1), sense(patch.sense) {}
};

/// A meridian point (r, z) and its derivative in v.
struct MeridianPoint {
  Eigen::Vector2d m, dm;
};

MeridianPoint meridian(const Turned& p, const AxisFrame& ax, double v) {
  gp_Pnt P;
  gp_Vec Du, Dv;
  p.surface.D1(p.u0, v, P, Du, Dv);
  const Eigen::Vector3d x = to_eigen(P) - ax.p0, dx = to_eigen(Dv);
  const double z = ax.w.dot(x), dz = ax.w.dot(dx);
  const Eigen::Vector3d rho = x - ax.w * z, drho = dx - ax.w * dz;
  const double r = rho.norm();
  return {{r, z}, {r > 0 ? rho.dot(drho) / r : drho.norm(), dz}};
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

/// Where the meridians come closest near (va, vb): a damped Gauss-Newton solve of ma(va) = mb(vb)
/// in the parameter boxes. Returns the distance left.
double closest_meridian_points(const Turned& a, const Turned& b, const AxisFrame& ax, double& va,
                               double& vb) {
  MeridianPoint A = meridian(a, ax, va), B = meridian(b, ax, vb);
  Eigen::Vector2d F = A.m - B.m;
  double lambda = 1e-12;
  for (int it = 0; it < 100 && F.norm() > 0; ++it) {
    Eigen::Matrix2d J;
    J.col(0) = A.dm;
    J.col(1) = -B.dm;
    const Eigen::Matrix2d H = J.transpose() * J;
    const Eigen::Vector2d g = J.transpose() * F;
    const double scale = H.diagonal().maxCoeff();
    if (!(scale > 0)) break;
    const Eigen::Vector2d step = -(H + lambda * scale * Eigen::Matrix2d::Identity()).ldlt().solve(g);
    const double na = std::clamp(va + step(0), std::min(a.v0, a.v1), std::max(a.v0, a.v1));
    const double nb = std::clamp(vb + step(1), std::min(b.v0, b.v1), std::max(b.v0, b.v1));
    const MeridianPoint A2 = meridian(a, ax, na), B2 = meridian(b, ax, nb);
    const Eigen::Vector2d F2 = A2.m - B2.m;
    if (F2.norm() < F.norm()) {
      const bool moved = std::abs(na - va) > 1e-15 * (1 + std::abs(va)) || std::abs(nb - vb) > 1e-15 * (1 + std::abs(vb));
      va = na, vb = nb, A = A2, B = B2, F = F2;
      lambda = std::max(1e-12, lambda * 0.1);
      if (!moved) break;
    } else {
      lambda *= 10;
      if (lambda > 1e8) break;
    }
  }
  return F.norm();
}

/// The arcs (start, length) where angle ranges [sa, sa + la] and [sb, sb + lb] overlap on the circle.
std::vector<std::pair<double, double>> overlapping_arcs(double sa, double la, double sb, double lb, double min_len) {
  const double full = 2 * M_PI;
  const bool whole_a = la >= full - 1e-12, whole_b = lb >= full - 1e-12;
  if (whole_a && whole_b) return {{0.0, full}};
  if (whole_a) return {{sb, lb}};
  if (whole_b) return {{sa, la}};
  std::vector<std::pair<double, double>> out;
  for (double shift : {-full, 0.0, full}) {
    const double lo = std::max(sa, sb + shift), hi = std::min(sa + la, sb + shift + lb);
    if (hi - lo > min_len) out.push_back({lo, hi - lo});
  }
  return out;
}

/// Patch p's angle range at meridian parameter v: (start, length) with the length >= 0.
std::pair<double, double> angle_range(const Turned& p, const AxisFrame& ax, double v) {
  const double phi = ax.angle(to_eigen(p.surface.Value(p.u0, v)));
  const double len = p.u1 - p.u0;
  return p.sense > 0 ? std::make_pair(phi, len) : std::make_pair(phi - len, len);
}

}  // namespace

std::optional<RevolutionPatch> revolution_patch(const TopoDS_Face& face, const ScrewJoint& j, double eps) {
  if (j.type != JointType::Revolute) return std::nullopt;
  RevolutionPatch p;
  p.face = face;
  const BRepAdaptor_Surface surface(face, false);
  switch (surface.GetType()) {
    case GeomAbs_SurfaceOfRevolution:
    case GeomAbs_Cylinder:
    case GeomAbs_Cone:
    case GeomAbs_Sphere:
    case GeomAbs_Torus:
      break;
    default:
      return std::nullopt;
  }
  BRepTools::UVBounds(face, p.u0, p.u1, p.v0, p.v1);
  if (!(p.u1 - p.u0 > 0) || !(p.v1 - p.v0 > 0) || p.u1 - p.u0 > 2 * M_PI + 1e-9) return std::nullopt;
  // one wire of iso-lines on the sides of the parameter box
  int wires = 0;
  for (TopExp_Explorer wx(face, TopAbs_WIRE); wx.More(); wx.Next()) ++wires;
  if (wires != 1) return std::nullopt;
  const double tu = 1e-9 * (1 + p.u1 - p.u0), tv = 1e-9 * (1 + std::abs(p.v0) + std::abs(p.v1));
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next()) {
    double f, l;
    const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), face, f, l);
    if (pc.IsNull()) return std::nullopt;
    bool on_u0 = true, on_u1 = true, on_v0 = true, on_v1 = true;
    for (double s : {f, 0.5 * (f + l), l}) {
      const gp_Pnt2d uv = pc->Value(s);
      on_u0 = on_u0 && std::abs(uv.X() - p.u0) <= tu;
      on_u1 = on_u1 && std::abs(uv.X() - p.u1) <= tu;
      on_v0 = on_v0 && std::abs(uv.Y() - p.v0) <= tv;
      on_v1 = on_v1 && std::abs(uv.Y() - p.v1) <= tv;
    }
    if (!(on_u0 || on_u1 || on_v0 || on_v1)) return std::nullopt;
  }
  // u is the angle about the joint's axis, turning one way
  const AxisFrame ax(j);
  const double du = p.u1 - p.u0;
  int sense = 0;
  bool off_axis = false;
  for (double fv : {0.2, 0.5, 0.8}) {
    const double v = p.v0 + fv * (p.v1 - p.v0);
    const Eigen::Vector3d x0 = to_eigen(surface.Value(p.u0, v));
    if (ax.radial(x0).norm() > 1e3 * eps) off_axis = true;
    for (double fu : {0.5, 1.0}) {
      const Eigen::Vector3d x = to_eigen(surface.Value(p.u0 + fu * du, v));
      const bool plus = (ax.turned(x0, fu * du) - x).norm() <= eps, minus = (ax.turned(x0, -fu * du) - x).norm() <= eps;
      if (!plus && !minus) return std::nullopt;
      if (plus && minus) continue;  // (on the axis, or a half turn)
      const int s = plus ? 1 : -1;
      if (sense != 0 && s != sense) return std::nullopt;
      sense = s;
    }
  }
  if (sense == 0 || !off_axis) return std::nullopt;
  p.sense = sense;
  return p;
}

std::optional<std::vector<TopoDS_Edge>> revolution_section(const RevolutionPatch& patch_a, const RevolutionPatch& patch_b,
                                                           const ScrewJoint& j, double boundary_tol) {
  const AxisFrame ax(j);
  const Turned a(patch_a), b(patch_b);
  constexpr int N = 96;
  auto samples = [&](const Turned& p, std::vector<Eigen::Vector2d>& m, double& sag) {
    m.resize(N + 1);
    for (int k = 0; k <= N; ++k) m[k] = meridian(p, ax, p.v0 + (p.v1 - p.v0) * k / N).m;
    sag = 0;
    for (int k = 0; k < N; ++k) {
      const Eigen::Vector2d mid = meridian(p, ax, p.v0 + (p.v1 - p.v0) * (k + 0.5) / N).m;
      sag = std::max(sag, (mid - 0.5 * (m[k] + m[k + 1])).norm());
    }
  };
  std::vector<Eigen::Vector2d> ma, mb;
  double sag_a, sag_b;
  samples(a, ma, sag_a);
  samples(b, mb, sag_b);
  const double near = 4 * (sag_a + sag_b) + 10 * boundary_tol;

  // One meridian (pieces of one curve's sweep): the faces meet along a meridian edge at most.
  bool same = true, reversed = true;
  for (int k = 0; k <= N && (same || reversed); ++k) {
    same = same && (ma[k] - mb[k]).norm() <= boundary_tol;
    reversed = reversed && (ma[k] - mb[N - k]).norm() <= boundary_tol;
  }
  if (same || reversed) {
    const double v = 0.5 * (a.v0 + a.v1);
    const double r = meridian(a, ax, v).m(0);
    const auto [sa, la] = angle_range(a, ax, v);
    const auto [sb, lb] = angle_range(b, ax, 0.5 * (b.v0 + b.v1));  // (the middle sample of both)
    if (!overlapping_arcs(sa, la, sb, lb, boundary_tol / std::max(r, boundary_tol)).empty()) return std::nullopt;
    return std::vector<TopoDS_Edge>{};
  }

  // Where the meridians meet: from every pair of sample segments that come near each other.
  struct Root {
    double va, vb;
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
      double va = a.v0 + (a.v1 - a.v0) * (i + s) / N, vb = b.v0 + (b.v1 - b.v0) * (k + t) / N;
      const double dist = closest_meridian_points(a, b, ax, va, vb);
      if (dist > boundary_tol) {
        if (gap <= 1e-12 * (1 + p.norm())) return std::nullopt;  // the polylines cross but no crossing was found
        continue;                                                // they pass near each other
      }
      const MeridianPoint A = meridian(a, ax, va), B = meridian(b, ax, vb);
      touches.push_back(A.m);
      auto at_end = [&](const Turned& pp, const Eigen::Vector2d& x) {
        return (meridian(pp, ax, pp.v0).m - x).norm() <= boundary_tol || (meridian(pp, ax, pp.v1).m - x).norm() <= boundary_tol;
      };
      if (at_end(a, A.m) || at_end(b, A.m) || A.m(0) <= boundary_tol) continue;  // on a boundary, or the axis
      const double sine = std::abs(A.dm(0) * B.dm(1) - A.dm(1) * B.dm(0)) / (A.dm.norm() * B.dm.norm());
      if (!(sine >= 1e-3)) return std::nullopt;  // tangent or nearly so
      interior.push_back({va, vb, A.m});
    }
  }

  std::vector<TopoDS_Edge> out;
  for (const auto& root : interior) {
    const double r = root.m(0), z = root.m(1);
    const auto [sa, la] = angle_range(a, ax, root.va);
    const auto [sb, lb] = angle_range(b, ax, root.vb);
    const Eigen::Vector3d centre = ax.p0 + ax.w * z;
    const Handle(Geom_Circle) circle = new Geom_Circle(gp_Ax2(to_pnt(centre), gp_Dir(to_vec(ax.w)), gp_Dir(to_vec(ax.e1))), r);
    for (const auto& [start, len] : overlapping_arcs(sa, la, sb, lb, boundary_tol / r)) {
      const double lo = std::remainder(start, 2 * M_PI);
      BRepBuilderAPI_MakeEdge mk(circle, lo, lo + std::min(len, 2 * M_PI));
      if (!mk.IsDone()) return std::nullopt;
      out.push_back(mk.Edge());
    }
  }
  return out;
}

}  // namespace sweep::occt
