// The core entities (sweep/entity.hpp): faces whose exact derivatives match differences, that
// close around the solid with the outward orientation (the divergence volume and the area against
// closed forms), that lie on the closed forms they name; boxes that hold them; inside tests and
// distance bounds that agree with them and with each other.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <sstream>

#include "sweep/entity.hpp"
#include "sweep/membership.hpp"

using Eigen::Vector3d;
using namespace sweep;

namespace {

std::string vec(const Vector3d& v) {
  std::ostringstream o;
  o.precision(17);
  o << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return o.str();
}

std::string num(double x) {
  std::ostringstream o;
  o.precision(17);
  o << x;
  return o.str();
}

EntityPtr entity_of(const std::string& entity_json) {
  const std::string text = R"({"sweep": 1, "entity": )" + entity_json +
                           R"(, "motion": {"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0],
                              "direction": [0, 0, 1], "range": [0, 1]}]}})";
  return make_entity(parse_spec(text, "").entity);
}

/// A random placement, as the spec's `placement` field.
std::string placement(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vector3d t(2 * u(rng), 2 * u(rng), 2 * u(rng)), axis(u(rng), u(rng), u(rng) + 1.5);
  std::ostringstream o;
  o.precision(17);
  o << R"(, "placement": {"translate": )" << vec(t) << R"(, "rotate": {"axis": )" << vec(axis)
    << R"(, "angle": )" << 3 * u(rng) << "}}";
  return o.str();
}

