#pragma once
// Section curves refitted onto both surfaces. OCCT approximates the curve where two faces cross
// and reports how far the approximation strays (the edge's tolerance); for some pairs (a cone and
// a surface of revolution of a spline) that is far above the requested tolerance. The refit puts
// points on the true intersection of the two surfaces and fits a B-spline through them.
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include <BRepAdaptor_Surface.hxx>
#include <gp_Pnt.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec.hxx>
#include <optional>

namespace sweep::occt {

/// The point where surfaces A and B cross in the plane through p normal to t, by Newton from
/// parameters uva on A and uvb on B (to 1e-3 tol); nothing when it does not converge.
std::optional<gp_Pnt> point_on_both(const BRepAdaptor_Surface& A, const BRepAdaptor_Surface& B, const gp_Pnt& p,
                                    const gp_Vec& t, gp_Pnt2d uva, gp_Pnt2d uvb, double tol);

/// Section edge e of faces a and b (with curves on both) with its curve refitted to within `tol`
/// of both surfaces when its tolerance exceeds `above`; e itself when that is not needed or the
/// refit does not converge. *err receives the refitted curve's largest distance from the true
/// intersection (0 when e is returned).
TopoDS_Edge refitted_section_edge(const TopoDS_Edge& e, const TopoDS_Face& a, const TopoDS_Face& b, double tol,
                                  double above, double* err);

}  // namespace sweep::occt
