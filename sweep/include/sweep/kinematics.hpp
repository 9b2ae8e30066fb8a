#pragma once
/// @file kinematics.hpp
/// Kinematic joint recognition with reciprocal screw theory (002_1f02696738e2eea2.txt).
///
/// Conventions (those of the paper):
///  - a twist is [omega; v]: angular velocity, then the velocity of the body point that is at the
///    world origin at this instant;
///  - a wrench is [f; m]: resultant force, then the moment about the world origin.
/// A twist t and a wrench w are reciprocal when t.head(3)·w.tail(3) + t.tail(3)·w.head(3) = 0,
/// i.e. the wrench does no work on the motion. Swapping the triplets of a screw (Delta in
/// Algorithm 1) turns the reciprocal product into the Euclidean dot product, so the twist space
/// allowed by a set of wrenches is Delta of the Euclidean orthogonal complement of their span.
///
/// Geometry is given in world coordinates at the assembled position, so every twist space is
/// expressed in one common frame and serial composition is a sum of subspaces, parallel
/// composition an intersection.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sweep/motion.hpp"

namespace sweep {
namespace kinematics {

using Vec3 = Eigen::Vector3d;
/// A screw as six numbers: direction-like triplet first (omega for twists, f for wrenches).
using Screw = Eigen::Matrix<double, 6, 1>;
using Twist = Screw;   ///< [omega; v], v = velocity of the body point at the origin
using Wrench = Screw;  ///< [f; m], m = moment about the origin
/// A set of screws, one per column.
using ScrewBasis = Eigen::Matrix<double, 6, Eigen::Dynamic>;

// ---------------------------------------------------------------------------------------------
// Screws

/// Rotation about the line through `point` along `direction`: [s; point x s], s = unit direction.
/// @pre direction is not zero.
Twist revolute_twist(const Vec3& point, const Vec3& direction);
/// Translation along `direction`: [0; s]. @pre direction is not zero.
Twist prismatic_twist(const Vec3& direction);
/// Screw motion about the line through `point` along `direction` with `pitch` (length per radian):
/// [s; point x s + pitch s]. @pre direction is not zero.
Twist helical_twist(const Vec3& point, const Vec3& direction, double pitch);
/// Unit force along `direction` acting on the line through `point`: [s; point x s].
Wrench force_wrench(const Vec3& point, const Vec3& direction);
/// Unit couple (pure moment) about `direction`: [0; s].
Wrench couple_wrench(const Vec3& direction);
/// omega·m + v·f: zero when the wrench does no work on the twist.
double reciprocal_product(const Twist& t, const Wrench& w);
/// Delta of Algorithm 1: exchanges the first and the second triplet.
Screw swap_triplets(const Screw& s);
/// The twist seen after moving the whole scene by `T` (adjoint map).
Twist transform_twist(const Eigen::Isometry3d& T, const Twist& t);
/// The wrench seen after moving the whole scene by `T`.
Wrench transform_wrench(const Eigen::Isometry3d& T, const Wrench& w);
/// Pitch omega·v / |omega|^2 (length per radian); +infinity for a pure translation.
double twist_pitch(const Twist& t);

// ---------------------------------------------------------------------------------------------
// Basic constraints (section 3.2). Bodies i and j carry vectors a_i, a_j and reference points
// P_i, P_j; d_ij = P_j - P_i.

/// Dot-1: a_i·a_j = const freezes the relative rotation about a_i x a_j: the couple [0; a_i x a_j]
/// (normalized). @pre a_i and a_j are not parallel (then the constraint is not a basic one).
Wrench dot1_wrench(const Vec3& a_i, const Vec3& a_j);
/// Dot-2: a_i·d_ij = const freezes the relative translation along a_i at P_j: the force
/// [a_i; P_j x a_i] (normalized). Exact in any configuration: d/dt(a_i·d_ij) is the reciprocal
/// product of this wrench with the twist of j relative to i. @pre a_i is not zero.
Wrench dot2_wrench(const Vec3& a_i, const Vec3& p_j);
/// Distance: |d_ij| = c. For c > `coincidence` one force along d_ij through P_j; otherwise
/// (coincident points) the three forces through P_j along x, y and z.
std::vector<Wrench> distance_wrenches(const Vec3& p_i, const Vec3& p_j, double coincidence);

// ---------------------------------------------------------------------------------------------
// Geometry constraints (section 3.3), in world coordinates at the assembled position.

struct Axis {
  Vec3 point = Vec3::Zero();
  Vec3 direction = Vec3::UnitZ();  ///< not zero; need not be unit
};
struct Plane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  ///< not zero; need not be unit
};

enum class ConstraintType { Coaxial, Coplanar, Spherical, Align, LineSurfaceDistance, PointOnLine };
/// "coaxial", "coplanar", "spherical", "align", "line_surface_distance", "point_on_line".
const char* to_string(ConstraintType t);
/// The number of basic components (degree of constraint): 4, 3, 3, 2, 2, 2.
int degree_of_constraint(ConstraintType t);

/// Two axes of the two parts lie on one line: two dot-1 (a_i = s1, a_j perpendicular to s2) and two dot-2
/// (a_i perpendicular to s1, through axis2.point). Cylindrical joint.
std::vector<Wrench> coaxial_wrenches(const Axis& axis1, const Axis& axis2);
/// Two planes coincide: two dot-1 (a_i = n1, a_j in plane 2) and one dot-2 (a_i = n1, through
/// plane2.point). Planar joint.
std::vector<Wrench> coplanar_wrenches(const Plane& plane1, const Plane& plane2);
/// Two points coincide: one distance constraint with c = 0 (three forces). Spherical joint.
std::vector<Wrench> spherical_wrenches(const Vec3& point1, const Vec3& point2);
/// Two planes stay parallel: two dot-1. Four dof, no common joint.
std::vector<Wrench> align_wrenches(const Plane& plane1, const Plane& plane2);
/// A line of part 1 stays parallel to a plane of part 2 at a fixed distance: one dot-1 (the couple
/// n2 x s1) and one dot-2 (a_i = n2 on part 2, through axis1.point). Four dof.
std::vector<Wrench> line_surface_distance_wrenches(const Axis& axis1, const Plane& plane2);
/// A point of part 1 stays on a line of part 2: two dot-2 (a_i perpendicular to s2 on part 2, through point1).
/// Four dof.
std::vector<Wrench> point_on_line_wrenches(const Vec3& point1, const Axis& axis2);

/// One geometry constraint between parts[0] (the "1" fields) and parts[1] (the "2" fields).
/// Only the fields of its type are meaningful.
struct GeometryConstraint {
  ConstraintType type = ConstraintType::Coaxial;
  std::array<int, 2> parts{{0, 0}};  ///< indices into Assembly::parts, different
  Axis axis1, axis2;                 ///< coaxial; line_surface_distance (axis1); point_on_line (axis2)
  Plane plane1, plane2;              ///< coplanar, align; line_surface_distance (plane2)
  Vec3 point1 = Vec3::Zero(), point2 = Vec3::Zero();  ///< spherical; point_on_line (point1)
  double distance = 0.0;                              ///< line_surface_distance, >= 0
};

/// The basic components of a constraint as wrenches, in the order documented above.
std::vector<Wrench> constraint_wrenches(const GeometryConstraint& c);

// ---------------------------------------------------------------------------------------------
// Numerics

/// Where rank decisions are made. Screws are expressed about `center` with lengths divided by
/// `scale`, so forces, couples, angular and linear velocities are all of order one whatever the
/// units and the position of the model.
struct NumericFrame {
  Vec3 center = Vec3::Zero();
  double scale = 1.0;  ///< model size in model units; must be positive
  /// Relative tolerance: two lengths closer than tolerance * scale are equal, two directions closer
  /// than `tolerance` radians are parallel.
  double tolerance = 1e-6;
  /// Singular values of matrices of unit screws in this frame at or below
  /// rank_factor * tolerance * max(1, largest singular value) count as zero.
  double rank_factor = 10.0;