/// Gauss-Legendre nodes and weights on [-1, 1], 8 points.
constexpr double kNode[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                             0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
constexpr double kWeight[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                               0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

struct Integrals {
  double volume = 0, area = 0;
};

/// The divergence volume (1/3 of x . n over the faces, n outward) and the area of the faces.
Integrals integrate(const Entity& e, int cells = 16) {
  Integrals out;
  for (const PatchPtr& f : e.faces()) {
    const double du = (f->hi(0) - f->lo(0)) / cells, dv = (f->hi(1) - f->lo(1)) / cells;
    for (int i = 0; i < cells; ++i)
      for (int k = 0; k < cells; ++k)
        for (int a = 0; a < 8; ++a)
          for (int b = 0; b < 8; ++b) {
            const double u = f->lo(0) + du * (i + 0.5 + 0.5 * kNode[a]), v = f->lo(1) + dv * (k + 0.5 + 0.5 * kNode[b]);
            const PatchPoint p = f->eval(u, v);
            const Vector3d n = p.xu.cross(p.xv);
            const double w = 0.25 * du * dv * kWeight[a] * kWeight[b];
            out.volume += f->orientation() * p.x.dot(n) / 3 * w;
            out.area += n.norm() * w;
          }
  }
  return out;
}

/// Samples of a patch over its parameter box (n per parameter, ends included).
std::vector<PatchPoint> samples(const Patch& f, int n) {
  std::vector<PatchPoint> out;
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= (f.dim() > 1 ? n : 0); ++k)
      out.push_back(f.eval(f.lo(0) + (f.hi(0) - f.lo(0)) * i / n,
                           f.dim() > 1 ? f.lo(1) + (f.hi(1) - f.lo(1)) * k / n : 0.0));
  return out;
}

/// How far x is from the closed form `form` names (0 for General).
double off_form(const PatchForm& form, const Vector3d& x) {
  const Vector3d l = x - form.origin;
  const double along = l.dot(form.axis), across = (l - along * form.axis).norm();
  switch (form.kind) {
    case PatchForm::Kind::General: return 0;
    case PatchForm::Kind::Plane: return std::abs(along);
    case PatchForm::Kind::Cylinder: return std::abs(across - form.radius);
    case PatchForm::Kind::Cone: return std::abs(across - form.radius - std::tan(form.semi_angle) * along);
    case PatchForm::Kind::Sphere: return std::abs(l.norm() - form.radius);
    case PatchForm::Kind::Torus: return std::abs(std::hypot(across - form.radius, along) - form.minor);
    case PatchForm::Kind::Line: return l.cross(form.axis).norm();
    case PatchForm::Kind::Circle: return std::abs(along) + std::abs(across - form.radius);
    case PatchForm::Kind::Ellipse: {
      const Vector3d y = form.axis.cross(form.ref);
      return std::abs(along) + std::abs(std::hypot(l.dot(form.ref) / form.radius, l.dot(y) / form.minor) - 1) *
                                   std::min(form.radius, form.minor);
    }
  }
  return 1e300;
}

/// The point of a form at its own parameters (PatchForm::surface_parameters), OCCT's conventions.
Vector3d form_point(const PatchForm& f, double u, double v) {
  const Vector3d y = f.axis.cross(f.ref), radial = std::cos(u) * f.ref + std::sin(u) * y;
  switch (f.kind) {
    case PatchForm::Kind::Plane: return f.origin + u * f.ref + v * y;
    case PatchForm::Kind::Cylinder: return f.origin + f.radius * radial + v * f.axis;
    case PatchForm::Kind::Cone: return f.origin + (f.radius + v * std::tan(f.semi_angle)) * radial + v * f.axis;
    case PatchForm::Kind::Sphere: return f.origin + f.radius * (std::cos(v) * radial + std::sin(v) * f.axis);
    case PatchForm::Kind::Torus: return f.origin + (f.radius + f.minor * std::cos(v)) * radial + f.minor * std::sin(v) * f.axis;
    default: return Vector3d::Constant(1e300);
  }
}

/// Every check that needs no closed form: derivatives, forms, box, faces on the boundary with the
/// inside on their inner side, edges on the boundary, inside test against the distance bound.
void check_entity(const Entity& e, double scale, bool tight_box, std::mt19937_64& rng) {
  INFO("entity of dimension " << e.dimension() << ", kind " << to_string(e.kind()));
  const double h = 1e-6;
  Eigen::AlignedBox3d seen;
  std::vector<const Patch*> patches;
  for (const PatchPtr& f : e.faces()) patches.push_back(f.get());
  for (const PatchPtr& f : e.edges()) patches.push_back(f.get());
  std::uniform_real_distribution<double> uni(0.02, 0.98);
  for (const Patch* f : patches) {
    INFO(f->what());
    for (int t = 0; t < 20; ++t) {
      const double u = f->lo(0) + (f->hi(0) - f->lo(0)) * uni(rng);
      const double v = f->dim() > 1 ? f->lo(1) + (f->hi(1) - f->lo(1)) * uni(rng) : 0.0;
      const PatchPoint p = f->eval(u, v);
      CHECK((p.xu - (f->eval(u + h, v).x - f->eval(u - h, v).x) / (2 * h)).norm() < 1e-6 * scale);
      if (f->dim() > 1) CHECK((p.xv - (f->eval(u, v + h).x - f->eval(u, v - h).x) / (2 * h)).norm() < 1e-6 * scale);
    }
    if (f->form().surface_parameters)
      for (int t = 0; t < 20; ++t) {
        const double u = f->lo(0) + (f->hi(0) - f->lo(0)) * uni(rng), v = f->lo(1) + (f->hi(1) - f->lo(1)) * uni(rng);
        CHECK((f->eval(u, v).x - form_point(f->form(), u, v)).norm() < 1e-12 * scale);
      }
    for (const PatchPoint& p : samples(*f, 40)) {
      seen.extend(p.x);
      CHECK(off_form(f->form(), p.x) < 1e-12 * scale);
      CHECK(e.box().exteriorDistance(p.x) < 1e-12 * scale);
      if (e.has_distance_bound()) CHECK(std::abs(e.distance(p.x)) < 1e-12 * scale);
    }
  }
  // primitives' boxes are exact; a parametric entity's holds cells enlarged by what the map moves in them
  if (tight_box) CHECK((e.box().sizes() - seen.sizes()).maxCoeff() < (e.dimension() == 3 ? 1e-2 : 3e-2) * scale);
  // just inside and just outside each face, away from poles and edges
  const double eps = 1e-7 * scale;
  for (const PatchPtr& f : e.faces())
    for (int t = 0; t < 50 && e.dimension() == 3; ++t) {
      const PatchPoint p = f->eval(f->lo(0) + (f->hi(0) - f->lo(0)) * uni(rng), f->lo(1) + (f->hi(1) - f->lo(1)) * uni(rng));
      const Vector3d n = f->orientation() * p.xu.cross(p.xv);
      if (n.norm() < 1e-3 * scale * scale) continue;
      INFO(f->what() << " at " << vec(p.x));
      CHECK(e.inside(p.x - eps * n.normalized()));
      CHECK_FALSE(e.inside(p.x + eps * n.normalized()));
    }
  // the inside test and the distance bound agree; the bound is below the distance to the faces
  std::vector<Vector3d> boundary;
  for (const PatchPtr& f : e.faces())
    for (const PatchPoint& p : samples(*f, 60)) boundary.push_back(p.x);
  std::uniform_real_distribution<double> in_box(-0.25, 1.25);
  for (int t = 0; t < 300; ++t) {
    const Vector3d p = e.box().min() + e.box().sizes().cwiseProduct(Vector3d(in_box(rng), in_box(rng), in_box(rng)));
    if (!e.has_distance_bound()) continue;
    const double d = e.distance(p);
    double nearest = 1e300;
    for (const Vector3d& q : boundary) nearest = std::min(nearest, (p - q).norm());
    CHECK(std::abs(d) <= nearest + 1e-12 * scale);
    if (std::abs(d) > 1e-9 * scale) CHECK(e.inside(p) == (d < 0));
  }
}

}  // namespace

