// Least-squares B-splines of uniform knots and the half balls that close tubes (tube_fit.hpp).
#include "varieties/tube_fit.hpp"

#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <cmath>

#include "base/internal.hpp"

namespace sweep::occt {
namespace {


/// Values of the p+1 non-zero B-spline basis functions at x (span index `span`, The NURBS Book A2.2).
void basis_funs(int span, double x, int p, const std::vector<double>& U, double* N) {
  std::vector<double> left(p + 1), right(p + 1);
  N[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = x - U[span + 1 - j];
    right[j] = U[span + j] - x;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const double tmp = N[r] / (right[r + 1] + left[j - r]);
      N[r] = saved + right[r + 1] * tmp;
      saved = left[j - r] * tmp;
    }
    N[j] = saved;
  }
}

/// The clamped uniform knot vector's span containing x (last span for x at the end).
int find_span(double x, int p, int npoles, const std::vector<double>& U) {
  if (x >= U[npoles]) return npoles - 1;
  int lo = p, hi = npoles;
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (x < U[mid] ? hi : lo) = mid;
  }
  return lo;
}

}  // namespace

Fit fit_bspline(const std::function<Eigen::RowVectorXd(double)>& f, int D, double L, int p, int spans, int mult) {
  Fit out;
  const int np = p + 1 + (spans - 1) * mult;
  std::vector<double> U;
  for (int i = 0; i <= p; ++i) U.push_back(0.0);
  for (int i = 1; i < spans; ++i)
    for (int k = 0; k < mult; ++k) U.push_back(L * i / spans);
  for (int i = 0; i <= p; ++i) U.push_back(L);
  out.knots.push_back(0.0);
  out.mults.push_back(p + 1);
  for (int i = 1; i < spans; ++i) {
    out.knots.push_back(L * i / spans);
    out.mults.push_back(mult);
  }
  out.knots.push_back(L);
  out.mults.push_back(p + 1);
  const int m = 4 * np + 8 * spans;  // samples, both ends included
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, np - 2);
  Eigen::MatrixXd Y(m, D);
  const Eigen::RowVectorXd first = f(0.0), last = f(L);
  std::vector<double> N(p + 1);
  for (int s = 0; s < m; ++s) {
    const double x = L * s / (m - 1);
    const int span = find_span(x, p, np, U);
    basis_funs(span, x, p, U, N.data());
    double n0 = 0, n1 = 0;
    for (int r = 0; r <= p; ++r) {
      const int i = span - p + r;
      if (i == 0) n0 = N[r];
      else if (i == np - 1) n1 = N[r];
      else A(s, i - 1) = N[r];
    }
    Y.row(s) = f(x) - n0 * first - n1 * last;
  }
  out.poles.resize(np, D);
  out.poles.row(0) = first;
  out.poles.row(np - 1) = last;
  out.poles.middleRows(1, np - 2) = A.colPivHouseholderQr().solve(Y);
  // error between the samples (8 points per span)
  const int ne = 8 * spans;
  for (int s = 0; s < ne; ++s) {
    const double x = L * (s + 0.5) / ne;
    const int span = find_span(x, p, np, U);
    basis_funs(span, x, p, U, N.data());
    Eigen::RowVectorXd v = Eigen::RowVectorXd::Zero(D);
    for (int r = 0; r <= p; ++r) v += out.poles.row(span - p + r) * N[r];
    const Eigen::RowVectorXd d = v - f(x);
    for (int g = 0; g + 3 <= D; g += 3) out.error = std::max(out.error, d.segment<3>(g).norm());
  }
  return out;
}

void knots_of(const Fit& fit, TColStd_Array1OfReal& knots, TColStd_Array1OfInteger& mults) {
  for (int i = 0; i < int(fit.knots.size()); ++i) {
    knots.SetValue(i + 1, fit.knots[i]);
    mults.SetValue(i + 1, fit.mults[i]);
  }
}

/// Half of a ball (centre c, radius r, pole in direction t) bounded by the closed curve `rim`
/// (points c + r C(v) with C a fitted unit circle perpendicular to t, its poles given): the
/// surface c + r (x(u) C(v) + z(u) t), with (x, z) the exact rational quarter circle from the rim
/// (u = 0) to the pole (u = pi / 2). Its first row is the rim itself.
Handle(Geom_BSplineSurface) half_ball(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& t,
                                     const std::vector<Eigen::Vector3d>& rim, const Fit& circle, int p) {
  const int nc = int(rim.size());
  // rows: rim, its corner above (weight 1/sqrt 2), the pole
  const std::vector<double> weight{1.0, std::sqrt(0.5), 1.0};
  const int rows = int(weight.size());
  TColgp_Array2OfPnt P(1, rows, 1, nc);
  TColStd_Array2OfReal W(1, rows, 1, nc);
  for (int l = 0; l < rows; ++l)
    for (int k = 0; k < nc; ++k) {
      P.SetValue(l + 1, k + 1, to_pnt(l == 0 ? rim[k] : l == 1 ? Eigen::Vector3d(rim[k] + r * t) : Eigen::Vector3d(c + r * t)));
      W.SetValue(l + 1, k + 1, weight[l]);
    }
  TColStd_Array1OfReal uk(1, 2), vk(1, int(circle.knots.size()));
  TColStd_Array1OfInteger um(1, 2), vm(1, int(circle.knots.size()));
  uk.SetValue(1, 0.0);
  uk.SetValue(2, M_PI / 2);
  um.Init(3);
  knots_of(circle, vk, vm);
  return new Geom_BSplineSurface(P, W, uk, vk, um, vm, 2, p);
}

Fit fit_unit_circle(int p, double tol) {
  Fit circle;
  for (int spans = 4; spans <= 256; spans += std::max(1, spans / 4)) {
    circle = fit_bspline([](double a) { return Eigen::RowVector3d(std::cos(a), std::sin(a), 0.0); }, 3, 2 * M_PI,
                         p, spans, 1);
    if (circle.error <= tol) break;
  }
  return circle;
}

}  // namespace sweep::occt
