#pragma once
// Where two faces turned about one axis cross. A face that is a rectangle in the parameters of a
// surface whose u is the angle about a revolute joint's axis (a curve's sweep by the joint:
// surfaces of revolution, coaxial cylinders, cones, spheres, tori) is the meridian curve v -> (r, z)
// turned through an angle range. Two such faces cross in circles about the axis, at the points
// where their meridians cross, over the overlap of their angle ranges: a 2-D problem solved here
// exactly, instead of a general surface-surface intersection.
#include <optional>
#include <vector>

#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include "sweep/motion.hpp"

namespace sweep::occt {

/// A face as a meridian turned through an angle range about the joint's axis.
struct RevolutionPatch {
  TopoDS_Face face;
  double u0 = 0, u1 = 0;        ///< the angle parameter's range
  double v0 = 0, v1 = 0;        ///< the meridian's parameter range
  int sense = 1;                ///< +1 when u turns positively about the joint's direction
};

/// The face as a revolution patch about joint j's axis, or nothing when it is not one: its surface
/// must turn about the axis with u (checked at sample points to `eps`) and its boundary must be the
/// four iso-lines of its parameter box.
std::optional<RevolutionPatch> revolution_patch(const TopoDS_Face& face, const ScrewJoint& j, double eps);

/// The circular arcs where patches a and b cross, leaving out arcs on either's boundary (within
/// `boundary_tol`), or nothing when their meridians touch, run along each other or cross at a
/// small angle: the caller then intersects the faces in general. Safe to call from several
/// threads at once.
std::optional<std::vector<TopoDS_Edge>> revolution_section(const RevolutionPatch& a, const RevolutionPatch& b,
                                                           const ScrewJoint& j, double boundary_tol);

}  // namespace sweep::occt
