// The solid built from the split faces of an arrangement that separate a set from its complement.
#include <BOPAlgo_Builder.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRep_Tool.hxx>
#include <ShapeFix_Solid.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_ListIteratorOfListOfShape.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <GProp_GProps.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <catch2/catch.hpp>

#include "arrangement/hole_fill.hpp"
#include "base/internal.hpp"

namespace {

using Pred = sweep::occt::PointTest;

/// The same test for every thread.
sweep::occt::PointTestMaker each(const Pred& p) {
  return [p] { return p; };
}

bool in_box(const Eigen::Vector3d& x, double lo, double hi) {
  return (x.array() > lo).all() && (x.array() < hi).all();
}

/// The split faces of the general fuse of the faces of boxes [lo, hi]^3.
std::vector<TopoDS_Face> split_faces(const std::vector<std::pair<double, double>>& boxes) {
  BOPAlgo_Builder gf;
  for (const auto& [lo, hi] : boxes) {
    const TopoDS_Shape b = BRepPrimAPI_MakeBox(gp_Pnt(lo, lo, lo), gp_Pnt(hi, hi, hi)).Shape();
    for (TopExp_Explorer ex(b, TopAbs_FACE); ex.More(); ex.Next()) gf.AddArgument(ex.Current());
  }
  gf.SetRunParallel(false);
  gf.Perform();
  REQUIRE_FALSE(gf.HasErrors());
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(gf.Shape(), TopAbs_FACE, faces);
  std::vector<TopoDS_Face> out;
  for (int k = 1; k <= faces.Extent(); ++k) out.push_back(TopoDS::Face(faces(k)));
  return out;
}

double volume(const TopoDS_Shape& s) {
  GProp_GProps g;
  BRepGProp::VolumeProperties(s, g);
  return g.Mass();
}

int count(const TopoDS_Shape& s, TopAbs_ShapeEnum type) {
  int n = 0;
  for (TopExp_Explorer ex(s, type); ex.More(); ex.Next()) ++n;
  return n;
}

}  // namespace

TEST_CASE("Boundary faces: the union of two overlapping boxes keeps only the faces between inside and outside") {
  const auto faces = split_faces({{0, 2}, {1, 3}});
  const Pred member = [](const Eigen::Vector3d& x) { return in_box(x, 0, 2) || in_box(x, 1, 3); };
  int kept = 0;
  const TopoDS_Shape s = sweep::occt::solid_from_boundary_faces(faces, each(member), 3, &kept);
  REQUIRE_FALSE(s.IsNull());
  CHECK(BRepCheck_Analyzer(s).IsValid());
  CHECK(count(s, TopAbs_SOLID) == 1);
  // of each box: its three faces away from the other whole, and of the three facing into it the
  // L-shaped pieces (the unit squares cut out of them lie inside the other box)
  CHECK(kept == 2 * (3 + 3));
  CHECK(volume(s) == Approx(8 + 8 - 1).epsilon(1e-12));
}

TEST_CASE("Boundary faces: a cavity becomes a hole of the solid around it, disjoint parts stay apart") {
  {
    const auto faces = split_faces({{0, 4}, {1, 2}});
    const Pred member = [](const Eigen::Vector3d& x) { return in_box(x, 0, 4) && !in_box(x, 1, 2); };
    const TopoDS_Shape s = sweep::occt::solid_from_boundary_faces(faces, each(member), 4);
    REQUIRE_FALSE(s.IsNull());
    CHECK(BRepCheck_Analyzer(s).IsValid());
    CHECK(count(s, TopAbs_SOLID) == 1);
    CHECK(count(s, TopAbs_SHELL) == 2);
    CHECK(volume(s) == Approx(64 - 1).epsilon(1e-12));
  }
  {
    const auto faces = split_faces({{0, 1}, {2, 4}});
    const Pred member = [](const Eigen::Vector3d& x) { return in_box(x, 0, 1) || in_box(x, 2, 4); };
    const TopoDS_Shape s = sweep::occt::solid_from_boundary_faces(faces, each(member), 4);
    REQUIRE_FALSE(s.IsNull());
    CHECK(count(s, TopAbs_SOLID) == 2);
    CHECK(volume(s) == Approx(1 + 8).epsilon(1e-12));
  }
  {  // a set with no boundary among the faces gives no solid
    const auto faces = split_faces({{0, 1}});
    const Pred nothing = [](const Eigen::Vector3d&) { return false; };
    CHECK(sweep::occt::solid_from_boundary_faces(faces, each(nothing), 1).IsNull());
  }
}

