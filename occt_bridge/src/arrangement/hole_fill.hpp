#pragma once
// Holes of a sewn shell that one face fills exactly (sewing it in with the others turns it to
// match its neighbours).
#include <BRepBuilderAPI_Sewing.hxx>
#include <TopoDS_Face.hxx>

#include <vector>

namespace sweep::occt {

/// The indices of the faces that each fill a hole of the sewn shape: every (not degenerate) edge
/// of such a face matches a free edge of the sewing, its ends and middle within `gap`.
std::vector<std::size_t> faces_filling_holes(const std::vector<TopoDS_Face>& faces, const BRepBuilderAPI_Sewing& sewing,
                                             double gap);

}  // namespace sweep::occt
