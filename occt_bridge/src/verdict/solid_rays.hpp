#pragma once
// Whether a point is inside a solid by rays against its exact faces: the crossings of a half-line
// from the point counted, and the first one's transition. The verdict's second opinion where the
// triangulated solid disagrees with the membership test, and the trajectory test's start point.
#include <BRepAdaptor_Surface.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <Bnd_Box.hxx>
#include <IntCurvesFace_Intersector.hxx>
#include <gp_Torus.hxx>

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "base/internal.hpp"

namespace sweep::occt {

/// A face's box and its intersector, which samples the face once for every line or curve it
/// meets; a torus face also keeps its torus and a classifier of its parameter domain (curves that
/// are circles meet it in closed form).
struct FaceHit {
  Bnd_Box box;
  std::unique_ptr<IntCurvesFace_Intersector> inter;
  std::unique_ptr<BRepAdaptor_Surface> surface;
  std::unique_ptr<gp_Torus> torus;
  std::unique_ptr<BRepTopAdaptor_FClass2d> fc;
};

/// The faces of `shape`, the analytic ones (intersected in closed form) first; boxes widened by tol.
std::vector<FaceHit> face_hits(const TopoDS_Shape& shape, double tol);

/// Whether x is inside the solid whose faces are `faces` by rays from it: 1 inside, 0 outside, -1
/// when no ray of three gives a clear answer (x on the boundary within tol, a ray tangent to or
/// grazing a face, the count of crossings and the first one's transition at odds).
int ray_inside(std::vector<FaceHit>& faces, const Eigen::Vector3d& x, double tol);

}  // namespace sweep::occt
