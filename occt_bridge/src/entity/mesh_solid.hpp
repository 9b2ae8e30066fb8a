// A `mesh` entity's file (STL or OFF) as an OCCT solid of planar faces.
#pragma once

#include <TopoDS_Shape.hxx>

#include "sweep/spec.hpp"

namespace sweep::occt {

/// The solid a mesh file bounds, scaled by the spec's `scale` (placement not applied): the triangles
/// read (STL, ASCII or binary, its repeated vertices merged; or OFF), checked to bound a solid
/// and not to cross itself (sweep/triangle_mesh.hpp), turned outward when they face inward, and made planar faces, the
/// coplanar neighbours of each merged into one. @throws InputError at /entity/file when the file
/// cannot be read or does not bound a solid; ComputeError when OCCT cannot make a valid solid of it.
TopoDS_Shape mesh_solid(const EntitySpec& e);

}  // namespace sweep::occt
