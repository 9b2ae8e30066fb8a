#pragma once
// Whether a point is inside a solid by rays against its exact faces: the crossings of a half-line
// from the point counted, and the first one's transition. The verdict's second opinion where the
// triangulated solid disagrees with the membership test, and the trajectory test's start point.
#include <BRepAdaptor_Surface.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <Bnd_Box.hxx>
#include <IntCurvesFace_Intersector.hxx>

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "base/internal.hpp"
#include "sweep/orbit.hpp"

namespace sweep::occt {

/// A face's box and its intersector, which samples the face once for every line or curve it
/// meets; a face on a plane, quadric or torus also keeps that surface's implicit form and a
/// classifier of its parameter domain (the orbits of a screw meet it by the roots of the implicit
/// function along them).
struct FaceHit {
  Bnd_Box box;
  std::unique_ptr<IntCurvesFace_Intersector> inter;
  std::unique_ptr<BRepAdaptor_Surface> surface;
  std::optional<OrbitSurface> implicit;
  std::unique_ptr<BRepTopAdaptor_FClass2d> fc;
};

/// The implicit form of a face's surface when it is a plane, cylinder, cone, sphere or torus.
std::optional<OrbitSurface> implicit_surface(const BRepAdaptor_Surface& s);

/// Whether the point p of the surface of face h (its implicit form set) lies on the face within
/// tol: in or on its parameter domain. Unknown (nullopt) when p is farther than tol from the surface.
std::optional<bool> on_face(const FaceHit& h, const Eigen::Vector3d& p, double tol);

/// The faces of `shape`, the analytic ones (intersected in closed form) first; boxes widened by tol.
std::vector<FaceHit> face_hits(const TopoDS_Shape& shape, double tol);

/// Whether x is inside the solid whose faces are `faces` by rays from it: 1 inside, 0 outside, -1
/// when no ray of three gives a clear answer (x on the boundary within tol, a ray tangent to or
/// grazing a face, the count of crossings and the first one's transition at odds).
int ray_inside(std::vector<FaceHit>& faces, const Eigen::Vector3d& x, double tol);

}  // namespace sweep::occt
