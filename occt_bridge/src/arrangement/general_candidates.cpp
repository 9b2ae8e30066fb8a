#include "arrangement/general_candidates.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "arrangement/facing.hpp"
#include "base/internal.hpp"
#include "base/stop.hpp"
#include "faces/patch_face.hpp"
#include "sweep/settings.hpp"

namespace sweep::occt {
namespace {

bool same_plane(const PatchPlane& a, const PatchPlane& b, double tol) {
  const double c = a.normal.dot(b.normal);
  return std::abs(std::abs(c) - 1) < 1e-12 && std::abs(a.offset - (c > 0 ? 1 : -1) * b.offset) <= tol;
}

/// The planes in which candidate sweeps (not the entity's copies) lie, given each patch's plane: a
/// motion that keeps a plane sweeps curves lying in it over regions of it, folded where a curve
/// moves along itself. Each plane once.
std::vector<PatchPlane> kept_planes(const std::vector<CandidatePatch>& patches,
                                    const std::vector<std::optional<PatchPlane>>& plane_of, double tol) {
  std::vector<PatchPlane> out;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const std::optional<PatchPlane>& p = plane_of[k];
    if (patches[k].type == "limit" || !p) continue;
    if (std::none_of(out.begin(), out.end(), [&](const PatchPlane& q) { return same_plane(q, *p, tol); }))
      out.push_back(*p);
  }
  return out;
}

/// Whether a patch whose plane is `p` lies in one of the planes (the plane's face holds it).
bool on_kept_plane(const std::optional<PatchPlane>& p, const std::vector<PatchPlane>& planes, double tol) {
  return p && std::any_of(planes.begin(), planes.end(), [&](const PatchPlane& q) { return same_plane(q, *p, tol); });
}

std::string plane_name(const PatchPlane& p) {
  char b[160];
  std::snprintf(b, sizeof b, "(%.6g, %.6g, %.6g) . x = %.6g", p.normal.x(), p.normal.y(), p.normal.z(), p.offset);
  return b;
}

/// The square of the plane that covers the box (widened by a tenth): the plane's candidate face,
/// of which the classification of the arrangement's cells keeps the swept region.
TopoDS_Face plane_face(const PatchPlane& p, const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3d c = box.center();
  const Eigen::Vector3d origin = c - (p.normal.dot(c) - p.offset) * p.normal;
  const double r = 0.55 * box.sizes().norm() + 1e-9;
  const gp_Pln plane(to_pnt(origin), gp_Dir(p.normal.x(), p.normal.y(), p.normal.z()));
  return BRepBuilderAPI_MakeFace(plane, -r, r, -r, r).Face();
}

/// The distance from q to the sheet's side at t (its second parameter): a scan of its first
/// parameter, then golden-section search about the nearest sample.
double distance_to_side(const Patch& sheet, double t, const Eigen::Vector3d& q) {
  const int n = 64;
  const double lo = sheet.lo(0), hi = sheet.hi(0), h = (hi - lo) / n;
  auto d = [&](double s) { return (sheet.eval(std::clamp(s, lo, hi), t).x - q).norm(); };
  int best = 0;
  for (int i = 1; i <= n; ++i)
    if (d(lo + i * h) < d(lo + best * h)) best = i;
  double a = lo + (best - 1) * h, b = lo + (best + 1) * h;
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  for (int it = 0; it < 60; ++it) {
    const double x1 = b - g * (b - a), x2 = a + g * (b - a);
    (d(x1) < d(x2) ? b : a) = d(x1) < d(x2) ? x2 : x1;
  }
  return std::min(d(0.5 * (a + b)), d(lo + best * h));
}

/// The edges of a sheet's faces that run along its side at t, to within tol.
std::vector<TopoDS_Edge> edges_at(const Patch& sheet, const std::vector<TopoDS_Face>& faces, double t, double tol) {
  std::vector<TopoDS_Edge> out;
  for (const TopoDS_Face& f : faces)
    for (TopExp_Explorer ex(f, TopAbs_EDGE); ex.More(); ex.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
      if (BRep_Tool::Degenerated(e)) continue;
      const BRepAdaptor_Curve c(e);
      bool along = true;
      for (double f : {0.0, 0.25, 0.5, 0.75, 1.0})
        along = along && distance_to_side(sheet, t, to_eigen(c.Value(c.FirstParameter() + f * (c.LastParameter() - c.FirstParameter())))) <= tol;
      if (along) out.push_back(e);
    }
  return out;
}

/// The faces split by the edges `tools` (the faces themselves when there are none); `why` is the
/// error when OCCT's splitter fails.
std::vector<TopoDS_Face> split_faces(const std::vector<TopoDS_Face>& faces, const TopTools_ListOfShape& tools,
                                     double fuzzy, const char* why) {
  if (tools.IsEmpty()) return faces;
  std::vector<TopoDS_Face> pieces;
  for (const TopoDS_Face& f : faces) {
    const TopoDS_Shape split = split_by_edges(f, tools, fuzzy, SplitMode::NonDestructive);
    if (split.IsNull()) throw ComputeError(why);
    for (TopExp_Explorer ex(split, TopAbs_FACE); ex.More(); ex.Next()) pieces.push_back(TopoDS::Face(ex.Current()));
  }
  return pieces;
}

/// The pieces of an end copy at t that can bound the swept set: the copy split along the sheets'
/// edges that leave it, then the pieces the motion leaves behind (at the start) or moves into (at
/// the end), slides within, or was not found to face one way.
std::vector<TopoDS_Face> bounding_pieces(const std::vector<TopoDS_Face>& copy, const std::vector<TopoDS_Edge>& tools,
                                         const StageMotion& motion, double t, bool start, double size,
                                         double fuzzy) {
  TopTools_ListOfShape list;
  for (const auto& e : tools) list.Append(e);
  const std::vector<TopoDS_Face> pieces =
      split_faces(copy, list, fuzzy, "an end copy could not be split where the envelope sheets leave it");
  std::vector<TopoDS_Face> out;
  for (const TopoDS_Face& p : pieces) {
    const Facing facing = facing_of(p, VelocityField(motion.twist(t)), size);
    if (facing != (start ? Facing::Front : Facing::Back)) out.push_back(p);
  }
  return out;
}

}  // namespace

