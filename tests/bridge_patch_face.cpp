// Core patches as OCCT faces (faces/patch_face.cpp): every primitive's faces, sewn, make a valid
// closed solid of its closed-form volume, on exact surfaces of the kinds their forms name; a
// patch with no closed form becomes a B-spline whose measured error is within the tolerance.
#include <BRepAdaptor_Surface.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRep_Tool.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <GProp_GProps.hxx>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sstream>

#include "base/internal.hpp"
#include "faces/patch_face.hpp"
#include "sweep/entity.hpp"
#include "sweep/spec.hpp"

namespace {

std::string num(double x) {
  std::ostringstream o;
  o.precision(17);
  o << x;
  return o.str();
}

sweep::EntityPtr entity_of(const std::string& entity_json) {
  const std::string text = R"({"sweep": 1, "entity": )" + entity_json +
                           R"(, "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [0, 0, 1],
                              "range": [0, 1]}]}})";
  return sweep::make_entity(sweep::parse_spec(text, "").entity);
}

GeomAbs_SurfaceType occt_type(sweep::PatchForm::Kind k) {
  switch (k) {
    case sweep::PatchForm::Kind::Plane: return GeomAbs_Plane;
    case sweep::PatchForm::Kind::Cylinder: return GeomAbs_Cylinder;
    case sweep::PatchForm::Kind::Cone: return GeomAbs_Cone;
    case sweep::PatchForm::Kind::Sphere: return GeomAbs_Sphere;
    case sweep::PatchForm::Kind::Torus: return GeomAbs_Torus;
    default: return GeomAbs_BSplineSurface;
  }
}

/// Placed primitives of random sizes (spheres, boxes, cylinders, cones with and without an apex,
/// tori, elliptic cylinders plain and twisted) as entity JSON, each with its closed-form volume.
std::vector<std::pair<std::string, double>> placed_primitives(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), size(0.3, 2.0);
  const double r = size(rng), r2 = size(rng), h = size(rng), a = size(rng), b = size(rng), c = size(rng);
  const double ax = u(rng), ay = u(rng), angle = 3 * u(rng), tx = u(rng), ty = u(rng);
  const std::string pl = R"(, "placement": {"translate": [)" + num(tx) + ", " + num(ty) +
                         R"(, 0.5], "rotate": {"axis": [)" + num(ax) + ", " + num(ay) + R"(, 1], "angle": )" +
                         num(angle) + "}}";
  const double big = std::max(r, r2), small = 0.45 * std::min(r, r2);
  return {
      {R"({"kind": "sphere", "center": [0.1, 0.2, 0.3], "radius": )" + num(r) + pl + "}", 4.0 / 3 * M_PI * r * r * r},
      {R"({"kind": "box", "min": [0, 0, 0], "max": [)" + num(a) + ", " + num(b) + ", " + num(c) + "]" + pl + "}",
       a * b * c},
      {R"({"kind": "cylinder", "base": [0, 0, 0], "axis": [1, 1, 0.3], "radius": )" + num(r) + R"(, "height": )" +
           num(h) + pl + "}",
       M_PI * r * r * h},
      {R"({"kind": "cone", "base": [0, 0, 0], "axis": [0.2, -1, 0.5], "radius1": )" + num(r) + R"(, "radius2": )" +
           num(r2) + R"(, "height": )" + num(h) + pl + "}",
       M_PI * h / 3 * (r * r + r * r2 + r2 * r2)},
      {R"({"kind": "cone", "base": [0, 0, 0], "axis": [0, 0, 1], "radius1": )" + num(r) +
           R"(, "radius2": 0, "height": )" + num(h) + pl + "}",
       M_PI * h / 3 * r * r},
      {R"({"kind": "cone", "base": [0, 0, 0], "axis": [0, 0, 1], "radius1": 0, "radius2": )" + num(r2) +
           R"(, "height": )" + num(h) + pl + "}",
       M_PI * h / 3 * r2 * r2},
      {R"({"kind": "torus", "center": [0, 0, 0], "axis": [1, 0, 1], "major": )" + num(big) + R"(, "minor": )" +
           num(small) + pl + "}",
       2 * M_PI * M_PI * big * small * small},
      {R"({"kind": "elliptic_cylinder", "base": [0, 0, 0], "axis": [0.3, 0.1, 1], "a": )" + num(a) + R"(, "b": )" +
           num(b) + R"(, "height": )" + num(h) + pl + "}",
       M_PI * a * b * h},
      {R"({"kind": "elliptic_cylinder", "base": [0, 0, 0], "axis": [0, 0, 1], "a": )" + num(a) + R"(, "b": )" +
           num(b) + R"(, "height": )" + num(h) + R"(, "twist": "1.2*u")" + pl + "}",
       M_PI * a * b * h},
  };
}

}  // namespace

