// Pieces of the tubes that balls sweep: B-splines of uniform knots fitted by least squares with
// their end poles exact, and the half ball that closes a tube on one of its end rows.
#pragma once

#include <Eigen/Dense>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <functional>
#include <vector>

namespace sweep::occt {

/// A clamped B-spline of degree p with `spans` uniform spans on [0, L] (interior knots of
/// multiplicity `mult`), fitted by least squares to samples of f (a row of D values), its end
/// poles the exact end values.
struct Fit {
  std::vector<double> knots;  ///< distinct knots
  std::vector<int> mults;     ///< their multiplicities
  Eigen::MatrixXd poles;      ///< one row per pole
  double error = 0;           ///< largest distance measured (per group of three values)
};
Fit fit_bspline(const std::function<Eigen::RowVectorXd(double)>& f, int D, double L, int p, int spans, int mult);

/// The fit's knots and multiplicities as OCCT arrays (sized to the distinct knots).
void knots_of(const Fit& fit, TColStd_Array1OfReal& knots, TColStd_Array1OfInteger& mults);

/// The unit circle (cos a, sin a, 0) over [0, 2 pi] fitted at degree p within `tol`; its error
/// above tol when no fit of up to 256 spans reaches it.
Fit fit_unit_circle(int p, double tol);

/// Half of a ball (centre c, radius r, pole in direction t) bounded by the closed curve `rim`
/// (points c + r C(v) with C a fitted unit circle perpendicular to t, its poles given): the
/// surface c + r (x(u) C(v) + z(u) t), with (x, z) the exact rational quarter circle from the rim
/// (u = 0) to the pole (u = pi / 2). Its first row is the rim itself.
Handle(Geom_BSplineSurface) half_ball(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& t,
                                     const std::vector<Eigen::Vector3d>& rim, const Fit& circle, int p);

}  // namespace sweep::occt
