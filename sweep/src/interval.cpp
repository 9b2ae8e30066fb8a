#include "sweep/interval.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sweep {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.141592653589793238462643383279502884;
// Rounding of the endpoints: 1e-15 relative is about four units in the last place, above the error
// of IEEE operations (half a unit) and of glibc's sin, cos, tan, exp, log, pow, asin, acos, atan
// and atan2 (at most one or two units); the absolute term covers results near zero.
constexpr double kRel = 1e-15, kAbs = 1e-300;

double down(double x) { return std::isinf(x) ? x : x - (std::abs(x) * kRel + kAbs); }
double up(double x) { return std::isinf(x) ? x : x + (std::abs(x) * kRel + kAbs); }

/// The rounded-out interval [lo, hi]; the whole line when an endpoint is NaN.
Interval out(double lo, double hi) {
  if (std::isnan(lo) || std::isnan(hi)) return Interval::entire();
  return {down(lo), up(hi)};
}

/// Whether [lo, hi] holds offset + period k for some integer k (rounding of the quotient allowed for).
bool holds_phase(double lo, double hi, double offset, double period) {
  const double a = (lo - offset) / period, b = (hi - offset) / period;
  const double slack = 1e-9 + 1e-14 * std::max(std::abs(a), std::abs(b));
  return std::ceil(a - slack) <= std::floor(b + slack);
}

/// f increasing on its domain [dlo, dhi]: the image of a clipped to it (whole line when a misses it).
template <class F>
Interval increasing(Interval a, double dlo, double dhi, F f) {
  const double lo = std::max(a.lo, dlo), hi = std::min(a.hi, dhi);
  if (!(lo <= hi)) return Interval::entire();
  return out(f(lo), f(hi));
}

/// x * y with 0 * inf = 0: products of reals in intervals with infinite ends.
double times(double x, double y) { return x == 0 || y == 0 ? 0.0 : x * y; }

bool is_integer(double k) { return std::isfinite(k) && k == std::floor(k); }

}  // namespace

Interval Interval::entire() { return {-kInf, kInf}; }
double Interval::mag() const { return std::max(std::abs(lo), std::abs(hi)); }
double Interval::mig() const { return contains(0.0) ? 0.0 : std::min(std::abs(lo), std::abs(hi)); }

Interval hull(Interval a, Interval b) { return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)}; }
Interval operator-(Interval a) { return {-a.hi, -a.lo}; }
Interval operator+(Interval a, Interval b) { return out(a.lo + b.lo, a.hi + b.hi); }
Interval operator-(Interval a, Interval b) { return out(a.lo - b.hi, a.hi - b.lo); }

Interval operator*(Interval a, Interval b) {
  if (a.is_zero() || b.is_zero()) return Interval::point(0.0);
  const double p[4] = {times(a.lo, b.lo), times(a.lo, b.hi), times(a.hi, b.lo), times(a.hi, b.hi)};
  return out(*std::min_element(p, p + 4), *std::max_element(p, p + 4));
}

Interval operator/(Interval a, Interval b) {
  if (b.contains(0.0)) return Interval::entire();
  return a * out(1.0 / b.hi, 1.0 / b.lo);
}

Interval sq(Interval a) {
  const double l = a.lo * a.lo, h = a.hi * a.hi;
  if (a.contains(0.0)) return out(0.0, std::max(l, h));
  return out(std::min(l, h), std::max(l, h));
}

Interval pow_const(Interval x, double k) {
  if (k == 0) return Interval::point(1.0);
  if (k == 1) return x;
  if (k == 2) return sq(x);
  if (is_integer(k)) {
    const bool even = std::fmod(k, 2.0) == 0;
    if (x.contains(0.0)) {
      if (k < 0) return Interval::entire();
      const double l = std::pow(x.lo, k), h = std::pow(x.hi, k);
      return even ? out(0.0, std::max(l, h)) : out(l, h);
    }
    // monotone on an interval of one sign
    const double l = std::pow(x.lo, k), h = std::pow(x.hi, k);
    return out(std::min(l, h), std::max(l, h));
  }
  const double lo = std::max(x.lo, 0.0);
  if (!(lo <= x.hi)) return Interval::entire();
  if (k > 0) return out(std::pow(lo, k), std::pow(x.hi, k));
  if (lo == 0) return out(std::pow(x.hi, k), kInf);
  return out(std::pow(x.hi, k), std::pow(lo, k));
}

