// Patches, the frames and revolved faces the primitives share, and make_entity(): the one switch
// on the entity kind.
#include "sweep/entity.hpp"

#include <algorithm>
#include <cmath>

#include "entity_internal.hpp"

namespace sweep {

const char* to_string(PatchForm::Kind k) {
  switch (k) {
    case PatchForm::Kind::General: return "general";
    case PatchForm::Kind::Plane: return "plane";
    case PatchForm::Kind::Cylinder: return "cylinder";
    case PatchForm::Kind::Cone: return "cone";
    case PatchForm::Kind::Sphere: return "sphere";
    case PatchForm::Kind::Torus: return "torus";
    case PatchForm::Kind::Line: return "line";
    case PatchForm::Kind::Circle: return "circle";
    case PatchForm::Kind::Ellipse: return "ellipse";
  }
  return "?";
}

Patch::Patch(int dim, std::vector<double> lo, std::vector<double> hi, Map map, PatchForm form, std::string what,
             int orientation)
    : dim_(dim), lo_(std::move(lo)), hi_(std::move(hi)), map_(std::move(map)), form_(form), what_(std::move(what)),
      orientation_(orientation < 0 ? -1 : 1) {}

Eigen::Vector3d side_point(const Patch& p, int side, double f) {
  const double u = p.lo(0) + (p.hi(0) - p.lo(0)) * f, v = p.lo(1) + (p.hi(1) - p.lo(1)) * f;
  switch (side) {
    case 0: return p.eval(u, p.lo(1)).x;
    case 1: return p.eval(p.hi(0), v).x;
    case 2: return p.eval(p.hi(0) + p.lo(0) - u, p.hi(1)).x;
    default: return p.eval(p.lo(0), p.hi(1) + p.lo(1) - v).x;
  }
}

std::vector<int> bounding_sides(const Patch& p, double tol, int n) {
  std::vector<Eigen::Vector3d> pts[4];
  for (int k = 0; k < 4; ++k)
    for (int i = 0; i <= n; ++i) pts[k].push_back(side_point(p, k, double(i) / n));
  bool keep[4];
  for (int k = 0; k < 4; ++k)
    keep[k] = std::any_of(pts[k].begin(), pts[k].end(), [&](const Eigen::Vector3d& q) { return (q - pts[k][0]).norm() > tol; });
  for (int k = 0; k < 2; ++k) {
    bool meet = true;  // opposite sides, both counter-clockwise, run against each other
    for (int i = 0; i <= n && meet; ++i) meet = (pts[k][i] - pts[k + 2][n - i]).norm() <= tol;
    if (meet) keep[k] = keep[k + 2] = false;
  }
  std::vector<int> out;
  for (int k = 0; k < 4; ++k)
    if (keep[k]) out.push_back(k);
  return out;
}

Eigen::Vector2d parameter_periods(const Patch& p) {
  Eigen::Vector2d period(0, 0);
  for (int k = 0; k < 2; ++k) {
    const int a = k == 0 ? 3 : 0, b = k == 0 ? 1 : 2;
    double size = (side_point(p, b, 0) - side_point(p, a, 0)).norm(), gap = 0;
    for (int i = 0; i <= 16; ++i) {
      const double f = i / 16.0;
      // both sides run counter-clockwise, so opposite sides meet point for point at f and 1 - f
      gap = std::max(gap, (side_point(p, a, f) - side_point(p, b, 1 - f)).norm());
      size = std::max(size, (side_point(p, a, f) - side_point(p, a, 0)).norm());
    }
    if (gap <= 1e-12 * std::max(size, 1.0)) period[k] = p.hi(k) - p.lo(k);
  }
  return period;
}

PatchPtr patch_part(const PatchPtr& p, const std::vector<double>& lo, const std::vector<double>& hi) {
  auto part = std::make_shared<Patch>(p->dim(), lo, hi, [p](const double* s) { return p->eval(s); }, p->form(),
                                      p->what(), p->orientation());
  part->fixed = p->fixed;
  part->trimmed = p->trimmed;
  return part;
}

Eigen::Vector2d wrapped_parameters(const Patch& p, Eigen::Vector2d s, const Eigen::Vector2d& period) {
  for (int k = 0; k < 2; ++k)
    if (period[k] > 0) s[k] = p.lo(k) + std::fmod(std::fmod(s[k] - p.lo(k), period[k]) + period[k], period[k]);
  return s;
}

namespace entity_detail {

using Eigen::Vector2d;
using Eigen::Vector3d;

Frame placed_frame(const Eigen::Isometry3d& placement, const Vector3d& origin, const Vector3d& axis) {
  const Vector3d z = axis.normalized();
  // x normal to z with one of its coordinates zero: the one of z's smallest magnitude (the first
  // such), the other two from z's larger two, so that OCCT's primitives have their seams here too
  const double a = z.x(), b = z.y(), c = z.z(), A = std::abs(a), B = std::abs(b), C = std::abs(c);
  Vector3d x;
  if (B <= A && B <= C)
    x = A > C ? Vector3d(-c, 0, a) : Vector3d(c, 0, -a);
  else if (A <= B && A <= C)
    x = B > C ? Vector3d(0, -c, b) : Vector3d(0, c, -b);
  else
    x = A > B ? Vector3d(-b, a, 0) : Vector3d(b, -a, 0);
  x.normalize();
  Frame f;
  f.o = placement * origin;
  f.z = placement.linear() * z;
  f.x = placement.linear() * x;
  f.y = f.z.cross(f.x);
  return f;
}

PatchPtr revolved_face(const Frame& f, std::function<Vector2d(double)> profile,
                       std::function<Vector2d(double)> dprofile, double v0, double v1, PatchForm form,
                       std::string what, int orientation) {
  auto map = [f, profile = std::move(profile), dprofile = std::move(dprofile)](const double* s) {
    const double c = std::cos(s[0]), sn = std::sin(s[0]);
    const Vector2d rz = profile(s[1]), d = dprofile(s[1]);
    const Vector3d radial = c * f.x + sn * f.y, around = -sn * f.x + c * f.y;
    return PatchPoint{f.o + rz[0] * radial + rz[1] * f.z, rz[0] * around, d[0] * radial + d[1] * f.z};
  };
  form.revolved = true;
  return std::make_shared<Patch>(2, std::vector<double>{0.0, v0}, std::vector<double>{2 * M_PI, v1}, std::move(map),
                                 form, std::move(what), orientation);
}

PatchPtr circle_edge(const Frame& f, double rho, double h, std::string what) {
  PatchForm form;
  form.kind = PatchForm::Kind::Circle;
  form.origin = f.o + h * f.z;
  form.axis = f.z;
  form.ref = f.x;
  form.radius = rho;
  auto map = [f, rho, h](const double* s) {
    const double c = std::cos(s[0]), sn = std::sin(s[0]);
    return PatchPoint{f.o + rho * (c * f.x + sn * f.y) + h * f.z, rho * (-sn * f.x + c * f.y), Vector3d::Zero()};
  };
  return std::make_shared<Patch>(1, std::vector<double>{0.0}, std::vector<double>{2 * M_PI}, std::move(map), form,
                                 std::move(what));
}

PatchPtr disk_face(const Frame& f, double rho, double h, std::string what, int orientation) {
  PatchForm form;
  form.kind = PatchForm::Kind::Plane;
  form.origin = f.o + h * f.z;
  form.axis = f.z;
  form.ref = f.x;
  return revolved_face(
      f, [h](double v) { return Vector2d(v, h); }, [](double) { return Vector2d(1.0, 0.0); }, 0.0, rho, form,
      std::move(what), orientation);
}

}  // namespace entity_detail

EntityPtr make_entity(const EntitySpec& e) {
  using namespace entity_detail;
  switch (e.kind) {
    case EntityKind::Point:
    case EntityKind::Curve:
    case EntityKind::Surface: return make_parametric(e);
    case EntityKind::Sphere: return make_sphere(e);
    case EntityKind::Box: return make_box(e);
    case EntityKind::Cylinder:
    case EntityKind::Cone: return make_cylinder_or_cone(e);
    case EntityKind::Torus: return make_torus(e);
    case EntityKind::EllipticCylinder: return make_elliptic_cylinder(e);
    default: return nullptr;  // brep and mesh: the bridge's; the others are not supported yet
  }
}

}  // namespace sweep
