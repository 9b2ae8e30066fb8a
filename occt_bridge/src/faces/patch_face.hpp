#pragma once
// A core patch (sweep/entity.hpp) as an OCCT face: the one place where patches become faces.
#include <TopoDS_Face.hxx>
#include <vector>

#include "sweep/entity.hpp"

namespace sweep::occt {

struct PatchFace {
  TopoDS_Face face;    ///< oriented as the patch (outwards for a solid's face)
  bool exact = false;  ///< on the patch's closed form (else a fitted B-spline)
  double error = 0;    ///< the largest distance measured from patch points to the face's surface
};

/// The face of a two-parameter patch: on the exact plane, cylinder, cone, sphere or torus its form
/// names, over the patch's own parameters when they are the surface's, else bounded by the images
/// of the domain's sides (less those that collapse to a point or meet their opposite side); any
/// other patch as a B-spline fitted within `tol`. The error is measured on a grid of patch points.
/// @throws ComputeError when no face can be made.
PatchFace patch_face(const Patch& patch, double tol);

/// The faces of a two-parameter patch within `tol`: patch_face's, or, when its fitted B-spline is
/// not within `tol`, the faces of the two halves of the domain (split across its longer side in
/// space), and so on up to `max_splits` times; a part that still does not fit is kept with its
/// measured error.
std::vector<PatchFace> patch_faces(const Patch& patch, double tol, int max_splits);

}  // namespace sweep::occt