TEST_CASE("Patch faces: the faces of placed primitives sew into their solids") {
  std::mt19937_64 rng(4040);
  for (int round = 0; round < 3; ++round) {
    const auto cases = placed_primitives(rng);
    for (const auto& [json, volume] : cases) {
      INFO(json);
      const sweep::EntityPtr e = entity_of(json);
      REQUIRE(e);
      const double scale = e->box().sizes().maxCoeff(), tol = 1e-6 * scale;
      std::vector<TopoDS_Face> faces;
      double area = 0, error = 0;
      for (const sweep::PatchPtr& p : e->faces()) {
        INFO(p->what());
        const sweep::occt::PatchFace f = sweep::occt::patch_face(*p, tol);
        const bool closed_form = p->form().kind != sweep::PatchForm::Kind::General;
        CHECK(f.exact == closed_form);
        CHECK(BRepAdaptor_Surface(f.face).GetType() == occt_type(p->form().kind));
        CHECK(f.error <= (closed_form ? 1e-12 * scale : tol));
        CHECK(BRepCheck_Analyzer(f.face).IsValid());  // poles as degenerate edges, not circles of radius 0
        error = std::max(error, f.error);
        GProp_GProps g;
        BRepGProp::SurfaceProperties(f.face, g);
        area += g.Mass();
        faces.push_back(f.face);
      }
      const TopoDS_Shape solid = sweep::occt::sew_solid(faces, std::max(1e-7 * scale, 10 * error));
      REQUIRE_FALSE(solid.IsNull());
      CHECK(BRepCheck_Analyzer(solid).IsValid());
      GProp_GProps g;
      BRepGProp::VolumeProperties(solid, g);
      // a fitted face moves the boundary by at most its error
      CHECK(std::abs(g.Mass() - volume) <= 1e-9 * volume + error * area);
    }
  }
}

TEST_CASE("Patch faces: primitives as the solids of their patch faces") {
  std::mt19937_64 rng(4041);
  for (int round = 0; round < 3; ++round) {
    const auto cases = placed_primitives(rng);
    for (const auto& [json, volume] : cases) {
      INFO(json);
      const std::string text = R"({"sweep": 1, "entity": )" + json +
                               R"(, "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [0, 0, 1],
                                  "range": [0, 1]}]}})";
      const TopoDS_Shape solid = sweep::occt::primitive_from_patches(*sweep::make_entity(sweep::parse_spec(text, "").entity));
      if (json.find("elliptic_cylinder") != std::string::npos) {
        CHECK(solid.IsNull());  // its lateral face has no closed form: not made here
        continue;
      }
      REQUIRE_FALSE(solid.IsNull());
      CHECK(solid.ShapeType() == TopAbs_SOLID);
      CHECK(BRepCheck_Analyzer(solid).IsValid());
      GProp_GProps g;
      BRepGProp::VolumeProperties(solid, g);
      CHECK(std::abs(g.Mass() - volume) <= 1e-9 * volume);
    }
  }
}

TEST_CASE("Patch faces: ruled patches become ruled faces between their fitted sides") {
  using sweep::Patch;
  using sweep::PatchPoint;
  // a line turning as it slides (a twisted ruled sheet), and one whose length shrinks to nothing as
  // sqrt(1 - t) at its end (a grazing line leaving a face through a corner moves so)
  const double tol = 1e-8;
  const Patch twisted(2, {0.0, 0.0}, {1.0, 2.0},
                      [](const double* s) {
                        const double a = 0.9 * s[1];
                        const Eigen::Vector3d c(0.3 * s[1], std::sin(s[1]), 0.5 * s[1] * s[1]);
                        return PatchPoint{c + (s[0] - 0.5) * Eigen::Vector3d(std::cos(a), std::sin(a), 0.2),
                                          Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
                      },
                      sweep::PatchForm{}, "a twisted ruled sheet");
  const Patch closing(2, {0.0, 0.0}, {1.0, 1.0},
                      [](const double* s) {
                        const double w = std::sqrt(std::max(0.0, 1 - s[1]));
                        const Eigen::Vector3d c(s[1], s[1] * s[1], 0);
                        return PatchPoint{c + s[0] * w * Eigen::Vector3d(0.2, -0.3, 1), Eigen::Vector3d::Zero(),
                                          Eigen::Vector3d::Zero()};
                      },
                      sweep::PatchForm{}, "a ruled sheet closing at its end");
  for (const Patch* p : {&twisted, &closing}) {
    INFO(p->what());
    const sweep::occt::PatchFace f = sweep::occt::patch_face(*p, tol);
    CHECK_FALSE(f.exact);
    CHECK(f.error <= tol);
    CHECK(BRepCheck_Analyzer(f.face).IsValid());
    // a ruled surface (degree 1 across), within tol of patch points the fit never saw
    const BRepAdaptor_Surface S(f.face);
    REQUIRE(S.GetType() == GeomAbs_BSplineSurface);
    CHECK(std::min(S.UDegree(), S.VDegree()) == 1);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    double worst = 0;
    for (int k = 0; k < 200; ++k) {
      const double u = unit(rng), v = p->lo(1) + (p->hi(1) - p->lo(1)) * unit(rng);
      const gp_Pnt x = sweep::occt::to_pnt(p->eval(u, v).x);
      GeomAPI_ProjectPointOnSurf proj(x, BRep_Tool::Surface(f.face));
      REQUIRE(proj.NbPoints() > 0);
      worst = std::max(worst, proj.LowerDistance());
    }
    CHECK(worst <= 2 * tol);
    // its area against the patch's points, triangulated finely (closer towards the end of v,
    // where the closing sheet's width changes as a square root)
    constexpr int n = 800;
    double area = 0;
    auto at = [p](int i, int j) {
      const double f = 1 - double(n - j) / n;
      return p->eval(double(i) / n, p->lo(1) + (p->hi(1) - p->lo(1)) * (1 - (1 - f) * (1 - f))).x;
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const Eigen::Vector3d a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
        area += 0.5 * ((b - a).cross(c - a).norm() + (c - a).cross(d - a).norm());
      }
    GProp_GProps g;
    BRepGProp::SurfaceProperties(f.face, g, 1e-10);
    CHECK(std::abs(g.Mass()) == Approx(area).epsilon(1e-5));
  }
}