TEST_CASE("Entities: primitives' faces close around the solid (volume and area against closed forms)", "[entity]") {
  std::mt19937_64 rng(20261205);
  std::uniform_real_distribution<double> size(0.3, 2.0);
  for (int round = 0; round < 4; ++round) {
    const double r = size(rng), h = size(rng), r2 = size(rng), a = size(rng), b = size(rng), c = size(rng);
    const std::string pl = placement(rng);
    struct Case {
      std::string json;
      double volume, area;  // area < 0: no closed form
      std::size_t edges;
    };
    const double small = std::min(r, r2) * 0.45, big = std::max(r, r2);
    const std::vector<Case> cases = {
        {R"({"kind": "sphere", "center": [0.3, -0.2, 0.5], "radius": )" + num(r) + pl + "}",
         4.0 / 3 * M_PI * r * r * r, 4 * M_PI * r * r, 0},
        {R"({"kind": "box", "min": [-0.1, 0.2, 0.3], "max": )" + vec(Vector3d(-0.1 + a, 0.2 + b, 0.3 + c)) + pl + "}",
         a * b * c, 2 * (a * b + b * c + c * a), 12},
        {R"({"kind": "cylinder", "base": [0.1, 0, -0.4], "axis": [1, 2, -0.5], "radius": )" + num(r) +
             R"(, "height": )" + num(h) + pl + "}",
         M_PI * r * r * h, 2 * M_PI * r * h + 2 * M_PI * r * r, 2},
        {R"({"kind": "cone", "base": [0, 0.5, 0], "axis": [-0.3, 0.1, 1], "radius1": )" + num(r) +
             R"(, "radius2": )" + num(r2) + R"(, "height": )" + num(h) + pl + "}",
         M_PI * h / 3 * (r * r + r * r2 + r2 * r2),
         M_PI * (r + r2) * std::hypot(r - r2, h) + M_PI * (r * r + r2 * r2), 2},
        {R"({"kind": "cone", "base": [0, 0, 0], "axis": [0, 1, 0], "radius1": )" + num(r) +
             R"(, "radius2": 0, "height": )" + num(h) + pl + "}",
         M_PI * h / 3 * r * r, M_PI * r * std::hypot(r, h) + M_PI * r * r, 1},
        {R"({"kind": "torus", "center": [0.2, 0.2, 0.2], "axis": [0.5, -1, 0.2], "major": )" + num(big) +
             R"(, "minor": )" + num(small) + pl + "}",
         2 * M_PI * M_PI * big * small * small, 4 * M_PI * M_PI * big * small, 0},
        {R"({"kind": "elliptic_cylinder", "base": [0, 0, 0.3], "axis": [0.2, 0.3, 1], "a": )" + num(a) +
             R"(, "b": )" + num(b) + R"(, "height": )" + num(h) + pl + "}",
         M_PI * a * b * h, -1, 2},
        {R"({"kind": "elliptic_cylinder", "base": [0, 0, 0.3], "axis": [0, 0, 1], "a": )" + num(a) +
             R"(, "b": )" + num(b) + R"(, "height": )" + num(h) + R"(, "twist": "2*u^2-0.5")" + pl +
             "}",
         M_PI * a * b * h, -1, 2},
    };
    for (const Case& k : cases) {
      INFO(k.json);
      const EntityPtr e = entity_of(k.json);
      REQUIRE(e);
      CHECK(e->dimension() == 3);
      CHECK(e->edges().size() == k.edges);
      const Integrals got = integrate(*e);
      CHECK(got.volume == Approx(k.volume).epsilon(1e-9));
      if (k.area > 0) CHECK(got.area == Approx(k.area).epsilon(1e-9));
      const bool twisted = k.json.find("twist") != std::string::npos;
      CHECK(e->has_distance_bound() == !twisted);
      check_entity(*e, e->box().sizes().maxCoeff(), !twisted, rng);
    }
  }
}

