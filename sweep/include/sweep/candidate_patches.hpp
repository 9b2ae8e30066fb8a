#pragma once
/// @file candidate_patches.hpp
/// The candidate boundary varieties of an entity under a one-parameter motion, as patches (000,
/// section 3; 001): the entity's faces at both ends of the range (limit varieties), its creased
/// edges swept over the range (boundary varieties), and the envelope sheets its faces' grazing
/// arcs sweep between the events of their grazing sets (interior varieties). Under any motion, a
/// screw's included; the bridge makes faces of them.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sweep/entity.hpp"
#include "sweep/stage_motion.hpp"

namespace sweep {

struct CandidatePatch {
  std::string type;  ///< "limit", "boundary" or "interior" (as the varieties report names them)
  PatchPtr patch;    ///< its map; patch->what() says what it is
  /// Parameters it fixes with their values, and those it leaves free with their ranges.
  std::vector<std::pair<std::string, double>> fixed;
  std::vector<std::pair<std::string, std::pair<double, double>>> free;
  /// For an end copy and an envelope sheet, the index of the entity's face it comes from (-1 else).
  int face = -1;
};

/// Whether any of the entity's faces is trimmed (Patch::trimmed): its candidate patches are not built
/// yet.
bool has_trimmed_faces(const Entity& entity);

/// Every candidate patch of `entity` under `motion`, limit varieties first, then boundary and
/// interior ones. `check` is called between patches (a stop request may throw from it). Throws
/// ComputeError for an entity with trimmed faces (B-rep solids).
std::vector<CandidatePatch> candidate_patches(const Entity& entity, const std::shared_ptr<const StageMotion>& motion,
                                              const std::function<void()>& check = {});

/// A plane: its points x with normal . x = offset (normal of unit length).
struct PatchPlane {
  Eigen::Vector3d normal;
  double offset = 0;
};

/// The plane a two-parameter patch lies in, when every point of an n x n grid of its domain lies
/// within `tol` of one plane and the points span it (not all on one line); empty otherwise. Under a
/// motion that keeps a plane, the sweeps of curves lying in it fill regions of it (folded where a
/// curve moves along itself), which no single face holds.
std::optional<PatchPlane> patch_plane(const Patch& patch, double tol, int n = 8);

/// The area of a two-parameter patch: the 4-point Gauss rule on n x n panels of its domain.
double patch_area(const Patch& patch, int n = 32);

}  // namespace sweep
