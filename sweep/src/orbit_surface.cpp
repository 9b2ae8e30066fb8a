// Crossings of orbits with planar, quadric and toroidal surfaces, by the roots of the surface's
// implicit function along the orbit.
#include <cmath>

#include "orbit_internal.hpp"
#include "sweep/orbit.hpp"

namespace sweep {

namespace {

using orbit_detail::TrigPoly;

/// f in local coordinates, for T either double or TrigPoly.
template <class T>
T implicit_value(const OrbitSurface& s, const T& x, const T& y, const T& z) {
  switch (s.kind) {
    case OrbitSurface::Kind::Plane:
      return z;
    case OrbitSurface::Kind::Cylinder:
      return x * x + y * y - s.radius * s.radius;
    case OrbitSurface::Kind::Cone: {
      const T r = z * s.slope + s.radius;
      return x * x + y * y - r * r;
    }
    case OrbitSurface::Kind::Sphere:
      return x * x + y * y + z * z - s.radius * s.radius;
    case OrbitSurface::Kind::Torus: {
      const T rho2 = x * x + y * y;
      const T q = rho2 + z * z + (s.radius * s.radius - s.minor * s.minor);
      return q * q - rho2 * (4 * s.radius * s.radius);
    }
  }
  return z;
}

}  // namespace

bool orbit_detail::curve_misses_box(const OrbitCurve& s, double w, const Eigen::AlignedBox3d& b) {
  for (int i = 0; i < 3; ++i) {
    const double at0 = s.c[i] + s.a[i], reach = w * (std::hypot(s.a[i], s.b[i]) + std::abs(s.d[i]));
    if (at0 + reach < b.min()[i] || at0 - reach > b.max()[i]) return true;
  }
  return false;
}

double OrbitSurface::value(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d l = frame.inverse() * p;
  return implicit_value(*this, l.x(), l.y(), l.z());
}

std::vector<double> surface_crossings(const OrbitSurface& s, const OrbitCurve& o, double lo, double hi,
                                      const Eigen::AlignedBox3d& region) {
  std::vector<double> out;
  if (!(hi > lo)) return out;
  const OrbitCurve local = o.mapped(s.frame.inverse());
  // windows of at most a quarter turn keep the polynomial bounds tight (a line needs one)
  const bool turns = o.a.squaredNorm() + o.b.squaredNorm() > 0;
  const int pieces = turns ? std::max(1, int(std::ceil((hi - lo) / (0.5 * M_PI)))) : 1;
  for (int p = 0; p < pieces; ++p) {
    const double a = lo + (hi - lo) * p / pieces, b = lo + (hi - lo) * (p + 1) / pieces;
    const double mid = 0.5 * (a + b), w = 0.5 * (b - a);
    if (orbit_detail::curve_misses_box(o.shifted(mid), w, region)) continue;
    const OrbitCurve c = local.shifted(mid);
    const TrigPoly X = TrigPoly::linear(c.c.x(), c.a.x(), c.b.x(), c.d.x());
    const TrigPoly Y = TrigPoly::linear(c.c.y(), c.a.y(), c.b.y(), c.d.y());
    const TrigPoly Z = TrigPoly::linear(c.c.z(), c.a.z(), c.b.z(), c.d.z());
    for (double r : orbit_detail::sign_changes(implicit_value(s, X, Y, Z), -w, w))
      if (out.empty() || r + mid > out.back()) out.push_back(r + mid);
  }
  return out;
}

}  // namespace sweep