Interval const_pow(double k, Interval x) {
  if (!(k > 0)) return Interval::entire();
  const double l = std::pow(k, x.lo), h = std::pow(k, x.hi);
  return out(std::min(l, h), std::max(l, h));
}

Interval pow(Interval x, Interval y) {
  if (!(x.lo > 0)) return Interval::entire();
  return exp(y * log(x));
}

Interval cos(Interval a) {
  if (!(a.hi - a.lo < 2 * kPi) || std::max(std::abs(a.lo), std::abs(a.hi)) > 1e9) return out(-1, 1);
  const double l = std::cos(a.lo), h = std::cos(a.hi);
  const double top = holds_phase(a.lo, a.hi, 0.0, 2 * kPi) ? 1.0 : std::max(l, h);
  const double bottom = holds_phase(a.lo, a.hi, kPi, 2 * kPi) ? -1.0 : std::min(l, h);
  return out(bottom, top);
}

Interval sin(Interval a) {
  if (!(a.hi - a.lo < 2 * kPi) || std::max(std::abs(a.lo), std::abs(a.hi)) > 1e9) return out(-1, 1);
  const double l = std::sin(a.lo), h = std::sin(a.hi);
  const double top = holds_phase(a.lo, a.hi, 0.5 * kPi, 2 * kPi) ? 1.0 : std::max(l, h);
  const double bottom = holds_phase(a.lo, a.hi, -0.5 * kPi, 2 * kPi) ? -1.0 : std::min(l, h);
  return out(bottom, top);
}

Interval tan(Interval a) {
  if (!(a.hi - a.lo < kPi) || std::max(std::abs(a.lo), std::abs(a.hi)) > 1e9 ||
      holds_phase(a.lo, a.hi, 0.5 * kPi, kPi))
    return Interval::entire();
  return out(std::tan(a.lo), std::tan(a.hi));
}

Interval asin(Interval a) { return increasing(a, -1, 1, [](double x) { return std::asin(x); }); }
Interval acos(Interval a) {
  const double lo = std::max(a.lo, -1.0), hi = std::min(a.hi, 1.0);
  if (!(lo <= hi)) return Interval::entire();
  return out(std::acos(hi), std::acos(lo));  // decreasing
}
Interval atan(Interval a) { return increasing(a, -kInf, kInf, [](double x) { return std::atan(x); }); }
Interval sqrt(Interval a) { return increasing(a, 0, kInf, [](double x) { return std::sqrt(x); }); }
Interval exp(Interval a) { return increasing(a, -kInf, kInf, [](double x) { return std::exp(x); }); }
Interval log(Interval a) { return increasing(a, 0, kInf, [](double x) { return std::log(x); }); }

Interval atan2(Interval y, Interval x) {
  // off the cut the angle has no critical point and is monotone along each side of the box
  if (y.contains(0.0) && x.lo <= 0) return out(-kPi, kPi);
  const double c[4] = {std::atan2(y.lo, x.lo), std::atan2(y.lo, x.hi), std::atan2(y.hi, x.lo), std::atan2(y.hi, x.hi)};
  return out(*std::min_element(c, c + 4), *std::max_element(c, c + 4));
}

Interval abs(Interval a) {
  if (a.contains(0.0)) return {0.0, a.mag()};
  return {a.mig(), a.mag()};
}

Interval min(Interval a, Interval b) { return {std::min(a.lo, b.lo), std::min(a.hi, b.hi)}; }
Interval max(Interval a, Interval b) { return {std::max(a.lo, b.lo), std::max(a.hi, b.hi)}; }

}  // namespace sweep
