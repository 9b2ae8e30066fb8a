// Elliptic cylinders: sections of semi-axes a (along X turned by the twist) and b over the height.
#include "entity/elliptic_cylinder.hpp"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Plane.hxx>
#include <gp_Elips.hxx>
#include <cmath>
#include <vector>

#include "base/internal.hpp"
#include "sweep/error.hpp"

namespace sweep::occt {
namespace {

/// The ellipse of the section at height fraction u, as an OCCT ellipse (major radius first).
gp_Elips section(const EntitySpec& e, double u) {
  const Eigen::Matrix3d F = e.elliptic_frame();
  const double phi = e.twist_at(u);
  Eigen::Vector3d X = std::cos(phi) * F.col(0) + std::sin(phi) * F.col(1);
  const Eigen::Vector3d Z = F.col(2), O = e.base + u * e.height * Z;
  double major = e.a, minor = e.b;
  if (e.b > e.a) {  // OCCT's ellipse has its major radius along its X direction
    X = Z.cross(X);
    std::swap(major, minor);
  }
  return gp_Elips(gp_Ax2(to_pnt(O), gp_Dir(to_vec(Z)), gp_Dir(to_vec(X))), major, minor);
}

TopoDS_Face cap(const gp_Elips& el) {
  const TopoDS_Wire w = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(el).Edge()).Wire();
  BRepBuilderAPI_MakeFace mf(gp_Pln(el.Position()), w);
  if (!mf.IsDone()) throw ComputeError("could not build an end face of the elliptic cylinder");
  return mf.Face();
}

}  // namespace

TopoDS_Shape elliptic_cylinder_shape(const EntitySpec& e, double tol, double* fit_error) {
  const Eigen::Vector3d Z = e.elliptic_frame().col(2);
  if (!e.twist || e.twist->is_constant()) {
    BRepPrimAPI_MakePrism prism(cap(section(e, 0.0)), to_vec(Z * e.height));
    if (!prism.IsDone()) throw ComputeError("could not extrude the elliptic cylinder");
    return prism.Shape();
  }
  const Eigen::Matrix3d F = e.elliptic_frame();
  const auto exact = [&](double fs, double fu) {
    const double s = 2 * M_PI * fs, phi = e.twist_at(fu);
    const Eigen::Vector3d X = std::cos(phi) * F.col(0) + std::sin(phi) * F.col(1), Y = Z.cross(X);
    return to_pnt(e.base + fu * e.height * Z + e.a * std::cos(s) * X + e.b * std::sin(s) * Y);
  };
  double err = 0;
  const Handle(Geom_BSplineSurface) side = fit_grid_surface(exact, tol, 0.1 * tol, 16, 256, &err);
  if (side.IsNull()) throw ComputeError("could not fit the side of the twisted elliptic cylinder");
  *fit_error = std::max(*fit_error, err);
  const std::vector<TopoDS_Face> faces{BRepBuilderAPI_MakeFace(side, 1e-7 * tol).Face(), cap(section(e, 0.0)),
                                       cap(section(e, 1.0))};
  const TopoDS_Shape solid = sew_solid(faces, std::max(4 * err, 1e-9 * (e.a + e.b + e.height)));
  if (solid.IsNull()) throw ComputeError("the side and ends of the twisted elliptic cylinder do not close");
  return solid;
}

}  // namespace sweep::occt
