#pragma once
// OCCT-side helpers shared by the bridge's translation units.
#include <Bnd_Box.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Geom_Curve.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Circ.hxx>
#include <gp_Pln.hxx>
#include <gp_Pnt.hxx>
#include <gp_Torus.hxx>
#include <gp_Trsf.hxx>
#include <gp_Vec.hxx>
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "occt_bridge/sweeper.hpp"
#include "sweep/entity.hpp"
#include "sweep/error.hpp"
#include "sweep/motion.hpp"
#include "sweep/orbit.hpp"
#include "sweep/spec.hpp"
#include "sweep/stage_motion.hpp"

namespace sweep::occt {

class Shape {
 public:
  explicit Shape(TopoDS_Shape s) : shape(std::move(s)) {}
  TopoDS_Shape shape;
};

inline gp_Pnt to_pnt(const Eigen::Vector3d& v) { return gp_Pnt(v.x(), v.y(), v.z()); }
inline gp_Vec to_vec(const Eigen::Vector3d& v) { return gp_Vec(v.x(), v.y(), v.z()); }
inline Eigen::Vector3d to_eigen(const gp_XYZ& p) { return {p.X(), p.Y(), p.Z()}; }
inline Eigen::Vector3d to_eigen(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
inline Eigen::Vector3d to_eigen(const gp_Vec& p) { return {p.X(), p.Y(), p.Z()}; }
gp_Trsf to_trsf(const Eigen::Isometry3d& T);
/// A copy of `s` under the rigid motion T.
TopoDS_Shape moved(const TopoDS_Shape& s, const Eigen::Isometry3d& T);

/// The entity as an OCCT shape in its own frame with its placement applied.
/// Solids for solid kinds, a face for `surface`, an edge for `curve`, a vertex for `point`.
/// `tol` is the fitting tolerance for parametric kinds; `fit_error` receives the measured error.
/// `core`: the core's entity of `e` when the caller has it (else it is built here).
TopoDS_Shape entity_shape(const EntitySpec& e, double tol, double* fit_error, const Entity* core = nullptr);
/// A primitive solid (sphere, box, cylinder, cone, torus) as the OCCT solid its core patches
/// (sweep/entity.hpp) make, each on its exact surface; null for other kinds.
TopoDS_Shape primitive_from_patches(const Entity& entity);

/// Fits a B-spline surface to exact(fu, fv), fu and fv fractions in [0, 1], on an (n+1)^2 grid, n
/// doubling from n0 to nmax until the distance measured between grid points is at most tol
/// (approximation tolerance approx_tol). The surface's parameters are uniform in the fractions.
/// Returns the fit with the smallest measured error (a finer grid can fit worse between its
/// points), null when no fit succeeds; *err receives the measured error of the surface returned.
Handle(Geom_BSplineSurface) fit_grid_surface(const std::function<gp_Pnt(double, double)>& exact, double tol,
                                             double approx_tol, int n0, int nmax, double* err);

/// Points sampled on a parametric curve or surface entity (placed), for its extent.
TopoDS_Shape sampled_points(const EntitySpec& e);

/// The entity's shape for its extent, before the tolerance is known: parametric curves and surfaces
/// as sampled points, every other kind as entity_shape builds it (within 1e-9; `core` as there).
TopoDS_Shape sizing_shape(const EntitySpec& e, double* fit_error, const Entity* core = nullptr);
/// The shape the stages sweep: `sizing` itself, but parametric curves and surfaces fitted within
/// fit_tol.
TopoDS_Shape fitted_entity_shape(const EntitySpec& e, const TopoDS_Shape& sizing, double fit_tol, double* fit_error);

/// A curve on a face where the motion's velocity is tangent to the face (n . v = 0), fitted to
/// tolerance, with the number of fitted points.
struct GrazingCurve {
  Handle(Geom_Curve) curve;
  double first = 0, last = 0;
  double error = 0;  ///< measured distance from the exact grazing curve (0 for lines and circles)
};
/// Grazing curves of a face (in its current position) under a velocity field: a screw joint's, or
/// a stage motion's at the instant the face is at. Faces whose whole surface is grazing (they slide
/// within themselves) give none.
std::vector<GrazingCurve> grazing_curves(const TopoDS_Face& face, const VelocityField& velocity, double tol,
                                         double size);
/// A grazing curve as an edge that splits its face: the curve in its canonical form (a line or a
/// circle where it is one, within tol) and an edge whose tolerance covers how far the curve strays
/// from the face (else a splitter takes a fitted curve for one beside the face and does not cut).
struct GrazingEdge {
  Handle(Geom_Curve) curve;
  double first = 0, last = 0;
  TopoDS_Edge edge;
};
GrazingEdge grazing_edge(const GrazingCurve& g, const TopoDS_Face& face, double tol);

/// How a curve's sweep under a helical joint becomes faces: the curve's poles carried along
/// polynomial helices (lines, conics and splines; other curves are fitted), or always fitted to grids
/// of exact points.
enum class HelicalFaces { Spline, Fitted };

/// The number of equal pieces of [0, T] that a curve turned or screwed through T is swept in (at most
/// a quarter turn each: such a piece never overlaps itself); its faces meet at the times T k / n.
inline int sweep_pieces(double T) { return std::max(1, int(std::ceil(T / (M_PI / 2) - 1e-9))); }

/// Faces swept by curve `c` (on [first,last]) under `joint` for q in [0, T]: exact surfaces of
/// revolution / extrusion, tensor-product or fitted B-spline surfaces for helical motions, one per
/// piece of at most a quarter turn (a fitted piece that no grid fits to `tol` is split into pieces of
/// the curve). `fit_error` is raised to the largest measured error from the exact sweep.
std::vector<TopoDS_Face> sweep_curve(const Handle(Geom_Curve)& c, double first, double last,
                                     const ScrewJoint& joint, double T, double tol, double* fit_error,
                                     HelicalFaces helical = HelicalFaces::Spline);

/// The sweep of c on [s0, s1] under the helical joint j for q in [q0, q1] (at most a half turn) as a
/// tensor-product spline: c as a B-spline (exact for lines, conics, Bezier and B-spline curves), each
/// of its poles carried along its helix with the rotation's cos and sin as Bezier polynomials of q.
/// *err: its largest distance from the exact sweep, bounded by the polynomials' error times the
/// poles' largest distance from the axis (a convex combination of the poles' helices) and at least
/// what a grid of exact points measures. Null for a curve of another kind.
Handle(Geom_BSplineSurface) helical_spline_surface(const Handle(Geom_Curve)& c, double s0, double s1,
                                                   const ScrewJoint& j, double q0, double q1, double tol,
                                                   double* err);

/// Parameters where the curve's coordinate along the joint axis turns (empty when it never
/// does, or when the curve lies in a plane perpendicular to the axis).
std::vector<double> axial_breaks(const Handle(Geom_Curve)& c, double first, double last, const ScrewJoint& joint);

/// A face's share of the divergence-theorem volume, (1/3) the integral of x . n over the face,
/// signed by its orientation: computed by Green's theorem in the face's parameter domain along its
/// pcurves. A solid's volume is the sum over its faces, each taken about the same `origin` (one
/// near the solid cancels least).
double face_divergence(const TopoDS_Face& face, const gp_XYZ& origin = gp_XYZ(0, 0, 0));
/// face_divergence and the face's area, integrated the same way at the same points.
std::pair<double, double> face_divergence_and_area(const TopoDS_Face& face, const gp_XYZ& origin = gp_XYZ(0, 0, 0));
/// The area of one face by the same quadrature.
double face_area(const TopoDS_Face& face);

/// The path of point x under a revolute or prismatic joint for q in [q0, q0 + T] (a circle arc
/// about the axis, or a segment), or a null edge when x is within min_radius of the axis.
TopoDS_Edge path_edge(const Eigen::Vector3d& x, const ScrewJoint& j, double q0, double T, double min_radius);

/// True when the motion keeps a plane containing the curve (then written to `plane`): a plane
/// perpendicular to a rotation axis, or one containing a translation direction.
bool keeps_plane_of(const Handle(Geom_Curve)& c, double first, double last, const ScrewJoint& j, double size,
                    gp_Pln* plane);
/// The planar region swept by such a curve, as faces of that plane.
std::vector<TopoDS_Face> planar_curve_sweep(const Handle(Geom_Curve)& c, double first, double last,
                                            const ScrewJoint& j, double T, const gp_Pln& plane, double size);

/// The centre and radius of `body` when it is one whole sphere.
bool sphere_of(const TopoDS_Shape& body, Eigen::Vector3d* centre, double* radius);
/// True when the helix arc followed by point c under screw joint j over [0, T] has a reach larger
/// than r + margin (its radius of curvature and the half lengths of its double normals and end
/// chord all exceed it): then the balls of radius r along it bound a tube closed by two half balls.
bool helix_reach_exceeds(const ScrewJoint& j, const Eigen::Vector3d& c, double T, double r, double margin);
/// That solid (tube and half balls), the tube fitted within fit_tol, or a null shape when the fit or
/// the build fails. `faces` receives the tube, the half ball at the start and the one at the end.
TopoDS_Shape ball_screw_sweep(const Eigen::Vector3d& c, double r, const ScrewJoint& j, double T, double fit_tol,
                              double size, double* fit_err, std::vector<TopoDS_Face>* faces);

/// A ball of centre c and radius r translated by length along the unit direction d: the capsule,
/// exact (a cylinder and two half balls). `roles` as below. Null for a degenerate input.
TopoDS_Shape ball_line_sweep(const Eigen::Vector3d& c, double r, const Eigen::Vector3d& d, double length,
                             std::vector<TopoDS_Face>* faces, std::vector<int>* roles);

/// The same sweep when the helix's neighbouring turns meet (and only those: balls half a turn or two
/// turns apart are disjoint) over a range of at least one and a half turns: the tube trimmed where
/// the next and the previous turn cover it, and the half balls trimmed where the turn after the start
/// and the turn before the end cover them. Null when these conditions do not hold or a step fails.
/// `roles` receives, per face, 0 for the tube, 1 for the start and 2 for the end.
TopoDS_Shape ball_screw_sweep_overlap(const Eigen::Vector3d& c, double r, const ScrewJoint& j, double T,
                                      double fit_tol, double size, double* fit_err, std::vector<TopoDS_Face>* faces,
                                      std::vector<int>* roles);

/// The axis-aligned box of a shape's vertices, edges and (trimmed) faces, without enlargement.
Bnd_Box shape_box(const TopoDS_Shape& s);
/// The same box as Eigen's (empty for an empty shape).
Eigen::AlignedBox3d box_of(const TopoDS_Shape& s);
/// The largest distance from the origin of a corner of the shape's box (0 for an empty shape).
double radius_of(const TopoDS_Shape& s);

/// A direction known to point out of the solid at one point of one of the faces to be sewn:
/// face `face` of the list, at (u, v) of its surface, where the outward direction is `out`.
struct OutwardHint {
  std::size_t face = 0;
  double u = 0, v = 0;
  gp_Vec out;
};

/// Sews faces into one closed solid, oriented outwards (null when they do not make one shell): by
/// the hint when one is given and its surface normal is not tangent to `out`, else by classifying
/// a point at infinity (OCCT's solid classifier: 8 ms on the overlapping spring's trimmed B-spline
/// faces, about 7 % of its whole run).
TopoDS_Shape sew_solid(const std::vector<TopoDS_Face>& fs, double tol, const OutwardHint* hint = nullptr);

/// The solid swept by a face translated by L along the unit direction d of prismatic joint j, built
/// directly when the face is a graph along d: n . d keeps one sign on it and its boundary, without seams and collapsed
/// edges, projects along d onto a simple closed curve. Then every line parallel to d meets the face
/// at most once and the solid is bounded by the face, its translate and the sweep of that boundary,
/// which meet only along their edges (the sweeps exact for lines and circles, else fitted within
/// tol, `fit_err` raised to their error). Null when the conditions do not hold or sewing fails.
/// `faces` receives the faces, each with its role.
struct GraphExtrusionFace {
  TopoDS_Face face;
  int role = 0;  ///< -1 the face at the start, -2 at the end, k >= 0 the sweep of boundary edge k
  double first = 0, last = 0;  ///< that edge's parameter range
};
TopoDS_Shape graph_extrusion(const TopoDS_Face& face, const ScrewJoint& j, double L, double size, double tol,
                             double* fit_err, std::vector<GraphExtrusionFace>* faces);

/// Keeps OCCT's translators from printing to stdout (stdout carries the report).
void quiet_occt();

/// The shape with the neighbouring pieces of each surface merged into one face, when that gives a
/// valid shape; a null shape otherwise (the caller keeps its own). A bounded walk, no time limit.
TopoDS_Shape unify_faces(const TopoDS_Shape& shape);

/// Runs work(i) for every i in [0, n) on the machine's cores (at most eight threads). Each thread
/// gets its own worker from make(): OCCT's classifiers and intersectors are not shared between
/// threads. The first exception thrown by a worker is rethrown.
void parallel_for(std::size_t n, const std::function<std::function<void(std::size_t)>()>& make);

/// How OCCT's splitter runs: on the machine's cores (the argument's sub-shapes may be modified in
/// place), or on one thread leaving the argument as it is (for callers already in parallel_for).
enum class SplitMode { Parallel, NonDestructive };
/// A copy of `face` on `surface`, which has the same parameters as the face's own (a trimmed copy,
/// an exact B-spline form): its curves on the surface, seams' pairs included, hold as they are.
/// The face itself when one of its edges has no curve on its surface.
TopoDS_Face face_on_surface(const TopoDS_Face& face, const Handle(Geom_Surface)& surface);
/// `shape` split by the edges `tools` at fuzzy value `fuzzy`; null when OCCT fails.
TopoDS_Shape split_by_edges(const TopoDS_Shape& shape, const TopTools_ListOfShape& tools, double fuzzy,
                            SplitMode mode);

/// A point membership test, and a maker of one per thread.
using PointTest = std::function<bool(const Eigen::Vector3d&)>;
using PointTestMaker = std::function<PointTest()>;
/// A membership test that may not decide: 1 in, 0 out, -1 undecided.
using MemberTest = std::function<int(const Eigen::Vector3d&)>;
using MemberTestMaker = std::function<MemberTest()>;
/// A decided test seen as a test that may not decide.
inline MemberTestMaker always_decided(PointTestMaker m) {
  return [m]() -> MemberTest {
    PointTest t = m();
    return [t](const Eigen::Vector3d& x) { return t(x) ? 1 : 0; };
  };
}

/// A test that may not decide, seen as a decided one: a point it leaves undecided throws
/// ComputeError(`why`) (the cells of an arrangement must each be in or out).
inline PointTestMaker decided_or_failed(MemberTestMaker m, std::string why) {
  return [m, why]() -> PointTest {
    MemberTest t = m();
    return [t, why](const Eigen::Vector3d& x) {
      const int r = t(x);
      if (r < 0) throw ComputeError(why);
      return r == 1;
    };
  };
}

/// The solid bounded by the split faces of an arrangement that separate the set (given by point
/// membership, a test per thread from `member`) from its complement, each oriented outward; null
/// when they bound no solid. `kept`, when given, receives the number of such faces, and
/// `free_edges` the edges that only one of them uses (seams aside): where they fail to close up.
TopoDS_Shape solid_from_boundary_faces(const std::vector<TopoDS_Face>& split, const PointTestMaker& member,
                                       double size, int* kept = nullptr,
                                       std::vector<TopoDS_Edge>* free_edges = nullptr);

/// Point membership in the sweep of `body` under a one-parameter motion M (M(t) body is the body at
/// t): x is swept when its path back through the motion, y(t) = M(t)^-1 x for t in [lo, hi], meets
/// the body's boundary, or (for a solid body) starts inside it. Under a screw, faces on planes,
/// quadrics and tori are met at the certified roots of their implicit functions along the path (an
/// orbit of the screw); other faces by OCCT's intersector, along a path that is exact when the
/// motion is one slide or turn (a segment, a circle), and otherwise (a helix too) the image of x
/// under the motion's inverse poses, fitted once within `tol` over the region the body sweeps.
/// Keeps OCCT state: one per thread. The motion must outlive it. `body_box` is box_of(body), when
/// the caller has it (it is measured on the faces, which costs about as much as the rest of the
/// set-up on a body of a hundred faces).
class TrajectoryMembership {
 public:
  TrajectoryMembership(const TopoDS_Shape& body, bool solid, const StageMotion& motion, double tol);
  TrajectoryMembership(const TopoDS_Shape& body, bool solid, const StageMotion& motion, double tol,
                       const Eigen::AlignedBox3d& body_box);
  ~TrajectoryMembership();
  TrajectoryMembership(const TrajectoryMembership&) = delete;
  TrajectoryMembership& operator=(const TrajectoryMembership&) = delete;
  bool operator()(const Eigen::Vector3d& x);
  /// Whether x is inside the solid body by rays from it: 1 inside, 0 outside, -1 when no ray
  /// gives a clear answer (x on the boundary; a ray tangent to a face).
  int ray_inside(const Eigen::Vector3d& x);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The solid `body` as an orbit solid (sweep/orbit.hpp): its faces' crossings with an orbit found
/// as roots of their surfaces' implicit functions and classified in the faces' domains, the pieces
/// between them by rays (OCCT's classifier where no ray decides). Nothing of a sweep enters it: the
/// reference volume of one-joint sweeps of parts read from STEP. Keeps OCCT state: one per thread.
/// @throws InputError when a face lies on a surface other than a plane, cylinder, cone, sphere or
/// torus (its index and kind named).
OrbitSolidPtr brep_orbit_solid(const TopoDS_Shape& body, double tol);

/// Reads a STEP or BREP file into a shape. @throws InputError at `pointer` when unreadable.
TopoDS_Shape read_shape_file(const std::string& path, const std::string& pointer);

/// The extension of a file's path, lower case, without its dot ("" when it has none).
std::string file_extension(const std::string& path);

}  // namespace sweep::occt

namespace sweep::occt {
/// Installs OCCT's handlers for SIGSEGV, SIGFPE, SIGBUS and the like, so that inside
/// OCC_CATCH_SIGNALS a fault in OCCT is thrown as a Standard_Failure and the run reports `failed`
/// instead of crashing. Without `replace_existing` only signals that have no handler yet get one
/// (inside FreeCAD or Python their own handlers stay).
void install_signal_handlers(bool replace_existing = false);
/// Replaces each pcurve of the face that strays from its edge by more than tol by a projection
/// of the edge onto the surface, and sets the edge's tolerance from the deviation measured.
void tighten_pcurves(const TopoDS_Face& face, double tol);
/// The curve as an exact line or circle when it is one within `tol` (fitted grazing curves of
/// planes and spheres are), else itself. first/last are updated to the new parametrization.
Handle(Geom_Curve) canonical_curve(const Handle(Geom_Curve)& c, double& first, double& last, double tol);
}  // namespace sweep::occt
