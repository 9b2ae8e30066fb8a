// The primitive solids as entities: sphere, box, cylinder, cone, torus and elliptic cylinder, each
// with exact boxes, faces and creased edges, a distance bound and an orbit solid (those two but for
// a twisted elliptic cylinder).
#include <cmath>
#include <string>

#include "entity_internal.hpp"

namespace sweep::entity_detail {

using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

/// Half the extent along each world axis of a circle of radius rho whose plane is normal to z.
Vector3d circle_half_extent(const Vector3d& z, double rho) {
  return rho * (Vector3d::Ones() - z.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
}

/// The frame of the entity's own coordinates whose third column is `axis` (placed_frame's, unplaced).
Eigen::Matrix3d local_frame(const Vector3d& axis) {
  const Frame f = placed_frame(Eigen::Isometry3d::Identity(), Vector3d::Zero(), axis);
  Eigen::Matrix3d F;
  F << f.x, f.y, f.z;
  return F;
}

/// A solid entity with the distance bound `local` (in its own frame; its sign is the inside test)
/// and, when it has one, the orbit solid `orbit` (in its own frame).
std::shared_ptr<BuiltEntity> solid(const EntitySpec& e, std::function<double(const Vector3d&)> local,
                                   OrbitSolidPtr orbit) {
  auto s = std::make_shared<BuiltEntity>();
  s->kind_ = e.kind;
  s->dimension_ = 3;
  s->distance_ = PlacedDistance(e.placement, std::move(local));
  if (orbit) s->orbit_ = e.placement.isApprox(Eigen::Isometry3d::Identity(), 0.0) ? orbit : orbit_placed(orbit, e.placement);
  return s;
}

/// The closed form of a revolved face whose (u, v) are its own parameters.
PatchForm form_of(PatchForm::Kind kind, const Frame& f, double radius = 0, double minor = 0) {
  PatchForm form;
  form.kind = kind;
  form.surface_parameters = true;
  form.origin = f.o;
  form.axis = f.z;
  form.ref = f.x;
  form.radius = radius;
  form.minor = minor;
  return form;
}

}  // namespace

std::shared_ptr<BuiltEntity> make_sphere(const EntitySpec& e) {
  const Vector3d c = e.center;
  const double r = e.radius;
  auto s = solid(e, [c, r](const Vector3d& p) { return (p - c).norm() - r; }, orbit_sphere(c, r));
  const Frame f = placed_frame(e.placement, c, Vector3d::UnitZ());
  s->box_ = Eigen::AlignedBox3d(f.o - Vector3d::Constant(r), f.o + Vector3d::Constant(r));
  s->faces_.push_back(revolved_face(
      f, [r](double v) { return Vector2d(r * std::cos(v), r * std::sin(v)); },
      [r](double v) { return Vector2d(-r * std::sin(v), r * std::cos(v)); }, -M_PI / 2, M_PI / 2,
      form_of(PatchForm::Kind::Sphere, f, r), "the sphere", 1));
  return s;
}

std::shared_ptr<BuiltEntity> make_torus(const EntitySpec& e) {
  const Eigen::Matrix3d F = local_frame(e.axis);
  const Vector3d c = e.center;
  const double major = e.major, minor = e.minor;
  auto s = solid(
      e,
      [F, c, major, minor](const Vector3d& p) {
        const Vector3d l = F.transpose() * (p - c);
        return std::hypot(std::hypot(l.x(), l.y()) - major, l.z()) - minor;
      },
      orbit_torus(c, e.axis, major, minor));
  const Frame f = placed_frame(e.placement, e.center, e.axis);
  const double R = e.major, r = e.minor;
  const Vector3d half = circle_half_extent(f.z, R) + Vector3d::Constant(r);
  s->box_ = Eigen::AlignedBox3d(f.o - half, f.o + half);
  s->faces_.push_back(revolved_face(
      f, [R, r](double v) { return Vector2d(R + r * std::cos(v), r * std::sin(v)); },
      [r](double v) { return Vector2d(-r * std::sin(v), r * std::cos(v)); }, 0.0, 2 * M_PI,
      form_of(PatchForm::Kind::Torus, f, R, r), "the torus", 1));
  return s;
}

std::shared_ptr<BuiltEntity> make_cylinder_or_cone(const EntitySpec& e) {
  const bool cone = e.kind == EntityKind::Cone;
  const double r1 = cone ? e.radius1 : e.radius, r2 = cone ? e.radius2 : e.radius, h = e.height;
  const Eigen::Matrix3d F = local_frame(e.axis);
  const Vector3d b = e.base;
  // the slab 0 <= z <= h and the side through both rims, whose larger signed distance is
  // 1-Lipschitz with the right sign (for a cylinder, the exact distance)
  std::function<double(const Vector3d&)> distance;
  if (cone)
    distance = [F, b, r1, r2, h](const Vector3d& p) {
      const Vector3d l = F.transpose() * (p - b);
      const double rho = std::hypot(l.x(), l.y()), slab = std::abs(l.z() - 0.5 * h) - 0.5 * h;
      // the line from (r1, 0) to (r2, h) in (rho, z), its outward normal (h, r1 - r2)
      const double side = ((rho - r1) * h + l.z() * (r1 - r2)) / std::hypot(h, r1 - r2);
      return std::max(slab, side);
    };
  else
    distance = [F, b, r1, h](const Vector3d& p) {
      const Vector3d l = F.transpose() * (p - b);
      const double dr = std::hypot(l.x(), l.y()) - r1, dz = std::abs(l.z() - 0.5 * h) - 0.5 * h;
      return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0)) + std::min(std::max(dr, dz), 0.0);
    };
  auto s = solid(e, std::move(distance), cone ? orbit_cone(b, e.axis, r1, r2, h) : orbit_cylinder(b, e.axis, r1, h));
  const Frame f = placed_frame(e.placement, e.base, e.axis);
  const Vector3d lo_half = circle_half_extent(f.z, r1), hi_half = circle_half_extent(f.z, r2);
  s->box_ = Eigen::AlignedBox3d(f.o - lo_half, f.o + lo_half);
  s->box_.extend(f.o + h * f.z - hi_half);
  s->box_.extend(f.o + h * f.z + hi_half);
  const std::string name = cone ? "cone" : "cylinder";
  const double slope = (r2 - r1) / h;
  PatchForm side = form_of(PatchForm::Kind::Cylinder, f, r1);
  if (std::abs(r2 - r1) > 1e-12 * std::max(r1, r2)) {
    side.kind = PatchForm::Kind::Cone;
    side.semi_angle = std::atan(slope);
  }
  s->faces_.push_back(revolved_face(
      f, [r1, slope](double v) { return Vector2d(r1 + slope * v, v); },
      [slope](double) { return Vector2d(slope, 1.0); }, 0.0, h, side, "the lateral face of the " + name, 1));
  if (r1 > 0) {
    s->faces_.push_back(disk_face(f, r1, 0.0, "the base of the " + name, 1));
    s->edges_.push_back(circle_edge(f, r1, 0.0, "the base rim of the " + name));
  }
  if (r2 > 0) {
    s->faces_.push_back(disk_face(f, r2, h, "the top of the " + name, -1));
    s->edges_.push_back(circle_edge(f, r2, h, "the top rim of the " + name));
  }
  return s;
}

