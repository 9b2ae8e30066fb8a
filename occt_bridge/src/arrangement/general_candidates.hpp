// The candidate faces of a solid under a general one-parameter motion (decision 0027): the core's
// candidate patches made faces, sweeps lying in a plane the motion keeps replaced by a square of
// that plane, and the end copies split where the envelope sheets leave them.
#pragma once

#include <Eigen/Geometry>
#include <memory>

#include "arrangement/stage_sweep.hpp"
#include "sweep/candidate_patches.hpp"
#include "sweep/entity.hpp"
#include "sweep/stage_motion.hpp"

namespace sweep::occt {

/// The variety a candidate patch lies on (stage 1), for the report.
Variety candidate_variety(const CandidatePatch& c);

/// The candidate faces of `entity` under `motion`, with their varieties (stage 1): `reach` a box
/// that holds the swept set, `size` the model size, faces fitted within `fit_tol` (`fit_err` raised
/// to their largest measured error). An end copy of a face is split along the edges of the
/// envelope sheets that leave it (the face's grazing arcs at that end, where each sheet is tangent
/// to it), and only its pieces that can bound the set are kept: those the motion leaves behind at
/// the start, those it moves into at the end, those it slides within. A stop request is honoured
/// between steps.
Candidates general_candidates(const Entity& entity, const std::shared_ptr<const StageMotion>& motion,
                              const Eigen::AlignedBox3d& reach, double size, double fit_tol, double& fit_err);

}  // namespace sweep::occt