TEST_CASE("Sewing: a solid is oriented by the outward hint when one is given, by classification otherwise") {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), gp_Pnt(1, 2, 3)).Shape();
  std::vector<TopoDS_Face> faces;
  for (TopExp_Explorer ex(box, TopAbs_FACE); ex.More(); ex.Next()) faces.push_back(TopoDS::Face(ex.Current()));
  REQUIRE(faces.size() == 6);
  // the first face of OCCT's box is the plane x = 0 (parameters y and z at its origin), whose
  // outward direction is -x
  sweep::occt::OutwardHint hint;
  hint.face = 0;
  hint.u = 0.5;
  hint.v = 0.5;
  SECTION("no hint") {
    const TopoDS_Shape s = sweep::occt::sew_solid(faces, 1e-7);
    REQUIRE_FALSE(s.IsNull());
    CHECK(volume(s) == Approx(6).epsilon(1e-12));
  }
  SECTION("an outward hint") {
    hint.out = gp_Vec(-1, 0.2, 0);
    const TopoDS_Shape s = sweep::occt::sew_solid(faces, 1e-7, &hint);
    REQUIRE_FALSE(s.IsNull());
    CHECK(BRepCheck_Analyzer(s).IsValid());
    CHECK(volume(s) == Approx(6).epsilon(1e-12));
  }
  SECTION("a hint pointing inwards is followed: the solid comes out inside out") {
    hint.out = gp_Vec(1, 0, 0);
    const TopoDS_Shape s = sweep::occt::sew_solid(faces, 1e-7, &hint);
    REQUIRE_FALSE(s.IsNull());
    CHECK(volume(s) == Approx(-6).epsilon(1e-12));
  }
  SECTION("a hint tangent to the face is not used") {
    hint.out = gp_Vec(0, 1, 0);
    const TopoDS_Shape s = sweep::occt::sew_solid(faces, 1e-7, &hint);
    REQUIRE_FALSE(s.IsNull());
    CHECK(volume(s) == Approx(6).epsilon(1e-12));
  }
}

