#pragma once
/// @file orbit.hpp
/// Orbits of one screw joint, and solids met by orbits in closed form.
///
/// Under a screw joint a point y moves along its orbit p(t) = exp(xi t) y: a circle about the axis
/// (revolute), a helix (helical) or a line (prismatic). In coordinates whose coordinate lines are the
/// orbits the joint is a translation along them, so the sweep of a solid B over t in [0, T] meets an
/// orbit in the union of B's intervals on it, each extended by T. Membership in the sweep and its
/// volume need nothing but those intervals, which this file computes without any boundary
/// representation: each primitive's inside is a few inequalities g(t) <= 0 where g is a polynomial in
/// t, cos t and sin t along the orbit, whose roots are isolated with a certified bound.
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "sweep/motion.hpp"
#include "sweep/spec.hpp"

namespace sweep {

/// Sorted, disjoint closed intervals of a parameter.
using Intervals = std::vector<std::pair<double, double>>;

Intervals unite(const Intervals& a, const Intervals& b);
Intervals intersect(const Intervals& a, const Intervals& b);
/// a minus the interior of b (closed result).
Intervals subtract(const Intervals& a, const Intervals& b);
double total_length(const Intervals& a);

/// p(t) = c + a cos t + b sin t + d t: an orbit, or its image under a rigid map.
struct OrbitCurve {
  Eigen::Vector3d c = Eigen::Vector3d::Zero(), a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero(),
                  d = Eigen::Vector3d::Zero();
  Eigen::Vector3d at(double t) const;
  /// The image under the rigid map T (same parameter).
  OrbitCurve mapped(const Eigen::Isometry3d& T) const;
  /// The same curve with its parameter shifted: result.at(s) == at(s + t0).
  OrbitCurve shifted(double t0) const;
};

/// The orbit of y under joint j: exp(xi t) y as a function of t.
OrbitCurve orbit_of(const ScrewJoint& j, const Eigen::Vector3d& y);

/// A solid whose intersection with any orbit is computed exactly (to rounding).
class OrbitSolid {
 public:
  virtual ~OrbitSolid() = default;
  /// The parameters t in [lo, hi] at which the curve lies in the solid.
  virtual Intervals on_curve(const OrbitCurve& o, double lo, double hi) const = 0;
  virtual bool contains(const Eigen::Vector3d& p) const = 0;
  /// A box that contains the solid.
  virtual Eigen::AlignedBox3d bounds() const = 0;
};
using OrbitSolidPtr = std::shared_ptr<const OrbitSolid>;

/// The orbit solid of a primitive entity (sphere, box, cylinder, cone, torus, untwisted elliptic
/// cylinder) with its placement
/// (Entity::orbit_solid()); nullptr for other kinds.
OrbitSolidPtr make_orbit_solid(const EntitySpec& e);

/// Building blocks, in the frame they are given in.
OrbitSolidPtr orbit_halfspace(const Eigen::Vector3d& normal, double offset);  ///< normal . p <= offset
OrbitSolidPtr orbit_box(const Eigen::Vector3d& min, const Eigen::Vector3d& max);
OrbitSolidPtr orbit_sphere(const Eigen::Vector3d& centre, double radius);
/// Cylinder from `base` along unit `axis`, and the frustum from radius r1 at base to r2 at height.
OrbitSolidPtr orbit_cylinder(const Eigen::Vector3d& base, const Eigen::Vector3d& axis, double radius, double height);
OrbitSolidPtr orbit_cone(const Eigen::Vector3d& base, const Eigen::Vector3d& axis, double r1, double r2, double height);
/// Elliptic cylinder from the origin of `frame` along its z axis, semi-axis a along its x axis and b
/// along its y axis (frame: a rigid map from local to given coordinates).
OrbitSolidPtr orbit_elliptic_cylinder(const Eigen::Isometry3d& frame, double a, double b, double height);
OrbitSolidPtr orbit_torus(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis, double major, double minor);
OrbitSolidPtr orbit_union(std::vector<OrbitSolidPtr> parts);
OrbitSolidPtr orbit_intersection(std::vector<OrbitSolidPtr> parts);
OrbitSolidPtr orbit_difference(OrbitSolidPtr a, OrbitSolidPtr b);
OrbitSolidPtr orbit_placed(OrbitSolidPtr s, const Eigen::Isometry3d& placement);

/// A surface f(p) = 0 whose f is a polynomial of degree at most four in the coordinates of `frame`
/// (a rigid map from local to given coordinates), so that along an orbit f is a polynomial in t,
/// cos t and sin t: the surfaces of planar and quadric B-rep faces, and tori.
struct OrbitSurface {
  enum class Kind {
    Plane,     ///< local z = 0
    Cylinder,  ///< about the local z axis, of `radius`
    Cone,      ///< about the local z axis, of radius `radius` + `slope` z (both nappes)
    Sphere,    ///< about the local origin, of `radius`
    Torus,     ///< about the local z axis: its centre circle of `radius` in z = 0, its tube of `minor`
  };
  Kind kind = Kind::Plane;
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  double radius = 0, slope = 0, minor = 0;
  /// f at p (given coordinates): negative inside a closed surface, below a plane.
  double value(const Eigen::Vector3d& p) const;
};

/// The parameters t in [lo, hi] at which curve o crosses surface s (f changes sign), sorted. The
/// roots are isolated with a certified bound and refined to rounding, so a crossing is found
/// however short the stretch of the curve beyond the surface; a point where the curve only touches
/// the surface is not a crossing. Stretches of the curve that keep out of `region` (given
/// coordinates) are not searched.
std::vector<double> surface_crossings(const OrbitSurface& s, const OrbitCurve& o, double lo, double hi,
                                      const Eigen::AlignedBox3d& region);

/// A face of a solid whose faces lie on orbit surfaces: its surface, a box that holds it, and
/// whether a point of the surface lies on the face (its parameter domain: the caller's to give).
struct OrbitFace {
  OrbitSurface surface;
  Eigen::AlignedBox3d box;
  std::function<bool(const Eigen::Vector3d&)> holds;
};

/// The solid bounded by `faces` (a B-rep whose faces all lie on planes, quadrics and tori), inside
/// `bounds`, with `inside` its point membership. An orbit is cut at the crossings of the faces'
/// surfaces that the faces hold, and each piece between cuts is in the solid when `inside` holds
/// at its middle (so a cut too many changes nothing). Independent of any sweep of the solid: the
/// reference volume of a sweep of a part read from STEP.
OrbitSolidPtr orbit_faces(std::vector<OrbitFace> faces, std::function<bool(const Eigen::Vector3d&)> inside,
                          const Eigen::AlignedBox3d& bounds);

/// The sweep of `body` (in its position at t = 0) by joint j over t in [0, T] (a revolute T is taken
/// modulo nothing: T >= 2 pi covers whole circles). True when some t puts exp(-xi t) x in the body.
bool in_joint_sweep(const OrbitSolid& body, const ScrewJoint& j, double T, const Eigen::Vector3d& x);

/// The volume of that sweep, integrated over the space of orbits: the measure of each orbit's part in
/// the sweep (the union of the body's intervals, each extended by T) times the orbits' density.
/// Breakpoints where that union changes its structure are located, and each smooth piece is
/// integrated by double-exponential quadrature, nested twice. `rel_tol` is the target relative
/// accuracy; `error`, when given, receives an estimate of the absolute error.
double joint_sweep_volume(const OrbitSolid& body, const ScrewJoint& j, double T, double rel_tol = 1e-9,
                          double* error = nullptr);

/// The same volume as the mean of `shifts` midpoint rules on n x n lattices over the space of
/// orbits, each shifted by a random offset (randomized lattice rule): no breakpoint is located, so
/// no narrow feature is stepped over, and the spread of the shifts' results is an honest error
/// estimate (`error` receives the standard error of their mean). It converges slowly (a jump of
/// the measure along a curve leaves an error of about n^-1.5): a check of joint_sweep_volume where
/// its scan of the orbits may miss a gap or strip narrower than its step (helical sweeps).
double joint_sweep_volume_lattice(const OrbitSolid& body, const ScrewJoint& j, double T, int n, int shifts,
                                  std::uint64_t seed, double* error = nullptr);

}  // namespace sweep
