// Merging the pieces of one surface after an arrangement split them (occt_bridge/src/faces/unify.cpp).
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepAlgoAPI_Splitter.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>
#include <gp_Ax2.hxx>
#include <gp_Pln.hxx>

#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "base/internal.hpp"

namespace {

int count_faces(const TopoDS_Shape& s) {
  int n = 0;
  for (TopExp_Explorer ex(s, TopAbs_FACE); ex.More(); ex.Next()) ++n;
  return n;
}

double volume_of(const TopoDS_Shape& s) {
  GProp_GProps p;
  BRepGProp::VolumeProperties(s, p);
  return p.Mass();
}

/// A solid cut into cells by a plane and the cells fused again, as the arrangement's kept cells
/// are: the faces the plane crossed stay split into pieces of one surface.
TopoDS_Shape split_and_refused(const TopoDS_Shape& solid, const gp_Pln& plane) {
  BRepAlgoAPI_Splitter split;
  TopTools_ListOfShape args, tools;
  args.Append(solid);
  tools.Append(BRepBuilderAPI_MakeFace(plane, -10, 10, -10, 10).Face());
  split.SetArguments(args);
  split.SetTools(tools);
  split.Build();
  REQUIRE(split.IsDone());
  std::vector<TopoDS_Shape> cells;
  for (TopExp_Explorer ex(split.Shape(), TopAbs_SOLID); ex.More(); ex.Next()) cells.push_back(ex.Current());
  REQUIRE(cells.size() == 2);
  BRepAlgoAPI_Fuse fuse;
  TopTools_ListOfShape a, t;
  a.Append(cells[0]);
  t.Append(cells[1]);
  fuse.SetArguments(a);
  fuse.SetTools(t);
  fuse.SetGlue(BOPAlgo_GlueShift);
  fuse.Build();
  REQUIRE(fuse.IsDone());
  return fuse.Shape();
}

}  // namespace

TEST_CASE("Merging faces: a box cut in two and fused again is one box of six faces") {
  const TopoDS_Shape s = split_and_refused(BRepPrimAPI_MakeBox(2, 2, 3).Shape(), gp_Pln(gp_Pnt(1, 0, 0), gp_Dir(1, 0, 0)));
  REQUIRE(count_faces(s) == 10);
  const TopoDS_Shape m = sweep::occt::unify_faces(s);
  REQUIRE_FALSE(m.IsNull());
  CHECK(BRepCheck_Analyzer(m).IsValid());
  CHECK(count_faces(m) == 6);
  CHECK(volume_of(m) == Approx(12.0).epsilon(1e-12));
}

TEST_CASE("Merging faces: a cylinder cut across and along its axis gets its lateral face back") {
  const TopoDS_Shape cyl = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 1, 3).Shape();
  const TopoDS_Shape s = split_and_refused(cyl, gp_Pln(gp_Pnt(0, 0, 1), gp_Dir(0, 0, 1)));
  REQUIRE(count_faces(s) == 4);
  const TopoDS_Shape m = sweep::occt::unify_faces(s);
  REQUIRE_FALSE(m.IsNull());
  CHECK(BRepCheck_Analyzer(m).IsValid());
  CHECK(count_faces(m) == 3);
  CHECK(volume_of(m) == Approx(3 * M_PI).epsilon(1e-9));
  // Cut along the axis, joining the two half-cylinder pieces would close the surface around
  // without a seam: whatever merges, the result stays valid and keeps its volume.
  const TopoDS_Shape along = split_and_refused(cyl, gp_Pln(gp_Pnt(0, 0, 0), gp_Dir(1, 0, 0)));
  const TopoDS_Shape m2 = sweep::occt::unify_faces(along);
  const TopoDS_Shape out = m2.IsNull() ? along : m2;
  CHECK(BRepCheck_Analyzer(out).IsValid());
  CHECK(volume_of(out) == Approx(3 * M_PI).epsilon(1e-9));
}

TEST_CASE("Merging faces: nothing to merge gives a null shape, the caller keeps its own") {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(1, 1, 1).Shape();
  CHECK(sweep::occt::unify_faces(box).IsNull());
}
