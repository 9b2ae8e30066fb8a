#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "sweep/expr.hpp"
#include "sweep/interval.hpp"

using sweep::Expr;
using sweep::Interval;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Enclosure {
  Interval value, slope;
  bool defined;
};

Enclosure enclose(const std::string& text, double lo, double hi) {
  const Expr e = Expr::parse(text, {"x"});
  const Interval box{lo, hi};
  Enclosure r;
  r.defined = e.enclose_d1(&box, 0, r.value, r.slope);
  return r;
}

/// Points of [lo, hi] (ends included) where the expression or its slope falls outside the
/// enclosure; points outside the expression's domain (a NaN or infinite value) are skipped.
int misses(const std::string& text, double lo, double hi, int samples) {
  const Expr e = Expr::parse(text, {"x"});
  const Enclosure r = enclose(text, lo, hi);
  int missed = 0;
  for (int k = 0; k <= samples; ++k) {
    const double x = k == samples ? hi : lo + (hi - lo) * k / samples;
    double g = 0;
    const double v = e.eval_d1(&x, &g);
    if (!std::isfinite(v) || !std::isfinite(g)) continue;
    if (!r.value.contains(v) || !r.slope.contains(g)) {
      ++missed;
      UNSCOPED_INFO(text << " on [" << lo << ", " << hi << "] at x = " << x << ": value " << v << " in ["
                         << r.value.lo << ", " << r.value.hi << "], slope " << g << " in [" << r.slope.lo
                         << ", " << r.slope.hi << "]");
    }
  }
  return missed;
}

}  // namespace

TEST_CASE("Interval: enclosures hold every sampled value and slope", "[interval]") {
  const std::vector<std::string> texts = {
      "sin(x)", "cos(3*x)", "sin(x)*cos(x)", "tan(x)", "asin(x/4)", "acos(x/4)", "atan(2*x)",
      "atan2(x, 2)", "atan2(1, x)", "atan2(x-0.5, x+0.2)", "sqrt(x+4)", "sqrt(abs(x))", "exp(x)",
      "log(x+4)", "abs(x-0.3)", "min(x, 1-x)", "max(x^2, 0.5)", "x^3", "x^-2", "(x+4)^0.5", "2^x",
      "0.5^x", "(x+4)^x", "x/(x+5)", "1/(x+5)", "x^2-x", "-x", "3-x", "x*sin(5*x)", "x/3",
      "exp(-x^2)*cos(7*x)", "sqrt(1+x^2)", "(1+x)^(2-x/2)", "log(2+sin(x))"};
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> centre(-3, 3), width(-3, 0.4);
  int missed = 0;
  for (const std::string& text : texts)
    for (int trial = 0; trial < 60; ++trial) {
      const double c = centre(rng), w = std::pow(10.0, width(rng));
      missed += misses(text, c - w, c + w, 64);
    }
  CHECK(missed == 0);
}

TEST_CASE("Interval: enclosures are tight where the range is known", "[interval]") {
  const double eps = 1e-12;
  Enclosure r = enclose("sin(x)", 0, kPi);
  CHECK(r.value.lo == Approx(0).margin(eps));
  CHECK(r.value.hi == Approx(1).margin(eps));
  CHECK(r.slope.lo == Approx(-1).margin(eps));
  CHECK(r.slope.hi == Approx(1).margin(eps));
  r = enclose("cos(x)", 0.1, 0.2);
  CHECK(r.value.lo == Approx(std::cos(0.2)).margin(eps));
  CHECK(r.value.hi == Approx(std::cos(0.1)).margin(eps));
  r = enclose("(x-1)^2", 0, 3);
  CHECK(r.value.lo == Approx(0).margin(eps));
  CHECK(r.value.hi == Approx(4).margin(eps));
  CHECK(r.slope.lo == Approx(-2).margin(eps));
  CHECK(r.slope.hi == Approx(4).margin(eps));
  r = enclose("abs(x)", -1, 2);
  CHECK(r.value.lo == Approx(0).margin(eps));
  CHECK(r.value.hi == Approx(2).margin(eps));
  CHECK(r.slope.lo == Approx(-1).margin(eps));
  CHECK(r.slope.hi == Approx(1).margin(eps));
  r = enclose("sqrt(x)", 0, 4);
  CHECK(r.value.lo == Approx(0).margin(eps));
  CHECK(r.value.hi == Approx(2).margin(eps));
  r = enclose("sqrt(x)", -1, 4);  // a box that leaves the domain: no bound
  CHECK_FALSE(r.defined);
  CHECK(std::isinf(r.value.lo));
  CHECK(std::isinf(r.value.hi));
  r = enclose("x^3", -2, 1);
  CHECK(r.value.lo == Approx(-8).margin(eps));
  CHECK(r.value.hi == Approx(1).margin(eps));
  CHECK(r.slope.lo == Approx(0).margin(eps));
  CHECK(r.slope.hi == Approx(12).margin(eps));
}

TEST_CASE("Interval: no finite bound gives the whole line", "[interval]") {
  const double inf = std::numeric_limits<double>::infinity();
  Enclosure r = enclose("1/x", -1, 1);
  CHECK(r.value.lo == -inf);
  CHECK(r.value.hi == inf);
  r = enclose("tan(x)", 1, 2);  // across the pole at pi/2
  CHECK(r.value.hi == inf);
  r = enclose("sqrt(x)", 0, 1);  // the slope is unbounded at 0
  CHECK(r.slope.hi == inf);
  r = enclose("sqrt(2)", 0, 1);  // but a constant has none
  CHECK(r.slope.is_zero());
  r = enclose("atan2(x, -1)", -1, 1);  // across the branch cut
  CHECK(r.value.lo <= -kPi);
  CHECK(r.value.hi >= kPi);
}

TEST_CASE("Interval: an expression that may leave its domain says so", "[interval]") {
  CHECK(enclose("sqrt(1+x^2)", -2, 2).defined);
  CHECK(enclose("log(x)", 0.5, 2).defined);
  CHECK_FALSE(enclose("sqrt(x-1)", 0, 2).defined);
  CHECK_FALSE(enclose("asin(x)", 0, 2).defined);
  CHECK_FALSE(enclose("x^0.5", -1, 1).defined);
  CHECK(enclose("x^3", -1, 1).defined);
  // min drops a NaN argument (C fmin): where sqrt is undefined the value is the other argument,
  // and an enclosure over a box that may leave a domain is the whole line
  const Enclosure r = enclose("min(sqrt(x-1), 2)", 0.9, 1.1);
  CHECK_FALSE(r.defined);
  CHECK(r.value.contains(2.0));
  CHECK(std::isinf(r.value.lo));
  CHECK_FALSE(enclose("log(2+x)^log(0+x)^e", -0.5, 1.5).defined);
  CHECK(misses("min(sqrt(x-1), 2)", 0.9, 1.1, 64) == 0);
}
