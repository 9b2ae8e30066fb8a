// Holes of a sewn shell that one face fills exactly, and faces kept across them.
#include "arrangement/hole_fill.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRep_Tool.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>

#include <algorithm>

namespace sweep::occt {

namespace {

/// An edge's ends and middle, to match it against others by position.
struct EdgeMarks {
  gp_Pnt a, m, b;
};

EdgeMarks marks_of(const TopoDS_Edge& e) {
  BRepAdaptor_Curve c(e);
  return {c.Value(c.FirstParameter()), c.Value(0.5 * (c.FirstParameter() + c.LastParameter())), c.Value(c.LastParameter())};
}

bool same_edge(const EdgeMarks& x, const EdgeMarks& y, double gap) {
  if (x.m.Distance(y.m) > gap) return false;
  return (x.a.Distance(y.a) <= gap && x.b.Distance(y.b) <= gap) || (x.a.Distance(y.b) <= gap && x.b.Distance(y.a) <= gap);
}

}  // namespace

std::vector<std::size_t> faces_filling_holes(const std::vector<TopoDS_Face>& faces, const BRepBuilderAPI_Sewing& sewing,
                                             double gap) {
  std::vector<EdgeMarks> free;
  for (int i = 1; i <= sewing.NbFreeEdges(); ++i) free.push_back(marks_of(sewing.FreeEdge(i)));
  std::vector<std::size_t> out;
  if (free.empty()) return out;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    bool fills = true;
    int edges = 0;
    for (TopExp_Explorer ex(faces[i], TopAbs_EDGE); ex.More() && fills; ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      if (BRep_Tool::Degenerated(e)) continue;
      const EdgeMarks m = marks_of(e);
      fills = std::any_of(free.begin(), free.end(), [&](const EdgeMarks& f) { return same_edge(m, f, gap); });
      ++edges;
    }
    if (fills && edges > 0) out.push_back(i);
  }
  return out;
}

std::vector<std::size_t> faces_left_over(const std::vector<TopoDS_Face>& faces, const BRepBuilderAPI_Sewing& sewing,
                                         double gap) {
  std::vector<EdgeMarks> free;
  for (int i = 1; i <= sewing.NbFreeEdges(); ++i) free.push_back(marks_of(sewing.FreeEdge(i)));
  std::vector<std::size_t> out;
  if (free.empty()) return out;
  std::vector<std::vector<EdgeMarks>> edges(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (TopExp_Explorer ex(faces[i], TopAbs_EDGE); ex.More(); ex.Next())
      if (!BRep_Tool::Degenerated(TopoDS::Edge(ex.Current()))) edges[i].push_back(marks_of(TopoDS::Edge(ex.Current())));
  auto is_free = [&](const EdgeMarks& m) {
    return std::any_of(free.begin(), free.end(), [&](const EdgeMarks& f) { return same_edge(m, f, gap); });
  };
  // the other faces with an edge on m
  auto others_on = [&](const EdgeMarks& m, std::size_t self) {
    int n = 0;
    for (std::size_t j = 0; j < faces.size(); ++j)
      if (j != self && std::any_of(edges[j].begin(), edges[j].end(), [&](const EdgeMarks& x) { return same_edge(m, x, gap); }))
        ++n;
    return n;
  };
  for (std::size_t i = 0; i < faces.size(); ++i) {
    int open = 0;
    bool left_over = !edges[i].empty();
    for (const EdgeMarks& m : edges[i]) {
      if (is_free(m)) {
        ++open;
        continue;
      }
      left_over = others_on(m, i) >= 2;
      if (!left_over) break;
    }
    if (left_over && open > 0) out.push_back(i);
  }
  return out;
}

}  // namespace sweep::occt
