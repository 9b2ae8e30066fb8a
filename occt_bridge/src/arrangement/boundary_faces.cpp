// The swept solid from the split faces of an arrangement that separate the set from its
// complement, for arrangements whose cells OCCT cannot build.
#include <BOPAlgo_BuilderSolid.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <GProp_GProps.hxx>
#include <ShapeAnalysis_Shell.hxx>
#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Iterator.hxx>

#include "base/internal.hpp"
#include "base/stop.hpp"

namespace sweep::occt {

namespace {

/// Which sides of the face are in the set: +1 the side its (oriented) normal points to, -1 the
/// other side, 0 both or neither (not a boundary piece), by a vote of points across the face.
int inside_side(const TopoDS_Face& f, const PointTest& member, double delta) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  BRepTopAdaptor_FClass2d fc(f, 1e-9);
  BRepAdaptor_Surface S(f);
  int plus = 0, minus = 0, other = 0, tested = 0;
  for (double a : {0.5, 0.37, 0.63, 0.21, 0.79, 0.09, 0.91}) {
    for (double b : {0.5, 0.41, 0.59, 0.27, 0.73, 0.13, 0.87}) {
      if (tested == 5) break;
      gp_Pnt2d uv(u0 + a * (u1 - u0), v0 + b * (v1 - v0));
      if (fc.Perform(uv) != TopAbs_IN) continue;
      BRepLProp_SLProps props(S, uv.X(), uv.Y(), 1, 1e-9);
      if (!props.IsNormalDefined()) continue;
      Eigen::Vector3d n = to_eigen(gp_Vec(props.Normal()));
      if (f.Orientation() == TopAbs_REVERSED) n = -n;
      const Eigen::Vector3d p = to_eigen(props.Value());
      const bool in_plus = member(p + delta * n), in_minus = member(p - delta * n);
      ++tested;
      if (in_plus && !in_minus) ++plus;
      else if (in_minus && !in_plus) ++minus;
      else ++other;
    }
  }
  if (plus > minus && plus > other) return 1;
  if (minus > plus && minus > other) return -1;
  return 0;
}

}  // namespace

TopoDS_Shape solid_from_boundary_faces(const std::vector<TopoDS_Face>& split, const PointTestMaker& member,
                                       double size, int* kept_out, std::vector<TopoDS_Edge>* free_edges) {
  const double delta = 1e-5 * size;
  std::vector<int> sides(split.size(), 0);
  parallel_for(split.size(), [&]() -> std::function<void(std::size_t)> {
    const PointTest test = member();
    return [&, test](std::size_t k) { sides[k] = inside_side(split[k], test, delta); };
  });
  TopTools_ListOfShape bounding;
  for (std::size_t k = 0; k < split.size(); ++k) {
    if (sides[k] == 0) continue;
    // outward: the normal points away from the set
    bounding.Append(sides[k] < 0 ? split[k] : TopoDS::Face(split[k].Reversed()));
  }
  if (kept_out) *kept_out = bounding.Extent();
  if (bounding.IsEmpty()) return {};
  if (free_edges) {
    // edges on one boundary piece only (seams and degenerate edges aside): where the pieces do
    // not close up
    free_edges->clear();
    TopoDS_Compound all;
    BRep_Builder b;
    b.MakeCompound(all);
    for (TopTools_ListIteratorOfListOfShape it(bounding); it.More(); it.Next()) b.Add(all, it.Value());
    TopTools_IndexedDataMapOfShapeListOfShape faces_of;
    TopExp::MapShapesAndUniqueAncestors(all, TopAbs_EDGE, TopAbs_FACE, faces_of);
    for (int k = 1; k <= faces_of.Extent(); ++k) {
      const TopoDS_Edge& e = TopoDS::Edge(faces_of.FindKey(k));
      const TopTools_ListOfShape& fs = faces_of(k);
      if (fs.Extent() != 1 || BRep_Tool::Degenerated(e) || BRep_Tool::IsClosed(e, TopoDS::Face(fs.First())))
        continue;
      free_edges->push_back(e);
    }
  }
  BOPAlgo_BuilderSolid bs;
  bs.SetShapes(bounding);
  bs.SetAvoidInternalShapes(true);
  bs.SetRunParallel(false);
  bs.Perform(stop_range());
  check_stop();
  // every boundary piece must end up on a shell: a solid built without some of them could look
  // valid and closed and still miss part of the set
  if (bs.HasErrors() || bs.HasWarnings()) return {};
  TopoDS_Compound comp;
  BRep_Builder bb;
  bb.MakeCompound(comp);
  int nsolids = 0;
  for (TopTools_ListIteratorOfListOfShape it(bs.Areas()); it.More(); it.Next()) {
    GProp_GProps g;
    BRepGProp::VolumeProperties(it.Value(), g);
    if (g.Mass() <= 0) return {};  // a hole shell left without its solid
    bb.Add(comp, it.Value());
    ++nsolids;
  }
  if (nsolids == 0) return {};
  TopoDS_Shape result = comp;
  if (nsolids == 1) result = TopoDS_Iterator(comp).Value();
  return result;
}

}  // namespace sweep::occt
