#pragma once
/// @file settings.hpp
/// Every tolerance and sampling constant of a run, with its default. "x size" marks a fraction of
/// the model size (the largest extent of the box that holds the swept set), "x tol" a multiple of
/// the requested tolerance.
#include <cstddef>
#include <cstdint>

namespace sweep {

struct Settings {
  // --- tolerances
  /// The requested tolerance when the spec gives none (x size).
  double default_tolerance = 1e-6;
  /// Fitted curves and surfaces are fitted to this (x tol), so that their error stays well inside
  /// the requested tolerance.
  double fit_fraction = 0.01;
  /// B-rep and divergence volumes may differ by this relative amount (the two integrations'
  /// rounding), plus tol times the model's surface scale (size^2).
  double volume_relative_band = 1e-9;
  /// A one-joint sweep of a primitive whose solid came from the arrangement of cells is checked
  /// against the volume integrated over the joint's orbits (sweep/orbit.hpp), to this relative
  /// accuracy (0: not checked).
  double independent_volume_rel_tol = 1e-5;

  // --- geometric resolution (constants of the kernel)
  /// Two points closer than this are one (x size): the fuzzy value of OCCT's booleans and splits,
  /// the tolerance of its classifiers, the resolution of the memberships' searches.
  static constexpr double resolution = 1e-9;
  /// Faces are sewn, and cells fused, across gaps up to this (x size), or a multiple of the fit
  /// error when that is larger.
  static constexpr double sewing_gap = 1e-7;
  /// How many measured fit errors apart two fitted curves or surfaces may lie and still meet: the
  /// sewing gap, the arrangement's fuzzy value and how far a section may lie from a face's boundary
  /// grow to this many fit errors, and the closest classification offset stays above it.
  static constexpr double fit_error_margin = 10;
  /// Two directions within this angle (radians) are parallel: axes of surfaces on one line, planes
  /// of one orientation, cones of one semi-angle.
  static constexpr double parallel_angle = 1e-9;

  /// Linear deflection of the triangulation behind a B-rep solid's distance bound (x the entity's
  /// size; the bound's slack is measured on it).
  static constexpr double brep_distance_deflection = 1e-4;
  /// A mesh's vertices closer than this (x the mesh's size) are one vertex (an STL file repeats each
  /// vertex in every triangle, rounded alike).
  static constexpr double mesh_vertex_merge = 1e-12;
  /// Neighbouring triangles of a mesh whose normals differ by less than this angle (radians) make one
  /// planar face.
  static constexpr double mesh_coplanar_angle = 1e-9;

  // --- building a stage's solid from its sweep boundary
  /// How far off a piece of the candidate boundary its two sides are tested (x size), and again at
  /// twice that; a piece is kept when exactly one side is in the swept set.
  double classify_offset = 2e-6;
  /// When the kept pieces do not close: the smallest offset (x size) down to which those tests are
  /// repeated, eight times closer each time (another sheet within classify_offset of a piece turns
  /// both probes); the closest answers that agree at both offsets decide. Never below ten times
  /// the pieces' fit error.
  double classify_finest_offset = 5e-9;
  /// A face whose pieces come out of OCCT's splitter with tolerances above this many requested
  /// tolerances is split again, its section curves given curves on it from points projected onto
  /// its surface (off: the splitter's pieces are kept).
  bool curves_on_faces = true;
  static constexpr double reprojected_split_ratio = 100;
  /// The most points a section curve is sampled at to fit its curve on a face it splits (doubling
  /// from 16 until the fit is within the fitting tolerance).
  static constexpr int curve_on_face_max_samples = 1024;
  /// Two candidate faces swept along a revolute or prismatic joint's orbits cross in circles or
  /// segments where their profiles cross: found so in the plane across the orbits (off: OCCT's
  /// general section of every pair).
  bool orbit_sections = true;
  /// The sweep of a grazing curve touches the copies of the face the curve lies on along the
  /// curve: their crossings are traced where the distance divided by the square of the time from
  /// the touching copy vanishes (off: OCCT's general section, which stalls or strays there).
  bool touching_sections = true;
  /// A candidate face crossing a face on a torus crosses it where the torus's exact distance
  /// vanishes over the other face's parameters: traced so (off: OCCT's general section, which walks
  /// for seconds on two tori).
  bool torus_sections = true;
  /// A fitted sweep crossing a face on a plane, cylinder, cone or sphere (a copy of the body) crosses
  /// it where that surface's exact distance vanishes over the sweep's parameters: traced so (off:
  /// OCCT's general section, 0.2 s a pair under a helical joint).
  bool spline_sections = true;
  /// Traced crossings (touching, torus and spline sections): the grid of the contour search over
  /// the traced face's parameters (per side), how far (x size) a traced point may lie from the
  /// other surface and still be on the crossing, and within what distance (x size) a side of the
  /// traced face lies on the other surface (the distance vanishes along it: no crossing is traced).
  static constexpr int traced_section_grid = 60;
  static constexpr double traced_section_stray = 1e-6;
  static constexpr double traced_section_side_on = 1e-7;
  /// Profiles that meet at a smaller sine of their angle are left to OCCT's general section (their
  /// crossing is too ill-conditioned to place along the profiles).
  static constexpr double orbit_section_min_sine = 1e-3;

