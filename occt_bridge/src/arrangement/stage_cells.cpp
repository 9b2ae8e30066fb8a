// The arrangement of a stage's candidate faces, the classification of its cells, and the stage
// itself (candidates, pruning, arrangement).
#include <BOPAlgo_Alerts.hxx>
#include <BOPAlgo_MakerVolume.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <IntCurvesFace_ShapeIntersector.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Curve2d.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <cstdlib>

#include "arrangement/stage_sweep.hpp"
#include "base/stop.hpp"
#include "sweep/error.hpp"

namespace sweep::occt {

namespace {

/// Whether OCCT's cell builder reported shells it could not orient.
bool unable_to_orient(const BOPAlgo_MakerVolume& mv) {
  const Message_ListOfAlert& alerts = mv.GetReport()->GetAlerts(Message_Warning);
  for (Message_ListOfAlert::Iterator it(alerts); it.More(); it.Next())
    if (it.Value()->IsInstance(STANDARD_TYPE(BOPAlgo_AlertUnableToOrientTheShape))) return true;
  return false;
}

/// A point of a face and the unit normal there that points into the solid the face bounds.
struct InwardPoint {
  gp_Pnt p;
  gp_Dir n;
};

/// The points of face f at the fractions a x b of its parameter box that lie inside it and have a
/// normal.
std::vector<InwardPoint> inward_points(const TopoDS_Face& f, std::initializer_list<double> as,
                                       std::initializer_list<double> bs) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  BRepTopAdaptor_FClass2d fc(f, Settings::face_sample_classifier_tolerance);
  const BRepAdaptor_Surface S(f);
  std::vector<InwardPoint> out;
  for (double a : as)
    for (double b : bs) {
      const gp_Pnt2d uv(u0 + a * (u1 - u0), v0 + b * (v1 - v0));
      if (fc.Perform(uv) != TopAbs_IN) continue;
      BRepLProp_SLProps props(S, uv.X(), uv.Y(), 1, Settings::normal_resolution);
      if (!props.IsNormalDefined()) continue;
      gp_Dir n = props.Normal();
      if (f.Orientation() != TopAbs_REVERSED) n.Reverse();
      out.push_back({props.Value(), n});
    }
  return out;
}

/// A point inside a cell too thin for fixed offsets: from points of its faces a ray goes inward
/// along the normal, and the middle of its way to the next face the ray meets is taken when OCCT's
/// classifier finds it inside.
bool thin_cell_point(const TopoDS_Solid& cell, double size, Eigen::Vector3d* out) {
  IntCurvesFace_ShapeIntersector hits;
  hits.Load(cell, Settings::resolution * size);
  for (TopExp_Explorer ex(cell, TopAbs_FACE); ex.More(); ex.Next())
    for (const auto& [p, n] :
         inward_points(TopoDS::Face(ex.Current()), {0.5, 0.29, 0.71, 0.13, 0.87}, {0.5, 0.31, 0.69, 0.17, 0.83})) {
      hits.Perform(gp_Lin(p, n), Settings::thin_cell_ray_start * size, 2 * size);
      if (!hits.IsDone() || hits.NbPnt() == 0) continue;
      double w = 2 * size;
      for (int k = 1; k <= hits.NbPnt(); ++k) w = std::min(w, hits.WParameter(k));
      const gp_Pnt mid = p.Translated(gp_Vec(n) * (0.5 * w));
      if (BRepClass3d_SolidClassifier(cell, mid, Settings::thin_cell_classifier * size).State() == TopAbs_IN) {
        *out = to_eigen(mid);
        return true;
      }
    }
  return false;
}

/// A point inside the solid cell, a small step inward from one of its faces (or, for a thin cell,
/// thin_cell_point's).
bool interior_point(const TopoDS_Solid& cell, double size, Eigen::Vector3d* out) {
  const double offset = Settings::cell_interior_offset;
  for (double frac : {offset, offset / 10, offset / 100})
    for (TopExp_Explorer ex(cell, TopAbs_FACE); ex.More(); ex.Next())
      for (const auto& [p, n] :
           inward_points(TopoDS::Face(ex.Current()), {0.5, 0.37, 0.63, 0.21, 0.79}, {0.5, 0.41, 0.59, 0.27, 0.73})) {
        const gp_Pnt q = p.Translated(gp_Vec(n) * (frac * size));
        if (BRepClass3d_SolidClassifier(cell, q, Settings::resolution * size).State() == TopAbs_IN) {
          *out = to_eigen(q);
          return true;
        }
      }
  return thin_cell_point(cell, size, out);
}


}  // namespace

