// The planar region swept by a curve lying in a plane the motion keeps (a plane perpendicular to
// a rotation axis, or a plane containing a translation direction). Its boundary lies on the curve
// at both range ends and on the paths of the curve's end points and of its grazing points (where
// the velocity is tangent to the curve); the plane is split by those edges and each piece kept when
// a point inside it is swept (its backward trajectory meets the curve).
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <ElSLib.hxx>
#include <algorithm>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <Bnd_Box.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Plane.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <cmath>

#include "base/internal.hpp"
#include "base/stop.hpp"
#include "sweep/error.hpp"

namespace sweep::occt {

TopoDS_Edge path_edge(const Eigen::Vector3d& x, const ScrewJoint& j, double q0, double T, double min_radius) {
  if (j.type == JointType::Prismatic)
    return BRepBuilderAPI_MakeEdge(to_pnt(x + q0 * j.direction), to_pnt(x + (q0 + T) * j.direction)).Edge();
  Eigen::Vector3d foot = j.point + j.direction * j.direction.dot(x - j.point);
  double r = (x - foot).norm();
  if (r < min_radius) return TopoDS_Edge();
  gp_Ax2 ax(to_pnt(foot), gp_Dir(to_vec(j.direction)), gp_Dir(to_vec((x - foot) / r)));
  Handle(Geom_Circle) c = new Geom_Circle(ax, r);
  return BRepBuilderAPI_MakeEdge(c, q0, q0 + T).Edge();
}

bool keeps_plane_of(const Handle(Geom_Curve)& c, double first, double last, const ScrewJoint& j, double size,
                    gp_Pln* plane) {
  if (j.type == JointType::Helical && std::abs(j.pitch) > 0) return false;
  const int n = 32;
  std::vector<Eigen::Vector3d> p(n + 1);
  for (int k = 0; k <= n; ++k) p[k] = to_eigen(c->Value(first + (last - first) * k / n));
  const double eps = 1e-10 * size;
  if (j.is_rotation()) {
    const double a0 = j.direction.dot(p[0]);
    for (const auto& q : p)
      if (std::abs(j.direction.dot(q) - a0) > eps) return false;
    *plane = gp_Pln(to_pnt(p[0]), gp_Dir(to_vec(j.direction)));
    return true;
  }
  // translation: the plane through the curve containing the direction
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (const auto& q : p) {
    Eigen::Vector3d cand = (q - p[0]).cross(j.direction);
    if (cand.norm() > normal.norm()) normal = cand;
  }
  if (normal.norm() < eps) return false;
  normal.normalize();
  for (const auto& q : p)
    if (std::abs(normal.dot(q - p[0])) > eps) return false;
  *plane = gp_Pln(to_pnt(p[0]), gp_Dir(to_vec(normal)));
  return true;
}

std::vector<TopoDS_Face> planar_curve_sweep(const Handle(Geom_Curve)& c, double first, double last,
                                            const ScrewJoint& j, double T, const gp_Pln& plane, double size) {
  // Grazing points: velocity parallel to the tangent, (v x c') . n = 0 in the plane.
  const Eigen::Vector3d n = to_eigen(gp_Vec(plane.Axis().Direction()));
  auto g = [&](double s) {
    gp_Pnt p;
    gp_Vec d;
    c->D1(s, p, d);
    return j.velocity(to_eigen(p)).cross(to_eigen(d)).dot(n);
  };
  std::vector<double> special{first, last};
  const int m = 256;
  double prev = g(first);
  for (int k = 1; k <= m; ++k) {
    double a = first + (last - first) * (k - 1) / m, b = first + (last - first) * k / m, gb = g(b);
    if ((prev > 0) != (gb > 0)) {
      double fa = prev;
      for (int it = 0; it < 80; ++it) {
        double mid = 0.5 * (a + b), fm = g(mid);
        if ((fm > 0) == (fa > 0)) { a = mid; fa = fm; } else b = mid;
      }
      special.push_back(0.5 * (a + b));
    }
    prev = gb;
  }
  TopoDS_Edge e0 = BRepBuilderAPI_MakeEdge(c, first, last).Edge();
  TopoDS_Edge e1 = TopoDS::Edge(BRepBuilderAPI_Transform(e0, to_trsf(j.transform(T)), true).Shape());
  TopTools_ListOfShape tools;
  tools.Append(e0);
  tools.Append(e1);
  for (double s : special) {
    TopoDS_Edge pe = path_edge(to_eigen(c->Value(s)), j, 0.0, T, 1e-12 * size);
    if (!pe.IsNull()) tools.Append(pe);
  }
  // A square of the plane around everything, split by the candidate edges.
  Bnd_Box box;
  for (TopTools_ListOfShape::Iterator it(tools); it.More(); it.Next()) BRepBndLib::Add(it.Value(), box);
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  const double half = std::max({x1 - x0, y1 - y0, z1 - z0}) + 0.1 * size;
  Handle(Geom_Plane) gpl = new Geom_Plane(plane);
  double cu, cv;
  ElSLib::Parameters(plane, gp_Pnt(0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1)), cu, cv);
  TopoDS_Face big = BRepBuilderAPI_MakeFace(gpl, cu - half, cu + half, cv - half, cv + half, 1e-7).Face();
  const TopoDS_Shape split = split_by_edges(big, tools, Settings::resolution * size, SplitMode::Parallel);
  if (split.IsNull()) throw ComputeError("could not split the plane of a planar sweep");

  TopoDS_Compound kept;
  BRep_Builder bb;
  bb.MakeCompound(kept);
  int nkept = 0;
  for (TopExp_Explorer ex(split, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& f = TopoDS::Face(ex.Current());
    double u0, u1, v0, v1;
    BRepTools::UVBounds(f, u0, u1, v0, v1);
    const double margin = Settings::resolution * size;
    if (u0 < cu - half + margin || u1 > cu + half - margin || v0 < cv - half + margin || v1 > cv + half - margin)
      continue;  // touches the outer square: outside
    BRepTopAdaptor_FClass2d fc(f, 1e-9);
    BRepAdaptor_Surface S(f);
    bool found = false, inside = false;
    for (int a = 1; a < 8 && !found; ++a)
      for (int b = 1; b < 8 && !found; ++b) {
        gp_Pnt2d uv(u0 + (u1 - u0) * (a + 0.1) / 8.2, v0 + (v1 - v0) * (b + 0.17) / 8.34);
        if (fc.Perform(uv) != TopAbs_IN) continue;
        found = true;
        // backward trajectory of the point meets the curve?
        Eigen::Vector3d x = to_eigen(S.Value(uv.X(), uv.Y()));
        TopoDS_Edge traj = path_edge(j.transform(-T) * x, j, 0.0, T, 1e-12 * size);
        if (traj.IsNull()) {
          BRepExtrema_DistShapeShape d(BRepBuilderAPI_MakeVertex(to_pnt(x)).Vertex(), e0);
          inside = d.IsDone() && d.Value() < Settings::resolution * size;
        } else {
          BRepExtrema_DistShapeShape d(traj, e0);
          inside = d.IsDone() && d.Value() < Settings::resolution * size;
        }
      }
    if (found && inside) {
      bb.Add(kept, f);
      ++nkept;
    }
  }
  std::vector<TopoDS_Face> out;
  if (nkept == 0) return out;
  ShapeUpgrade_UnifySameDomain unify(kept, true, true, true);
  unify.Build();
  for (TopExp_Explorer ex(unify.Shape(), TopAbs_FACE); ex.More(); ex.Next()) out.push_back(TopoDS::Face(ex.Current()));
  return out;
}

}  // namespace sweep::occt
