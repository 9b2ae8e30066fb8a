#pragma once
// Interpolating cubic splines of points in the plane, twice continuously differentiable: what the
// envelope sheets interpolate their exact points with (a kink in the second derivative of a
// sheet's parametrization costs a fitted B-spline many knots).
#include <Eigen/Core>
#include <vector>

namespace sweep::detail {

class CubicSpline2 {
 public:
  CubicSpline2() = default;
  /// Through p[i] at increasing knots x[i]. Open: each end interval is a parabola (the second
  /// derivative is the same at the two knots of an end interval); closed: periodic with period
  /// x.back() - x.front(), p.back() being p.front() again.
  CubicSpline2(std::vector<double> x, std::vector<Eigen::Vector2d> p, bool closed);
  /// The spline at x (clamped to the knots' range when open, taken modulo the period when closed).
  Eigen::Vector2d operator()(double x) const;
  /// Its derivative at x (the same clamping).
  Eigen::Vector2d derivative(double x) const;

 private:
  /// x moved into the knots' range, and the interval [x_[i], x_[i+1]] it falls in.
  double placed(double x, std::size_t& i) const;
  std::vector<double> x_;
  std::vector<Eigen::Vector2d> p_, m_;  // points and second derivatives at the knots
  bool closed_ = false;
};

}  // namespace sweep::detail