std::shared_ptr<BuiltEntity> make_box(const EntitySpec& e) {
  const Vector3d centre = 0.5 * (e.min + e.max), half = 0.5 * (e.max - e.min);
  auto s = solid(
      e,
      [centre, half](const Vector3d& p) {
        const Vector3d q = (p - centre).cwiseAbs() - half;
        return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
      },
      orbit_box(e.min, e.max));
  const Eigen::Matrix3d R = e.placement.linear();
  const Vector3d o = e.placement * e.min, L = e.max - e.min;
  s->box_ = Eigen::AlignedBox3d(o, o);
  for (int k = 0; k < 8; ++k)
    s->box_.extend(e.placement * Vector3d(k & 1 ? e.max.x() : e.min.x(), k & 2 ? e.max.y() : e.min.y(),
                                          k & 4 ? e.max.z() : e.min.z()));
  const char* axis_name = "xyz";
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const Vector3d Ei = R.col(i), Ej = R.col(j), Ek = R.col(k);
    for (int side = 0; side < 2; ++side) {
      // x = corner + u Ei + v Ej: xu x xv = Ek, outward on the max side
      const Vector3d corner = o + side * L[k] * Ek;
      PatchForm form;
      form.kind = PatchForm::Kind::Plane;
      form.origin = corner;
      form.axis = Ek;
      form.ref = Ei;
      form.surface_parameters = true;
      auto map = [corner, Ei, Ej](const double* t) { return PatchPoint{corner + t[0] * Ei + t[1] * Ej, Ei, Ej}; };
      s->faces_.push_back(std::make_shared<Patch>(2, std::vector<double>{0.0, 0.0}, std::vector<double>{L[i], L[j]},
                                                  std::move(map), form,
                                                  std::string("the ") + (side ? "max " : "min ") + axis_name[k] +
                                                      " face of the box",
                                                  side ? 1 : -1));
    }
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        const Vector3d start = o + a * L[i] * Ei + b * L[j] * Ej;
        PatchForm form;
        form.kind = PatchForm::Kind::Line;
        form.origin = start;
        form.axis = Ek;
        auto map = [start, Ek](const double* t) { return PatchPoint{start + t[0] * Ek, Ek, Vector3d::Zero()}; };
        s->edges_.push_back(std::make_shared<Patch>(1, std::vector<double>{0.0}, std::vector<double>{L[k]},
                                                    std::move(map), form,
                                                    std::string("an edge of the box along its ") + axis_name[k]));
      }
  }
  return s;
}

