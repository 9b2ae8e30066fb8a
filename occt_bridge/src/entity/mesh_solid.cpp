// A triangle mesh as a polyhedral OCCT solid (see mesh_solid.hpp).
#include "entity/mesh_solid.hpp"

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <Poly_Triangulation.hxx>
#include <RWStl.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <algorithm>
#include <fstream>

#include "base/internal.hpp"
#include "sweep/error.hpp"
#include "sweep/settings.hpp"
#include "sweep/triangle_mesh.hpp"

namespace sweep::occt {
namespace {

const char* const kPointer = "/entity/file";

TriangleMesh read_mesh(const std::string& path) {
  if (file_extension(path) == "off") {
    std::ifstream in(path);
    if (!in) throw InputError(kPointer, "cannot read '" + path + "'");
    return read_off(in, kPointer);
  }
  const Handle(Poly_Triangulation) t = RWStl::ReadFile(path.c_str());
  if (t.IsNull() || t->NbTriangles() == 0) throw InputError(kPointer, "'" + path + "' is not a readable STL file");
  TriangleMesh m;
  for (int k = 1; k <= t->NbNodes(); ++k) m.vertices.push_back(to_eigen(t->Node(k)));
  for (int k = 1; k <= t->NbTriangles(); ++k) {
    int a, b, c;
    t->Triangle(k).Get(a, b, c);
    m.triangles.push_back({a - 1, b - 1, c - 1});
  }
  return m;
}

}  // namespace

TopoDS_Shape mesh_solid(const EntitySpec& e) {
  TriangleMesh mesh = merged_vertices(read_mesh(e.file), Settings::mesh_vertex_merge);
  for (auto& p : mesh.vertices) p *= e.scale;
  check_closed_oriented(mesh, kPointer);
  check_not_crossing_itself(mesh, kPointer);
  if (signed_volume(mesh) < 0)
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  const double size = bounding_box(mesh).sizes().maxCoeff();
  // one planar face per triangle, sewn along the shared edges (exactly shared: no gap to close)
  BRepBuilderAPI_Sewing sewing(Settings::resolution * size);
  for (const auto& t : mesh.triangles) {
    BRepBuilderAPI_MakePolygon poly(to_pnt(mesh.vertices[t[0]]), to_pnt(mesh.vertices[t[1]]),
                                    to_pnt(mesh.vertices[t[2]]), true);
    BRepBuilderAPI_MakeFace face(poly.Wire(), true);
    if (!face.IsDone()) throw ComputeError("a triangle of the mesh makes no planar face");
    sewing.Add(face.Face());
  }
  sewing.Perform();
  TopExp_Explorer shells(sewing.SewedShape(), TopAbs_SHELL);
  if (!shells.More()) throw ComputeError("the mesh's triangles do not sew into a shell");
  const TopoDS_Shell shell = TopoDS::Shell(shells.Current());
  shells.Next();
  if (shells.More()) throw InputError(kPointer, "the mesh is made of more than one closed surface");
  BRepBuilderAPI_MakeSolid make(shell);
  if (!make.IsDone()) throw ComputeError("the mesh's shell makes no solid");
  // coplanar neighbours as one face, collinear edges as one
  ShapeUpgrade_UnifySameDomain unify(make.Solid(), true, true, false);
  unify.SetLinearTolerance(Settings::resolution * size);
  unify.SetAngularTolerance(Settings::mesh_coplanar_angle);
  unify.Build();
  TopoDS_Shape solid = unify.Shape();
  GProp_GProps g;
  BRepGProp::VolumeProperties(solid, g);
  if (g.Mass() < 0) solid.Reverse();
  if (!BRepCheck_Analyzer(solid).IsValid()) throw ComputeError("the mesh's faces make no valid solid");
  return solid;
}

}  // namespace sweep::occt
