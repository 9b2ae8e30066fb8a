// A face moved onto another surface with the same parameters (see internal.hpp).
#include <BRepBuilderAPI_Copy.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include "base/internal.hpp"

namespace sweep::occt {

TopoDS_Face face_on_surface(const TopoDS_Face& face, const Handle(Geom_Surface)& surface) {
  const TopoDS_Face copy = TopoDS::Face(BRepBuilderAPI_Copy(face).Shape());
  TopLoc_Location loc;
  BRep_Tool::Surface(copy, loc);
  BRep_Builder bb;
  // (the surface has the face's parameters: every curve on it holds as it is)
  for (TopExp_Explorer ex(copy, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
    double first, last;
    const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, copy, first, last);
    if (pc.IsNull()) return face;
    if (BRep_Tool::IsClosed(e, copy)) {
      const Handle(Geom2d_Curve) pc2 = BRep_Tool::CurveOnSurface(TopoDS::Edge(e.Reversed()), copy, first, last);
      bb.UpdateEdge(e, pc, pc2, surface, loc, BRep_Tool::Tolerance(e));
    } else {
      bb.UpdateEdge(e, pc, surface, loc, BRep_Tool::Tolerance(e));
    }
    bb.Range(e, surface, loc, first, last);
  }
  bb.UpdateFace(copy, surface, loc, BRep_Tool::Tolerance(copy));
  return copy;
}

}  // namespace sweep::occt
