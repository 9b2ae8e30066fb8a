#pragma once
// Shared by the entity implementations (entity*.cpp): frames, the patches of revolved profiles,
// and the one Entity class that every core kind fills in.
#include <optional>
#include <vector>

#include "sweep/entity.hpp"
#include "sweep/membership.hpp"

namespace sweep::entity_detail {

/// A right-handed orthonormal frame in world coordinates.
struct Frame {
  Eigen::Vector3d o = Eigen::Vector3d::Zero(), x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(),
                  z = Eigen::Vector3d::UnitZ();
};

/// The frame at `origin` whose z is `axis`, both given in the entity's own frame, carried into
/// the world by `placement` (x: normal to the axis with the coordinate zero where the axis's is
/// smallest, as OCCT's axis placements take it, so that faces have their seams where OCCT's
/// primitives have them).
Frame placed_frame(const Eigen::Isometry3d& placement, const Eigen::Vector3d& origin, const Eigen::Vector3d& axis);

/// The face swept by the profile (rho(v), z(v)), v in [v0, v1], turned a whole turn about f's z
/// axis: x = o + rho (cos u x + sin u y) + z z over u in [0, 2 pi]. `orientation` +1 when the
/// profile's normal (z', -rho') points out of the solid.
PatchPtr revolved_face(const Frame& f, std::function<Eigen::Vector2d(double)> profile,
                       std::function<Eigen::Vector2d(double)> dprofile, double v0, double v1, PatchForm form,
                       std::string what, int orientation);
/// The circle of radius rho at height h about f's z axis, as an edge.
PatchPtr circle_edge(const Frame& f, double rho, double h, std::string what);
/// The disk of radius rho at height h about f's z axis (its normal -z when orientation is +1).
PatchPtr disk_face(const Frame& f, double rho, double h, std::string what, int orientation);

/// A distance given in the entity's own frame, carried by its placement (rigid: still 1-Lipschitz).
class PlacedDistance : public SignedDistance {
 public:
  PlacedDistance(const Eigen::Isometry3d& placement, std::function<double(const Eigen::Vector3d&)> f)
      : inverse_(placement.inverse()), f_(std::move(f)) {}
  double operator()(const Eigen::Vector3d& p) const override { return f_(inverse_ * p); }

 private:
  Eigen::Isometry3d inverse_;
  std::function<double(const Eigen::Vector3d&)> f_;
};

/// The Entity that every core kind builds: its parts filled in by the kind's maker.
class BuiltEntity : public Entity {
 public:
  EntityKind kind_ = EntityKind::Point;
  int dimension_ = 3;
  Eigen::AlignedBox3d box_;
  /// The inside test when it is not the distance bound's sign (a twisted elliptic cylinder).
  std::function<bool(const Eigen::Vector3d&)> inside_;
  std::optional<PlacedDistance> distance_;
  OrbitSolidPtr orbit_;
  std::vector<PatchPtr> faces_, edges_;

  EntityKind kind() const override { return kind_; }
  int dimension() const override { return dimension_; }
  Eigen::AlignedBox3d box() const override { return box_; }
  bool inside(const Eigen::Vector3d& p) const override {
    if (inside_) return inside_(p);
    return distance_ && (*distance_)(p) <= 0;
  }
  bool has_distance_bound() const override { return bool(distance_); }
  double distance(const Eigen::Vector3d& p) const override { return (*distance_)(p); }
  std::unique_ptr<SignedDistance> distance_bound() const override {
    return distance_ ? std::make_unique<PlacedDistance>(*distance_) : nullptr;
  }
  OrbitSolidPtr orbit_solid() const override { return orbit_; }
  const std::vector<PatchPtr>& faces() const override { return faces_; }
  const std::vector<PatchPtr>& edges() const override { return edges_; }
};

/// The makers of each kind (entity_primitives.cpp, entity_parametric.cpp).
std::shared_ptr<BuiltEntity> make_sphere(const EntitySpec& e);
std::shared_ptr<BuiltEntity> make_box(const EntitySpec& e);
std::shared_ptr<BuiltEntity> make_cylinder_or_cone(const EntitySpec& e);
std::shared_ptr<BuiltEntity> make_torus(const EntitySpec& e);
std::shared_ptr<BuiltEntity> make_elliptic_cylinder(const EntitySpec& e);
std::shared_ptr<BuiltEntity> make_parametric(const EntitySpec& e);

}  // namespace sweep::entity_detail