void Candidates::add(int id, const std::vector<TopoDS_Face>& fs, bool quadrature) {
  for (const auto& f : fs) {
    faces.push_back(f);
    ids.push_back(id);
    by_quadrature.push_back(quadrature);
    vars[id].faces += 1;
  }
}

void Candidates::keep_only(const std::vector<char>& keep, DroppedFaces* dropped) {
  std::size_t n = 0;
  for (std::size_t k = 0; k < faces.size(); ++k) {
    if (keep[k]) {
      faces[n] = faces[k];
      ids[n] = ids[k];
      by_quadrature[n] = by_quadrature[k];
      ++n;
    } else if (dropped) {
      dropped->faces.push_back(faces[k]);
      dropped->ids.push_back(ids[k]);
    }
  }
  faces.resize(n);
  ids.resize(n);
  by_quadrature.resize(n);
}

void Candidates::restore(const TopoDS_Face& f, int id) {
  faces.push_back(f);
  ids.push_back(id);
  by_quadrature.push_back(false);
}

void Candidates::compute_areas() {
  for (auto& v : vars) v.area = 0;
  for (std::size_t k = 0; k < faces.size(); ++k) {
    double a = 0;
    if (by_quadrature[k]) {
      a = face_area(faces[k]);
    } else {
      GProp_GProps g;
      BRepGProp::SurfaceProperties(faces[k], g);
      a = g.Mass();
    }
    vars[ids[k]].area += a;
  }
}

StageInput::StageInput(const TopoDS_Shape& body, int dim, std::shared_ptr<const StageMotion> motion, double esize,
                       double size, double tol, double fit_tol, int stage, int joint_no)
    : body(body), dim(dim), motion(std::move(motion)), esize(esize), size(size), tol(tol), fit_tol(fit_tol),
      stage(stage), joint_no(joint_no) {
  screw = this->motion->as_screw(radius_of(body));
}

const Eigen::AlignedBox3d& StageInput::body_box() const {
  std::call_once(body_box_->measured, [this] { body_box_->box = box_of(body); });
  return body_box_->box;
}

const ScrewJoint& StageInput::j() const {
  if (!screw) throw InternalError("a stage under a motion that is no screw has no screw joint");
  return screw->joint;
}

std::shared_ptr<const StageMotion> screw_stage_motion(const ScrewJoint& j, double T) {
  ScrewJoint from_body = j;
  from_body.lo = 0;
  from_body.hi = T;
  return std::make_shared<ScrewStage>(from_body);
}

PointTest stage_trajectory_membership(const StageInput& in, double tol_factor) {
  auto by_trajectory = std::make_shared<std::unique_ptr<TrajectoryMembership>>();
  return [in, by_trajectory, tol_factor](const Eigen::Vector3d& x) {
    if (!*by_trajectory)
      *by_trajectory = std::make_unique<TrajectoryMembership>(in.body, in.dim == 3, *in.motion, tol_factor * in.size,
                                                              in.body_box());
    return (**by_trajectory)(x);
  };
}

PointTestMaker orbit_membership(const OrbitSolidPtr& start, const ScrewJoint& j, double T) {
  return [start, j, T]() -> PointTest {
    return [start, j, T](const Eigen::Vector3d& x) { return in_joint_sweep(*start, j, T, x); };
  };
}

PointTestMaker trajectory_membership(const TopoDS_Shape& body, std::shared_ptr<const StageMotion> motion, double ttol,
                                     bool solid) {
  const Eigen::AlignedBox3d body_box = box_of(body);  // (once for every thread's test)
  return [body, motion, ttol, solid, body_box]() -> PointTest {
    auto test = std::make_shared<TrajectoryMembership>(body, solid, *motion, ttol, body_box);
    return [test](const Eigen::Vector3d& x) { return (*test)(x); };
  };
}

PointTest stage_membership(const StageInput& in) {
  if (in.member) return in.member();
  if (in.sd && in.sd_motion)
    return [in](const Eigen::Vector3d& x) { return in_swept_set(*in.sd, *in.sd_motion, x, Settings::resolution * in.size); };
  if (in.pe && in.sd_motion)
    return [in](const Eigen::Vector3d& x) {
      return in_swept_image(*in.pe, *in.sd_motion, x, Settings::resolution * in.size, in.size);
    };
  if (!in.screw) throw InternalError("a stage under a motion that is no screw needs its membership test");
  return stage_trajectory_membership(in, Settings::resolution);
}

