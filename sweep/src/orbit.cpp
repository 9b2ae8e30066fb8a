#include "sweep/orbit.hpp"

#include "sweep/entity.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "orbit_internal.hpp"
#include "sweep/error.hpp"

namespace sweep {

// ---------------------------------------------------------------------------------------------
// Interval sets

namespace {

/// Merges sorted intervals that overlap or touch.
Intervals merged(Intervals v) {
  std::sort(v.begin(), v.end());
  Intervals out;
  for (const auto& s : v) {
    if (!out.empty() && s.first <= out.back().second) out.back().second = std::max(out.back().second, s.second);
    else out.push_back(s);
  }
  return out;
}

}  // namespace

Intervals unite(const Intervals& a, const Intervals& b) {
  Intervals v = a;
  v.insert(v.end(), b.begin(), b.end());
  return merged(std::move(v));
}

Intervals intersect(const Intervals& a, const Intervals& b) {
  Intervals out;
  std::size_t i = 0, k = 0;
  while (i < a.size() && k < b.size()) {
    const double lo = std::max(a[i].first, b[k].first), hi = std::min(a[i].second, b[k].second);
    if (lo <= hi) out.push_back({lo, hi});
    (a[i].second < b[k].second ? i : k) += 1;
  }
  return out;
}

Intervals subtract(const Intervals& a, const Intervals& b) {
  Intervals out;
  for (auto s : a) {
    for (const auto& c : b) {
      if (c.second <= s.first || c.first >= s.second) continue;
      if (c.first > s.first) out.push_back({s.first, c.first});
      s.first = c.second;
      if (s.first >= s.second) break;
    }
    if (s.first < s.second) out.push_back(s);
  }
  return out;
}

double total_length(const Intervals& a) {
  double L = 0;
  for (const auto& s : a) L += s.second - s.first;
  return L;
}

// ---------------------------------------------------------------------------------------------
// Orbits

Eigen::Vector3d OrbitCurve::at(double t) const { return c + a * std::cos(t) + b * std::sin(t) + d * t; }

OrbitCurve OrbitCurve::mapped(const Eigen::Isometry3d& T) const {
  const Eigen::Matrix3d R = T.linear();
  return {T * c, R * a, R * b, R * d};
}

OrbitCurve OrbitCurve::shifted(double t0) const {
  const double ct = std::cos(t0), st = std::sin(t0);
  // a cos(s + t0) + b sin(s + t0) = (a ct + b st) cos s + (b ct - a st) sin s
  return {c + d * t0, a * ct + b * st, b * ct - a * st, d};
}

OrbitCurve orbit_of(const ScrewJoint& j, const Eigen::Vector3d& y) {
  OrbitCurve o;
  if (j.type == JointType::Prismatic) {
    o.c = y;
    o.d = j.direction;
    return o;
  }
  const Eigen::Vector3d w = j.direction;
  const Eigen::Vector3d r = y - j.point, along = w * w.dot(r), radial = r - along;
  // rotation by t about w: radial cos t + (w x radial) sin t
  o.c = j.point + along;
  o.a = radial;
  o.b = w.cross(radial);
  o.d = w * j.pitch;
  return o;
}

// ---------------------------------------------------------------------------------------------
// Solids

namespace orbit_detail {

int new_surface_ids(int count) {
  static std::atomic<int> next{1};
  return next.fetch_add(count);
}

}  // namespace orbit_detail

namespace {

using orbit_detail::Spans;
using orbit_detail::TrigPoly;

/// A solid that is the intersection of sub-level sets g_k <= 0 of functions given in a local frame.
/// `G` provides `template <class T> void values(const T& x, const T& y, const T& z, double m, T* out) const`
/// for count() functions, with T either double or TrigPoly, whose sub-level set holds every point
/// within m of the solid (m = 0: the solid itself), and a local-frame box.
template <class G>
class Primitive : public orbit_detail::LabeledSolid {
 public:
  Primitive(G g, const Eigen::Isometry3d& frame) : g_(std::move(g)), to_local_(frame.inverse()), frame_(frame) {
    ids_ = orbit_detail::new_surface_ids(G::count());
  }
  Spans on_curve_labeled(const OrbitCurve& world, double lo, double hi, double margin) const override {
    const OrbitCurve o = world.mapped(to_local_);
    Spans acc;
    // windows of at most a quarter turn keep the polynomial bounds tight
    const int pieces = std::max(1, int(std::ceil((hi - lo) / (0.5 * M_PI))));
    for (int p = 0; p < pieces; ++p) {
      const double a = lo + (hi - lo) * p / pieces, b = lo + (hi - lo) * (p + 1) / pieces;
      const double mid = 0.5 * (a + b), w = 0.5 * (b - a);
      const OrbitCurve s = o.shifted(mid);
      if (misses_box(s, w, margin)) continue;  // (spans on either side of it stay apart)
      TrigPoly X = TrigPoly::linear(s.c.x(), s.a.x(), s.b.x(), s.d.x());
      TrigPoly Y = TrigPoly::linear(s.c.y(), s.a.y(), s.b.y(), s.d.y());
      TrigPoly Z = TrigPoly::linear(s.c.z(), s.a.z(), s.b.z(), s.d.z());
      TrigPoly gs[G::count()];
      g_.values(X, Y, Z, margin, gs);
      Spans piece{{a, b, -1, -1}};
      for (int k = 0; k < G::count() && !piece.empty(); ++k)
        piece = orbit_detail::intersect(piece, orbit_detail::negative_set(gs[k], -w, w, mid, ids_ + k));
      acc = orbit_detail::join_adjacent(acc, piece);
    }
    return acc;
  }
  bool contains(const Eigen::Vector3d& p) const override {
    const Eigen::Vector3d l = to_local_ * p;
    double v[G::count()];
    g_.values(l.x(), l.y(), l.z(), 0.0, v);
    for (double x : v)
      if (x > 0) return false;
    return true;
  }
  Eigen::AlignedBox3d bounds() const override { return orbit_detail::mapped_box(g_.box(), frame_); }

