#pragma once
/// @file interval.hpp
/// Closed intervals with outward rounding: every operation returns an interval that holds the
/// exact result for every choice of arguments in its operands (endpoints widened by a few units in
/// the last place, enough for IEEE arithmetic and the C library's transcendental functions).
/// Functions are taken on their domain (sqrt of [-1, 4] is [0, 2]); an operation that has no finite
/// bound there (division by an interval that holds 0, tan across a pole) gives the whole line.
namespace sweep {

struct Interval {
  double lo = 0, hi = 0;
  static Interval point(double x) { return {x, x}; }
  static Interval entire();
  bool contains(double x) const { return lo <= x && x <= hi; }
  bool is_zero() const { return lo == 0 && hi == 0; }
  /// The largest |x| over the interval.
  double mag() const;
  /// The smallest |x| over the interval.
  double mig() const;
};

Interval hull(Interval a, Interval b);
Interval operator-(Interval a);
Interval operator+(Interval a, Interval b);
Interval operator-(Interval a, Interval b);
Interval operator*(Interval a, Interval b);
Interval operator/(Interval a, Interval b);
Interval sq(Interval a);
/// x^k for a constant k (integer powers of negative numbers included).
Interval pow_const(Interval x, double k);
/// k^x for a constant k > 0.
Interval const_pow(double k, Interval x);
/// x^y for x > 0 (exp(y log x)); the whole line when x reaches 0 or below.
Interval pow(Interval x, Interval y);
Interval sin(Interval a);
Interval cos(Interval a);
Interval tan(Interval a);
Interval asin(Interval a);
Interval acos(Interval a);
Interval atan(Interval a);
/// The angle of (x, y); [-pi, pi] when the box meets the branch cut (y = 0, x <= 0).
Interval atan2(Interval y, Interval x);
Interval sqrt(Interval a);
Interval exp(Interval a);
Interval log(Interval a);
Interval abs(Interval a);
Interval min(Interval a, Interval b);
Interval max(Interval a, Interval b);

}  // namespace sweep
