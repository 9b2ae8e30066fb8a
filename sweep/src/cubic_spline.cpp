#include "cubic_spline.hpp"

#include <algorithm>
#include <cmath>

namespace sweep::detail {

using Eigen::Vector2d;

namespace {

/// Solves a[i] m[i-1] + b[i] m[i] + c[i] m[i+1] = d[i] (a[0] and c[n-1] unused), diagonally
/// dominant after the first row, by elimination.
std::vector<Vector2d> tridiagonal(std::vector<double> a, std::vector<double> b, std::vector<double> c,
                                  std::vector<Vector2d> d) {
  const std::size_t n = b.size();
  for (std::size_t i = 1; i < n; ++i) {
    const double w = a[i] / b[i - 1];
    b[i] -= w * c[i - 1];
    d[i] -= w * d[i - 1];
  }
  std::vector<Vector2d> m(n);
  m[n - 1] = d[n - 1] / b[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) m[i] = (d[i] - c[i] * m[i + 1]) / b[i];
  return m;
}

}  // namespace

CubicSpline2::CubicSpline2(std::vector<double> x, std::vector<Vector2d> p, bool closed)
    : x_(std::move(x)), p_(std::move(p)), closed_(closed) {
  const std::size_t n = p_.size();
  m_.assign(n, Vector2d::Zero());
  if (n < 3) return;  // a line
  if (!closed_) {
    std::vector<double> a(n, 0), b(n, 0), c(n, 0);
    std::vector<Vector2d> d(n, Vector2d::Zero());
    b[0] = 1, c[0] = -1;          // m[0] = m[1]
    a[n - 1] = -1, b[n - 1] = 1;  // m[n-1] = m[n-2]
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const double h0 = x_[i] - x_[i - 1], h1 = x_[i + 1] - x_[i];
      a[i] = h0, b[i] = 2 * (h0 + h1), c[i] = h1;
      d[i] = 6 * ((p_[i + 1] - p_[i]) / h1 - (p_[i] - p_[i - 1]) / h0);
    }
    m_ = tridiagonal(a, b, c, d);
    return;
  }
  // periodic, knots 0..n-1 with p[n-1] == p[0]: the n - 1 distinct knots' equations, cyclic, by
  // Gauss-Seidel (each diagonal is twice its row's other two entries)
  const std::size_t k = n - 1;
  auto h = [&](std::size_t i) { return x_[i + 1] - x_[i]; };  // interval i, i in [0, k)
  std::vector<Vector2d> m(k, Vector2d::Zero()), d(k);
  for (std::size_t i = 0; i < k; ++i) {
    const std::size_t prev = (i + k - 1) % k;
    d[i] = 6 * ((p_[i + 1] - p_[i]) / h(i) - (p_[i] - p_[prev]) / h(prev));
  }
  for (int sweep = 0; sweep < 200; ++sweep) {
    double change = 0;
    for (std::size_t i = 0; i < k; ++i) {
      const std::size_t prev = (i + k - 1) % k, next = (i + 1) % k;
      const Vector2d mi = (d[i] - h(prev) * m[prev] - h(i) * m[next]) / (2 * (h(prev) + h(i)));
      change = std::max(change, (mi - m[i]).cwiseAbs().maxCoeff());
      m[i] = mi;
    }
    double scale = 0;
    for (const Vector2d& v : m) scale = std::max(scale, v.cwiseAbs().maxCoeff());
    if (change <= 1e-15 * scale) break;
  }
  for (std::size_t i = 0; i < k; ++i) m_[i] = m[i];
  m_[k] = m[0];
}

double CubicSpline2::placed(double x, std::size_t& i) const {
  const std::size_t n = p_.size();
  if (closed_) {
    const double period = x_.back() - x_.front();
    x = x_.front() + std::fmod(std::fmod(x - x_.front(), period) + period, period);
  } else {
    x = std::clamp(x, x_.front(), x_.back());
  }
  i = std::size_t(std::upper_bound(x_.begin(), x_.end(), x) - x_.begin());
  i = std::clamp<std::size_t>(i, 1, n - 1) - 1;
  return x;
}

Vector2d CubicSpline2::operator()(double x) const {
  if (p_.size() == 1) return p_[0];
  std::size_t i = 0;
  x = placed(x, i);
  const double h = x_[i + 1] - x_[i], f = (x - x_[i]) / h, g = 1 - f;
  return g * p_[i] + f * p_[i + 1] + h * h / 6 * ((g * g * g - g) * m_[i] + (f * f * f - f) * m_[i + 1]);
}

Vector2d CubicSpline2::derivative(double x) const {
  if (p_.size() == 1) return Vector2d::Zero();
  std::size_t i = 0;
  x = placed(x, i);
  const double h = x_[i + 1] - x_[i], f = (x - x_[i]) / h, g = 1 - f;
  return (p_[i + 1] - p_[i]) / h + h / 6 * ((1 - 3 * g * g) * m_[i] + (3 * f * f - 1) * m_[i + 1]);
}

}  // namespace sweep::detail
