// The checks of a solid that use its own boundary: OCCT's validity, closedness, OCCT's volume
// and the divergence volume, connected parts, tolerances; and OCCT's healing of an invalid solid.
#pragma once

#include <Bnd_Box.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Pnt.hxx>
#include <cmath>
#include <vector>

#include "occt_bridge/sweeper.hpp"

namespace sweep::occt {

/// How far two volumes of a solid may differ: a band `tol` wide over its whole boundary (`area`),
/// plus rounding.
inline double volume_band(double tol, double area, double volume) { return tol * area + 1e-9 * std::abs(volume); }

/// What the validation measures on a solid: OCCT's validity, closedness, OCCT's adaptive volume
/// and the divergence volume computed independently in the faces' parameter domains with the area
/// at the same quadrature points, and the box (check_solid: tasks on the machine's cores that only
/// read the shape).
struct SolidChecks {
  bool valid = false, closed = false;
  double volume_brep = 0, volume_divergence = 0, area = 0;
  gp_Pnt centroid;
  Bnd_Box box;
  /// Valid, closed, with a positive volume on which both integrals agree within volume_band.
  bool agree(double tol) const {
    return valid && closed && volume_brep > 0 &&
           std::abs(volume_brep - volume_divergence) <= volume_band(tol, area, volume_brep);
  }
};

/// The checks, as tasks on the machine's cores that only read the shape.
SolidChecks check_solid(const TopoDS_Shape& result);

/// Closed: every shell of every solid has each edge used twice, with opposite orientations.
/// Checked solid by solid, so solids that touch along an edge do not count as open.
bool closed_solids(const TopoDS_Shape& shape);

/// OCCT's shape healing of a solid that fails OCCT's validity check (as a self-intersecting wire
/// of one face left by the union of a stage's cells); null when the healed shape is not valid
/// either. The caller checks the healed solid like any other.
TopoDS_Shape healed(const TopoDS_Shape& s);

/// The number of connected groups among the solids, two solids being connected when they come
/// within `gap` of each other.
int separate_parts(const std::vector<TopoDS_Shape>& parts, double gap);

/// The largest tolerance of the shape's vertices and edges.
double max_tolerance(const TopoDS_Shape& s);

/// The report's centroid and box.
void set_centroid_and_box(Report& rep, const gp_Pnt& c, const Bnd_Box& bb);

}  // namespace sweep::occt
