#pragma once
// Internals of orbit.cpp shared with the orbit-space volume integral: polynomials in (t, cos t, sin t),
// their certified negative sets, and intervals whose ends remember the surface that made them.
#include <Eigen/Geometry>
#include <vector>

#include "sweep/orbit.hpp"

namespace sweep::orbit_detail {

/// g(t) = sum over k <= 4, n <= 4 of t^k (c[k][n] cos(n t) + s[k][n] sin(n t)): what the squares and
/// products of an orbit's coordinates (linear in 1, t, cos t, sin t) make, up to degree four.
struct TrigPoly {
  static constexpr int K = 4, N = 4;
  double c[K + 1][N + 1] = {};
  double s[K + 1][N + 1] = {};
  int kmax = 0, nmax = 0;

  TrigPoly() = default;
  TrigPoly(double constant) { c[0][0] = constant; }  // NOLINT: a constant converts implicitly
  /// c0 + a cos t + b sin t + d t
  static TrigPoly linear(double c0, double a, double b, double d);

  /// g(t) and g'(t).
  void eval(double t, double* g, double* dg) const;
  double operator()(double t) const;
  /// An upper bound of |g''| on [-w, w], and of the size of the terms there (for rounding).
  double second_derivative_bound(double w) const;
  double magnitude(double w) const;
};
TrigPoly operator+(const TrigPoly& a, const TrigPoly& b);
TrigPoly operator-(const TrigPoly& a, const TrigPoly& b);
TrigPoly operator-(const TrigPoly& a);
TrigPoly operator*(const TrigPoly& a, const TrigPoly& b);
TrigPoly operator*(const TrigPoly& a, double k);
TrigPoly operator+(const TrigPoly& a, double k);
TrigPoly operator-(const TrigPoly& a, double k);

/// A closed interval whose ends carry the id of the surface that bounds them (-1: a window's end).
struct Span {
  double lo, hi;
  int lo_id, hi_id;
};
using Spans = std::vector<Span>;

/// The roots of g in [a, b] at which it changes sign, sorted: isolated by g's value and slope at
/// cell centres against the bound on g'' (a cell is skipped only when g cannot vanish in it), then
/// refined to rounding. A root at which g touches zero without changing sign is not among them.
std::vector<double> sign_changes(const TrigPoly& g, double a, double b);

/// Where g < 0 on [a, b], shifted by `shift`, cut at g's sign changes. Ends at roots get `id`, ends
/// at a or b get -1.
Spans negative_set(const TrigPoly& g, double a, double b, double shift, int id);

Spans unite(const Spans& a, const Spans& b);
Spans intersect(const Spans& a, const Spans& b);
Spans subtract(const Spans& a, const Spans& b);
/// a followed by b over the next window: spans meeting at the shared window end are joined.
Spans join_adjacent(const Spans& a, const Spans& b);

/// `count` fresh surface ids (unique in the process).
int new_surface_ids(int count);

/// Every orbit solid of orbit.cpp: intervals with labelled ends.
class LabeledSolid : public OrbitSolid {
 public:
  /// The spans of the curve in the solid, or with margin > 0 in a superset of the points within
  /// `margin` of it (whose spans are empty only where the curve keeps that far from the solid).
  virtual Spans on_curve_labeled(const OrbitCurve& o, double lo, double hi, double margin) const = 0;
  Intervals on_curve(const OrbitCurve& o, double lo, double hi) const override;
};

/// True when curve s on [-w, w] keeps outside box b: each coordinate stays within w times its speed
/// bound of its value at 0.
bool curve_misses_box(const OrbitCurve& s, double w, const Eigen::AlignedBox3d& b);

/// The box of the image of box b under T.
inline Eigen::AlignedBox3d mapped_box(const Eigen::AlignedBox3d& b, const Eigen::Isometry3d& T) {
  if (b.min().maxCoeff() < -1e299 || b.max().minCoeff() > 1e299) return b;
  Eigen::AlignedBox3d out;
  for (int k = 0; k < 8; ++k) out.extend(T * b.corner(Eigen::AlignedBox3d::CornerType(k)));
  return out;
}

}  // namespace sweep::orbit_detail
