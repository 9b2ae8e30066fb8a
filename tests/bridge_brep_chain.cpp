// A solid read from STEP under chains of joints (a robot link through its joints): built stage by
// stage and judged by the search over the joint box with the B-rep's distance bound.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "occt_bridge/sweeper.hpp"
#include "sweep/spec.hpp"
#include "util/box_hole.hpp"

namespace {

/// The box with its hole under `joints`, from a STEP file of the test's own (`name`: tests run side
/// by side).
sweep::occt::RunResult run_box_hole(const std::string& name, const std::string& joints) {
  REQUIRE(sweep_test::write_box_with_hole(SWEEP_BINARY_DIR "/" + name + ".step"));
  const sweep::Spec spec = sweep::parse_spec(R"({"sweep": 1, "angles": "deg",
      "entity": {"kind": "brep", "file": ")" + name + R"(.step"},
      "motion": {"kind": "axes", "joints": )" + joints + "}}",
                                             SWEEP_BINARY_DIR);
  return sweep::occt::run_sweep(spec);
}

}  // namespace

TEST_CASE("B-rep chains: the box with its hole slid along two directions, against the closed form") {
  // Slid 2 along z (the hole's axis) and 0.3 along x: each section z in [0, 3] is the square
  // stretched to [-1, 1.3] x [-1, 1] less the lens the hole and its copy 0.3 along x share.
  const auto r = run_box_hole("brep_chain_slid", R"([{"type": "prismatic", "direction": [0, 0, 1], "range": [0, 2]},
                                  {"type": "prismatic", "direction": [1, 0, 0], "range": [0, 0.3]}])");
  CAPTURE(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(r.report.has_verdict);
  CHECK(r.report.verdict_membership == "certified search over the joint box (signed distance)");
  CHECK(r.report.verdict_mismatches == 0);
  const double d = 0.3, R = 0.5;
  const double lens = 2 * R * R * std::acos(d / (2 * R)) - 0.5 * d * std::sqrt(4 * R * R - d * d);
  const double expected = 3 * (2.3 * 2 - lens);
  CHECK(r.report.volume_brep == Approx(expected).epsilon(1e-7));
}

TEST_CASE("B-rep chains: the box with its hole extruded then turned about an outside axis") {
  // Reference: scripts/reference_volume_ring_square.py 3 0.5 3 90 (a one-dimensional integral over
  // the radius about the axis): 43.124440224457 +- 4.8e-08.
  const auto r = run_box_hole("brep_chain_turned", R"([{"type": "prismatic", "direction": [0, 0, 1], "range": [0, 2]},
                                  {"type": "revolute", "point": [3, 0, 0], "direction": [0, 0, 1],
                                   "range": [0, 90]}])");
  CAPTURE(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(r.report.has_verdict);
  CHECK(r.report.verdict_mismatches == 0);
  CHECK(r.report.volume_brep == Approx(43.124440224457).epsilon(1e-7));
}