  // --- grazing sets followed over a motion's range (grazing_family.hpp)
  /// Events of a grazing set are located by bisection to this fraction of the range.
  static constexpr double grazing_event_resolution = 1e-9;
  /// The most events one face's grazing set may have over a range (a set that changes more often
  /// is reported incomplete).
  static constexpr int grazing_events_max = 256;
  /// Instants a grazing set is traced at over a range (besides the events' bisections), and the
  /// cells per side of the grid it is traced on.
  static constexpr int grazing_instants = 32;
  static constexpr int grazing_grid = 64;
  /// The fewest intervals a span between two events is traced at (instants are added evenly where
  /// the range's instants leave fewer in it).
  static constexpr int grazing_span_intervals = 8;
  /// The flat value of a grazing set's tracer (contour.hpp), x the largest |g| on the face: two
  /// arcs cross where |g| at the saddle of a cell is below a hundred times it.
  static constexpr double grazing_crossing = 1e-11;
  /// Tracks and grazing sides over less than this fraction of the range (slivers between two
  /// events) make no candidate.
  static constexpr double grazing_sliver = 1e-6;
  /// How far (x the range) an arc that appears from or vanishes into a point of a side of its face
  /// is followed past the traced instants to that point (grazing_family: the traced sets see such
  /// an arc only once it spans a node of their grid).
  static constexpr double grazing_event_reach = 0.05;
  /// The longest Newton step that puts a point of an envelope sheet on its grazing arc (x the
  /// face's parameter domain).
  static constexpr double envelope_newton_step = 0.01;

  // --- solids under general motions (the candidate patches' arrangement)
  /// Solids other than balls under a path that is no screw are built from their candidate patches
  /// (off: they fail as not supported yet).
  bool general_motions = false;
  /// How many times a patch that no single fitted B-spline holds is halved (patch_faces).
  static constexpr int patch_face_splits = 4;

  // --- faces swept by a curve under a helical joint, fitted to grids of exact points
  /// The grid's intervals per side: the first tried, doubled up to the last while the fit's
  /// measured error exceeds its tolerance.
  static constexpr int helical_fit_grid_first = 12;
  static constexpr int helical_fit_grid_last = 96;
  /// The fitter's own tolerance at the grid points (x the face's fit tolerance).
  static constexpr double helical_fit_approx = 0.05;
  /// How many times a span of the curve that no grid fits to the tolerance is halved.
  static constexpr int helical_fit_splits = 4;
  /// The share of a face's tolerance that the polynomial helices of a tensor-product helical face
  /// may stray from the exact sweep (sweep_curve).
  static constexpr double helical_spline_share = 0.01;

  // --- building a stage from the arrangement of its candidate faces
  /// A stage whose arrangement of the candidates left after pruning fails its checks is built
  /// again from every candidate when they are at most this many (the arrangement's time grows
  /// fast with their number: 390 faces take about 20 minutes).
  std::size_t rebuild_candidate_limit = 200;

  // --- the verdict: the solid against a membership test that does not use it
  /// Points sampled uniformly in the box that holds the swept set.
  std::size_t verdict_samples = 4096;
  /// Points on the solid's faces, each tested just outside and just inside the boundary.
  std::size_t verdict_probes = 512;
  /// How far off the boundary the probes lie (x tol); probes lie at least ten times that from the
  /// solid's edges.
  double probe_offset = 4;
  /// Linear deflection of the triangulation the samples are classified against (x size); samples
  /// within three deflections plus the tolerance of the triangulated boundary are left out (the
  /// probes test that band).
  double verdict_deflection = 2e-3;
  /// Sub-boxes a joint-space search may split for one verdict point (chains); a point it cannot
  /// decide is left out and counted as undecided.
  std::size_t membership_budget = 20000;
  /// A joint-space search looks for a joint and entity value that reaches the point by damped
  /// Gauss-Newton; it gives up on a start whose iteration leaves more than this fraction of the
  /// residual (a local minimum off the point: the search splits the box and starts again).
  static constexpr double membership_newton_stall = 0.5;
  /// The largest fraction of the verdict's samples that may be undecided (undecided probes are
  /// reported only).
  double undecided_fraction = 0.1;
  /// One-sided confidence of the bound on the volume of the symmetric difference.
  double confidence = 0.95;
  /// Seed of every sampler (runs are deterministic).
  std::uint64_t seed = 20261123;

  // --- --verify
  /// Monte Carlo samples of the independent volume (one joint; chains take an eighth, at least 20000).
  std::size_t mc_samples = 400000;
};

}  // namespace sweep