  double rank_tolerance() const { return rank_factor * tolerance; }
  double length_tolerance() const { return tolerance * scale; }
  Wrench wrench_to_local(const Wrench& w) const;
  Twist twist_to_local(const Twist& t) const;
  Twist twist_to_world(const Twist& local) const;
};

/// Settings of recognition, with their defaults.
struct Settings {
  /// Used when the assembly gives no "tolerance": lengths within relative_tolerance times the
  /// model size are equal; directions within relative_tolerance radians are parallel.
  double relative_tolerance = 1e-6;
  /// See NumericFrame::rank_factor.
  double rank_factor = 10.0;
};

/// The joint kinds of section 2.2, plus `Fixed` (no relative motion) and `Unrecognized`.
enum class JointKind { Fixed, Revolute, Prismatic, Helical, Cylindrical, Spherical, Planar, Unrecognized };
/// "fixed", "revolute", "prismatic", "helical", "cylindrical", "spherical", "planar", "unrecognized".
const char* to_string(JointKind k);

/// A recognized twist space.
struct Joint {
  JointKind kind = JointKind::Unrecognized;
  int dof = 0;         ///< dimension of the twist space
  int components = 0;  ///< number of basic wrench components collected (0 when built from twists)
  int rank = 0;        ///< dimension of their span
  int redundant = 0;   ///< components - rank: components that add no restriction
  /// Basis of the twist space in world coordinates, one twist per column. Canonical for the
  /// recognized kinds: revolute [s; p x s], prismatic [0; s], helical [s; p x s + h s],
  /// cylindrical [s; p x s], [0; s], spherical [e_k; c x e_k] (k = x, y, z), planar [n; 0], [0; u],
  /// [0; n x u]; p is the point of the axis nearest to the origin, s and n unit with their largest
  /// component positive. Otherwise the reduced row echelon form of the space (empty for fixed).
  ScrewBasis twists;
  Vec3 point =
      Vec3::Zero();  ///< revolute, helical, cylindrical: axis point nearest the origin; spherical: centre
  Vec3 direction = Vec3::Zero();  ///< revolute, prismatic, helical, cylindrical: axis; planar: normal
  double pitch = 0.0;             ///< helical: length per radian (SPEC pitch = 2 pi times this)