TEST_CASE("Entities: a twisted elliptic cylinder turns its sections by the twist", "[entity]") {
  const EntityPtr e = entity_of(
      R"({"kind": "elliptic_cylinder", "base": [0, 0, 0], "axis": [0, 0, 1], "a": 2, "b": 0.5, "height": 4, "twist": "pi/2*u"})");
  REQUIRE(e);
  // at half height the a semi-axis has turned 45 degrees from world x
  const double s = std::sqrt(0.5);
  CHECK(e->inside(Vector3d(1.9 * s, 1.9 * s, 2)));
  CHECK_FALSE(e->inside(Vector3d(1.9, 0, 2)));
  // at the top it lies along y
  CHECK(e->inside(Vector3d(0, 1.9, 3.999)));
  CHECK_FALSE(e->inside(Vector3d(1.9, 0, 3.999)));
  CHECK_FALSE(e->inside(Vector3d(0, 0, 4.001)));
}

TEST_CASE("Entities: points, curves and surfaces are their own patch", "[entity]") {
  std::mt19937_64 rng(7);
  const std::string pl = placement(rng);
  const EntityPtr point = entity_of(R"({"kind": "point", "at": [1, 2, 3])" + pl + "}");
  REQUIRE(point);
  CHECK(point->dimension() == 0);
  CHECK(point->box().sizes().norm() == 0);
  CHECK_FALSE(point->inside(point->box().min()));

  const EntityPtr curve =
      entity_of(R"J({"kind": "curve", "params": {"s": [0, 2]}, "xyz": ["cos(3*s)", "sin(3*s)", "s^2"])J" + pl + "}");
  REQUIRE(curve);
  CHECK(curve->dimension() == 1);
  REQUIRE(curve->faces().size() == 1);
  CHECK(curve->edges().empty());
  // its length: integral of sqrt(9 + 4 s^2) over [0, 2], placement or not
  double length = 0;
  const Patch& c = *curve->faces()[0];
  for (int i = 0; i < 64; ++i)
    for (int a = 0; a < 8; ++a) length += c.eval((i + 0.5 + 0.5 * kNode[a]) * 2.0 / 64).xu.norm() * kWeight[a] / 64;
  const double exact = 0.25 * (2 * 2 * 5 + 9 * std::asinh(4.0 / 3));  // [s/2 sqrt(9+4s^2) + 9/4 asinh(2s/3)]_0^2
  CHECK(length == Approx(exact).epsilon(1e-10));
  check_entity(*curve, 4.0, true, rng);

  // a hemisphere: the pole and the seam are no edges, the equator is one
  const EntityPtr dome = entity_of(
      R"J({"kind": "surface", "params": {"u": [0, 6.283185307179586], "v": [0, 1.5707963267948966]},
          "xyz": ["cos(u)*cos(v)", "sin(u)*cos(v)", "sin(v)"])J" + pl + "}");
  REQUIRE(dome);
  CHECK(dome->dimension() == 2);
  REQUIRE(dome->edges().size() == 1);
  CHECK(dome->edges()[0]->fixed.at(0).first == "v");
  CHECK(integrate(*dome).area == Approx(2 * M_PI).epsilon(1e-9));
  check_entity(*dome, 2.0, true, rng);

  const EntityPtr square =
      entity_of(R"J({"kind": "surface", "params": {"u": [0, 1], "v": [0, 2]}, "xyz": ["u", "v", "u*v"]})J");
  REQUIRE(square);
  CHECK(square->edges().size() == 4);
}