std::shared_ptr<BuiltEntity> make_elliptic_cylinder(const EntitySpec& e) {
  auto s = std::make_shared<BuiltEntity>();
  s->kind_ = e.kind;
  s->dimension_ = 3;
  const Eigen::Matrix3d F = e.elliptic_frame();
  const Frame f{e.placement * e.base, e.placement.linear() * F.col(0), e.placement.linear() * F.col(1),
                e.placement.linear() * F.col(2)};
  const double A = e.a, B = e.b, h = e.height;
  const std::optional<Expr> twist = e.twist;
  // the section's axes at height fraction w, and the twist's rate there
  auto axes = [f, twist](double w, Vector3d& X, Vector3d& Y, double* rate) {
    double g = 0;
    const double phi = twist ? (rate ? twist->eval_d1(&w, &g) : twist->eval(&w)) : 0.0;
    if (rate) *rate = g;
    X = std::cos(phi) * f.x + std::sin(phi) * f.y;
    Y = f.z.cross(X);
  };
  s->inside_ = [f, A, B, h, axes](const Vector3d& p) {
    const Vector3d l = p - f.o;
    const double w = l.dot(f.z) / h;
    if (!(w >= 0 && w <= 1)) return false;
    Vector3d X, Y;
    axes(w, X, Y, nullptr);
    return std::pow(l.dot(X) / A, 2) + std::pow(l.dot(Y) / B, 2) <= 1;
  };
  const bool twisted = e.twist && !e.twist->is_constant();
  if (!twisted) {
    // the slab and min(a, b) (|(x/a, y/b)| - 1), whose gradient is at most 1 in norm: the larger of
    // the two is 1-Lipschitz with the right sign (a twisted one has none here)
    const Eigen::Matrix3d F = e.elliptic_frame();
    const double phi = e.twist_at(0.0);
    const Vector3d X = std::cos(phi) * F.col(0) + std::sin(phi) * F.col(1), Y = F.col(2).cross(X), Z = F.col(2);
    const Vector3d base = e.base;
    s->distance_ = PlacedDistance(e.placement, [X, Y, Z, base, A, B, h](const Vector3d& p) {
      const Vector3d l = p - base;
      const double slab = std::abs(l.dot(Z) - 0.5 * h) - 0.5 * h;
      const double side = std::min(A, B) * (std::hypot(l.dot(X) / A, l.dot(Y) / B) - 1.0);
      return std::max(slab, side);
    });
    Eigen::Isometry3d local = Eigen::Isometry3d::Identity();
    local.linear() << X, Y, Z;
    local.translation() = base;
    s->orbit_ = orbit_placed(orbit_elliptic_cylinder(local, A, B, h), e.placement);
  }
  // a section's box: exact when untwisted, else that of the circle about it
  Vector3d X0, Y0;
  axes(0.0, X0, Y0, nullptr);
  const Vector3d reach = twisted ? circle_half_extent(f.z, std::max(A, B))
                                 : Vector3d(((A * X0).cwiseAbs2() + (B * Y0).cwiseAbs2()).cwiseSqrt());
  s->box_ = Eigen::AlignedBox3d(f.o - reach, f.o + reach);
  s->box_.extend(f.o + h * f.z - reach);
  s->box_.extend(f.o + h * f.z + reach);
  auto lateral = [f, A, B, h, axes](const double* t) {
    Vector3d X, Y;
    double rate = 0;
    axes(t[1], X, Y, &rate);
    const double c = std::cos(t[0]), sn = std::sin(t[0]);
    return PatchPoint{f.o + A * c * X + B * sn * Y + t[1] * h * f.z, -A * sn * X + B * c * Y,
                      rate * (A * c * Y - B * sn * X) + h * f.z};
  };
  s->faces_.push_back(std::make_shared<Patch>(2, std::vector<double>{0.0, 0.0}, std::vector<double>{2 * M_PI, 1.0},
                                              lateral, PatchForm{}, "the lateral face of the elliptic cylinder", 1));
  for (int end = 0; end < 2; ++end) {
    Vector3d X, Y;
    axes(end, X, Y, nullptr);
    const Vector3d c0 = f.o + end * h * f.z;
    PatchForm plane;
    plane.kind = PatchForm::Kind::Plane;
    plane.origin = c0;
    plane.axis = f.z;
    plane.ref = X;
    // (u, rho): x = c0 + rho (A cos u X + B sin u Y), xu x xrho = -rho A B z
    auto cap = [c0, X, Y, A, B](const double* t) {
      const double c = std::cos(t[0]), sn = std::sin(t[0]);
      return PatchPoint{c0 + t[1] * (A * c * X + B * sn * Y), t[1] * (-A * sn * X + B * c * Y), A * c * X + B * sn * Y};
    };
    s->faces_.push_back(std::make_shared<Patch>(2, std::vector<double>{0.0, 0.0}, std::vector<double>{2 * M_PI, 1.0},
                                                cap, plane,
                                                std::string("the ") + (end ? "top" : "base") +
                                                    " of the elliptic cylinder",
                                                end ? -1 : 1));
    PatchForm ellipse = plane;
    ellipse.kind = PatchForm::Kind::Ellipse;
    ellipse.radius = A;
    ellipse.minor = B;
    auto rim = [c0, X, Y, A, B](const double* t) {
      const double c = std::cos(t[0]), sn = std::sin(t[0]);
      return PatchPoint{c0 + A * c * X + B * sn * Y, -A * sn * X + B * c * Y, Vector3d::Zero()};
    };
    s->edges_.push_back(std::make_shared<Patch>(1, std::vector<double>{0.0}, std::vector<double>{2 * M_PI}, rim,
                                                ellipse,
                                                std::string("the ") + (end ? "top" : "base") +
                                                    " rim of the elliptic cylinder"));
  }
  return s;
}

}  // namespace sweep::entity_detail