namespace {

/// The cells of the arrangement in the swept set.
std::vector<TopoDS_Solid> swept_cells(const PointTestMaker& membership, double size, const BOPAlgo_MakerVolume& mv,
                                      StageRecord& record) {
  const PointTest member = membership();
  std::vector<TopoDS_Solid> kept;
  int ncells = 0;
  for (TopExp_Explorer ex(mv.Shape(), TopAbs_SOLID); ex.More(); ex.Next()) {
    check_stop();
    ++ncells;
    TopoDS_Solid cell = TopoDS::Solid(ex.Current());
    Eigen::Vector3d p;
    if (!interior_point(cell, size, &p)) {
      GProp_GProps g;
      BRepGProp::VolumeProperties(cell, g);
      if (std::abs(g.Mass()) < Settings::sliver_cell_volume * size * size * size) continue;  // a sliver of nothing
      throw ComputeError("no interior point found for a cell of volume " + std::to_string(g.Mass()));
    }
    if (member(p)) kept.push_back(cell);
  }
  record.cells += ncells;
  if (kept.empty()) throw ComputeError("no cell of the arrangement is in the swept set");
  return kept;
}

/// The union of cells of one arrangement (they share faces exactly).
TopoDS_Shape union_of_cells(const std::vector<TopoDS_Solid>& kept) {
  if (kept.size() == 1) return kept[0];
  BRepAlgoAPI_Fuse fuse;
  TopTools_ListOfShape a, t;
  a.Append(kept[0]);
  for (std::size_t k = 1; k < kept.size(); ++k) t.Append(kept[k]);
  fuse.SetArguments(a);
  fuse.SetTools(t);
  fuse.SetRunParallel(true);
  fuse.SetGlue(BOPAlgo_GlueShift);
  fuse.Build(stop_range());
  check_stop();
  if (!fuse.IsDone() || fuse.HasErrors()) throw ComputeError("the union of the swept cells failed");
  return fuse.Shape();
}

/// OCCT's arrangement of the candidate faces into `mv`. It can build no cell at one fuzzy value and
/// every cell at a neighbouring one (a ball extruded along (1, 0, 1): none at 1e-6, all at 1e-7 and
/// 1e-5): other values are tried when it builds none.
void arrange(const std::vector<TopoDS_Face>& faces, double fuzzy, BOPAlgo_MakerVolume& mv) {
  TopTools_ListOfShape args;
  for (const auto& f : faces) args.Append(f);
  if (const char* dump = std::getenv("SWEEP_DUMP_CANDIDATES")) {  // diagnostics: the arrangement's input (written first: OCCT may run on)
    TopoDS_Compound comp;
    BRep_Builder bb;
    bb.MakeCompound(comp);
    for (const auto& f : faces) bb.Add(comp, f);
    BRepTools::Write(comp, dump);
  }
  const double step = Settings::arrangement_fuzzy_factor;
  for (double factor : {1.0, 1 / step, step}) {
    mv.Clear();
    mv.SetArguments(args);
    mv.SetRunParallel(true);
    mv.SetFuzzyValue(fuzzy * factor);
    mv.SetNonDestructive(true);
    mv.Perform(stop_range());
    check_stop();
    if (!mv.HasErrors() && TopExp_Explorer(mv.Shape(), TopAbs_SOLID).More()) break;
  }
}

/// The faces of the arrangement (each candidate's split images, or the candidate itself).
std::vector<TopoDS_Face> split_faces_of(const BOPAlgo_MakerVolume& mv, const std::vector<TopoDS_Face>& faces) {
  TopTools_IndexedMapOfShape split;
  for (const auto& f : faces) {
    if (mv.Images().IsBound(f))
      for (TopTools_ListIteratorOfListOfShape it(mv.Images().Find(f)); it.More(); it.Next()) split.Add(it.Value());
    else
      split.Add(f);
  }
  std::vector<TopoDS_Face> out;
  for (int k = 1; k <= split.Extent(); ++k) out.push_back(TopoDS::Face(split(k)));
  return out;
}

}  // namespace

TopoDS_Shape stage_cells_solid(const StageInput& in, double fit_err, Candidates& cand, DroppedFaces& dropped,
                               StageRecord& record) {
  return cells_solid([&in]() { return stage_membership(in); }, in.size, fit_err, cand, dropped, record);
}

