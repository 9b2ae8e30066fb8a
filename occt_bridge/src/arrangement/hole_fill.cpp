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

/// The marks of the sewing's free edges.
std::vector<EdgeMarks> free_edges_of(const BRepBuilderAPI_Sewing& sewing) {
  std::vector<EdgeMarks> out;
  for (int i = 1; i <= sewing.NbFreeEdges(); ++i) out.push_back(marks_of(sewing.FreeEdge(i)));
  return out;
}

/// The marks of a face's edges that are not degenerate.
std::vector<EdgeMarks> edges_of(const TopoDS_Face& face) {
  std::vector<EdgeMarks> out;
  for (TopExp_Explorer ex(face, TopAbs_EDGE); ex.More(); ex.Next())
    if (!BRep_Tool::Degenerated(TopoDS::Edge(ex.Current()))) out.push_back(marks_of(TopoDS::Edge(ex.Current())));
  return out;
}

/// Whether m is one of the edges.
bool among(const EdgeMarks& m, const std::vector<EdgeMarks>& edges, double gap) {
  return std::any_of(edges.begin(), edges.end(), [&](const EdgeMarks& e) { return same_edge(m, e, gap); });
}

}  // namespace

std::vector<std::size_t> faces_filling_holes(const std::vector<TopoDS_Face>& faces, const BRepBuilderAPI_Sewing& sewing,
                                             double gap) {
  const std::vector<EdgeMarks> free = free_edges_of(sewing);
  std::vector<std::size_t> out;
  if (free.empty()) return out;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const std::vector<EdgeMarks> edges = edges_of(faces[i]);
    if (!edges.empty() && std::all_of(edges.begin(), edges.end(), [&](const EdgeMarks& m) { return among(m, free, gap); }))
      out.push_back(i);
  }
  return out;
}

std::vector<std::size_t> faces_left_over(const std::vector<TopoDS_Face>& faces, const BRepBuilderAPI_Sewing& sewing,
                                         double gap) {
  const std::vector<EdgeMarks> free = free_edges_of(sewing);
  std::vector<std::size_t> out;
  if (free.empty()) return out;
  std::vector<std::vector<EdgeMarks>> edges(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) edges[i] = edges_of(faces[i]);
  // the other faces with an edge on m
  auto others_on = [&](const EdgeMarks& m, std::size_t self) {
    int n = 0;
    for (std::size_t j = 0; j < faces.size(); ++j) n += j != self && among(m, edges[j], gap);
    return n;
  };
  for (std::size_t i = 0; i < faces.size(); ++i) {
    int open = 0;
    bool left_over = !edges[i].empty();
    for (const EdgeMarks& m : edges[i]) {
      if (among(m, free, gap)) {
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
