#pragma once
/// @file drawing.hpp
/// Drawings of computed shapes: planar cross-sections of a solid (with their areas from OCCT
/// geometry) and a parallel projection of the boundary variety faces, both as SVG text. Like
/// sweeper.hpp this header holds no OCCT type.
#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "occt_bridge/sweeper.hpp"

namespace sweep::occt {

/// The cross-section of a solid by the plane z = const.
struct Section {
  double z = 0;
  double area = 0;  ///< area of the common of the solid with the plane (BRepGProp), 0 when empty
  int loops = 0;    ///< closed boundary loops (outer boundaries and holes), 0 when empty
  std::array<double, 2> bbox_min{0, 0}, bbox_max{0, 0};  ///< of the section; zeros when empty
  /// The outline, one polyline per loop, discretized for drawing only (never used for the area).
  std::vector<std::vector<std::array<double, 2>>> polylines;
  bool empty() const { return loops == 0; }
  /// {"z", "area", "loops", "bbox": [[xmin, ymin], [xmax, ymax]]}
  nlohmann::json to_json() const;
};

/// Settings of sections().
struct SectionOptions {
  /// Chordal deflection of the drawn outline as a fraction of the section's size. Must be positive.
  double relative_deflection = 1e-3;
};

/// Cuts `solid` by the planes z = heights[k] (finite). A plane that misses the solid gives an empty
/// section. @throws ComputeError when OCCT's boolean fails.
std::vector<Section> sections(const Shape& solid, const std::vector<double>& heights,
                              const SectionOptions& options = {});

/// The sections side by side, one panel per section on a common scale (equal in x and y), each
/// with its title, axis ticks, the region filled (even-odd, so holes show) and its area below.
std::string sections_svg(const std::vector<Section>& sections, const std::string& title);

/// Settings of varieties_svg().
struct VarietyDrawingOptions {
  /// Direction the view looks from (towards the viewer); z is drawn up. Must be non-zero and not
  /// along z.
  std::array<double, 3> view_from{1, 1, 1};
  /// Chordal deflection of the mesh as a fraction of the faces' size; raised until the mesh has at
  /// most `max_triangles` triangles, so the file stays small.
  double relative_deflection = 2e-3;
  int max_triangles = 40000;
};

/// The variety faces (`RunOptions::variety_faces`) in a parallel projection: triangle edges thin
/// and face boundaries thick, one colour per variety, grey for faces whose variety is unknown,
/// and a legend listing every variety of `varieties` (id = 1-based index, type, fixed parameters).
/// `face_variety[k]` is the 0-based index into `varieties` of the k-th face of `faces` (explorer
/// order), or -1 when unknown; missing entries count as unknown.
std::string varieties_svg(const Shape& faces, const std::vector<int>& face_variety,
                          const std::vector<Variety>& varieties, const std::string& title,
                          const VarietyDrawingOptions& options = {});

/// Writes `text` to `path` through a temporary file in the same directory renamed into place, so
/// no half-written file is left. @throws ComputeError when writing fails.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace sweep::occt
