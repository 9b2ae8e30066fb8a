#pragma once
// Where the sweep of a grazing curve crosses the face the curve lies on. The swept face
// E(s, t) = M(t) c(s) touches that face's copy at t* (the start or the end of the range) along the
// curve itself: the distance d of E(s, t) from the copy's surface vanishes to second order in
// t - t*, which is where OCCT's section of the two faces stalls or strays (its curves leave the
// touching curve 1e-4 away from where they should). Divided by (t - t*)^2 the distance becomes a
// function whose zero set is regular: the crossing curves, starting on the touching curve where
// the swept face goes from one side of the copy to the other.
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <optional>
#include <vector>

#include "sweep/motion.hpp"

namespace sweep::occt {

/// The sweep of a grazing curve c over [first, last] (at the pose of t = 0) by joint j over [0, T],
/// and the body's surface it lies on.
struct TouchingSweep {
  Handle(Geom_Curve) curve;
  double first = 0, last = 0;
  ScrewJoint joint;
  double T = 0;
  Handle(Geom_Surface) surface;  ///< the body face's surface, without its location
  std::vector<double> breaks;    ///< the times between 0 and T where the sweep's faces meet
};

/// The curves where the sweep crosses `copy` (a face on the sweep's surface carried to the pose of
/// t_touch, 0 or T) at t != t_touch, cut to the copy face and at the sweep's breaks (so that each
/// lies on one of the sweep's faces) and fitted to within `tol` (*fit_err: the
/// largest distance measured from the crossing). Nothing when a fit does not reach `tol`; the caller
/// then intersects the faces otherwise.
std::optional<std::vector<TopoDS_Edge>> touching_section(const TouchingSweep& sweep, double t_touch,
                                                         const TopoDS_Face& copy, double tol, double size,
                                                         double* fit_err);

/// The curves where face `a` crosses face `b`, a face on a torus (whose distance is exact): the zero
/// set of b's distance over a's parameters, cut to both faces and fitted to within `tol`
/// (*fit_err: the largest distance measured). Nothing when b is no torus or a fit does not reach
/// `tol`; the caller then intersects the faces otherwise. (OCCT's section of two tori walks for
/// seconds.)
std::optional<std::vector<TopoDS_Edge>> torus_section(const TopoDS_Face& a, const TopoDS_Face& b, double tol,
                                                      double size, double* fit_err);

/// The same for a B-spline face `a` (a fitted sweep) crossing `b`, a face on a plane, cylinder,
/// cone, sphere or torus, none of whose sides lies on b's surface (there the distance vanishes
/// along the side). Nothing otherwise, or when a fit does not reach `tol`. (OCCT's section of a
/// helical sweep with a copy of the body took 0.2 s a pair.)
std::optional<std::vector<TopoDS_Edge>> spline_section(const TopoDS_Face& a, const TopoDS_Face& b, double tol,
                                                       double size, double* fit_err);

}  // namespace sweep::occt
