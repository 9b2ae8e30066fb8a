// Points of a face with their outward normals, and how a motion meets the face: the sign of
// n . v over it, for the end copies of both engines (the sweep boundary of a joint, the candidates
// of a general motion).
#pragma once

#include <BRepAdaptor_Surface.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pnt.hxx>
#include <gp_Pnt2d.hxx>
#include <gp_Vec.hxx>
#include <vector>

#include "sweep/stage_motion.hpp"

namespace sweep::occt {

/// A point of a face with its outward normal (the face's orientation applied).
struct SurfacePoint {
  gp_Pnt p;
  gp_Vec n;
};
/// Appends the point of face f at uv with its outward normal, when the normal is defined.
bool add_surface_point(const BRepAdaptor_Surface& S, const TopoDS_Face& f, const gp_Pnt2d& uv,
                       std::vector<SurfacePoint>& out);
/// Points inside a face with their outward normals, on an n x n grid of its parameter box (offset
/// by irrational fractions of a cell, off the middle lines of symmetric faces).
std::vector<SurfacePoint> face_samples(const TopoDS_Face& f, int n);

/// The motion leaves the face behind where n . v < 0 (Back), moves into what lies in front of it
/// where n . v > 0 (Front), slides within it where n . v = 0 everywhere; Mixed when both signs
/// occur (a face no grazing curve split), Unknown when no sample tells.
enum class Facing { Back, Front, Slides, Mixed, Unknown };

/// The facing of `f` (its orientation applied to its normal) in the velocity field at points of
/// a 7 x 7 grid inside it. Points where the field is slower than 1e-12 of `size` (on a rotation's
/// axis) tell nothing; n . v / |v| within 1e-9 of zero counts as sliding.
Facing facing_of(const TopoDS_Face& f, const VelocityField& field, double size);

}  // namespace sweep::occt