 private:
  /// True when curve s on [-w, w] keeps outside the local box grown by the margin: each
  /// coordinate stays within w times its speed bound of its value at 0.
  bool misses_box(const OrbitCurve& s, double w, double margin) const {
    const Eigen::AlignedBox3d box = g_.box();
    for (int i = 0; i < 3; ++i) {
      const double at0 = s.c[i] + s.a[i], reach = w * (std::hypot(s.a[i], s.b[i]) + std::abs(s.d[i]));
      if (at0 + reach < box.min()[i] - margin || at0 - reach > box.max()[i] + margin) return true;
    }
    return false;
  }
  G g_;
  Eigen::Isometry3d to_local_, frame_;
  int ids_ = 0;
};

Eigen::Isometry3d frame_on_axis(const Eigen::Vector3d& origin, const Eigen::Vector3d& axis) {
  const Eigen::Vector3d z = axis.normalized();
  const Eigen::Vector3d x = z.unitOrthogonal(), y = z.cross(x);
  Eigen::Isometry3d F = Eigen::Isometry3d::Identity();
  F.linear().col(0) = x;
  F.linear().col(1) = y;
  F.linear().col(2) = z;
  F.translation() = origin;
  return F;
}

struct HalfspaceG {
  Eigen::Vector3d n;
  double h;
  static constexpr int count() { return 1; }
  template <class T>
  void values(const T& x, const T& y, const T& z, double m, T* out) const {
    out[0] = x * n.x() + y * n.y() + z * n.z() - (h + m * n.norm());
  }
  Eigen::AlignedBox3d box() const {
    // unbounded; a halfspace is only ever used inside an intersection with bounded parts
    return Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-1e300), Eigen::Vector3d::Constant(1e300));
  }
};

struct BoxG {
  Eigen::Vector3d lo, hi;
  static constexpr int count() { return 6; }
  template <class T>
  void values(const T& x, const T& y, const T& z, double m, T* out) const {
    out[0] = -x + (lo.x() - m);
    out[1] = x - (hi.x() + m);
    out[2] = -y + (lo.y() - m);
    out[3] = y - (hi.y() + m);
    out[4] = -z + (lo.z() - m);
    out[5] = z - (hi.z() + m);
  }
  Eigen::AlignedBox3d box() const { return Eigen::AlignedBox3d(lo, hi); }
};

struct SphereG {
  Eigen::Vector3d c;
  double r;
  static constexpr int count() { return 1; }
  template <class T>
  void values(const T& x, const T& y, const T& z, double m, T* out) const {
    const T dx = x - c.x(), dy = y - c.y(), dz = z - c.z();
    out[0] = dx * dx + dy * dy + dz * dz - (r + m) * (r + m);
  }
  Eigen::AlignedBox3d box() const { return Eigen::AlignedBox3d(c.array() - r, c.array() + r); }
};

