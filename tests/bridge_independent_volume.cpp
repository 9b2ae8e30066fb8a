// A one-joint sweep of a primitive whose solid comes from the arrangement of cells (its sweep
// boundary did not close) is held to the volume integrated over the joint's orbits, which does not
// use the solid: sampling alone bounds a wrong region only to a share of the box.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>

#include "occt_bridge/sweeper.hpp"
#include "sweep/spec.hpp"

namespace {

/// Runs the spec with the arrangement of cells forced for the entity's own stage.
sweep::occt::RunResult run_by_cells(const std::string& path) {
  setenv("SWEEP_CELLS_ENGINE", "1", 1);
  auto r = sweep::occt::run_sweep(sweep::load_spec(path));
  unsetenv("SWEEP_CELLS_ENGINE");
  return r;
}

}  // namespace

TEST_CASE("A right solid from the cells agrees with the orbit volume, which the report gives", "[verdict]") {
  const auto r = run_by_cells(SWEEP_SOURCE_DIR "/examples/box_revolve_90.json");
  const double exact = 1 + M_PI / 4 * (5 - 1);
  REQUIRE(r.report.status == "ok");
  CHECK(std::abs(r.report.volume_brep - exact) < 1e-9 * exact);
  REQUIRE(r.report.has_independent_volume);
  CHECK(r.report.volume_independent_error < 1e-5 * exact);
  CHECK(std::abs(r.report.volume_independent - exact) < 3 * r.report.volume_independent_error + 1e-12);
  const auto j = r.report.to_json();
  CHECK(j["volume"]["orbits"].get<double>() == r.report.volume_independent);
}

TEST_CASE("A torus extruded obliquely: the solid from the cells is never reported ok with a wrong volume",
          "[verdict]") {
  // random case torus_prismatic_28 of seed 43: its sweep boundary does not close, and the
  // arrangement of cells gave 6.3754314 (8e-5 too large) while sampling found no mismatch
  const std::string text = R"({"sweep": 1, "angles": "deg",
    "entity": {"kind": "torus", "center": [-0.936927, -0.920231, 0.554466], "axis": [0.131774, -0.777194, 0.615309],
               "major": 1.303154, "minor": 0.371590},
    "motion": {"kind": "axes", "joints": [{"type": "prismatic", "point": [0.568812, -0.898840, 0.544245],
               "direction": [-0.023640, -0.253716, -0.966990], "range": [0, 0.633272]}]}})";
  const double reference = 6.37491757983;  // orbit-space integral to 1.7e-7 (random_cases, 1e-9 asked)
  const auto r = sweep::occt::run_sweep(sweep::parse_spec(text, "."));
  if (r.report.status == "ok") {
    CHECK(std::abs(r.report.volume_brep - reference) < 1e-6 * reference + 3 * 1.7e-7);
  } else {
    CHECK(r.report.message.find("disagrees with the volume integrated over the orbits") != std::string::npos);
  }
  if (r.report.has_independent_volume)
    CHECK(std::abs(r.report.volume_independent - reference) < 3 * r.report.volume_independent_error + 3 * 1.7e-7);
}
