#pragma once
/// @file envelope.hpp
/// The envelope sheet a face's grazing arc sweeps while the motion carries it (000's interior
/// varieties, 001's envelopes): (s, t) -> M(t) x(s, t), with x(s, t) the point of the face at which
/// the arc traced at t reaches the fraction s of its length. Points are exact roots of the grazing
/// function at t (found by Newton from the track's interpolated arcs), so the sheet is tangent to
/// the moved face along the arc, whatever the motion.
#include <memory>
#include <string>

#include "sweep/entity.hpp"
#include "sweep/grazing_family.hpp"
#include "sweep/stage_motion.hpp"

namespace sweep {

/// The sheet swept by `track` (grazing_family's, traced on `face` under `motion`): a patch over
/// s in [0, 1] (along the arc; periodic when the arc is closed) and t over the track's instants.
/// Its derivatives follow the root as the interpolated point moves and the grazing function changes
/// with t (what is left out, the Newton line's turning times the root's distance from the
/// interpolated point, is of the order of the interpolation's error); its orientation is the one of
/// (ds, dt), which classification decides on later. The ends of an open
/// arc that lie on a side of the face's domain stay on that side (the sheet meets the sweep of the
/// face's edge there). Throws std::invalid_argument for a track with fewer than two instants.
PatchPtr envelope_patch(const PatchPtr& face, std::shared_ptr<const StageMotion> motion, const GrazingTrack& track,
                        const std::string& what);

}  // namespace sweep
