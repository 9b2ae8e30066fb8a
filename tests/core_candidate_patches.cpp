// Candidate patches under a general motion (sweep/candidate_patches.hpp), on seed 001's rolling
// cylinder: the lines x = -0.5 and x = +0.5 of its lateral face graze at every t, so the sheets
// on either plane x = +-0.5 together cover the strip a segment of length 2 sweeps in its plane
// while turning at pi about its middle and moving at 4 across it; their areas against that
// integral, done here without patches.
#include <catch2/catch.hpp>

#include <cmath>

#include "sweep/candidate_patches.hpp"

using Eigen::Vector3d;
using namespace sweep;

namespace {

/// The area a segment z in [-1, 1] of a rolling wheel sweeps over t in [a, b]: at t, the point at
/// height z moves across the segment at 4 cos(pi t) + pi z.
double strip_area(double a, double b) {
  auto rate = [](double t) {
    const double c = 4 * std::cos(M_PI * t);
    return std::abs(c) >= M_PI ? 2 * std::abs(c) : (c * c + M_PI * M_PI) / M_PI;  // integral of |c + pi z| dz
  };
  const int n = 20000;  // Simpson's rule
  const double h = (b - a) / n;
  double s = rate(a) + rate(b);
  for (int k = 1; k < n; ++k) s += (k % 2 ? 4 : 2) * rate(a + k * h);
  return s * h / 3;
}

}  // namespace

TEST_CASE("Candidate patches: seed 001's rolling cylinder sweeps the strips of its grazing lines", "[variety]") {
  const Spec spec = parse_spec(
      R"({"sweep": 1, "entity": {"kind": "cylinder", "base": [0, 0, -1], "axis": [0, 0, 1], "radius": 0.5,
          "height": 2}, "motion": {"kind": "path", "t": [0, 1], "translate": ["0", "4*t", "0"],
          "rotate": [{"axis": [1, 0, 0], "angle": "pi*t"}]}})",
      "");
  const EntityPtr cyl = make_entity(spec.entity);
  REQUIRE(cyl);
  int calls = 0;
  const std::vector<CandidatePatch> cands = candidate_patches(*cyl, spec.motion.stage, [&calls] { ++calls; });
  CHECK(calls > 0);
  int limits = 0, boundaries = 0;
  double plus = 0, minus = 0;
  for (const CandidatePatch& c : cands) {
    limits += c.type == "limit";
    boundaries += c.type == "boundary";
    if (c.type != "interior") continue;
    // a sheet on one of the planes x = +-0.5, or elsewhere (the circle's, the caps')
    const double x0 = c.patch->eval(0.3, 0.5 * (c.patch->lo(1) + c.patch->hi(1))).x.x();
    bool on_plane = std::abs(std::abs(x0) - 0.5) < 1e-12;
    for (double s : {0.0, 0.5, 1.0})
      for (double f : {0.0, 0.5, 1.0}) {
        const double t = c.patch->lo(1) + f * (c.patch->hi(1) - c.patch->lo(1));
        on_plane = on_plane && std::abs(c.patch->eval(c.patch->lo(0) + s * (c.patch->hi(0) - c.patch->lo(0)), t).x.x() - x0) < 1e-12;
      }
    if (!on_plane) continue;
    (x0 > 0 ? plus : minus) += patch_area(*c.patch, 64);
  }
  CHECK(limits == 6);
  CHECK(boundaries == 2);
  const double t1 = std::acos(M_PI / 4) / M_PI;
  const double strip = strip_area(0, t1) + strip_area(t1, 1 - t1) + strip_area(1 - t1, 1);
  // the plane x = -0.5 in pieces (its line crossed by the circle), x = +0.5 one sheet along the seam
  // (whose integrand kinks where the circle crosses it: the panels' rule is good to about 1e-6 there)
  CHECK(minus == Approx(strip).epsilon(1e-7));
  CHECK(plus == Approx(strip).epsilon(2e-6));
}

TEST_CASE("Candidate patches: the planes that sweeps lie in", "[variety]") {
  const Spec spec = parse_spec(
      R"({"sweep": 1, "entity": {"kind": "box", "min": [-0.5, -0.4, -1], "max": [0.5, 0.4, 1]},
          "motion": {"kind": "path", "t": [0, 1], "translate": ["0", "4*t", "0"],
          "rotate": [{"axis": [1, 0, 0], "angle": "pi*t"}]}})",
      "");
  const EntityPtr box = make_entity(spec.entity);
  REQUIRE(box);
  int in_planes = 0, limits_in_planes = 0;
  for (const CandidatePatch& c : candidate_patches(*box, spec.motion.stage)) {
    const std::optional<PatchPlane> p = patch_plane(*c.patch, 1e-9);
    if (c.type == "limit") {
      // every face of a box is flat
      REQUIRE(p);
      limits_in_planes += std::abs(std::abs(p->normal.x()) - 1) < 1e-12;
      continue;
    }
    if (!p) continue;
    // the motion keeps the planes x = const only: the edges lying in x = +-0.5 sweep regions of them
    ++in_planes;
    CHECK(std::abs(p->normal.x()) == Approx(1).margin(1e-12));
    CHECK(std::abs(p->offset) == Approx(0.5).margin(1e-12));
  }
  CHECK(limits_in_planes == 4);
  CHECK(in_planes == 8);  // the edges along y and along z of both faces x = +-0.5
  // a curved sheet, a patch that collapses onto a line, and a skew one: no plane
  const Patch cyl(2, {0.0, 0.0}, {M_PI, 1.0},
                  [](const double* s) {
                    return PatchPoint{Eigen::Vector3d(std::cos(s[0]), std::sin(s[0]), s[1]), Eigen::Vector3d::Zero(),
                                      Eigen::Vector3d::Zero()};
                  },
                  PatchForm{}, "half a cylinder");
  CHECK_FALSE(patch_plane(cyl, 1e-9));
  const Patch line(2, {0.0, 0.0}, {1.0, 1.0},
                   [](const double* s) {
                     return PatchPoint{Eigen::Vector3d(s[0] + s[1], 2 * (s[0] + s[1]), 0), Eigen::Vector3d::Zero(),
                                       Eigen::Vector3d::Zero()};
                   },
                   PatchForm{}, "a patch on a line");
  CHECK_FALSE(patch_plane(line, 1e-9));
  const Patch saddle(2, {-1.0, -1.0}, {1.0, 1.0},
                     [](const double* s) {
                       return PatchPoint{Eigen::Vector3d(s[0], s[1], 1e-6 * s[0] * s[1]), Eigen::Vector3d::Zero(),
                                         Eigen::Vector3d::Zero()};
                     },
                     PatchForm{}, "a nearly flat saddle");
  CHECK_FALSE(patch_plane(saddle, 1e-9));
  const std::optional<PatchPlane> loose = patch_plane(saddle, 1e-5);
  REQUIRE(loose);
  CHECK(std::abs(loose->normal.z()) == Approx(1).margin(1e-9));
}