Variety candidate_variety(const CandidatePatch& c) {
  Variety v;
  v.stage = 1;
  v.type = c.type;
  v.what = c.patch->what();
  for (const auto& [name, value] : c.fixed) v.fixed[name] = value;
  for (const auto& [name, range] : c.free) v.free[name] = {range.first, range.second};
  return v;
}

Candidates general_candidates(const Entity& entity, const std::shared_ptr<const StageMotion>& motion,
                              const Eigen::AlignedBox3d& reach, double size, double fit_tol, double& fit_err) {
  Candidates cand;
  const std::vector<CandidatePatch> patches = candidate_patches(entity, motion, [] { check_stop(); });
  const double flat = Settings::resolution * size;
  std::vector<std::optional<PatchPlane>> plane_of;
  for (const CandidatePatch& c : patches) plane_of.push_back(patch_plane(*c.patch, flat));
  const std::vector<PatchPlane> planes = kept_planes(patches, plane_of, flat);
  for (const PatchPlane& plane : planes) {
    Variety v;
    v.stage = 1;
    v.type = "interior";
    v.what = "the plane " + plane_name(plane) + ", which the motion keeps: the region swept within it";
    cand.add(cand.add_variety(std::move(v)), {plane_face(plane, reach)});
  }
  // the sweeps first: the end copies are split along the edges of the sheets that leave them
  std::vector<std::vector<TopoDS_Face>> faces(patches.size());
  std::vector<char> skip(patches.size(), 0);
  for (std::size_t k = 0; k < patches.size(); ++k) {
    skip[k] = on_kept_plane(plane_of[k], planes, flat);
    if (skip[k] || patches[k].type == "limit") continue;
    for (const PatchFace& pf : patch_faces(*patches[k].patch, fit_tol, Settings::patch_face_splits)) {
      faces[k].push_back(pf.face);
      fit_err = std::max(fit_err, pf.error);
      check_stop();
    }
  }
  const double lo = motion->lo(), hi = motion->hi(), at_end = 1e-12 * (hi - lo);
  const double fuzzy = std::max(Settings::sewing_gap * size, Settings::fit_error_margin * fit_err);
  // an envelope sheet whose arc ends on a side of its face meets the sweep of the edge there
  // tangentially (both are tangent to the moving face): the edge sweeps are split along the
  // sheets' edges, so that the two meet on an edge of each
  TopTools_ListOfShape sheet_edges;
  for (std::size_t j = 0; j < patches.size(); ++j)
    if (patches[j].type == "interior")
      for (const TopoDS_Face& f : faces[j])
        for (TopExp_Explorer ex(f, TopAbs_EDGE); ex.More(); ex.Next())
          if (!BRep_Tool::Degenerated(TopoDS::Edge(ex.Current()))) sheet_edges.Append(ex.Current());
  for (std::size_t k = 0; k < patches.size(); ++k) {
    if (skip[k] || patches[k].type != "boundary") continue;
    faces[k] = split_faces(faces[k], sheet_edges, fuzzy, "the sweep of an edge could not be split where envelope sheets meet it");
    check_stop();
  }
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const CandidatePatch& c = patches[k];
    if (skip[k] || c.type != "limit") continue;
    const double t = c.fixed.front().second;
    std::vector<TopoDS_Edge> tools;
    for (std::size_t j = 0; j < patches.size(); ++j) {
      const Patch& sheet = *patches[j].patch;
      if (patches[j].type != "interior" || patches[j].face != c.face || faces[j].empty()) continue;
      if (!(std::abs(sheet.lo(1) - t) <= at_end || std::abs(sheet.hi(1) - t) <= at_end)) continue;
      for (const TopoDS_Edge& e : edges_at(sheet, faces[j], t, std::max(100 * fit_tol, 10 * flat))) tools.push_back(e);
    }
    std::vector<TopoDS_Face> copy;
    for (const PatchFace& pf : patch_faces(*c.patch, fit_tol, Settings::patch_face_splits)) {
      copy.push_back(pf.face);
      fit_err = std::max(fit_err, pf.error);
    }
    faces[k] = bounding_pieces(copy, tools, *motion, t, t == lo, size, fuzzy);
    check_stop();
  }
  for (std::size_t k = 0; k < patches.size(); ++k) {
    if (skip[k]) continue;
    const int id = cand.add_variety(candidate_variety(patches[k]));
    cand.add(id, faces[k], patches[k].type != "limit");
  }
  cand.varieties = int(cand.vars.size());
  return cand;
}

}  // namespace sweep::occt
