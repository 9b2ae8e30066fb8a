// A `brep` entity read from a STEP file the test writes: a box with a cylindrical through hole.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "occt_bridge/sweeper.hpp"
#include "sweep/error.hpp"
#include "sweep/spec.hpp"
#include "util/box_hole.hpp"
#include "util/cases.hpp"

TEST_CASE("Brep entity: box with a hole from STEP, extruded along the hole") {
  REQUIRE(sweep_test::write_box_with_hole(SWEEP_BINARY_DIR "/box_hole.step"));
  // The example spec, with its relative file name resolved in the build tree.
  const std::string text = sweep_test::read_text(SWEEP_SOURCE_DIR "/examples/brep_box_hole.json");
  sweep::Spec spec = sweep::parse_spec(text, SWEEP_BINARY_DIR);
  const double expected = 16.0 - M_PI;
  REQUIRE(spec.json["_expected_volume"].get<double>() == Approx(expected).epsilon(1e-15));
  auto r = sweep::occt::run_sweep(spec);
  CAPTURE(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(r.report.valid);
  CHECK(r.report.closed);
  CHECK(r.report.volume_brep == Approx(expected).epsilon(1e-6));
  CHECK(r.report.volume_divergence == Approx(expected).epsilon(1e-6));
  // the pieces of each surface merged: the box's six faces and the hole's cylinder
  CHECK(r.report.faces == 7);
  const std::string out = SWEEP_BINARY_DIR "/box_hole_swept.step";
  sweep::occt::write_shape(*r.shape, out, 1e-3);
  CHECK(sweep::occt::file_volume(out) == Approx(expected).epsilon(1e-6));
}

TEST_CASE("Brep entity: unreadable STEP is an input error naming /entity/file") {
  const std::string junk = SWEEP_BINARY_DIR "/junk.step";
  std::ofstream(junk) << "this is not a STEP file\n";
  sweep::Spec spec = sweep::parse_spec(
      R"({"sweep": 1, "entity": {"kind": "brep", "file": "junk.step"},
          "motion": {"kind": "axes", "joints": [{"type": "prismatic", "direction": [0, 0, 1], "range": [0, 1]}]}})",
      SWEEP_BINARY_DIR);
  try {
    sweep::occt::run_sweep(spec);
    FAIL("no error for an unreadable STEP file");
  } catch (const sweep::InputError& e) {
    CHECK(e.pointer() == "/entity/file");
  }
}
