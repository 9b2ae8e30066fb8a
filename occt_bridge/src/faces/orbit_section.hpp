#pragma once
// Where two faces swept along one joint's orbits cross. A revolute joint's orbits are circles about
// its axis, a prismatic joint's are lines along its direction, a helical joint's are helices (whose
// profiles lie in a plane across the axis: faces whose profiles never meet there never cross). A face that is a rectangle in the
// parameters of a surface one of whose parameters runs along the orbits (a curve's sweep by the
// joint: surfaces of revolution, coaxial cylinders, cones, spheres and tori under a revolute joint;
// extrusions, planes and cylinders along a prismatic joint's direction) is a profile curve in the
// plane across the orbits (the meridian (r, z), or the projection along the direction) carried
// through a range of the orbit coordinate (an angle, or a distance). Two such faces cross in orbit
// arcs (circles or segments) at the points where their profiles cross, over the overlap of their
// ranges: a 2-D problem solved here exactly, instead of a general surface-surface intersection.
#include <optional>
#include <vector>

#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <Geom_Surface.hxx>

#include "sweep/motion.hpp"

namespace sweep::occt {

/// A face as a profile carried along the joint's orbits.
struct OrbitPatch {
  TopoDS_Face face;
  bool orbit_is_u = true;  ///< whether u (else v) is the parameter along the orbits
  double a0 = 0, a1 = 0;   ///< the orbit parameter's range
  double b0 = 0, b1 = 0;   ///< the profile's parameter range
  /// The orbit coordinate (radians or length) per unit of the orbit parameter, signed: negative
  /// when the parameter runs against the joint's direction.
  double rate = 1;
};

/// The face as an orbit patch of joint j, or nothing when it is not one: moving along its orbit
/// parameter must move its points along the joint's orbits (checked at sample points to `eps`)
/// and its boundary must be the four iso-lines of its parameter box. Under a helical joint only
/// with `helix_tol` > 0: a B-spline face fitted to a helical sweep, whose points follow the helices
/// to `helix_tol` (its fit error).
std::optional<OrbitPatch> orbit_patch(const TopoDS_Face& face, const ScrewJoint& j, double eps, double helix_tol = 0);

/// The profile parameters where the patch's profile crosses itself over a common range of the
/// orbits (the face passes through itself there, as the extrusion of a curve whose projection along
/// the direction loops), and halfway between the two places of each crossing: cut there, the
/// pieces are embedded and none begins and ends on one line. Sorted; empty when there is none.
std::vector<double> profile_self_crossings(const OrbitPatch& patch, const ScrewJoint& j, double boundary_tol);

/// A piece of a patch cut where its profile crosses itself: a face on the patch's surface, and the
/// sheet it lies on (the surface trimmed to the piece's profile range, with the same parameters).
struct PatchPiece {
  TopoDS_Face face;
  Handle(Geom_Surface) sheet;
};

/// The patch cut at those profile parameters into faces over its whole orbit range (empty when a
/// face cannot be made).
std::vector<PatchPiece> patch_pieces(const OrbitPatch& patch, const std::vector<double>& cuts);

/// A copy of a piece of such a face (the same pcurves) on its sheet, so that curves projected onto
/// it (as sewing does where it joins edges) land on that sheet, not on the other sheet through the
/// same points.
TopoDS_Face on_own_sheet(const TopoDS_Face& piece, const Handle(Geom_Surface)& sheet);

/// The orbit arcs where patches a and b cross, leaving out arcs on either's boundary (within
/// `boundary_tol`), or nothing when their profiles touch, run along each other or cross at a
/// small angle: the caller then intersects the faces in general. Under a helical joint the arcs
/// are the curves where the faces' own (fitted) surfaces cross along those helices, each within
/// a tenth of `boundary_tol` of both (the largest such distance goes to *fit_err when given).
/// Profiles that touch at a small angle but run within `contact_band` of each other from there
/// into an end they share (two arms of a cusp of the grazing curve's profile) meet at that end
/// only: a crossing between them is below the tolerance. Safe to call from several threads at once.
std::optional<std::vector<TopoDS_Edge>> orbit_section(const OrbitPatch& a, const OrbitPatch& b, const ScrewJoint& j,
                                                      double boundary_tol, double* fit_err = nullptr,
                                                      double contact_band = 0);

}  // namespace sweep::occt