TEST_CASE("Entities: kinds the core does not build give none", "[entity]") {
  EntitySpec brep;
  brep.kind = EntityKind::Brep;
  CHECK_FALSE(make_entity(brep));
  EntitySpec mesh;
  mesh.kind = EntityKind::Mesh;
  CHECK_FALSE(make_entity(mesh));
}

TEST_CASE("Entities: the signed distances and orbit solids of membership and orbits are the entity's", "[entity]") {
  std::mt19937_64 rng(16);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::string pl = placement(rng);
  for (const std::string& json :
       {R"({"kind": "sphere", "center": [0.3, 0, 0], "radius": 0.7)" + pl + "}",
        R"({"kind": "box", "min": [0, 0, 0], "max": [1, 0.5, 0.7])" + pl + "}",
        R"({"kind": "cylinder", "base": [0, 0, 0], "axis": [1, 0, 1], "radius": 0.4, "height": 1.2)" + pl + "}",
        R"({"kind": "cone", "base": [0, 0, 0], "axis": [0, 1, 1], "radius1": 0.6, "radius2": 0.2, "height": 1)" + pl + "}",
        R"({"kind": "torus", "center": [0, 0, 0], "axis": [0, 0, 1], "major": 1, "minor": 0.3)" + pl + "}",
        R"({"kind": "elliptic_cylinder", "base": [0.1, 0, 0], "axis": [1, 1, 0], "a": 0.8, "b": 0.3, "height": 1.1,
            "twist": 0.4)" + pl + "}"}) {
    INFO(json);
    const EntitySpec spec = parse_spec(R"({"sweep": 1, "entity": )" + json +
                                           R"(, "motion": {"kind": "axes", "joints": [{"type": "prismatic",
                                              "direction": [0, 0, 1], "range": [0, 1]}]}})",
                                       "")
                                .entity;
    const EntityPtr e = make_entity(spec);
    const auto sd = make_signed_distance(spec);
    const OrbitSolidPtr orbit = make_orbit_solid(spec);
    REQUIRE(e);
    REQUIRE(sd);
    REQUIRE(orbit);
    for (int k = 0; k < 500; ++k) {
      const Vector3d p = e->box().center() + e->box().sizes().cwiseProduct(Vector3d(u(rng), u(rng), u(rng)));
      CHECK((*sd)(p) == e->distance(p));
      if (std::abs(e->distance(p)) > 1e-9) CHECK(orbit->contains(p) == e->inside(p));
    }
  }
  EntitySpec twisted = parse_spec(R"J({"sweep": 1, "entity": {"kind": "elliptic_cylinder", "base": [0, 0, 0],
      "axis": [0, 0, 1], "a": 1, "b": 0.5, "height": 2, "twist": "u"}, "motion": {"kind": "axes", "joints": [
      {"type": "prismatic", "direction": [0, 0, 1], "range": [0, 1]}]}})J",
                                  "")
                           .entity;
  CHECK_FALSE(make_signed_distance(twisted));
  CHECK_FALSE(make_orbit_solid(twisted));
}
