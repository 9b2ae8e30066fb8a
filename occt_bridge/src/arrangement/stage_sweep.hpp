// One stage of the cells path: the solid swept by a body under one joint, in four steps, each in
// its own file: candidate varieties (varieties/stage_candidates.cpp), candidates left out as
// duplicates or as internal (arrangement/candidate_pruning.cpp), the arrangement of the rest and
// the classification of its cells (arrangement/stage_cells.cpp).
#pragma once

#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <nlohmann/json.hpp>
#include <vector>

#include "base/internal.hpp"
#include "sweep/membership.hpp"
#include "sweep/entity.hpp"
#include "sweep/orbit.hpp"
#include "sweep/stage_motion.hpp"

namespace sweep::occt {

using Clock = std::chrono::steady_clock;
inline double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Accumulates seconds per step over stages.
struct Seconds {
  nlohmann::json& j;
  double& operator[](const char* key) {
    if (!j.contains(key)) j[key] = 0.0;
    return *j[key].get_ptr<double*>();
  }
};

/// Seconds per step (a JSON object from step to seconds): `s` added to step `key`.
inline void add_step_seconds(nlohmann::json& seconds, const std::string& key, double s) {
  seconds[key] = seconds.value(key, 0.0) + s;
}
/// Every step of `from` added to `into`.
inline void merge_step_seconds(nlohmann::json& into, const nlohmann::json& from) {
  for (auto it = from.begin(); it != from.end(); ++it) add_step_seconds(into, it.key(), it.value().get<double>());
}

/// What one solid stage did, for the report (write_run_record puts it there): the varieties and
/// cells it made, candidates it restored (one count per round), whether it was built from the
/// arrangement of cells, built again from every candidate, or healed, and its seconds per step.
struct StageRecord {
  int stage = 0;
  int varieties = 0, cells = 0;
  std::vector<int> restored;
  bool from_cells = false, unpruned = false, healed = false;
  nlohmann::json seconds = nlohmann::json::object();
  /// Adds `s` seconds to step `key`.
  void add_seconds(const std::string& key, double s) { add_step_seconds(seconds, key, s); }
};

/// Candidate faces left out of the arrangement, with their varieties.
struct DroppedFaces {
  std::vector<TopoDS_Face> faces;
  std::vector<int> ids;
};

/// The candidate faces of a stage and the varieties they lie on.
struct Candidates {
  std::vector<TopoDS_Face> faces;
  std::vector<int> ids;  ///< variety of each face (index into vars)
  std::vector<Variety> vars;
  int varieties = 0;
  int add_variety(Variety v) {
    vars.push_back(std::move(v));
    return int(vars.size()) - 1;
  }
  /// Faces of variety `id`; `quadrature`: their areas come from the divergence quadrature
  /// (cheaper than OCCT's integration on high-degree faces).
  void add(int id, const std::vector<TopoDS_Face>& fs, bool quadrature = false);
  /// Keeps the faces whose flag is set; the others go to `dropped` when given.
  void keep_only(const std::vector<char>& keep, DroppedFaces* dropped = nullptr);
  /// A face dropped earlier, taken back (its variety already counts it).
  void restore(const TopoDS_Face& f, int id);
  /// The varieties' candidate areas (only the varieties report needs them).
  void compute_areas();

 private:
  std::vector<bool> by_quadrature;
};

/// How many candidate faces pruning saw and left out.
struct PruneCount {
  int candidates = 0;  ///< candidate faces before pruning
  int dropped = 0;     ///< left out as internal (some may be restored later)
};

/// What a stage sweeps and how: `body` (a solid, or faces when dim == 2) moved by `motion` over
/// [motion->lo(), motion->hi()] (the body as given is what the motion moves). `sd`, when given, is
/// the entity's signed distance, or `pe` its parametric map, and `sd_motion` the chain that
/// carries the entity to this stage's swept set (for the membership test independent of the
/// B-rep). `member`, when given, is that test itself (a general motion's search over t); `core` is
/// the entity as the core sees it, at the body's pose (a general motion's candidates need it).
struct StageInput {
  /// `screw` is found from the motion (StageMotion::as_screw over the body's reach).
  StageInput(const TopoDS_Shape& body, int dim, std::shared_ptr<const StageMotion> motion, double esize, double size,
             double tol, double fit_tol, int stage, int joint_no);
  const TopoDS_Shape& body;
  int dim;
  std::shared_ptr<const StageMotion> motion;
  double esize;  ///< the body's extent
  double size;   ///< the model's size
  double tol;
  double fit_tol;
  int stage;
  int joint_no;
  const SignedDistance* sd = nullptr;
  const ParametricEntity* pe = nullptr;
  const Motion* sd_motion = nullptr;
  PointTestMaker member;
  const Entity* core = nullptr;
  /// The motion as one screw joint from the body's pose, q in [0, T()]: the screw engine's closed
  /// forms (fixed grazing curves, orbit sections, surfaces of revolution and extrusion) apply.
  /// None under a general motion.
  std::optional<ScrewSegment> screw;
  /// The screw's joint; throws InternalError under a general motion.
  const ScrewJoint& j() const;
  /// The screw's range.
  double T() const { return j().hi; }
  bool full_turn() const { return screw && j().type == JointType::Revolute && T() >= 2 * M_PI - 1e-12; }
  /// box_of(body), measured once for every copy of the input and every thread.
  const Eigen::AlignedBox3d& body_box() const;

