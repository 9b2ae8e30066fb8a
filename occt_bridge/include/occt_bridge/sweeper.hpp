#pragma once
/// @file sweeper.hpp
/// The swept solid of a spec as an OCCT B-rep, its validation and its report. This header holds
/// no OCCT type: the shape travels as an opaque handle.
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "sweep/spec.hpp"

namespace sweep::occt {

/// Settings with their defaults.
struct RunOptions {
  bool verify = false;                 ///< add the Monte Carlo volume (--verify)
  std::size_t mc_samples = 400000;     ///< Monte Carlo sample count
  std::uint64_t mc_seed = 20261123;    ///< fixed, so runs are deterministic
  /// Called with a short line at each step of a long run (the CLI prints it on a terminal).
  std::function<void(const std::string&)> progress;
};

/// Report v1 (SPEC.md), plus `dimension` (3 solid, 2 surface, 1 curve, 0 point).
struct Report {
  std::string status = "failed";
  std::string message;
  double volume_brep = 0, volume_divergence = 0;
  bool has_mc = false;
  double volume_mc = 0, volume_mc_stderr = 0;
  double area = 0;
  double centroid[3] = {0, 0, 0};
  double bbox_min[3] = {0, 0, 0}, bbox_max[3] = {0, 0, 0};
  bool valid = false, closed = false;
  int faces = 0, varieties = 0, dimension = 3, cells = 0;
  double tol_requested = 0, tol_achieved = 0;
  double seconds_total = 0;
  nlohmann::json seconds = nlohmann::json::object();

  bool ok() const { return status == "ok"; }
  nlohmann::json to_json() const;
};

/// The computed shape (an OCCT TopoDS_Shape inside).
class Shape;

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