TopoDS_Shape cells_solid(const PointTestMaker& member, double size, double fit_err, Candidates& cand,
                         DroppedFaces& dropped, StageRecord& record) {
  Seconds sec{record.seconds};
  // OCCT's cell builder can leave shells it cannot orient and lose the cells they bound, or build
  // no cell at all, or fail after splitting the faces: then the solid is built from the split faces
  // that separate the swept set from its complement, each classified by the membership of points
  // just off both of its sides. When those leave free edges where candidates that pruning dropped
  // lie (a thin strip of boundary on a face that is internal almost everywhere), such candidates
  // are restored and the arrangement is made again, at most three times.
  const double fuzzy = std::max(Settings::sewing_gap * size, Settings::fit_error_margin * fit_err);
  BOPAlgo_MakerVolume mv;
  TopoDS_Shape result;
  std::string arrangement_error;
  for (int round = 0;; ++round) {
    const auto t_arr = Clock::now();
    arrange(cand.faces, fuzzy, mv);
    arrangement_error.clear();
    if (mv.HasErrors()) {
      std::ostringstream why;
      mv.DumpErrors(why);
      arrangement_error = "the arrangement of the candidate faces failed: " + why.str();
      if (mv.Images().IsEmpty()) throw ComputeError(arrangement_error);
    }
    sec["arrangement"] += since(t_arr);

    const auto t_bnd = Clock::now();
    std::vector<TopoDS_Edge> free_edges;
    if (mv.HasErrors() || unable_to_orient(mv) || !TopExp_Explorer(mv.Shape(), TopAbs_SOLID).More()) {
      const TopoDS_Shape bounded =
          solid_from_boundary_faces(split_faces_of(mv, cand.faces), member, size, nullptr, &free_edges);
      if (valid_and_closed(bounded)) {
        for (TopExp_Explorer ex(bounded, TopAbs_SOLID); ex.More(); ex.Next()) ++record.cells;
        result = bounded;
      }
    }
    // (not after a failed arrangement: OCCT's solid builder can then run for many minutes without
    // polling the stop request)
    const int restored = result.IsNull() && round < 3 && !free_edges.empty() && arrangement_error.empty()
                             ? restore_near_edges(free_edges, size, dropped, cand)
                             : 0;
    sec["classification"] += since(t_bnd);
    if (restored == 0) break;
    record.restored.push_back(restored);
  }
  if (result.IsNull() && !arrangement_error.empty()) throw ComputeError(arrangement_error);
  // Otherwise: classify the cells.
  const auto t_cls = Clock::now();
  const std::vector<TopoDS_Solid> kept = result.IsNull() ? swept_cells(member, size, mv, record) : std::vector<TopoDS_Solid>();
  sec["classification"] += since(t_cls);
  const auto t_build = Clock::now();
  if (result.IsNull()) result = union_of_cells(kept);
  // Merging the pieces of a surface is cosmetic: its result is used only when it is a valid solid.
  const TopoDS_Shape merged = unify_faces(result);
  if (!merged.IsNull()) result = merged;
  sec["build"] += since(t_build);
  return result;
}

TopoDS_Shape solid_sweep(const StageInput& in, double& fit_err, StageRecord& record, Candidates* cand_out, bool prune,
                         PruneCount* pruned, bool direct_builds) {
  Seconds sec{record.seconds};
  const auto t_cand = Clock::now();
  Candidates cand;
  if (direct_builds) {
    const TopoDS_Shape direct = direct_stage(in, fit_err, cand);
    if (!direct.IsNull()) {
      record.varieties += cand.varieties;
      record.cells += 1;
      sec["varieties"] += since(t_cand);
      if (cand_out) *cand_out = std::move(cand);
      return direct;
    }
  }
  const LimitIds limits = stage_candidates(in, fit_err, cand);
  record.varieties += cand.varieties;
  sec["varieties"] += since(t_cand);
  // Duplicates first, so that a candidate restored after pruning cannot duplicate one kept: the
  // general fuse handles coincident analytic faces, but not coincident general ones.
  drop_duplicate_candidates(cand, in.size);
  // Keeping a face is always safe; dropping internal ones spares the arrangement needless (often
  // tangential) intersections. Sampling can miss a strip of boundary on a face that is internal
  // almost everywhere (next to where the envelope touches it tangentially): the caller checks the
  // stage's solid and builds it again without pruning when a check fails.
  if (pruned) *pruned = PruneCount{int(cand.faces.size()), 0};
  DroppedFaces dropped;
  if (prune && in.screw) {  // (the quick tests that pruning needs are a screw's)
    const auto t_prune = Clock::now();
    dropped = prune_internal_candidates(in, limits, fit_err, cand);
    sec["pruning"] += since(t_prune);
    if (pruned) pruned->dropped = int(dropped.faces.size());
  }
  TopoDS_Shape result = stage_cells_solid(in, fit_err, cand, dropped, record);
  if (cand_out) *cand_out = std::move(cand);
  return result;
}

}  // namespace sweep::occt
