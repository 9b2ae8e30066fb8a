// Each variety's share of the result's boundary.
#include <BRepAdaptor_Surface.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <map>

#include "run/run_steps.hpp"

namespace sweep::occt {

namespace {

/// The varieties of the candidates that the sample points of face f lie on, and how many points
/// lie on each (an 8 x 8 grid in f's parameter box).
std::map<int, int> candidates_under(const TopoDS_Face& f, const Candidates& cands, double size, int* total) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  BRepTopAdaptor_FClass2d fc(f, 1e-9);
  BRepAdaptor_Surface S(f);
  std::map<int, int> hits;
  *total = 0;
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b) {
      gp_Pnt2d uv(u0 + (u1 - u0) * (a + 0.5) / 8, v0 + (v1 - v0) * (b + 0.5) / 8);
      if (fc.Perform(uv) != TopAbs_IN) continue;
      const gp_Pnt p = S.Value(uv.X(), uv.Y());
      for (std::size_t k = 0; k < cands.faces.size(); ++k) {
        const TopoDS_Face& cf = cands.faces[k];
        GeomAPI_ProjectPointOnSurf proj(p, BRep_Tool::Surface(cf));
        if (proj.NbPoints() == 0 || proj.LowerDistance() > 1e-6 * size) continue;
        double pu, pv;
        proj.LowerDistanceParameters(pu, pv);
        if (BRepTopAdaptor_FClass2d(cf, 1e-9).Perform(gp_Pnt2d(pu, pv)) == TopAbs_OUT) continue;
        ++hits[cands.ids[k]];
        ++*total;
        break;
      }
    }
  return hits;
}

}  // namespace

void attribute_result_faces(Candidates& cands, const TopoDS_Shape& result, double size) {
  cands.compute_areas();
  std::map<const Geom_Surface*, int> by_surface;
  TopLoc_Location loc;
  for (std::size_t k = 0; k < cands.faces.size(); ++k)
    by_surface[BRep_Tool::Surface(cands.faces[k], loc).get()] = cands.ids[k];
  for (auto& v : cands.vars) v.final_stage = true;
  for (TopExp_Explorer ex(result, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& f = TopoDS::Face(ex.Current());
    GProp_GProps g;
    BRepGProp::SurfaceProperties(f, g);
    const double area = g.Mass(), vol = face_divergence(f);
    auto it = by_surface.find(BRep_Tool::Surface(f, loc).get());
    if (it != by_surface.end()) {
      cands.vars[it->second].boundary_area += area;
      cands.vars[it->second].volume += vol;
      continue;
    }
    int total = 0;
    for (const auto& [id, count] : candidates_under(f, cands, size, &total)) {
      cands.vars[id].boundary_area += area * count / total;
      cands.vars[id].volume += vol * count / total;
    }
  }
}

}  // namespace sweep::occt
