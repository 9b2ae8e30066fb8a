// A ball translated along a line: a capsule, the cylinder of the centre's segment closed by two
// half balls, all exact (the revolve of its half profile about the segment).
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Ax1.hxx>

#include "base/internal.hpp"

namespace sweep::occt {

TopoDS_Shape ball_line_sweep(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& d, double length,
                             std::vector<TopoDS_Face>* faces, std::vector<int>* roles) {
  if (!(r > 0) || !(length > 0) || !(d.norm() > 0)) return {};
  const Eigen::Vector3d u = d.normalized();
  // a unit vector across the segment: the half profile lies in the plane of u and e
  const Eigen::Vector3d e = u.unitOrthogonal();
  const Eigen::Vector3d c1 = c + length * u;
  const gp_Pnt south = to_pnt(c - r * u), north = to_pnt(c1 + r * u);
  const gp_Pnt rim0 = to_pnt(c + r * e), rim1 = to_pnt(c1 + r * e);
  const gp_Pnt mid0 = to_pnt(c + r * (e - u).normalized()), mid1 = to_pnt(c1 + r * (e + u).normalized());
  BRepBuilderAPI_MakeWire wire;
  wire.Add(BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(south, mid0, rim0).Value()).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(rim0, rim1).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(GC_MakeArcOfCircle(rim1, mid1, north).Value()).Edge());
  wire.Add(BRepBuilderAPI_MakeEdge(north, south).Edge());
  if (!wire.IsDone()) return {};
  BRepBuilderAPI_MakeFace profile(wire.Wire(), true);
  if (!profile.IsDone()) return {};
  BRepPrimAPI_MakeRevol revol(profile.Face(), gp_Ax1(to_pnt(c), gp_Dir(u.x(), u.y(), u.z())), 2 * M_PI);
  if (!revol.IsDone()) return {};
  const TopoDS_Shape solid = revol.Shape();
  faces->clear();
  roles->clear();
  for (TopExp_Explorer x(solid, TopAbs_FACE); x.More(); x.Next()) {
    const TopoDS_Face f = TopoDS::Face(x.Current());
    BRepAdaptor_Surface s(f);
    faces->push_back(f);
    if (s.GetType() != GeomAbs_Sphere) roles->push_back(0);
    else roles->push_back((to_eigen(s.Sphere().Location()) - c).norm() < 0.5 * length ? 1 : 2);
  }
  return solid;
}

}  // namespace sweep::occt
