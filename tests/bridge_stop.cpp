// A run stopped through RunOptions::stop ends as `failed` with the reason, wherever it is stopped,
// and a request that never fires changes nothing.
#include <atomic>
#include <string>

#include <catch2/catch.hpp>

#include "occt_bridge/sweeper.hpp"
#include "sweep/spec.hpp"

namespace {

// a cylinder turned about an axis that crosses it: the general pipeline (arrangement and cells)
const char* kSpec = R"({"sweep": 1, "angles": "deg",
  "entity": {"kind": "cylinder", "base": [0, 0, -1], "axis": [0, 0, 1], "radius": 0.5, "height": 2},
  "motion": {"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0.3], "direction": [1, 0, 0],
                                        "range": [0, 90]}]}})";

/// A request that fires at its `fire_at`-th poll (never when 0) and counts the polls.
struct CountingStop {
  std::shared_ptr<std::atomic<long>> polls = std::make_shared<std::atomic<long>>(0);
  long fire_at = 0;
  std::function<std::string()> request() const {
    return [polls = polls, fire_at = fire_at]() -> std::string {
      const long k = ++*polls;
      return fire_at > 0 && k >= fire_at ? "after " + std::to_string(fire_at) + " polls" : std::string();
    };
  }
};

}  // namespace

TEST_CASE("Stop: a request polled through the run stops it as failed wherever it fires") {
  const sweep::Spec spec = sweep::parse_spec(kSpec, ".");
  const sweep::occt::RunResult free = sweep::occt::run_sweep(spec);
  REQUIRE(free.report.ok());

  CountingStop never;
  sweep::occt::RunOptions opt;
  opt.stop = never.request();
  const sweep::occt::RunResult counted = sweep::occt::run_sweep(spec, opt);
  CHECK(counted.report.ok());
  CHECK(counted.report.volume_brep == Approx(free.report.volume_brep).epsilon(1e-12));
  const long total = *never.polls;
  CAPTURE(total);
  REQUIRE(total >= 10);  // the run polls the request at its steps and inside OCCT's algorithms

  // fired at the first poll, at tenths of the run and near its end: failed with the reason, no
  // shape; or (polls from OCCT's worker threads vary in number) ok with the same solid
  int stopped = 0;
  for (long at : {1L, total / 10, total / 3, total / 2, 2 * total / 3, 9 * total / 10}) {
    CountingStop stop;
    stop.fire_at = std::max(1L, at);
    opt.stop = stop.request();
    const sweep::occt::RunResult r = sweep::occt::run_sweep(spec, opt);
    CAPTURE(at, r.report.status, r.report.message);
    if (r.report.ok()) {
      CHECK(r.report.volume_brep == Approx(free.report.volume_brep).epsilon(1e-12));
      continue;
    }
    ++stopped;
    CHECK(r.report.message == "stopped: after " + std::to_string(stop.fire_at) + " polls");
    CHECK(r.shape == nullptr);
  }
  CHECK(stopped >= 5);
}
