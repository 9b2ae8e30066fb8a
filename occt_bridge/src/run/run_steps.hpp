// The steps of run_sweep around the stages: the sweeps of points and curves, the membership that
// judges the solid, the checks of the final solid and its verdict, the Monte Carlo volume of
// --verify, and the share of the result's boundary that each variety carries.
#pragma once

#include <Eigen/Geometry>
#include <TopoDS_Shape.hxx>
#include <functional>
#include <string>
#include <vector>

#include "base/internal.hpp"
#include "arrangement/stage_sweep.hpp"
#include "sweep/entity.hpp"
#include "sweep/membership.hpp"
#include "sweep/settings.hpp"

namespace sweep::occt {

/// The sweep of a spec whose motion is a one-parameter stage motion (`path`, `keyframes`).
RunResult run_stage_motion_sweep(const Spec& spec, const RunOptions& opt);

/// The run's tolerance: the spec's when it gives one, else Settings::default_tolerance x the model
/// size; and the tolerance fitted curves and surfaces keep (Settings::fit_fraction x tol).
struct RunTolerance {
  double tol, fit_tol;
};
RunTolerance run_tolerance(double spec_tolerance, double size, const Settings& settings);

/// The Monte Carlo volume of --verify against the B-rep volume: why they disagree (by more than
/// 4.5 standard errors plus tol x size^2 + Settings::volume_relative_band x size^3), or empty
/// (also when there is no Monte Carlo volume).
std::string monte_carlo_disagreement(const Report& rep, double tol, double size, const Settings& settings);

/// The largest side of the shape's box.
double extent(const TopoDS_Shape& s);
/// The model size: the extent of the entity's box corners carried by the motion sampled at the
/// ends and middles of the joint ranges (a point entity has no extent of its own).
double model_size(const TopoDS_Shape& raw, const Motion& motion);

/// The entity of a run, built once from its spec (the one place that tells the core's kinds from
/// the bridge's): the core's entity, or the bridge's for a B-rep file (read once), and its signed
/// distance, parametric map and orbit solid (each null when it has none).
struct RunEntity {
  explicit RunEntity(const EntitySpec& spec);
  const EntitySpec& spec;
  /// The shape of an entity given by a file, placement applied; null for the other kinds.
  TopoDS_Shape file_shape;
  EntityPtr core;
  /// A distance bound that vanishes on the boundary only (Entity::tight_distance), for the stages'
  /// searches; null for entities without one.
  std::shared_ptr<const SignedDistance> sd;
  std::shared_ptr<const ParametricEntity> pe;
  OrbitSolidPtr orbit;
  /// The distance bound for the verdict's searches: `sd`, or a looser bound (a B-rep solid's,
  /// built at the first call); null when the entity has none.
  std::shared_ptr<const SignedDistance> search_bound() const;
  /// The entity's shape for its extent: the file's shape, or sizing_shape() of the spec.
  TopoDS_Shape sizing_shape(double* fit_error) const;
};

/// The entity as the stages of a chain take it: the run's entity, its shape before the motion's
/// home pose (parametric entities fitted within fit_tol), the model size and the tolerances.
struct ChainEntity {
  const RunEntity& run;
  TopoDS_Shape raw;
  double size, tol, fit_tol;
};

/// What the stages of a run did, in the order they were built, and the seconds of steps outside
/// them (the entity, the union of segments): the report's counts and timings come from here only.
struct RunRecord {
  std::vector<StageRecord> stages;
  nlohmann::json seconds = nlohmann::json::object();
  void add_seconds(const std::string& key, double s) { add_step_seconds(seconds, key, s); }
  /// Whether a solid stage was built from the arrangement of cells.
  bool any_from_cells() const;
};
/// Writes the record into the report (once per run: it adds its seconds to the report's): the
/// varieties and cells summed over stages, the stages built from cells, without pruning or healed,
/// and the candidates restored.
void write_run_record(const RunRecord& record, Report& rep);

/// What the stages of a chain built: the swept set (a solid when `dim` is 3), the entity's shape
/// the last stages swept (`raw`, extended where a joint slid it along itself), the last solid
/// stage's candidates, and the rebuild of that stage from every candidate when pruning left some
/// out (empty otherwise, and always for a chain that is not judged on its own; it starts the
/// stage's record again, its seconds kept).
struct ChainSweep {
  TopoDS_Shape shape;
  int dim = 0;
  TopoDS_Shape raw;
  Candidates last_cands;
  std::function<TopoDS_Shape(Candidates*, StageRecord&)> redo_last;
};

/// The stages of `motion`, innermost joint first, each sweeping the set the previous one built.
/// A chain that is `judged` leaves its last stage for the final checks (and `redo_last`); one that
/// is not (a segment of a longer motion) checks it like every other stage, rebuilding it from every
/// candidate when the check fails. Fit errors go to `fit_err`, what each stage did to `record`.
ChainSweep sweep_chain(const ChainEntity& entity, const Motion& motion, bool judged, const RunOptions& opt,
                       double& fit_err, RunRecord& record, const std::function<void(const std::string&)>& step);

/// The trajectory of a point under one joint as an edge (the sweep of a point).
TopoDS_Shape point_sweep(const TopoDS_Shape& body, const ScrewJoint& j, double T, double tol, double size);

/// The surface swept by the edges of a curve (a compound of faces).
TopoDS_Shape curve_sweep(const TopoDS_Shape& body, const ScrewJoint& j, double T, double tol, double fit_tol,
                         double size, double* fit_err);

/// A swept set of dimension 1 or 2 (no volume) and its report: the faces of a surface in one
/// general fuse, so that overlapping sweeps count once, for the area too. Returns the result.
TopoDS_Shape finish_curve_or_surface(const TopoDS_Shape& shape, int dim, double size, double fit_err, bool verify,
                                     Report& rep);

/// A membership test that never looks at the computed solid, for the verdict, and its name for
/// the report; no test when none exists.
struct IndependentMembership {
  MemberTestMaker test;
  std::string name;
  /// The swept set's volume computed without the solid (the orbit-space integral of a primitive
  /// under one joint) to relative accuracy `rel_tol`, with an estimate of its error; empty when
  /// there is none.
  std::function<double(double rel_tol, double* error)> volume;
};
/// The entity's orbit intervals for a primitive under one joint, the trajectory's intersections
/// with the entity's own faces for other solids under one joint, for a surface under one joint its
/// trajectory against the surface and the parameter search where that misses it (decision 0023),
/// the certified search over the joint box for primitives under chains and for points, curves and
/// surfaces otherwise. `clipped`: the
/// motion with no revolute joint beyond a whole turn; `raw`: the entity before the motion's home.
IndependentMembership independent_membership(const RunEntity& entity, const Motion& clipped, const TopoDS_Shape& raw,
                                             double size, const Settings& settings);

/// The checks of the final solid, which fill in the report: the reason it fails, or empty. Bands
/// come from the requested tolerance and the model size, never from what the computation achieved.
class FinalChecks {
 public:
  /// `fit_err`: the computation's fitting error (read at each check: a rebuild can change it);
  /// `cells_built`: a solid stage was built from the arrangement of cells (the solid is then held to
  /// the independent volume too); `no_test`: why there is no verdict when `independent` is empty.
  FinalChecks(Report& rep, IndependentMembership independent, const Eigen::AlignedBox3d& true_box, double tol,
              double size, const double& fit_err, const Settings& settings, bool cells_built, std::string no_test);
  std::string operator()(const TopoDS_Shape& solid);
  /// The checks of `result`, which an invalid solid passes once healed (then `result` is the
  /// healed solid and result_healed() is true) and a solid with a geometric error passes with its pcurves
  /// projected again: the reason it fails, or empty.
  std::string judge(TopoDS_Shape& result);
  /// Whether the last judge() healed the solid.
  bool result_healed() const { return healed_; }
  /// Whether the last failure is one that a face left out by pruning can cause (a missing or
  /// wrong piece of boundary); a geometric error or an undecided verdict is not.
  bool rebuild_may_help() const { return rebuild_may_help_; }
  bool geometric_error() const { return geometric_error_; }
  static const std::string invalid;

 private:
  std::string verdict(const TopoDS_Shape& solid);
  Report& rep_;
  /// The volume against the independent volume, for solids built from cells (empty when it agrees).
  std::string independent_volume_check();
  IndependentMembership independent_;
  Eigen::AlignedBox3d true_box_;
  double tol_, size_;
  const double& fit_err_;
  const Settings& settings_;
  bool cells_built_;
  std::string no_test_;
  bool rebuild_may_help_ = false, geometric_error_ = false, healed_ = false;
};

/// The Monte Carlo volume of --verify into the report, in the solid's box enlarged by 1 % of the
/// model size, with a membership independent of the one that classified the cells.
void monte_carlo_check(const RunEntity& entity, const Motion& clipped, const TopoDS_Shape& raw,
                       const TopoDS_Shape& result, double size, const Settings& settings, Report& rep);

/// Each variety's share of the result's boundary (area and divergence volume): a face of the
/// result lies on the surface of the candidate it was cut from, or, merged from several, on the
/// candidates its sample points lie on.
void attribute_result_faces(Candidates& cands, const TopoDS_Shape& result, double size);

}  // namespace sweep::occt