  bool is_screw() const {
    return kind == JointKind::Revolute || kind == JointKind::Prismatic || kind == JointKind::Helical;
  }
};

/// Orthonormal basis (columns) of the span of `screws` (columns) under the rank tolerance of
/// `frame`; the screws are compared as they are (call it on local-frame screws).
ScrewBasis orthonormal_span(const ScrewBasis& screws, const NumericFrame& frame);

/// Algorithm 1: the twists reciprocal to all `wrenches` (world coordinates), as an orthonormal
/// basis in the local coordinates of `frame`. `rank` receives the dimension of the wrench span.
ScrewBasis reciprocal_twists_local(const std::vector<Wrench>& wrenches, const NumericFrame& frame,
                                   int* rank = nullptr);

/// Algorithm 1 and classification: the joint allowed by `wrenches` (world coordinates).
Joint recognize_joint(const std::vector<Wrench>& wrenches, const NumericFrame& frame);
/// Classification of the space spanned by `twists` (world coordinates, columns).
Joint classify_twists(const ScrewBasis& twists, const NumericFrame& frame);

/// Serial composition: the span of both twist spaces (world coordinates in and out).
ScrewBasis twist_sum(const ScrewBasis& a, const ScrewBasis& b, const NumericFrame& frame);
/// Parallel composition: the twists in both spaces (world coordinates in and out).
ScrewBasis twist_intersection(const ScrewBasis& a, const ScrewBasis& b, const NumericFrame& frame);
/// Dimension of the span of `twists` (world coordinates).
int twist_dimension(const ScrewBasis& twists, const NumericFrame& frame);
/// True when both sets of world twists span the same space.
bool same_twist_space(const ScrewBasis& a, const ScrewBasis& b, const NumericFrame& frame);

// ---------------------------------------------------------------------------------------------
// Assemblies (SPEC.md "Assembly file v1")

/// A joint range given in the assembly file or on the command line. It targets either the joint
/// between parts `joint[0]` and `joint[1]`, or (part >= 0) the joint through which `part` is
/// reached from the ground on the chosen path.
struct RangeSpec {
  std::array<int, 2> joint{{-1, -1}};
  int part = -1;
  double lo = 0.0, hi = 0.0;  ///< lo <= hi; angles as the sweep spec reads them, lengths in model units
  std::string source;         ///< JSON pointer or command-line argument, for messages
};

struct Assembly {
  std::string name;
  std::vector<std::string> parts;  ///< unique, non-empty
  int ground = 0;                  ///< index into parts
  std::vector<GeometryConstraint> constraints;
  std::vector<RangeSpec> ranges;  ///< from "ranges" and constraint-level "range"
  double tolerance = 0.0;         ///< "tolerance" in model units; 0 = relative default

