#pragma once
/// @file entity.hpp
/// The moving shape as the engine sees it: a box that holds it, an inside test, a signed-distance
/// bound, and its boundary as patches with exact first derivatives. One implementation per entity
/// kind; make_entity() is the one place that switches on the kind. B-rep and mesh entities are
/// the bridge's (they need a geometry kernel); make_entity() gives none for them. Their faces are
/// trimmed patches (Patch::trimmed).
#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sweep/membership.hpp"
#include "sweep/orbit.hpp"
#include "sweep/spec.hpp"

namespace sweep {

/// A point of a patch with its first derivatives in the patch's parameters.
struct PatchPoint {
  Eigen::Vector3d x = Eigen::Vector3d::Zero(), xu = Eigen::Vector3d::Zero(), xv = Eigen::Vector3d::Zero();
};

/// The closed-form surface or curve a patch is an exact piece of, in the frame OCCT's elementary
/// surfaces use: `origin`, `axis` (unit, Z) and `ref` (unit, X, normal to the axis).
/// - plane: the plane through origin normal to axis;
/// - cylinder: radius about the axis line; cone: radius at origin, `semi_angle` (radius grows by
///   tan(semi_angle) per unit along axis); sphere: centre origin; torus: `radius` major, `minor`;
/// - line: through origin along axis; circle: centre origin, radius, in the plane normal to axis;
///   ellipse: the same with semi-axis `radius` along ref and `minor` across it.
struct PatchForm {
  enum class Kind { General, Plane, Cylinder, Cone, Sphere, Torus, Line, Circle, Ellipse };
  Kind kind = Kind::General;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::UnitZ(), ref = Eigen::Vector3d::UnitX();
  double radius = 0, minor = 0, semi_angle = 0;
  /// True when the patch's (u, v) are the form's own parameters: u the angle about axis from ref
  /// and v the height along axis (cylinder, cone), the latitude (sphere) or the angle about the
  /// tube (torus); for a plane, the coordinates along ref and axis x ref.
  bool surface_parameters = false;
  /// True when the patch is a surface of revolution about `axis` swept by its own u: u is the angle
  /// about the axis (from `ref`) and each v = const is a circle about it (the faces of cylinders,
  /// cones, spheres, tori and disks).
  bool revolved = false;
};
const char* to_string(PatchForm::Kind k);

/// A piece of an entity's boundary (dimension 2: a face; 1: an edge; 0: a point) or of a sweep's
/// boundary variety: a smooth map from a parameter box into space. For a face of a solid,
/// `orientation` * (xu x xv) points out of the solid.
class Patch {
 public:
  using Map = std::function<PatchPoint(const double* s)>;
  Patch(int dim, std::vector<double> lo, std::vector<double> hi, Map map, PatchForm form, std::string what,
        int orientation = 1);

  int dim() const { return dim_; }
  double lo(int k) const { return lo_[k]; }
  double hi(int k) const { return hi_[k]; }
  /// The point at parameters s (dim() of them) with its derivatives (xv is zero for dim() < 2,
  /// xu too for dim() 0).
  PatchPoint eval(const double* s) const { return map_(s); }
  PatchPoint eval(double u, double v = 0) const {
    const double s[2] = {u, v};
    return map_(s);
  }
  /// +1 or -1: the sign that makes xu x xv the outward normal of a solid's face.
  int orientation() const { return orientation_; }
  const PatchForm& form() const { return form_; }
  /// What it is, for reports ("lateral face of the cylinder", "edge 3 of the box").
  const std::string& what() const { return what_; }
  /// Parameters it fixes and their values (a variety's limit joint value, an edge's face
  /// parameter); empty for an entity's own faces.
  std::vector<std::pair<std::string, double>> fixed;
  /// True when only part of the domain belongs to the shape: the face of a B-rep solid, whose
  /// boundary curves cut its surface, is its surface over the face's parameter box.
  bool trimmed = false;

 private:
  int dim_;
  std::vector<double> lo_, hi_;
  Map map_;
  PatchForm form_;
  std::string what_;
  int orientation_;
};
using PatchPtr = std::shared_ptr<const Patch>;

/// The point of side `side` of a two-parameter patch's domain (0: v = lo, 1: u = hi, 2: v = hi,
/// 3: u = lo) at fraction f along it, the sides taken counter-clockwise.
Eigen::Vector3d side_point(const Patch& p, int side, double f);
/// The sides of a two-parameter patch's domain that bound it: neither collapsed to a point (a pole)
/// nor running back along the opposite side (a closed parameter), judged on n + 1 points of each
/// to within `tol`.
std::vector<int> bounding_sides(const Patch& p, double tol, int n = 64);

/// The periods of a two-parameter patch's parameters: the span of u (of v) when the patch closes
/// on itself across it (its sides u = lo and u = hi coincide, judged on 17 points of each to 1e-12
/// of the patch's size), else 0.
Eigen::Vector2d parameter_periods(const Patch& p);
/// The patch over the part [lo, hi] of its domain: the same map, form, name, orientation and fixed
/// parameters.
PatchPtr patch_part(const PatchPtr& p, const std::vector<double>& lo, const std::vector<double>& hi);
/// Parameters of the domain's cover (shifted by whole periods) moved back into the domain.
Eigen::Vector2d wrapped_parameters(const Patch& p, Eigen::Vector2d s, const Eigen::Vector2d& period);

/// The entity of a spec, placement applied.
class Entity {
 public:
  virtual ~Entity() = default;
  virtual EntityKind kind() const = 0;
  /// 0 point, 1 curve, 2 surface, 3 solid.
  virtual int dimension() const = 0;
  /// A box that holds the whole entity.
  virtual Eigen::AlignedBox3d box() const = 0;
  /// Solids: whether p is in the closed solid. Lower dimensions: false.
  virtual bool inside(const Eigen::Vector3d& p) const = 0;
  /// Solids that have one: a signed lower bound on the distance to the boundary, negative inside,
  /// 1-Lipschitz, |d(p)| <= dist(p, boundary). False when the entity has none (then `distance`
  /// is not called).
  virtual bool has_distance_bound() const = 0;
  virtual double distance(const Eigen::Vector3d& p) const = 0;
  /// True when the distance bound vanishes on the boundary only (the primitives' exact distances),
  /// so that a search with it decides points however near the boundary. A B-rep's bound, taken
  /// from a triangulation of its faces, vanishes within the triangulation's measured deviation.
  virtual bool tight_distance() const { return true; }
  /// The same bound as a function object of its own (for the membership tests), or null.
  virtual std::unique_ptr<SignedDistance> distance_bound() const = 0;
  /// The solid as orbit.hpp's exact orbit intersections take it (primitives), or null.
  virtual OrbitSolidPtr orbit_solid() const = 0;
  /// The boundary of a solid as faces (each with its outward orientation); a surface entity is its
  /// own one face, a curve its own one edge, a point its own one patch.
  virtual const std::vector<PatchPtr>& faces() const = 0;
  /// The curves where the faces meet at a crease (not where a face closes on itself smoothly);
  /// a surface entity's sides, less those that collapse to a point or meet their opposite side.
  virtual const std::vector<PatchPtr>& edges() const = 0;
};
using EntityPtr = std::shared_ptr<const Entity>;

/// The entity of `spec` (placement applied): primitives (sphere, box, cylinder, cone, torus,
/// elliptic cylinder), points, parametric curves and surfaces. Null for kinds whose entity the
/// core does not build (brep, mesh and the kinds not supported yet).
EntityPtr make_entity(const EntitySpec& spec);

}  // namespace sweep
