#pragma once
/// @file variety.hpp
/// The boundary varieties of one stage of a sweep as patches (000, section 3): the entity's faces
/// carried to the ends of the range (limit varieties), its edges swept over the range (boundary
/// varieties), and the grazing curves of its faces, where the motion is tangent to the face
/// (n . v = 0), which swept over the range make the envelope (interior varieties).
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "sweep/entity.hpp"
#include "sweep/settings.hpp"
#include "sweep/stage_motion.hpp"

namespace sweep {

/// The patch carried by the motion's pose at t: x -> M(t) x. It fixes t (a limit variety when t
/// is an end of the range).
PatchPtr moved_patch(const PatchPtr& patch, std::shared_ptr<const StageMotion> motion, double t,
                     const std::string& what);

/// The sweep of a curve patch over the motion's range: (s, t) -> M(t) c(s), a boundary variety.
/// Its orientation is the one of (dc/ds, dM/dt c), which classification decides on later.
PatchPtr swept_curve(const PatchPtr& curve, std::shared_ptr<const StageMotion> motion, const std::string& what);

/// The grazing function of a face at its parameters (u, v) at the pose `pose`: g = n . w, with
/// n = xu x xv (not normalised) and w = R^T (dR x + dp) the velocity of the body point x seen in
/// the body's frame. Its zero set is the face's grazing set at that instant.
double grazing_value(const Patch& face, const PoseJet& pose, double u, double v);

/// The rate of change in t of the grazing function at fixed face parameters (u, v):
/// dg/dt = n . (dR^T (dR x + dp) + R^T (ddR x + ddp)). Zero under a screw motion at constant rate
/// (its velocity field is the same in the body's frame at every t).
double grazing_rate(const Patch& face, const PoseJet& pose, double u, double v);

/// How a point of the grazing set moves across the face as t grows: the step in (u, v), normal to
/// the set's curve, that keeps g = 0 to first order, -g_t grad g / |grad g|^2 (gradient in the face's
/// parameters, by central differences of step h times the domain). Zero where g does not change
/// with t; not defined where grad g vanishes (a crossing of two branches: then zero).
Eigen::Vector2d grazing_drift(const Patch& face, const PoseJet& pose, double u, double v, double h = 1e-6);

/// The grazing points of one circle v = const of a face of revolution (PatchForm::revolved) at a
/// pose, in closed form (seed 003): there n is a combination of the circle's radial direction and
/// the axis, and w is affine in the point with a skew linear part, so g = A cos u + B sin u + C
/// exactly, with A, B, C from g at u = 0, pi/2 and pi. Its roots in [lo(0), lo(0) + 2 pi), none or
/// one (touching) or two; `whole` (when given) is set when g vanishes on the whole circle to
/// 1e-12 of `scale` (|g| at the face's size) and then no root is listed.
std::vector<double> grazing_roots_on_circle(const Patch& face, const PoseJet& pose, double v, double scale,
                                            bool* whole = nullptr);

/// The grazing set of a face at one instant, in its parameter domain.
struct GrazingSet {
  /// Polylines on which g vanishes (each point the root of g on an edge of the grid); a closed one
  /// repeats its first point at the end.
  std::vector<std::vector<Eigen::Vector2d>> curves;
  /// Sides of the domain (0: v = lo, 1: u = hi, 2: v = hi, 3: u = lo) along which g vanishes
  /// everywhere (the face grazes all along them: a seam line, a rim; or the side is a pole, where
  /// the normal vanishes).
  std::vector<int> sides;
};

/// The grazing set of `face` at time t, traced on a grid of about n x n cells of the domain
/// (marching squares: every sign change of g between grid points is found; curves closer together
/// than a grid cell may be joined; where two cross inside a cell they end at the crossing). The
/// counts of cells are odd, so that lines of symmetry of a face (its half and quarter turns) fall
/// inside cells rather than on grid lines.
GrazingSet grazing_set(const Patch& face, const StageMotion& motion, double t, int n = Settings::grazing_grid);

}  // namespace sweep