 private:
  struct BodyBox {
    std::once_flag measured;
    Eigen::AlignedBox3d box;
  };
  std::shared_ptr<BodyBox> body_box_ = std::make_shared<BodyBox>();
};

/// A screw joint's stage motion over q in [0, T] from the body's pose.
std::shared_ptr<const StageMotion> screw_stage_motion(const ScrewJoint& j, double T);

/// The varieties of the body at both ends of the range (hi -1 over a full turn).
struct LimitIds {
  int lo = -1, hi = -1;
};

/// Valid and closed (the checks a directly built solid must pass to be used).
bool valid_and_closed(const TopoDS_Shape& s);

/// A ball under a screw motion, built directly as a tube about its centre's helix closed by two
/// half balls (trimmed where neighbouring turns overlap), or under a prismatic joint as a capsule;
/// null for a revolute joint, a screw of pitch 0, a body that is not one ball, or a build that is
/// not valid and closed. `faces` and `roles` (0 tube, 1 start, 2 end) describe it.
TopoDS_Shape direct_ball_screw(const TopoDS_Shape& body, const ScrewJoint& j, double T, double fit_tol, double size,
                               double tol, double* fit_err, std::vector<TopoDS_Face>* faces, std::vector<int>* roles);

/// A ball under a screw or a prismatic joint built directly (direct_ball_screw), its tube and end
/// varieties in `cand`; null when the stage is not one or the build does not pass (`cand` unchanged).
TopoDS_Shape ball_screw_stage(const StageInput& in, double& fit_err, Candidates& cand);

/// The stage built without an arrangement (a ball under a screw, a face translated along a
/// direction in which it is a graph) when such a build exists and is valid and closed; its faces
/// and varieties go to `cand`. Null otherwise (`cand` unchanged).
TopoDS_Shape direct_stage(const StageInput& in, double& fit_err, Candidates& cand);

/// The candidate varieties of the stage: the sweeps of the body's edges and grazing curves, and
/// the body's faces (split at the grazing curves) at both ends of the range.
LimitIds stage_candidates(const StageInput& in, double& fit_err, Candidates& cand);

/// Point membership in the stage's swept set that never looks at a computed solid: the certified
/// analytic test for primitive solids and parametric entities, else the trajectory test.
PointTest stage_membership(const StageInput& in);
/// The trajectory test at offset tol_factor x the model size (one per thread: it keeps OCCT state).
PointTest stage_trajectory_membership(const StageInput& in, double tol_factor);

/// Membership in the sweep of a primitive (at its start pose) by joint j over [0, T], from its
/// orbit intervals: one test per thread.
PointTestMaker orbit_membership(const OrbitSolidPtr& start, const ScrewJoint& j, double T);
/// Membership in the sweep of a solid under `motion` (which moves `body` as given), from each
/// point's trajectory against the solid's faces (TrajectoryMembership): one test per thread.
/// `solid` false: the body is faces only (a surface), and a point is swept when its trajectory
/// meets one.
PointTestMaker trajectory_membership(const TopoDS_Shape& body, std::shared_ptr<const StageMotion> motion, double ttol,
                                     bool solid = true);

/// Leaves out candidates that are the same face reached twice (e.g. by symmetric edges).
void drop_duplicate_candidates(Candidates& cand, double size);
/// Leaves out candidates found inside the swept set at sampled points (both sides in the set).
DroppedFaces prune_internal_candidates(const StageInput& in, LimitIds limits, double fit_err, Candidates& cand);
/// Dropped candidates that contain a point of one of the edges (within 1e-5 of the model size),
/// moved back among the candidates; how many.
int restore_near_edges(const std::vector<TopoDS_Edge>& edges, double size, DroppedFaces& dropped, Candidates& cand);

/// The solid bounded by the arrangement of the candidates: its cells in the swept set, or the split
/// faces that separate the set from its complement. Throws ComputeError when neither can be built.
TopoDS_Shape stage_cells_solid(const StageInput& in, double fit_err, Candidates& cand, DroppedFaces& dropped,
                               StageRecord& record);
/// The same for any motion: the arrangement of `cand`'s faces (fuzzy from the model `size` and the
/// candidates' fit error), its cells classified by `member`, which never looks at the solid.
TopoDS_Shape cells_solid(const PointTestMaker& member, double size, double fit_err, Candidates& cand,
                         DroppedFaces& dropped, StageRecord& record);

/// One stage: candidate varieties, pruning (with `prune`; `pruned` receives how many of how
/// many), the arrangement and its cells. With `direct_builds`, the shapes that have a direct
/// construction are built so first. The stage's candidates go to `cand_out`, what it did to `record`.
TopoDS_Shape solid_sweep(const StageInput& in, double& fit_err, StageRecord& record, Candidates* cand_out, bool prune,
                         PruneCount* pruned, bool direct_builds);

}  // namespace sweep::occt
