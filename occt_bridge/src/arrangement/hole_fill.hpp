#pragma once
// Holes of a sewn shell that one face fills exactly (sewing it in with the others turns it to
// match its neighbours), and faces kept across such holes.
#include <BRepBuilderAPI_Sewing.hxx>
#include <TopoDS_Face.hxx>

#include <vector>

namespace sweep::occt {

/// The indices of the faces that each fill a hole of the sewn shape: every (not degenerate) edge
/// of such a face matches a free edge of the sewing, its ends and middle within `gap`.
std::vector<std::size_t> faces_filling_holes(const std::vector<TopoDS_Face>& faces, const BRepBuilderAPI_Sewing& sewing,
                                             double gap);

/// The indices of the faces that leave a hole of the sewn shape open by lying across it: every
/// (not degenerate) edge of such a face is free in the sewing, or has two other faces on it (the
/// face is a third sheet at that edge), and one at least is free. Without them the neighbours
/// that meet at those edges close the hole.
std::vector<std::size_t> faces_left_over(const std::vector<TopoDS_Face>& faces, const BRepBuilderAPI_Sewing& sewing,
                                         double gap);

}  // namespace sweep::occt
