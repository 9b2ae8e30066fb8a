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
  /// grow to this many fit errors, the closest classification offset stays above it, and points of
  /// a ball's screw-swept tube may lie this many of its fit errors from the half balls they are
  /// projected on.
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
  /// Two angles closer than this (radians) are one: an arc of a circle whose end meets its start
  /// runs a whole turn, and a rotation this close to a whole turn is one.
  static constexpr double angle_resolution = 1e-12;
  /// A face whose parameter range falls short of its surface's period, or of a sphere's poles, by
  /// less than this spans it whole.
  static constexpr double whole_period_margin = 1e-9;
  /// A point nearer a rotation axis than this (x the local scale: a sphere's radius, a ball's
  /// radius plus the screw's pitch) lies on it.
  static constexpr double on_axis_resolution = 1e-9;
  /// Two areas that differ by less than this fraction are one: the pieces of a split face cover
  /// it, a spherical patch has its exact area, two candidate faces may be the same face.
  static constexpr double area_relative_tolerance = 1e-6;
  /// The resolution (absolute) below which a surface's derivatives vanish when its normal is
  /// computed at a sampled point.
  static constexpr double normal_resolution = 1e-9;
  /// An edge's tolerance is raised to this many times its measured distance from the face it
  /// lies on (its curve on the face, or the face's surface).
  static constexpr double edge_tolerance_margin = 1.5;

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
  /// the traced face's parameters (per side) and its tracer's flat value (x size), how far (x size)
  /// a traced point may lie from the other surface and still be on the crossing, and within what
  /// distance (x size) a side of the traced face lies on the other surface (the distance vanishes
  /// along it: no crossing is traced).
  static constexpr int traced_section_grid = 60;
  static constexpr double traced_section_flat = 1e-12;
  static constexpr double traced_section_stray = 1e-6;
  static constexpr double traced_section_side_on = 1e-7;
  /// Profiles that meet at a smaller sine of their angle are left to OCCT's general section (their
  /// crossing is too ill-conditioned to place along the profiles).
  static constexpr double orbit_section_min_sine = 1e-3;
  /// Candidate faces whose boxes, widened by this many times the boundary's resolution (the points
  /// it takes as one), meet are tested for a common surface and for crossings.
  static constexpr int candidate_box_gap = 10;
  /// How far a section may lie from a face's boundary and still run along it: at least this many
  /// times the boundary's resolution (fit_error_margin fit errors, when that is more).
  static constexpr int section_boundary_margin = 100;
  /// A closed edge of a body's face is its seam along u (v) when its ends' u (v) agree within this
  /// (x one plus the face's u (v) range).
  static constexpr double seam_end_resolution = 1e-9;
  /// Points are projected onto a surface, to test whether an edge lies on it within a distance, to
  /// this precision (x that distance).
  static constexpr double on_surface_projection = 0.01;
  /// A crossing traced where a grazing curve's sweep touches a face splits each face of the pair
  /// whose surface it lies on within this many tolerances.
  static constexpr int touching_on_face = 10;
  /// A piece is classified at its points on a grid of this many cells per side of its parameter
  /// box; when none decides, at up to this many points stepped in across its edges, in steps (x the
  /// edge's chord in the parameter plane) from the first down to the second, a third as long each
  /// time, kept where the piece's classifier (this tolerance, absolute in its parameters) finds
  /// them inside.
  static constexpr int classify_grid = 4;
  static constexpr int classify_edge_samples = 12;
  static constexpr double edge_sample_first_step = 0.25;
  static constexpr double edge_sample_min_step = 1e-4;
  static constexpr double edge_sample_classifier_tolerance = 1e-12;
  /// Two faces of the solid lie on one surface of revolution when their frames and sizes agree
  /// within this many times the largest tolerance of its faces (such faces whose angles turn
  /// opposite ways are not merged).
  static constexpr int same_domain_tolerances = 10;

  // --- crossings of faces swept along one joint's orbits (orbit_section.cpp)
  /// A face follows the orbits when some of its points lie this far from the joint's axis and it
  /// spans this far along the orbits (x the distance within which it follows them); under a helical
  /// joint, when it spans more than the second (radians of the joint).
  static constexpr double orbit_patch_extent = 1e3;
  static constexpr double orbit_patch_min_turn = 1e-6;
  /// A curve on a face lies on a side of the face's parameter box when its points are within this
  /// of the side (x one plus the magnitudes of the box's bounds).
  static constexpr double box_side_resolution = 1e-9;
  /// Intervals each profile is sampled on (a polyline) to find where profiles cross.
  static constexpr int orbit_profile_samples = 96;
  /// A solve for a crossing starts where two sample segments pass within this many times the
  /// polylines' bound on their distance from the profiles (per profile), plus the second times
  /// the boundary tolerance.
  static constexpr int orbit_near_sags = 4;
  static constexpr int orbit_near_tols = 10;
  /// Where two profiles come closest: damped Gauss-Newton steps, at most this many; the damping
  /// (x the largest diagonal entry of J^T J) starts at, and falls no lower than, the second; the
  /// solve gives up when it rises above the third, and stops at a step below the fourth (x one plus
  /// the parameter).
  static constexpr int profile_solve_iterations = 100;
  static constexpr double profile_solve_damping = 1e-12;
  static constexpr double profile_solve_max_damping = 1e8;
  static constexpr double profile_solve_step = 1e-15;
  /// Sample polylines that pass within this (x one plus the size of the point's profile
  /// coordinates) cross: when no crossing of the profiles is found there, the pair is left to OCCT's
  /// general section.
  static constexpr double polyline_crossing_rounding = 1e-12;
  /// Two crossings of two profiles closer than this (x each profile's parameter range) are one (a
  /// crossing found again from another start); where a profile crosses itself, two crossings, or a
  /// cut and an end or another cut, closer than the second are one.
  static constexpr double crossing_found_again = 1e-6;
  static constexpr double self_crossing_apart = 1e-7;
  /// A crossing along a helix is fitted through its points on this many intervals per quarter turn,
  /// doubled up to the second while the fit strays.
  static constexpr int helix_section_samples_first = 8;
  static constexpr int helix_section_samples_last = 128;
  /// The pieces of a face cut where its profile crosses itself: a side of a piece shorter than this
  /// (absolute) is a degenerate edge.
  static constexpr double profile_piece_degenerate = 1e-7;

  // --- crossings traced as the zero set of a distance (touching_section.cpp)
  /// Bisections that end a run of traced points where it leaves a face or passes a time where the
  /// sweep's faces meet; a point within the second of such a time (x one plus the time) lies on it.
  static constexpr int traced_run_bisections = 50;
  static constexpr double traced_break_rounding = 1e-12;
  /// Within this (x the range) of the touching time, the distance divided by the square of the time
  /// from it is interpolated (rounding would dominate it there).
  static constexpr double touching_time_band = 1e-3;
  /// A run of a touching crossing reaching less than this (x size) is a point where the grazing
  /// curve meets the joint's axis (its orbit is that point, on the copy at every time): no crossing.
  static constexpr double touching_run_min_reach = 1e-4;

  // --- section curves refitted onto both faces (section_refit.cpp)
  /// A point on both faces near a section point: Newton steps, at most this many, until it lies on
  /// both within the second (x tol), the precision also of the projections that measure the
  /// refitted curve's distance from the surfaces.
  static constexpr int point_on_both_iterations = 30;
  static constexpr double section_point_precision = 1e-3;
  /// An edge is refitted only when its curves on both faces span its 3-D curve's parameter range,
  /// within this (x one plus the bound).
  static constexpr double refit_range_resolution = 1e-9;
  /// The refitted points may lie this many of the edge's tolerances from its curve.
  static constexpr int refit_stray_tolerances = 10;
  /// Intervals of the points the curve is refitted through: the first tried, doubled up to the last
  /// while the fit strays.
  static constexpr int refit_samples_first = 32;
  static constexpr int refit_samples_last = 512;

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
  /// The steps of the central differences of g on a face (x its parameter domain): its gradient,
  /// and the gradient's own differences (the Hessian at a saddle where two arcs cross).
  static constexpr double envelope_gradient_step = 1e-7;
  static constexpr double envelope_hessian_step = 1e-5;
  /// Newton's steps onto an arc or a saddle stop below this (x the parameter domain).
  static constexpr double envelope_newton_stop = 1e-15;
  /// An interpolated arc shorter than this where it is met (x the parameter domain) has no
  /// direction: the point goes along the gradient of g instead.
  static constexpr double envelope_arc_degenerate = 1e-9;
  /// An arc ends where it crosses another when the gradient of g there is below this fraction of
  /// its size in the arc's middle.
  static constexpr double envelope_saddle_gradient = 1e-3;
  /// A point is on a side of a face's domain within this (x the domain's extent in that parameter).
  static constexpr double grazing_side_rounding = 1e-9;
  /// The double root of g on a side of its face (where an arc appears or vanishes): the step of
  /// g's differences along the side (x its length), Newton's stops in the side's parameter (x its
  /// length) and in t (x 1 + |t|), and the least second derivative of g along the side, against
  /// g's rates, that makes the root a double one and not a pole's.
  static constexpr double side_root_step = 1e-5;
  static constexpr double side_root_stop = 1e-13;
  static constexpr double side_root_time_stop = 1e-15;
  static constexpr double side_root_curvature = 1e-6;

  // --- motions that are screws (stage_motion.cpp: paths taken as one screw, keyframe segments)
  /// A path is one screw when every sampled twist lies within this (x the path's speed) of that
  /// screw's at some rate, and the screw's poses move the body as the path does to within
  /// screw_pose_match (x the body's reach).
  static constexpr double screw_twist_match = 1e-9;
  static constexpr double screw_pose_match = 1e-10;
  /// Rounding in recognising screws (relative): a turning too slow to count against the sliding,
  /// rates that change sign, a pitch of zero, a keyframe rotation of no angle, a rotation axis that
  /// vanishes, and two keyframe segments on one screw.
  static constexpr double screw_rounding = 1e-12;
  /// Bounds on a path's rates, computed in rounded arithmetic from enclosures, are widened by this
  /// (relative).
  static constexpr double rate_bound_rounding = 1e-12;

  // --- joints recognised from assembly constraints (kinematics.cpp), the image membership
  /// A pivot of a screw system's echelon form below this (x its largest entry) is zero: the
  /// system's rank.
  static constexpr double screw_rank_rounding = 1e-9;
  /// Rounding in the screw systems and the joints read from them (relative): parallel directions,
  /// ties between components, components cleaned to zero.
  static constexpr double kinematics_rounding = 1e-12;
  /// The damping of the image membership's Gauss-Newton steps (x the trace of J J^T).
  static constexpr double image_newton_damping = 1e-12;
  /// A point is in the image when the membership's Gauss-Newton brings its residual below this
  /// (x size).
  static constexpr double image_newton_residual = 1e-10;
  /// A joint moves an entity along one of its own parameters when its velocity is that
  /// parameter's derivative times one rate at every sample, and its poses shift the parameter, to
  /// this (relative; x size for the poses).
  static constexpr double parameter_shift_match = 1e-9;

  // --- solids under general motions (the candidate patches' arrangement)
  /// Solids other than balls under a path that is no screw are built from their candidate patches
  /// (off: they fail as not supported yet).
  bool general_motions = false;
  /// How many times a patch that no single fitted B-spline holds is halved (patch_faces).
  static constexpr int patch_face_splits = 4;
  /// A patch's face on the surface of its form: its sides sampled on this many intervals, each a
  /// line, circle or ellipse when every sample lies on it within the second (x the side's size, at
  /// least 1); its error measured on a grid of this many intervals per side.
  static constexpr int patch_side_samples = 64;
  static constexpr double patch_side_rounding = 1e-13;
  static constexpr int patch_error_grid = 16;
  /// A ruled patch runs straight along a parameter within this (x tol); its two sides are fitted on
  /// this many intervals, then four and sixteen times as many; its error is measured on a grid of
  /// this many intervals per side; a side of its face shorter than this (x tol) is degenerate.
  static constexpr double ruled_straightness = 1e-3;
  static constexpr int ruled_side_samples = 64;
  static constexpr int ruled_error_grid = 24;
  static constexpr double ruled_face_degenerate = 1e-3;
  /// A patch fitted as a B-spline surface: the grid's intervals per side doubling from the first to
  /// the last, the fitter's own tolerance at the grid points (x tol), and the least tolerance of its
  /// face (x tol).
  static constexpr int patch_fit_grid_first = 16;
  static constexpr int patch_fit_grid_last = 256;
  static constexpr double patch_fit_approx = 0.1;
  static constexpr double patch_face_min_tolerance = 1e-9;

  // --- faces swept by a curve under one screw joint (sweep_curve)
  /// Points a curve is sampled at to tell whether the motion slides it along itself, whether it
  /// lies on a rotation axis, and whether it is a line or a circle (canonical_curve).
  static constexpr int curve_slide_samples = 16;
  static constexpr int curve_on_axis_samples = 32;
  static constexpr int canonical_curve_samples = 64;
  /// A point of a curve slower than this under the joint (absolute) stays put: it does not tell
  /// whether the curve slides along itself.
  static constexpr double still_speed = 1e-12;
  /// A curve within this (x size) of a line or a circle is that line or circle: points of a
  /// grazing curve (roots of n . v to rounding), and the least tolerance an edge of the entity is
  /// recognised with.
  static constexpr double canonical_curve_rounding = 1e-10;
  /// A segment whose direction makes a cosine below this with a revolute joint's axis lies across
  /// the axis: it sweeps a planar region.
  static constexpr double planar_segment_cosine = 1e-12;
  /// Curves are cut where their axial coordinate turns and where they meet a rotation axis: the
  /// points sampled to bracket those places, the bisections that locate them, and how near an end
  /// (x the curve's parameter range) a cut makes no piece.
  static constexpr int profile_cut_samples = 64;
  static constexpr int profile_cut_bisections = 80;
  static constexpr double profile_cut_end = 1e-7;
  /// A curve whose axial coordinate spans less than this (x one plus its largest value) keeps to a
  /// plane across the axis (it has no axial turns); its axial slope vanishes where it is below the
  /// second (x its largest sampled value).
  static constexpr double profile_axial_flat = 1e-9;
  static constexpr double profile_slope_zero = 1e-12;
  /// A circle recognised from fitted points lies on a sphere or a torus about the rotation axis
  /// when it misses it by at most this (x tol: its fitting error), or by rounding: x the circle's
  /// scale (the distance of its axis from the rotation axis), x the torus's size (its ends).
  static constexpr double recognised_circle_slack = 0.01;
  static constexpr double circle_axis_rounding = 1e-12;
  static constexpr double torus_end_rounding = 1e-9;
  /// Spheres swept exactly by arcs: an arc whose ends' latitudes differ by less than the first
  /// (radians) sweeps nothing; a latitude within the second of a pole is on it (the zone or patch
  /// is left to the general revolution).
  static constexpr double sphere_latitude_span_min = 1e-9;
  static constexpr double sphere_pole_margin = 1e-7;
  /// The relative precision of a spherical patch's integrated area (checked against its exact
  /// area).
  static constexpr double sphere_patch_area_precision = 1e-9;
  /// Points at which an edge's curve on a face is compared with its 3-D curve (tighten_pcurves, and
  /// the solid's measured geometric error).
  static constexpr int pcurve_gap_samples = 23;

  // --- grazing curves of a face of the body at one instant (grazing_curves)
  /// The contour grid over the face's parameters (cells along u and along v) and the tracer's
  /// flat value (x size plus the velocity's reach).
  static constexpr int grazing_curve_grid_u = 61;
  static constexpr int grazing_curve_grid_v = 59;
  static constexpr double grazing_curve_flat = 1e-9;
  /// A point of the face is a pole of its parametrisation where |Su x Sv| is below this
  /// x (|Su| + |Sv|); the normal there is read this far inside the domain (x its parameter range).
  static constexpr double parametric_pole = 1e-12;
  static constexpr double pole_normal_offset = 1e-7;
  /// A point is moved onto a grazing curve along the gradient of n . v: the gradient's
  /// finite-difference step (x the parameter range), and the longest step (x the larger side of the
  /// parameter domain; near a crossing of two branches the gradient vanishes).
  static constexpr double grazing_gradient_step = 1e-7;
  static constexpr double grazing_point_step = 0.01;
  /// The precision (absolute) of the projections of points onto a face's surface.
  static constexpr double surface_projection_precision = 1e-12;
  /// Points of a grazing curve closer than this (absolute) are one to the interpolator that fits
  /// a cubic through them.
  static constexpr double grazing_interpolation_tolerance = 1e-12;
  /// Points each boundary edge of the face is sampled at for the roots of n . v (the exact ends of
  /// the grazing curves that leave the face).
  static constexpr int grazing_boundary_samples = 400;
  /// Bisections that put the end of a grazing curve on the face's trimmed boundary.
  static constexpr int grazing_boundary_bisections = 60;
  /// The tolerance of the classifier of points against the face's trimmed domain (x the larger
  /// side of its parameter box).
  static constexpr double parameter_resolution = 1e-9;
  /// How far (x the parameter range) a grazing curve along the face's boundary is probed on both
  /// sides: where the face lies on both, the boundary is a seam and the curve is interior.
  static constexpr double seam_probe_offset = 1e-6;
  /// A run of a grazing curve inside the face shorter than this (x size) makes no curve.
  static constexpr double grazing_curve_min_length = 1e-7;
  /// Points at which a grazing edge's distance from the face's surface is measured.
  static constexpr int grazing_edge_samples = 64;

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

  // --- a ball swept by a screw, built directly as a tube and two half balls (helical_tube.cpp)
  /// The sweep is one tube and two half balls when the reach of the centre's helix exceeds the
  /// radius by this (x the radius) or this many tolerances, whichever is larger (else neighbouring
  /// turns may meet).
  static constexpr double ball_tube_margin = 1e-6;
  static constexpr int ball_tube_margin_tol = 100;
  /// The lower bound of the helix's chords over a range of angles is taken on at least this many
  /// samples, spaced at most this (x the radius / the helix's speed) apart.
  static constexpr int helix_chord_samples = 64;
  static constexpr double helix_chord_spacing = 0.01;
  /// The first zero of the chords' growth (past half a turn) is bracketed on this many samples of
  /// the next half turn, then bisected this many times.
  static constexpr int helix_turn_samples = 256;
  static constexpr int helix_turn_bisections = 60;
  /// The most spans of the B-spline fitted to the helices of the grazing circle's poles.
  static constexpr int ball_tube_max_spans = 512;
  /// A point's distance from the helix: samples along the range, then safeguarded Newton steps,
  /// at most this many, until a step is below this (x one plus the angle).
  static constexpr int helix_distance_samples = 24;
  static constexpr int helix_distance_iterations = 60;
  static constexpr double helix_distance_precision = 1e-14;
  /// Roots bracketed along the tube (the times a ball's surface passes a point, the ends of the
  /// covered arcs): regula falsi steps, at most this many, until the bracket is below this (x one
  /// plus its lower end).
  static constexpr int helix_root_iterations = 100;
  static constexpr double helix_root_precision = 1e-15;
  /// More than a turn and a half, neighbouring turns meeting: how far (x the radius) the helix's
  /// radius of curvature and its chords must stay above their limits (r and 2 r), the samples of
  /// the start circle that find the arcs the neighbouring turns cover (then located on this many
  /// samples of the tube's start row), and the angle of the screw on either side of the start
  /// within which balls are left out of that test (they touch the start circle).
  static constexpr double overlap_margin = 1e-3;
  static constexpr int overlap_circle_samples = 360;
  static constexpr int overlap_arc_samples = 720;
  static constexpr double overlap_local_gap = 0.05;
  /// The curves of the tongues in a face's parameters: the most spans of their fits, the margin on
  /// the number of spans that the error's fall predicts to reach the tolerance, and the largest
  /// degree and most segments of the 3-D curves built from them.
  static constexpr int tongue_fit_max_spans = 256;
  static constexpr double tongue_fit_span_margin = 1.25;
  static constexpr int tongue_edge_max_degree = 14;
  static constexpr int tongue_edge_max_segments = 200;
  /// Points of the tube's tongue are projected onto a half ball by Gauss-Newton steps, at most
  /// this many, until a step is below this (absolute, in the ball's parameters); the projections
  /// may miss the ball by fit_error_margin of the tube's fit errors plus this rounding (x size),
  /// and the ball's tongue stays below this latitude (x pi).
  static constexpr int ball_projection_iterations = 30;
  static constexpr double ball_projection_step = 1e-13;
  static constexpr double ball_projection_rounding = 1e-12;
  static constexpr double ball_tongue_latitude_max = 0.45;
  /// The guard that samples the covered set: points whose squared distance from the nearest ball
  /// centre is within this (x the radius squared) of the radius squared are not compared; its grid
  /// on the tube (along the motion, around the circle), the rings of its grid on each half ball,
  /// and the points of the polygon that stands for a ball's tongue.
  static constexpr double overlap_guard_band = 1e-4;
  static constexpr int overlap_guard_grid_u = 40;
  static constexpr int overlap_guard_grid_v = 48;
  static constexpr int overlap_guard_ball_rings = 16;
  static constexpr int overlap_guard_polygon = 200;
  /// The faces of an overlapping sweep are sewn across this many fit errors (when that is more
  /// than the sewing gap).
  static constexpr int overlap_sewing_fit_errors = 20;

  // --- a stage's candidate faces (stage_candidates.cpp, candidate_pruning.cpp)
  /// Curve pieces revolved by less than a turn lie on one surface of revolution when their axial
  /// ranges and radii agree within this (x size); the radii are sampled at heights found by this
  /// many bisections; their angular ranges cover the whole turn when the gaps between their starts
  /// exceed the range by no more than this (radians).
  static constexpr double same_profile_distance = 1e-7;
  static constexpr int profile_height_bisections = 100;
  static constexpr double revolve_cover_slack = 1e-9;
  /// Faces whose normals along a shared edge differ by less than this angle (radians) meet
  /// smoothly there; the motion is tangent to a face where |n . v| is at most this x |v|.
  static constexpr double smooth_edge_angle = 1e-9;
  static constexpr double tangent_motion = 1e-9;
  /// A point of a face slower than this under the motion (x size) lies on the axis: it does not
  /// tell which way the motion meets the face.
  static constexpr double on_axis_speed = 1e-12;
  /// The tolerance (absolute, in a face's parameters) of the classifiers that tell which of a
  /// face's sampled points lie inside it.
  static constexpr double face_sample_classifier_tolerance = 1e-9;
  /// Two candidate faces are one when their areas agree, their boxes agree within the first
  /// (x size), and sampled points of each lie within the second (x size) of the other.
  static constexpr double duplicate_box_tolerance = 1e-6;
  static constexpr double duplicate_face_distance = 1e-7;
  /// A candidate is internal when its sampled points are inside the swept set just off both its
  /// sides: at this offset (x size) by the stage's membership test, or else by the trajectory test
  /// (its tolerance x size) at the larger of the second offset (x size) and this many fit errors.
  static constexpr double prune_offset = 1e-4;
  static constexpr double prune_fine_offset = 1e-7;
  static constexpr int prune_fine_fit_errors = 20;
  static constexpr double prune_trajectory_tolerance = 1e-10;
  /// A face of the body at an end of the range is internal by the sign of n . v alone where the
  /// range moves each of its sampled points along the normal by more than this many offsets.
  static constexpr int prune_sign_reach = 10;
  /// A dropped candidate is restored when a free edge of the arrangement passes within this
  /// (x size) of it.
  static constexpr double restore_distance = 1e-5;

  // --- building a stage from the arrangement of its candidate faces
  /// A stage whose arrangement of the candidates left after pruning fails its checks is built
  /// again from every candidate when they are at most this many (the arrangement's time grows
  /// fast with their number: 390 faces take about 20 minutes).
  std::size_t rebuild_candidate_limit = 200;
  /// A point inside a cell is sought this far (x size) inward from points of its faces, then ten and
  /// a hundred times closer; in a thin cell, at the middle of a ray's way across it, the ray starting
  /// this far (x size) off the face and the point classified at this tolerance (x size).
  static constexpr double cell_interior_offset = 1e-3;
  static constexpr double thin_cell_ray_start = 1e-7;
  static constexpr double thin_cell_classifier = 1e-10;
  /// A cell with no interior point and a volume below this (x size^3) is a sliver of nothing.
  static constexpr double sliver_cell_volume = 1e-9;
  /// OCCT's cell builder can build no cell at one fuzzy value and every cell at a neighbouring one:
  /// when it builds none, the fuzzy value this many times smaller, then larger, is tried.
  static constexpr double arrangement_fuzzy_factor = 10;

  // --- the trajectory membership test (trajectory.cpp)
  /// The membership by trajectories meets each point's path with the body's faces over pieces of
  /// the path, each cut once its tangent has turned by more than this angle (radians; OCCT's
  /// curve-face intersector samples the range it is given and steps over short chords through a
  /// face on a longer one), its turning summed at this many points of the path (a piece may pass
  /// the angle by the turning between two of them).
  static constexpr double trajectory_piece_turn = 0.7853981633974483;
  static constexpr int trajectory_turn_samples = 32;
  /// The reach of the body's centre over the motion is sampled at this many intervals.
  static constexpr int path_reach_samples = 256;
  /// A point nearer a revolute joint's axis than this (absolute) does not move: it has no path.
  static constexpr double path_on_axis = 1e-12;
  /// A point's helix fitted on its own: on at least this many intervals, at most pi / the second
  /// (radians of the joint) apart.
  static constexpr int helix_path_min_samples = 16;
  static constexpr int helix_path_samples_per_half_turn = 32;
  /// The motion's inverse poses, fitted once for every path: spans from the first, doubled up to the
  /// second (the third under a screw, whose paths have a way out: each point's own).
  static constexpr int path_fit_spans_first = 4;
  static constexpr int path_fit_spans_max = 1024;
  static constexpr int screw_path_fit_spans_max = 256;
  /// The running cost of each of its two tests (the cheaper goes first) starts from this (seconds).
  static constexpr double membership_cost_prior = 1e-3;

  // --- the verdict: the solid against a membership test that does not use it
  /// Points sampled uniformly in the box that holds the swept set.
  std::size_t verdict_samples = 4096;
  /// Points on the solid's faces, each tested just outside and just inside the boundary.
  std::size_t verdict_probes = 512;
  /// How far off the boundary the probes lie (x tol).
  double probe_offset = 4;
  /// Probes lie at least this many probe offsets, plus the deflection, from the solid's edges.
  static constexpr int probe_edge_clearance = 10;
  /// Where the membership cannot decide at the probe offset, the offset grows up to the deflection,
  /// which it may pass by this rounding (relative).
  static constexpr double probe_offset_rounding = 1e-12;
  /// Probes are tested in batches of this many (when almost every probe of the first is undecided,
  /// the rest are not tried).
  static constexpr std::size_t probe_batch = 64;
  /// Linear deflection of the triangulation the samples are classified against (x size); samples
  /// within three deflections plus the tolerance of the triangulated boundary are left out (the
  /// probes test that band).
  double verdict_deflection = 2e-3;
  /// When no mesh at that deflection passes its checks, a finer one at this fraction of it is made.
  static constexpr double verdict_finer_deflection = 0.25;
  /// An edge whose polyline within the deflection fails is cut into this many segments (the
  /// distance of probes from the solid's edges).
  static constexpr int edge_polyline_segments = 16;
  /// A face without triangles is a hole in the mesh when its area exceeds this (x the mesh's area)
  /// and pi deflection^2; a face's triangles cover it when they miss at most this fraction of its
  /// area plus the second (absolute), or pi deflection^2.
  static constexpr double mesh_missing_area = 1e-9;
  static constexpr double mesh_area_loss = 0.05;
  static constexpr double mesh_area_loss_floor = 1e-9;
  /// The mesh is closed when every triangle side is shared, vertices matched on a grid of this step
  /// (x the mesh's size).
  static constexpr double mesh_side_resolution = 1e-9;
  /// Triangles are boxed in groups of this many for the regions rays keep off (faces their
  /// triangles do not cover).
  static constexpr int region_triangle_group = 16;
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

  // --- the solid's checks on its own boundary (solid_checks.cpp)
  /// The relative precision of OCCT's adaptive volume integral of the solid's faces.
  static constexpr double brep_volume_precision = 1e-10;
  /// A face on an extrusion of a spline is integrated on the surface's exact B-spline form over the
  /// face's parameter box widened by the first (x its range along the curve), and by the second
  /// (x its range along the extrusion) plus the third (absolute); the form is taken when its points
  /// agree with the surface's within the fourth (x one plus their distance from the origin).
  static constexpr double bspline_form_curve_margin = 1e-9;
  static constexpr double bspline_form_extrusion_margin = 1e-3;
  static constexpr double bspline_form_extrusion_floor = 1e-9;
  static constexpr double bspline_form_rounding = 1e-12;

  // --- --verify
  /// Monte Carlo samples of the independent volume (one joint; chains take an eighth, at least 20000).
  std::size_t mc_samples = 400000;
};

}  // namespace sweep
