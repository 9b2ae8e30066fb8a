// Merging the pieces of one surface that an arrangement split into one face each.
//
// The arrangement splits every candidate face where other faces cross it; the cells kept share
// the pieces' surfaces exactly (the same Geom_Surface), so neighbouring pieces of one surface can
// be joined by dropping the edges between them and chaining the rest into wires. This is a bounded
// walk over faces and edges (no iteration that can stall, as OCCT's ShapeUpgrade_UnifySameDomain
// does on some spline-bounded arrangements); a group whose merged face is not valid stays split.
#include <BRepCheck_Analyzer.hxx>
#include <BRepTools_ReShape.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Surface.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Wire.hxx>

#include <map>
#include <numeric>
#include <vector>

#include "base/internal.hpp"

namespace sweep::occt {
namespace {

bool solids_valid(const TopoDS_Shape& sh) {
  for (TopExp_Explorer ex(sh, TopAbs_SOLID); ex.More(); ex.Next())
    if (!BRepCheck_Analyzer(ex.Current()).IsValid()) return false;
  return BRepCheck_Analyzer(sh).IsValid();
}

struct SurfaceOf {
  Handle(Geom_Surface) surface;
  TopLoc_Location location;
  bool same(const SurfaceOf& o) const { return surface == o.surface && location.IsEqual(o.location); }
};

SurfaceOf surface_of(const TopoDS_Face& f) {
  SurfaceOf s;
  s.surface = BRep_Tool::Surface(f, s.location);
  return s;
}

/// Disjoint sets over face indices.
struct Groups {
  std::vector<int> parent;
  explicit Groups(int n) : parent(std::size_t(n)) { std::iota(parent.begin(), parent.end(), 0); }
  int root(int i) {
    while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
    return i;
  }
  void join(int a, int b) { parent[std::size_t(root(a))] = root(b); }
};

/// Whether the edge between two faces may be dropped to join them: a manifold edge (two faces),
/// not degenerate, not a seam of either, both faces on the same surface with the same orientation.
bool joinable(const TopoDS_Edge& e, const TopoDS_Face& a, const TopoDS_Face& b) {
  if (BRep_Tool::Degenerated(e)) return false;
  if (a.Orientation() != b.Orientation()) return false;
  if (BRep_Tool::IsClosed(e, a) || BRep_Tool::IsClosed(e, b)) return false;
  if (e.Orientation() != TopAbs_FORWARD && e.Orientation() != TopAbs_REVERSED) return false;
  return surface_of(a).same(surface_of(b));
}

/// One face from a group of faces on one surface: its edges (as in the forward faces) but the
/// edges shared inside the group, chained into closed wires by their vertices and, at a vertex
/// where several continue, by the nearest start of a pcurve. Null when the chaining fails or the
/// face is not valid.
TopoDS_Face merged_face(const std::vector<TopoDS_Face>& group) {
  const SurfaceOf surf = surface_of(group[0]);
  const TopoDS_Face ref = TopoDS::Face(group[0].Oriented(TopAbs_FORWARD));
  // An edge met once in each of two faces of the group lies inside the merged face; a seam is met
  // twice in one face and stays.
  struct Meetings {
    int uses = 0, faces = 0;
    std::size_t last_face = std::size_t(-1);
  };
  std::map<const void*, Meetings> met;
  std::vector<TopoDS_Edge> all;
  for (std::size_t i = 0; i < group.size(); ++i) {
    for (TopExp_Explorer ex(group[i].Oriented(TopAbs_FORWARD), TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge e = TopoDS::Edge(ex.Current());
      if (e.Orientation() != TopAbs_FORWARD && e.Orientation() != TopAbs_REVERSED) return {};
      double f = 0, l = 0;
      if (BRep_Tool::CurveOnSurface(e, ref, f, l).IsNull()) return {};
      all.push_back(e);
      Meetings& m = met[e.TShape().get()];
      ++m.uses;
      if (m.last_face != i) ++m.faces, m.last_face = i;
    }
  }
  std::vector<TopoDS_Edge> boundary;
  for (const TopoDS_Edge& e : all) {
    const Meetings& m = met[e.TShape().get()];
    if (!(m.uses == 2 && m.faces == 2)) boundary.push_back(e);
  }
  if (boundary.empty()) return {};
  auto uv_end = [&](const TopoDS_Edge& e, bool start) {
    double f = 0, l = 0;
    const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, ref, f, l);
    const bool fwd = e.Orientation() == TopAbs_FORWARD;
    return pc->Value((start == fwd) ? f : l);
  };
  BRep_Builder bb;
  TopoDS_Face face;
  bb.MakeFace(face, surf.surface, surf.location, BRep_Tool::Tolerance(group[0]));
  std::vector<bool> used(boundary.size(), false);
  for (std::size_t first = 0; first < boundary.size(); ++first) {
    if (used[first]) continue;
    TopoDS_Wire wire;
    bb.MakeWire(wire);
    const TopoDS_Vertex start = TopExp::FirstVertex(boundary[first], true);
    std::size_t cur = first;
    std::size_t steps = 0;
    for (;;) {
      used[cur] = true;
      bb.Add(wire, boundary[cur]);
      if (++steps > boundary.size()) return {};
      const TopoDS_Vertex end = TopExp::LastVertex(boundary[cur], true);
      const gp_Pnt2d at = uv_end(boundary[cur], false);
      std::size_t next = boundary.size();
      double best = 1e300;
      for (std::size_t k = 0; k < boundary.size(); ++k) {
        if (used[k] || !TopExp::FirstVertex(boundary[k], true).IsSame(end)) continue;
        const double d = uv_end(boundary[k], true).SquareDistance(at);
        if (d < best) best = d, next = k;
      }
      if (next == boundary.size()) {
        if (!end.IsSame(start)) return {};
        break;
      }
      cur = next;
    }
    wire.Closed(true);
    bb.Add(face, wire);
  }
  face.Orientation(group[0].Orientation());
  if (!BRepCheck_Analyzer(face).IsValid()) return {};
  return face;
}

}  // namespace

TopoDS_Shape unify_faces(const TopoDS_Shape& shape) {
  try {
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(shape, TopAbs_FACE, faces);
    TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
    TopExp::MapShapesAndUniqueAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
    Groups groups(faces.Extent());
    bool any = false;
    for (int i = 1; i <= edge_faces.Extent(); ++i) {
      const TopTools_ListOfShape& fl = edge_faces(i);
      if (fl.Extent() != 2) continue;
      const TopoDS_Face a = TopoDS::Face(fl.First()), b = TopoDS::Face(fl.Last());
      TopoDS_Edge e;
      for (TopExp_Explorer ex(a, TopAbs_EDGE); ex.More() && e.IsNull(); ex.Next())
        if (ex.Current().IsSame(edge_faces.FindKey(i))) e = TopoDS::Edge(ex.Current());
      if (e.IsNull() || !joinable(e, a, b)) continue;
      groups.join(faces.FindIndex(a) - 1, faces.FindIndex(b) - 1);
      any = true;
    }
    if (!any) return {};
    std::map<int, std::vector<TopoDS_Face>> by_root;
    for (int i = 0; i < faces.Extent(); ++i) by_root[groups.root(i)].push_back(TopoDS::Face(faces(i + 1)));
    Handle(BRepTools_ReShape) reshape = new BRepTools_ReShape;
    bool changed = false;
    for (auto& [root, group] : by_root) {
      if (group.size() < 2) continue;
      const TopoDS_Face merged = merged_face(group);
      if (merged.IsNull()) continue;
      reshape->Replace(group[0], merged);
      for (std::size_t k = 1; k < group.size(); ++k) reshape->Remove(group[k]);
      changed = true;
    }
    if (!changed) return {};
    const TopoDS_Shape out = reshape->Apply(shape);
    if (out.IsNull() || !solids_valid(out)) return {};
    return out;
  } catch (const Standard_Failure&) {
    return {};
  }
}

}  // namespace sweep::occt
