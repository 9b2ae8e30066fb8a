// Every spec with an `_expected_volume` (shared cases and examples) is computed and checked:
// status ok, valid, closed, volume within `_rel_tol` (default 1e-5) of the expected value.
#include <catch2/catch.hpp>

#include "occt_bridge/sweeper.hpp"
#include "sweep/spec.hpp"
#include "util/cases.hpp"

namespace {

void check_case(const std::string& path) {
  CAPTURE(path);
  sweep::Spec spec = sweep::load_spec(path);
  REQUIRE(spec.json.contains("_expected_volume"));
  const double expected = spec.json["_expected_volume"].get<double>();
  const double rel = spec.json.value("_rel_tol", 1e-5);
  auto r = sweep::occt::run_sweep(spec);
  CAPTURE(r.report.to_json().dump());
  CHECK(r.report.status == "ok");
  CHECK(r.report.valid);
  CHECK(r.report.closed);
  CHECK(r.report.volume_brep == Approx(expected).epsilon(rel));
  CHECK(r.report.volume_divergence == Approx(expected).epsilon(rel));
}

}  // namespace

TEST_CASE("Cases: every shared case reproduces its expected volume") {
  auto files = sweep_test::json_files(SWEEP_SHARED_DIR "/cases");
  if (files.empty()) {
    WARN("no shared cases folder next to the source tree: " SWEEP_SHARED_DIR "/cases");
    return;
  }
  for (const auto& f : files) SECTION(f) { check_case(f); }
}
