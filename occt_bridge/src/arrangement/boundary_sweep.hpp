#pragma once
// One stage of a sweep built from its sweep boundary: the solid swept by a body under one screw
// joint is bounded by parts of (1) the body's faces that the motion leaves behind, at the start,
// (2) the faces it moves into, at the end, (3) the sweeps of the silhouette between them (grazing
// curves, where the velocity is tangent to a face, and edges between a face it leaves and one it
// moves into), and (4) for faces the motion slides within (n . v = 0 everywhere), the regions they
// sweep in their own surface. These candidates are split where they cross each other, and a piece
// is kept where one side of it is in the swept set and the other is not (by a membership test that
// does not use the candidates); the kept pieces are sewn into the solid, which fails unless it
// closes (as it is or healed) and is valid as it is.
#include <string>
#include <vector>

#include "base/internal.hpp"
#include "sweep/settings.hpp"

namespace sweep::occt {

struct BoundarySweep {
  TopoDS_Shape solid;   ///< null on failure
  std::string failure;  ///< why, when it failed
  double fit_error = 0;
  int candidates = 0, pieces = 0, kept = 0;
  /// how many pairs of a sweep and a copy it touches had their crossings traced
  /// (Settings::touching_sections; none under a helical joint)
  int touching_sections = 0;
  /// groups of candidates on one surface: those of one copy's faces (kept as they are), and the
  /// others, which OCCT's arrangement replaced
  int copy_groups = 0, arranged_groups = 0;
  /// the candidates' varieties and each candidate face's variety (an index into them)
  std::vector<Variety> varieties;
  std::vector<TopoDS_Face> candidate_faces;
  std::vector<int> candidate_ids;
  nlohmann::json seconds = nlohmann::json::object();
};

/// The solid swept by `body` (a solid, at the start of the range) under joint j over [0, T].
/// `member` makes membership tests of the swept set, independent of the boundary (one per thread);
/// `size` is the model size and `tol` the requested tolerance. `stage` and `joint_no` label the
/// varieties.
BoundarySweep boundary_sweep(const TopoDS_Shape& body, const ScrewJoint& j, double T, const PointTestMaker& member,
                             double size, double tol, const Settings& settings, int stage, int joint_no);

}  // namespace sweep::occt
