// cos and sin over a range as Bezier polynomials (sweep/trig_bezier.hpp), checked against the
// functions themselves on a grid finer than the fit's own.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "sweep/error.hpp"
#include "sweep/trig_bezier.hpp"

using namespace sweep;

namespace {

/// The largest distance of the fit from (cos q, sin q) on 4,001 points of the range.
double stray(const TrigBezier& f, double q0, double q1) {
  double worst = 0;
  for (int i = 0; i <= 4000; ++i) {
    const double t = i / 4000.0, q = q0 + (q1 - q0) * t;
    worst = std::max(worst, std::hypot(bezier_value(f.cos, t) - std::cos(q), bezier_value(f.sin, t) - std::sin(q)));
  }
  return worst;
}

}  // namespace

TEST_CASE("Trig Bezier: quarter turns anywhere on the circle reach the asked error, ends exact") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> start(-20.0, 20.0), length(0.05, M_PI / 2);
  for (int k = 0; k < 40; ++k) {
    const double q0 = start(rng), q1 = q0 + length(rng);
    for (double asked : {1e-6, 1e-10, 1e-13}) {
      const TrigBezier f = trig_bezier(q0, q1, asked);
      INFO("q0 " << q0 << " q1 " << q1 << " asked " << asked << " degree " << f.cos.size() - 1);
      CHECK(f.error <= asked);
      // the reported error is what a finer grid measures, to within a tenth
      const double measured = stray(f, q0, q1);
      CHECK(measured <= 1.1 * f.error + 1e-15);
      CHECK(f.cos.front() == std::cos(q0));
      CHECK(f.sin.back() == std::sin(q1));
      CHECK(bezier_value(f.cos, 1.0) == Approx(std::cos(q1)).margin(1e-15));
    }
  }
}

TEST_CASE("Trig Bezier: a quarter turn to 1e-12 needs a degree below 15, a coarse error a lower one") {
  const TrigBezier fine = trig_bezier(0.3, 0.3 + M_PI / 2, 1e-12);
  const TrigBezier coarse = trig_bezier(0.3, 0.3 + M_PI / 2, 1e-4);
  CHECK(fine.error <= 1e-12);
  CHECK(fine.cos.size() - 1 < 15);
  CHECK(coarse.cos.size() < fine.cos.size());
  CHECK(coarse.error <= 1e-4);
}

TEST_CASE("Trig Bezier: a range that is empty, reversed or over a half turn is refused") {
  CHECK_THROWS_AS(trig_bezier(1.0, 1.0, 1e-9), InternalError);
  CHECK_THROWS_AS(trig_bezier(1.0, 0.5, 1e-9), InternalError);
  CHECK_THROWS_AS(trig_bezier(0.0, 3.5, 1e-9), InternalError);
}