/// Frustum on the local z axis from radius r1 at z = 0 to r2 at z = h (a cylinder when equal).
struct FrustumG {
  double r1, r2, h;
  static constexpr int count() { return 3; }
  template <class T>
  void values(const T& x, const T& y, const T& z, double m, T* out) const {
    // a margin m widens the radius by m / cos(half angle), and the slab by m
    const double k = (r2 - r1) / h, widen = m * std::sqrt(1 + k * k);
    const T r = z * k + (r1 + widen);
    out[0] = x * x + y * y - r * r;
    out[1] = -z - m;
    out[2] = z - (h + m);
  }
  Eigen::AlignedBox3d box() const {
    const double m = std::max(r1, r2);
    return Eigen::AlignedBox3d(Eigen::Vector3d(-m, -m, 0), Eigen::Vector3d(m, m, h));
  }
};

/// Elliptic cylinder on the local z axis from z = 0 to h, semi-axes a along local x and b along y.
struct EllipticG {
  double a, b, h;
  static constexpr int count() { return 3; }
  template <class T>
  void values(const T& x, const T& y, const T& z, double m, T* out) const {
    // the ellipse scaled by 1 + m / min(a, b) holds every point within m of it (its support
    // function grows by at least m in every direction)
    const double s = 1 + m / std::min(a, b);
    out[0] = x * x * (1 / (a * a)) + y * y * (1 / (b * b)) - s * s;
    out[1] = -z - m;
    out[2] = z - (h + m);
  }
  Eigen::AlignedBox3d box() const { return Eigen::AlignedBox3d(Eigen::Vector3d(-a, -b, 0), Eigen::Vector3d(a, b, h)); }
};

/// Torus about the local z axis.
struct TorusG {
  double R, r;
  static constexpr int count() { return 1; }
  template <class T>
  void values(const T& x, const T& y, const T& z, double m, T* out) const {
    const T rho2 = x * x + y * y;
    if (r + m >= 0.999 * R) {  // a margin that fills the hole: the ball about the centre bounds it
      out[0] = rho2 + z * z - (R + r + m) * (R + r + m);
      return;
    }
    const T s = rho2 + z * z + (R * R - (r + m) * (r + m));
    out[0] = s * s - rho2 * (4 * R * R);
  }
  Eigen::AlignedBox3d box() const {
    return Eigen::AlignedBox3d(Eigen::Vector3d(-R - r, -R - r, -r), Eigen::Vector3d(R + r, R + r, r));
  }
};

class Csg : public orbit_detail::LabeledSolid {
 public:
  enum class Op { Union, Intersection, Difference };
  Csg(Op op, std::vector<OrbitSolidPtr> parts) : op_(op), parts_(std::move(parts)) {
    SWEEP_ASSERT(!parts_.empty(), "a CSG solid needs parts");
    for (const auto& p : parts_)
      SWEEP_ASSERT(dynamic_cast<const orbit_detail::LabeledSolid*>(p.get()), "CSG parts must be orbit solids");
  }
  Spans on_curve_labeled(const OrbitCurve& o, double lo, double hi, double margin) const override {
    Spans acc = part(0).on_curve_labeled(o, lo, hi, margin);
    // with a margin, a difference is bounded by its first part alone
    const std::size_t n = margin > 0 && op_ == Op::Difference ? 1 : parts_.size();
    for (std::size_t k = 1; k < n; ++k) {
      if (op_ != Op::Union && acc.empty()) break;
      const Spans s = part(k).on_curve_labeled(o, lo, hi, margin);
      acc = op_ == Op::Union          ? orbit_detail::unite(acc, s)
            : op_ == Op::Intersection ? orbit_detail::intersect(acc, s)
                                      : orbit_detail::subtract(acc, s);
    }
    return acc;
  }
  bool contains(const Eigen::Vector3d& p) const override {
    if (op_ == Op::Union) {
      for (const auto& s : parts_)
        if (s->contains(p)) return true;
      return false;
    }
    if (op_ == Op::Intersection) {
      for (const auto& s : parts_)
        if (!s->contains(p)) return false;
      return true;
    }
    if (!parts_[0]->contains(p)) return false;
    for (std::size_t k = 1; k < parts_.size(); ++k)
      if (parts_[k]->contains(p)) return false;
    return true;
  }
  Eigen::AlignedBox3d bounds() const override {
    if (op_ == Op::Difference) return parts_[0]->bounds();
    Eigen::AlignedBox3d b = parts_[0]->bounds();
    for (std::size_t k = 1; k < parts_.size(); ++k) {
      if (op_ == Op::Union) b.extend(parts_[k]->bounds());
      else b = b.intersection(parts_[k]->bounds());
    }
    return b;
  }

