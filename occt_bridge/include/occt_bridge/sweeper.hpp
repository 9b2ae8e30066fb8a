#pragma once
/// @file sweeper.hpp
/// The swept solid of a spec as an OCCT B-rep, its validation and its report. This header holds
/// no OCCT type: the shape travels as an opaque handle.
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sweep/settings.hpp"
#include "sweep/spec.hpp"

namespace sweep::occt {

/// The computed shape (an OCCT TopoDS_Shape inside).
class Shape;

/// One boundary variety of a stage (000_0a5975c48c1ac19b.txt, section 3): the parameters it fixes,
/// the ones left free with their domain, and for the last stage the part of it on the final
/// boundary with its divergence-theorem contribution to the volume (eq. 14).
struct Variety {
  int stage = 0;            ///< 1 = innermost joint's sweep
  int joint = 0;            ///< 1-based joint number, outermost first (SPEC.md)
  std::string type;         ///< "limit" (joint at a range end), "boundary" (an entity edge swept),
                            ///< "interior" (a grazing curve swept: Jacobian rank deficiency, n . v = 0)
  std::string what;         ///< a readable description
  nlohmann::json fixed = nlohmann::json::object();  ///< fixed parameters and values
  nlohmann::json free = nlohmann::json::object();   ///< free parameters and their domains
  int faces = 0;            ///< candidate faces built for it
  double area = 0;          ///< their area
  bool final_stage = false;
  double boundary_area = 0; ///< area of the final boundary lying on it (last stage only)
  double volume = 0;        ///< its contribution to the volume, 1/3 integral of x . n (last stage only)
  nlohmann::json to_json() const;
};

/// What a run does beyond the spec.
struct RunOptions {
  bool verify = false;                 ///< add the Monte Carlo volume (--verify)
  /// Build the shapes that have a direct construction (balls under screws, graph extrusions)
  /// directly; off, they go through the general pipeline like every other shape.
  bool direct_builds = true;
  Settings settings;                   ///< tolerances and sampling
  /// Called with a short line at each step of a long run (the CLI prints it on a terminal).
  std::function<void(const std::string&)> progress;
  /// Polled during the run (from several threads, so it must be thread-safe and cheap): a
  /// non-empty answer stops the run, which then reports `failed` with "stopped: " and the answer
  /// (a user's cancel, a time limit). OCCT's long algorithms poll it through their user break.
  std::function<std::string()> stop;
  /// When set, receives every boundary variety of every stage.
  std::vector<Variety>* varieties = nullptr;
  /// When set, receives the candidate faces of the last stage (a compound), for display.
  std::shared_ptr<const Shape>* variety_faces = nullptr;
  /// When set with `variety_faces`, receives the variety of each of those faces (in explorer order)
  /// as an index into `varieties` (or into the last stage's varieties when `varieties` is unset).
  std::vector<int>* variety_face_ids = nullptr;
};

/// A stop request for RunOptions::stop: `also`'s answer when it gives one, else "the time limit of
/// S s was reached" once `seconds` (> 0; 0: no limit) have passed since this call.
std::function<std::string()> stop_after(double seconds, std::function<std::string()> also = {});

/// Report v1 (SPEC.md), plus `dimension` (3 solid, 2 surface, 1 curve, 0 point).
struct Report {
  std::string status = "failed";
  std::string message;
  double volume_brep = 0, volume_divergence = 0;
  bool has_mc = false;
  double volume_mc = 0, volume_mc_stderr = 0;
  // samples of the Monte Carlo volume; under chains also the estimated volume of the symmetric
  // difference between the solid and the independent membership (from the samples where the two
  // disagree)
  bool mc_compared = false;
  std::size_t mc_samples = 0, mc_mismatches = 0;
  double volume_mc_mismatch = 0;
  double area = 0;
  double centroid[3] = {0, 0, 0};
  double bbox_min[3] = {0, 0, 0}, bbox_max[3] = {0, 0, 0};
  bool valid = false, closed = false;
  int faces = 0, varieties = 0, dimension = 3, cells = 0;
  /// stages (1 = innermost) built again from every candidate face after the solid built without
  /// the faces that sampling found inside the swept set failed its checks
  std::vector<int> unpruned_stages;
  /// stages whose solid failed OCCT's validity check and passed every check after OCCT's shape
  /// healing (ShapeFix_Shape)
  std::vector<int> healed_stages;
  /// solid stages built from the arrangement of cells (every stage of a chain after the first; the
  /// first when its sweep boundary did not close)
  std::vector<int> cell_stages;
  /// the swept set's volume integrated over the orbits without the solid, and its error estimate
  bool has_independent_volume = false;
  double volume_independent = 0, volume_independent_error = 0;
  /// (stage, faces): candidate faces that pruning had dropped, restored because the boundary
  /// pieces of the arrangement without them left free edges on them
  std::vector<std::pair<int, int>> restored_candidates;
  /// The verdict (SPEC.md `verify`): points in a box that holds the true swept set and points just
  /// off the solid's faces, classified against the solid and by a membership test that does not
  /// use it.
  bool has_verdict = false;
  std::size_t verdict_samples = 0, verdict_near_boundary = 0, verdict_mismatches = 0, verdict_probes = 0,
              verdict_probe_mismatches = 0, verdict_undecided = 0, verdict_probe_undecided = 0;
  double verdict_difference_bound = 0, verdict_box_volume = 0;
  double verdict_probe_offset = 0;  ///< the largest offset off the boundary at which a probe was decided
  std::string verdict_membership;  ///< which membership test judged
  std::string verdict_classifier;  ///< what the samples were classified against (the solid's triangulation, ...)
  double tol_requested = 0, tol_achieved = 0;
  double seconds_total = 0;
  nlohmann::json seconds = nlohmann::json::object();

  bool ok() const { return status == "ok"; }
  nlohmann::json to_json() const;
};

struct RunResult {
  Report report;
  std::shared_ptr<const Shape> shape;  ///< null when nothing could be built
};

/// Computes the swept set of `spec`, validates it and fills the report. Never throws for a
/// computation that fails: the report says `failed` with the reason. Throws InputError for input
/// found bad only while reading it (an unreadable STEP file).
RunResult run_sweep(const Spec& spec, const RunOptions& options = {});

/// Writes `shape` to `path` by extension (.step/.stp, .brep, .stl binary, .off). Writes to a
/// temporary file renamed into place, so no half-written file is left.
/// @throws InputError (pointer "-o") for an unknown extension; ComputeError when writing fails.
void write_shape(const Shape& shape, const std::string& path, double mesh_tolerance);

/// The shape as BRep text (for bindings) and the volume of a STEP/BREP file read back.
std::string shape_to_brep_string(const Shape& shape);
double file_volume(const std::string& path);

/// True when `path` ends with an extension write_shape() supports.
bool supported_output(const std::string& path);

}  // namespace sweep::occt
