// The elliptic cylinder entity (SPEC.md `elliptic_cylinder`), seed 003's cutter shape.
#pragma once

#include <TopoDS_Shape.hxx>

#include "sweep/spec.hpp"

namespace sweep::occt {

/// The solid in the entity's frame (placement not applied): untwisted, the extrusion of an exact
/// ellipse; twisted, the side fitted within `tol` as a B-spline closed by the two exact elliptic
/// caps (*fit_error raised to the side's measured error).
TopoDS_Shape elliptic_cylinder_shape(const EntitySpec& e, double tol, double* fit_error);

}  // namespace sweep::occt