TEST_CASE("Hole filling: the one face whose edges are the free edges of a sewn shell closes it, sewn in turned to match its neighbours") {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(0.2, -0.1, 0.3), 1.0, 2.0, 0.5).Shape();
  std::vector<TopoDS_Face> faces;
  for (TopExp_Explorer ex(box, TopAbs_FACE); ex.More(); ex.Next()) faces.push_back(TopoDS::Face(ex.Current()));
  REQUIRE(faces.size() == 6);
  BRepBuilderAPI_Sewing sewing(1e-7);
  for (std::size_t i = 1; i < faces.size(); ++i) sewing.Add(faces[i]);
  sewing.Perform();
  // candidates: a face of another box, the missing face turned over, and a face the hole's edges
  // only partly bound
  const TopoDS_Shape other = BRepPrimAPI_MakeBox(gp_Pnt(3, 3, 3), 1.0, 2.0, 0.5).Shape();
  const TopoDS_Face away = TopoDS::Face(TopExp_Explorer(other, TopAbs_FACE).Current());
  const TopoDS_Face half = BRepBuilderAPI_MakeFace(BRep_Tool::Surface(faces[0]), 0, 0.5, 0, 0.5, 1e-7).Face();
  const std::vector<TopoDS_Face> dropped{away, TopoDS::Face(faces[0].Reversed()), half};
  const std::vector<std::size_t> fill = sweep::occt::faces_filling_holes(dropped, sewing, 1e-7);
  REQUIRE(fill == std::vector<std::size_t>{1});
  BRepBuilderAPI_Sewing closing(1e-7);
  for (std::size_t i = 1; i < faces.size(); ++i) closing.Add(faces[i]);
  closing.Add(dropped[1]);
  closing.Perform();
  CHECK(closing.NbFreeEdges() == 0);
  const TopoDS_Shape shell = closing.SewedShape();
  BRepBuilderAPI_MakeSolid ms;
  for (TopExp_Explorer ex(shell, TopAbs_SHELL); ex.More(); ex.Next()) ms.Add(TopoDS::Shell(ex.Current()));
  ShapeFix_Solid fix;
  fix.Init(ms.Solid());
  fix.Perform();
  GProp_GProps props;
  BRepGProp::VolumeProperties(fix.Solid(), props);
  CHECK(props.Mass() == Approx(1.0).epsilon(1e-9));
  CHECK(BRepCheck_Analyzer(fix.Solid()).IsValid());
  // every face runs its shared edges opposite to its neighbour's
  TopTools_IndexedDataMapOfShapeListOfShape faces_of_edge;
  TopExp::MapShapesAndAncestors(shell, TopAbs_EDGE, TopAbs_FACE, faces_of_edge);
  int same = 0;
  for (int k = 1; k <= faces_of_edge.Extent(); ++k) {
    std::vector<TopAbs_Orientation> o;
    for (TopTools_ListIteratorOfListOfShape it(faces_of_edge(k)); it.More(); it.Next())
      for (TopExp_Explorer ex(it.Value(), TopAbs_EDGE); ex.More(); ex.Next())
        if (ex.Current().IsSame(faces_of_edge.FindKey(k))) o.push_back(ex.Current().Orientation());
    if (o.size() == 2 && o[0] == o[1]) ++same;
  }
  CHECK(same == 0);
}

TEST_CASE("Left-over faces: a sliver kept across a hole of the sewn shell, a third sheet at its other edges, is found and the shell closes without it") {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(0.2, -0.1, 0.3), 1.0, 2.0, 0.5).Shape();
  std::vector<TopoDS_Face> faces;
  for (TopExp_Explorer ex(box, TopAbs_FACE); ex.More(); ex.Next()) faces.push_back(TopoDS::Face(ex.Current()));
  REQUIRE(faces.size() == 6);
  auto sewn = [](const std::vector<TopoDS_Face>& fs) {
    auto s = std::make_unique<BRepBuilderAPI_Sewing>(1e-7);
    for (const TopoDS_Face& f : fs) s->Add(f);
    s->Perform();
    return s;
  };
  SECTION("a triangle on the top face's plane with two of its edges on the box's: it and only it") {
    // (as a piece of an end copy between the two envelope sheets that leave the copy at its edges)
    const gp_Pnt a(0.2, -0.1, 0.8), b(1.2, -0.1, 0.8), c(0.2, 1.9, 0.8);
    BRepBuilderAPI_MakePolygon triangle(a, b, c, true);
    const TopoDS_Face sliver = BRepBuilderAPI_MakeFace(triangle.Wire(), true).Face();
    std::vector<TopoDS_Face> with = faces;
    with.push_back(sliver);
    const auto open = sewn(with);
    REQUIRE(open->NbFreeEdges() > 0);
    CHECK(sweep::occt::faces_left_over(with, *open, 1e-7) == std::vector<std::size_t>{6});
    const auto closed = sewn(faces);
    CHECK(closed->NbFreeEdges() == 0);
  }
  SECTION("a box without its top: no face lies across the hole") {
    const std::vector<TopoDS_Face> five(faces.begin(), faces.end() - 1);
    const auto open = sewn(five);
    REQUIRE(open->NbFreeEdges() == 4);
    CHECK(sweep::occt::faces_left_over(five, *open, 1e-7).empty());
  }
}
