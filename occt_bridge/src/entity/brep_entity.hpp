// A solid (or a set of faces) read from a B-rep file as the engine's Entity.
#pragma once

#include <TopoDS_Shape.hxx>

#include "sweep/entity.hpp"

namespace sweep::occt {

/// The entity of a B-rep shape, placement applied (`shape` as entity_shape gives it):
/// - its box, from the exact faces;
/// - its faces as trimmed patches on their exact surfaces (Patch::trimmed: the face's surface over
///   its parameter box), its edges as patches on their exact curves (seams and degenerate edges
///   left out), each with its closed form when it has one;
/// - for a solid, an inside test and a signed distance bound. The bound is the distance to a
///   triangulation of the faces less the triangulation's deviation from them (measured at the
///   triangles' centroids and sides' midpoints, and doubled), signed by the triangulation's ray
///   parity. Within twice that deviation of the triangles the side is not known: the bound is
///   then the smallest positive double, which says neither inside nor any distance, and its
///   slack() (so tight_distance() is false). The inside test is exact: OCCT's classifier near the
///   faces. The triangulation is made at the bound's first use, which throws ComputeError when
///   it is not closed.
/// `kind`: what the spec named it (brep, or mesh for a polyhedron read from a triangle mesh).
EntityPtr brep_entity(const TopoDS_Shape& shape, EntityKind kind = EntityKind::Brep);

}  // namespace sweep::occt