  int part_index(const std::string& name) const;  ///< -1 when unknown
  /// "a-b" with the parts in the order of `parts`.
  std::string joint_name(int a, int b) const;
};

/// Parses and validates assembly text (SPEC.md). Checks that each constraint holds at the given
/// position within the tolerance.
/// @throws InputError naming the JSON pointer of the offending field.
Assembly parse_assembly(const std::string& text, const Settings& settings = {});
/// Reads the file and calls parse_assembly. @throws InputError (pointer "") when unreadable.
Assembly load_assembly(const std::string& path, const Settings& settings = {});

/// The numeric frame of an assembly: centre and diagonal of the bounding box of its constraint
/// points (1 when they all coincide), and its tolerance.
NumericFrame assembly_frame(const Assembly& a, const Settings& settings = {});

/// Resolves a range key: a joint name "a-b" (either order) of two constrained parts, or a part
/// name. @throws InputError(pointer, ...) when it names nothing or is ambiguous.
RangeSpec resolve_range_key(const Assembly& a, const std::string& key, const std::string& pointer);

/// The joint between one pair of constrained parts.
struct PairJoint {
  std::array<int, 2> parts{{0, 0}};  ///< parts[0] < parts[1]
  std::vector<int> constraints;      ///< indices into Assembly::constraints, ascending
  Joint joint;
};

/// The joint graph of an assembly and the mobility of each part relative to the ground.
struct Analysis {
  NumericFrame frame;
  std::vector<PairJoint> joints;  ///< sorted by (parts[0], parts[1])
  std::vector<int> part_dof;      ///< per part; 0 for the ground
  std::vector<ScrewBasis>
      part_twists;         ///< per part, world coordinates: all its twists relative to the ground
  int mobility = 0;        ///< dimension of the instantaneous motions of the whole assembly
  int loop_redundant = 0;  ///< wrench components made redundant by closed loops of the graph

  /// Index into `joints` of the joint between parts a and b (either order), or -1.
  int find_joint(int a, int b) const;
  /// Indices into `joints` of the pairs with redundant components.
  std::vector<int> over_constrained() const;
};

/// Recognizes every pairwise joint (Algorithm 1) and solves the whole graph at first order: the
/// twists of all parts with the ground fixed such that each pair's relative twist lies in its
/// joint's twist space. A part's dof is the dimension of its twists in that solution; on a serial
/// chain this is the sum of the joint spaces, on parallel paths their intersection.
Analysis analyze(const Assembly& a, const Settings& settings = {});

/// A path from the ground to `part` as joint indices, outermost (ground side) first. Prefers a
/// shortest path through 1-dof screw joints, then a shortest path through any joints; empty when
/// `part` is the ground or unreachable.
std::vector<int> joint_path(const Assembly& a, const Analysis& an, int part);

/// The `axes` motion (SPEC.md) that moves `part` relative to the ground along joint_path: one
/// screw joint per joint of the path, axes at the assembled position. Ranges come from
/// `overrides` first, then from the assembly; a range keyed by a joint name wins over one keyed
/// by a part name.
/// @throws InputError when the part is the ground or unreachable, when a joint on the path is not
/// a 1-dof screw joint, or has no range.
Motion motion_for(const Assembly& a, const Analysis& an, int part,
                  const std::vector<RangeSpec>& overrides = {});

// ---------------------------------------------------------------------------------------------
// Reports

/// The JSON of `sweepvol joints --json` (SPEC.md), with extra fields: per joint "constraints",
/// "rank", and "axis"/"center"/"normal"/"pitch" (pitch in length per turn) where they apply;
/// top-level "ground", "mobility", "loop_redundant" and "over_constrained".
nlohmann::ordered_json report_json(const Assembly& a, const Analysis& an);
/// The joint graph in Graphviz DOT: parts as nodes (the ground boxed), joints as labelled edges.
std::string report_dot(const Assembly& a, const Analysis& an);
/// A human-readable table of joints and part mobilities.
std::string report_table(const Assembly& a, const Analysis& an);
/// The `motion` object of kind `axes` for a sweep spec (pitch in length per turn).
nlohmann::ordered_json motion_json(const Motion& m);
/// Indented JSON text that keeps arrays of scalars (twists, points, ranges) on one line and
/// prints numbers with 12 significant digits.
std::string format_json(const nlohmann::ordered_json& j);

}  // namespace kinematics
}  // namespace sweep
