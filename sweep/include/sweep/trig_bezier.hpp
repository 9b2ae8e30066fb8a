#pragma once
// cos q and sin q over a range of q as polynomials: the rotation part of a screw's helices in a
// Bezier form, so that a curve carried along a screw is a tensor-product spline whose poles are the
// curve's own poles carried along polynomial helices. The ends are exact, so that pieces of
// consecutive ranges meet where the screw puts them.
#include <vector>

namespace sweep {

/// cos q and sin q for q in [q0, q1] as Bezier polynomials of one degree in t = (q - q0) / (q1 - q0):
/// `cos[k]` and `sin[k]` are the coefficients of the Bernstein polynomials B_k^n(t), n = cos.size() - 1.
struct TrigBezier {
  std::vector<double> cos, sin;
  /// The largest distance of (cos(t), sin(t)) from (cos q, sin q), measured on a grid 16 times finer
  /// than the degree's (a unit radius strays that far; a radius r, r times that).
  double error = 0;
};

/// The lowest degree from 3 to `max_degree` whose least-squares fit (ends exact) keeps the measured
/// error within `max_error`, or the highest degree's fit when none does. @throws InternalError when
/// q1 <= q0 or the range exceeds a half turn.
TrigBezier trig_bezier(double q0, double q1, double max_error, int max_degree = 15);

/// The Bezier polynomial with coefficients `b` at t in [0, 1] (de Casteljau).
double bezier_value(const std::vector<double>& b, double t);

}  // namespace sweep
