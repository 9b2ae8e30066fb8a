#pragma once
// Section curves made ready to split a face.
// - A curve that stops just short of where it ends: near a tangential contact (a sweep touching
//   the copy it came from along a grazing curve) OCCT's section of two faces can end a little
//   before the curve it runs into. The splitter then keeps it as a dangling internal edge and the
//   face is not split there.
// - A curve with no curve on the face's surface: the splitter projects it itself, and on a surface
//   of revolution of a spline it can raise the tolerances of the pieces to a tenth of the model.
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include <vector>

namespace sweep::occt {

/// For each end of the curves `tools` that split `face`: when it lies farther than the tolerances
/// of its vertex and the nearest edge from every edge of the face's boundary and every other
/// curve, but within `max_gap` of one, its vertex's tolerance is raised to reach that edge (so the
/// splitter joins them). Returns how many ends were bridged. Changes the tools' vertices in place:
/// never while a split that shares them runs.
int bridge_section_ends(const TopoDS_Face& face, const std::vector<TopoDS_Edge>& tools, double max_gap);

/// Gives each of `tools` that has none a curve on `face`'s surface, its points projected and
/// interpolated until the surface along it is within `target` of the edge, or the closest such fit
/// when that is within `accept` (the edge's tolerance grows to the distance measured; a curve that
/// runs a little past the end of a swept surface lies off it there); a tool no fit brings within
/// `accept` is left to the splitter. Changes the tools in place, like bridge_section_ends.
/// Returns how many were added.
int add_curves_on_face(const TopoDS_Face& face, const std::vector<TopoDS_Edge>& tools, double target, double accept);

}  // namespace sweep::occt