 private:
  const orbit_detail::LabeledSolid& part(std::size_t k) const {
    return static_cast<const orbit_detail::LabeledSolid&>(*parts_[k]);
  }
  Op op_;
  std::vector<OrbitSolidPtr> parts_;
};

class Placed : public orbit_detail::LabeledSolid {
 public:
  Placed(OrbitSolidPtr s, const Eigen::Isometry3d& T) : s_(std::move(s)), T_(T), inv_(T.inverse()) {
    SWEEP_ASSERT(dynamic_cast<const orbit_detail::LabeledSolid*>(s_.get()), "placed solids must be orbit solids");
  }
  Spans on_curve_labeled(const OrbitCurve& o, double lo, double hi, double margin) const override {
    return static_cast<const orbit_detail::LabeledSolid&>(*s_).on_curve_labeled(o.mapped(inv_), lo, hi, margin);
  }
  bool contains(const Eigen::Vector3d& p) const override { return s_->contains(inv_ * p); }
  Eigen::AlignedBox3d bounds() const override { return orbit_detail::mapped_box(s_->bounds(), T_); }

 private:
  OrbitSolidPtr s_;
  Eigen::Isometry3d T_, inv_;
};

}  // namespace

Intervals orbit_detail::LabeledSolid::on_curve(const OrbitCurve& o, double lo, double hi) const {
  Intervals out;
  for (const auto& s : on_curve_labeled(o, lo, hi, 0.0)) out.push_back({s.lo, s.hi});
  return out;
}

OrbitSolidPtr orbit_halfspace(const Eigen::Vector3d& normal, double offset) {
  return std::make_shared<Primitive<HalfspaceG>>(HalfspaceG{normal, offset}, Eigen::Isometry3d::Identity());
}
OrbitSolidPtr orbit_box(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  return std::make_shared<Primitive<BoxG>>(BoxG{min, max}, Eigen::Isometry3d::Identity());
}
OrbitSolidPtr orbit_sphere(const Eigen::Vector3d& centre, double radius) {
  return std::make_shared<Primitive<SphereG>>(SphereG{centre, radius}, Eigen::Isometry3d::Identity());
}
OrbitSolidPtr orbit_cylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& axis, double radius, double height) {
  return orbit_cone(base, axis, radius, radius, height);
}
OrbitSolidPtr orbit_cone(const Eigen::Vector3d& base, const Eigen::Vector3d& axis, double r1, double r2, double height) {
  return std::make_shared<Primitive<FrustumG>>(FrustumG{r1, r2, height}, frame_on_axis(base, axis));
}
OrbitSolidPtr orbit_elliptic_cylinder(const Eigen::Isometry3d& frame, double a, double b, double height) {
  return std::make_shared<Primitive<EllipticG>>(EllipticG{a, b, height}, frame);
}
OrbitSolidPtr orbit_torus(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis, double major, double minor) {
  return std::make_shared<Primitive<TorusG>>(TorusG{major, minor}, frame_on_axis(centre, axis));
}
OrbitSolidPtr orbit_union(std::vector<OrbitSolidPtr> parts) {
  return std::make_shared<Csg>(Csg::Op::Union, std::move(parts));
}
OrbitSolidPtr orbit_intersection(std::vector<OrbitSolidPtr> parts) {
  return std::make_shared<Csg>(Csg::Op::Intersection, std::move(parts));
}
OrbitSolidPtr orbit_difference(OrbitSolidPtr a, OrbitSolidPtr b) {
  return std::make_shared<Csg>(Csg::Op::Difference, std::vector<OrbitSolidPtr>{std::move(a), std::move(b)});
}
OrbitSolidPtr orbit_placed(OrbitSolidPtr s, const Eigen::Isometry3d& placement) {
  return std::make_shared<Placed>(std::move(s), placement);
}

OrbitSolidPtr make_orbit_solid(const EntitySpec& e) {
  const EntityPtr entity = make_entity(e);
  return entity ? entity->orbit_solid() : nullptr;
}

bool in_joint_sweep(const OrbitSolid& body, const ScrewJoint& j, double T, const Eigen::Vector3d& x) {
  // x = exp(xi t) y with y in the body: the orbit of x, followed backwards over [0, T], meets it
  if (j.type == JointType::Revolute) T = std::min(T, 2 * M_PI);
  return !body.on_curve(orbit_of(j, x), -T, 0.0).empty();
}

}  // namespace sweep
