#pragma once
// The verdict on a computed solid: points sampled in a box that holds the true swept set, and
// points just off the solid's faces, classified against the solid and by a membership test that
// never looks at the solid. Any disagreement away from the boundary makes the result fail.
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "base/internal.hpp"
#include "sweep/mesh_index.hpp"
#include "sweep/settings.hpp"

namespace sweep::occt {

/// The triangles of a shape's faces, outward for a solid (BRepMesh at linear deflection
/// `deflection`, angular 0.5 rad; the shape keeps the triangulation). With `problem`, the
/// triangulation is checked: every face triangulated, covering its area (to 5 %, or to pi
/// deflection^2 on a small face), and closed;
/// *problem says what is wrong, or is empty. With `uncovered`, faces whose triangles do not cover
/// them are put there (with what is wrong in *problem's place) instead of making a problem.
std::vector<Triangle> triangulate(const TopoDS_Shape& shape, double deflection, std::string* problem = nullptr,
                                  std::vector<std::pair<TopoDS_Face, std::string>>* uncovered = nullptr);

struct VerdictResult {
  std::size_t samples = 0;        ///< points sampled in the box
  std::size_t near_boundary = 0;  ///< of those, left out for lying near the triangulated boundary
  std::size_t mismatches = 0;     ///< of the others, where the solid and the membership disagree
  std::size_t undecided = 0;      ///< of the others, where the membership did not decide
  std::size_t probes = 0;         ///< points just outside and just inside the faces (pairs)
  std::size_t probe_mismatches = 0;
  std::size_t probe_undecided = 0;
  double probe_offset_max = 0;  ///< the largest offset at which a probe was decided
  double box_volume = 0;
  /// upper bound (at the settings' confidence) of the volume of the symmetric difference between
  /// the solid and the swept set, from the box samples (near-boundary ones counted as differing)
  double difference_bound = 0;
  std::string first_mismatch;  ///< where, for the message
  std::string classifier;  ///< what the box samples were classified against
  double undecided_fraction = 0.1;  ///< the most of the samples that may be undecided
  /// Undecided probes are reported and weaken nothing else: the samples decide.
  bool decided() const { return undecided <= undecided_fraction * samples; }
  bool ok() const { return mismatches == 0 && probe_mismatches == 0 && decided(); }
};

/// The verdict on `solid` against `member` (a membership test per thread, independent of the
/// solid, that may leave a point undecided). `box` holds the true swept set; `tol` is the requested tolerance and `size` the model
/// size.
VerdictResult judge_solid(const TopoDS_Shape& solid, const Eigen::AlignedBox3d& box, const MemberTestMaker& member,
                          double tol, double size, const Settings& settings);

/// The largest gap the shape's geometry has, measured rather than read from OCCT's tolerance
/// flags: between each edge's curve and its curve on each face (at 23 points), and between each
/// vertex and the ends of its edges' curves, in 3-D and on the faces. (Vertex tolerances at
/// points where edges meet tangentially are often far larger than any such gap.)
double measured_geometric_error(const TopoDS_Shape& shape);

/// One-sided upper confidence bound of a binomial proportion with k of n (Wilson's score interval).
double proportion_upper_bound(std::size_t k, std::size_t n, double confidence);

}  // namespace sweep::occt
