// B-rep solids as orbit solids: their intervals on orbits against those of the same parts built of
// orbit primitives, and the faces they cannot take named.
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRep_Builder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS_Compound.hxx>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "base/internal.hpp"
#include "util/random_parts.hpp"

namespace {

/// The largest distance between the ends of two interval sets with as many intervals (infinite
/// when their counts differ).
double ends_apart(const sweep::Intervals& a, const sweep::Intervals& b) {
  if (a.size() != b.size()) return INFINITY;
  double d = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    d = std::max({d, std::abs(a[k].first - b[k].first), std::abs(a[k].second - b[k].second)});
  return d;
}

}  // namespace

TEST_CASE("B-rep orbit solid: random parts' intervals on random orbits agree with those of their orbit primitives") {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const int index : {0, 1, 2, 3, 4, 10, 11, 12, 13, 14}) {
    const sweep::testing::RandomPart p = sweep::testing::random_part_case(43, index);
    const sweep::testing::JointSweep s = sweep::testing::part_joint_sweep(p);
    const sweep::OrbitSolidPtr brep = sweep::occt::brep_orbit_solid(p.shape, 1e-9);
    const Eigen::AlignedBox3d box = p.orbit->bounds();
    int met = 0, differ = 0;
    double worst = 0;
    for (int k = 0; k < 150; ++k) {
      const Eigen::Vector3d y = box.min() + (box.sizes().array() * Eigen::Array3d(u(rng), u(rng), u(rng))).matrix();
      const sweep::OrbitCurve o = sweep::orbit_of(s.j, y);
      const double lo = -std::min(s.T, 7.0), hi = std::min(s.T, 7.0);
      const sweep::Intervals want = p.orbit->on_curve(o, lo, hi), got = brep->on_curve(o, lo, hi);
      met += !want.empty();
      const double apart = ends_apart(want, got);
      // (a piece shorter than rounding may be there in one and not the other)
      differ += !(apart < 1e-7) && std::abs(sweep::total_length(want) - sweep::total_length(got)) > 1e-9;
      if (apart < 1e-7) worst = std::max(worst, apart);
    }
    CAPTURE(p.name, met, differ, worst);
    CHECK(met >= 40);  // the orbits start in the part's box, many meet it
    CHECK(differ == 0);
  }
}

TEST_CASE("B-rep orbit solid: a face on a surface without an implicit form is named") {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(1.0, 2.0, 3.0).Shape();
  CHECK_NOTHROW(sweep::occt::brep_orbit_solid(box, 1e-9));
  const TopoDS_Shape nurbs = BRepBuilderAPI_NurbsConvert(box).Shape();
  CHECK_THROWS_WITH(sweep::occt::brep_orbit_solid(nurbs, 1e-9), Catch::Contains("face 0") && Catch::Contains("B-spline surface"));
  // the third face of six made a spline: it is named by its place in the shape
  TopoDS_Compound faces;
  BRep_Builder builder;
  builder.MakeCompound(faces);
  int k = 0;
  for (TopExp_Explorer ex(box, TopAbs_FACE); ex.More(); ex.Next(), ++k)
    builder.Add(faces, k == 2 ? BRepBuilderAPI_NurbsConvert(ex.Current()).Shape() : ex.Current());
  CHECK_THROWS_WITH(sweep::occt::brep_orbit_solid(faces, 1e-9), Catch::Contains("face 2") && Catch::Contains("B-spline surface"));
}
