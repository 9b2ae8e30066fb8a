// cos and sin over a range as Bezier polynomials (trig_bezier.hpp): least squares at Chebyshev nodes
// over the interior coefficients, the two end coefficients fixed at the exact values.
#include "sweep/trig_bezier.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "sweep/error.hpp"

namespace sweep {
namespace {

/// The Bernstein polynomials of degree n at t.
Eigen::VectorXd bernstein(int n, double t) {
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n + 1);
  b(0) = 1;
  for (int d = 1; d <= n; ++d)
    for (int k = d; k >= 0; --k) b(k) = (k < d ? (1 - t) * b(k) : 0.0) + (k > 0 ? t * b(k - 1) : 0.0);
  return b;
}

/// The fit of one degree, and its measured error.
TrigBezier fit_of_degree(double q0, double q1, int n) {
  const int m = 3 * n + 1;  // Chebyshev nodes in (0, 1)
  Eigen::MatrixXd A(m, n - 1);
  Eigen::MatrixXd rhs(m, 2);
  const double c0 = std::cos(q0), s0 = std::sin(q0), c1 = std::cos(q1), s1 = std::sin(q1);
  for (int i = 0; i < m; ++i) {
    const double t = 0.5 - 0.5 * std::cos(M_PI * (i + 0.5) / m);
    const Eigen::VectorXd b = bernstein(n, t);
    A.row(i) = b.segment(1, n - 1).transpose();
    const double q = q0 + (q1 - q0) * t;
    rhs(i, 0) = std::cos(q) - b(0) * c0 - b(n) * c1;
    rhs(i, 1) = std::sin(q) - b(0) * s0 - b(n) * s1;
  }
  const Eigen::MatrixXd inner = A.colPivHouseholderQr().solve(rhs);
  TrigBezier f;
  f.cos.assign(n + 1, 0.0);
  f.sin.assign(n + 1, 0.0);
  f.cos.front() = c0, f.cos.back() = c1, f.sin.front() = s0, f.sin.back() = s1;
  for (int k = 1; k < n; ++k) f.cos[k] = inner(k - 1, 0), f.sin[k] = inner(k - 1, 1);
  const int samples = 16 * n;
  for (int i = 0; i <= samples; ++i) {
    const double t = double(i) / samples, q = q0 + (q1 - q0) * t;
    f.error = std::max(f.error, std::hypot(bezier_value(f.cos, t) - std::cos(q), bezier_value(f.sin, t) - std::sin(q)));
  }
  return f;
}

}  // namespace

double bezier_value(const std::vector<double>& b, double t) {
  std::vector<double> w = b;
  for (std::size_t d = w.size(); d-- > 1;)
    for (std::size_t k = 0; k < d; ++k) w[k] = (1 - t) * w[k] + t * w[k + 1];
  return w.empty() ? 0.0 : w[0];
}

TrigBezier trig_bezier(double q0, double q1, double max_error, int max_degree) {
  if (!(q1 > q0) || q1 - q0 > M_PI + 1e-12) throw InternalError("trig_bezier: the range must be increasing and at most a half turn");
  TrigBezier best;
  for (int n = 3; n <= std::max(3, max_degree); ++n) {
    best = fit_of_degree(q0, q1, n);
    if (best.error <= max_error) break;
  }
  return best;
}

}  // namespace sweep
