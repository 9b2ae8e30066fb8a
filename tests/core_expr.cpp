#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "sweep/expr.hpp"

using sweep::Expr;
using sweep::ExprError;

namespace {

constexpr double kPi = 3.14159265358979323846;

double ev(const std::string& text, const std::vector<std::string>& vars = {},
          const std::vector<double>& x = {}) {
  return Expr::parse(text, vars).eval(x);
}

Approx near(double v) { return Approx(v).epsilon(1e-12).margin(1e-14); }

struct Derivs {
  double v1 = 0, v2 = 0;
  std::vector<double> g1, g2, h;
};

/// eval_d1 and eval_d2 at x; also checks that they agree with each other and with eval.
Derivs derivs(const Expr& e, const std::vector<double>& x) {
  const std::size_t n = e.num_vars();
  REQUIRE(x.size() == n);
  Derivs d;
  d.g1.assign(n, -7.0);
  d.g2.assign(n, -7.0);
  d.h.assign(n * n, -7.0);
  d.v1 = e.eval_d1(x.data(), d.g1.data());
  d.v2 = e.eval_d2(x.data(), d.g2.data(), d.h.data());
  const double v = e.eval(x);
  CHECK(d.v1 == near(v));
  CHECK(d.v2 == near(v));
  for (std::size_t i = 0; i < n; ++i) CHECK(d.g1[i] == near(d.g2[i]));
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) CHECK(d.h[i * n + j] == near(d.h[j * n + i]));
  return d;
}

void check_derivs(const std::string& text, const std::vector<std::string>& vars,
                  const std::vector<double>& x, double value, const std::vector<double>& grad,
                  const std::vector<double>& hess) {
  CAPTURE(text);
  const Expr e = Expr::parse(text, vars);
  const Derivs d = derivs(e, x);
  CHECK(d.v2 == near(value));
  for (std::size_t i = 0; i < grad.size(); ++i) {
    CAPTURE(i);
    CHECK(d.g2[i] == near(grad[i]));
  }
  for (std::size_t i = 0; i < hess.size(); ++i) {
    CAPTURE(i);
    CHECK(d.h[i] == near(hess[i]));
  }
}

/// Runs parse and returns the error (fails the test when there is none).
ExprError parse_error(const std::string& text, const std::vector<std::string>& vars = {}) {
  try {
    Expr::parse(text, vars);
  } catch (const ExprError& e) {
    return e;
  }
  FAIL("no ExprError for \"" << text << "\"");
  return ExprError("", 0);
}

}  // namespace

TEST_CASE("Expr: numbers") {
  CHECK(ev("42") == near(42.0));
  CHECK(ev("1e-3") == near(1e-3));
  CHECK(ev(".5") == near(0.5));
  CHECK(ev("5.") == near(5.0));
  CHECK(ev("2.5E+2") == near(250.0));
  CHECK(ev("0.1") == near(0.1));
  CHECK(ev("  7 \t") == near(7.0));
  CHECK_THROWS_AS(ev("1e2e"), ExprError);  // no implicit product with the constant e
  CHECK(ev("2e+1") == near(20.0));
}

TEST_CASE("Expr: precedence and associativity") {
  CHECK(ev("1+2*3") == near(7.0));
  CHECK(ev("(1+2)*3") == near(9.0));
  CHECK(ev("10-4-3") == near(3.0));
  CHECK(ev("8/4/2") == near(1.0));
  CHECK(ev("2*3/4") == near(1.5));
  CHECK(ev("2^3^2") == near(512.0));
  CHECK(ev("-2^2") == near(-4.0));
  CHECK(ev("(-2)^2") == near(4.0));
  CHECK(ev("2^-1") == near(0.5));
  CHECK(ev("2*3^2") == near(18.0));
  CHECK(ev("-3*-2") == near(6.0));
  CHECK(ev("--3") == near(3.0));
  CHECK(ev("+3") == near(3.0));
  CHECK(ev("1-+2") == near(-1.0));
  CHECK(ev("1 - 2 + 3") == near(2.0));
  CHECK(ev("-x^2", {"x"}, {3.0}) == near(-9.0));
  CHECK(ev("x^-2", {"x"}, {2.0}) == near(0.25));
  CHECK(ev("-x^2^x", {"x"}, {2.0}) == near(-16.0));
  CHECK(ev("((((2))))") == near(2.0));
}

TEST_CASE("Expr: every function") {
  const double x = 0.3;
  const std::vector<std::string> v{"x"};
  CHECK(ev("sin(x)", v, {x}) == near(std::sin(x)));
  CHECK(ev("cos(x)", v, {x}) == near(std::cos(x)));
  CHECK(ev("tan(x)", v, {x}) == near(std::tan(x)));
  CHECK(ev("asin(x)", v, {x}) == near(std::asin(x)));
  CHECK(ev("acos(x)", v, {x}) == near(std::acos(x)));
  CHECK(ev("atan(x)", v, {x}) == near(std::atan(x)));
  CHECK(ev("atan2(1, -1)") == near(0.75 * kPi));
  CHECK(ev("atan2(x, 2)", v, {x}) == near(std::atan2(x, 2.0)));
  CHECK(ev("sqrt(x)", v, {x}) == near(std::sqrt(x)));
  CHECK(ev("exp(x)", v, {x}) == near(std::exp(x)));
  CHECK(ev("log(x)", v, {x}) == near(std::log(x)));
  CHECK(ev("abs(-x)", v, {x}) == near(x));
  CHECK(ev("abs(x)", v, {-2.5}) == near(2.5));
  CHECK(ev("min(x, 1)", v, {x}) == near(x));
  CHECK(ev("min(2, x)", v, {3.0}) == near(2.0));
  CHECK(ev("max(x, 1)", v, {x}) == near(1.0));
  CHECK(ev("max(2, x)", v, {3.0}) == near(3.0));
  CHECK(ev("sqrt(16)") == near(4.0));
  CHECK(ev("sin ( x )", v, {x}) == near(std::sin(x)));
}

TEST_CASE("Expr: constants") {
  CHECK(ev("pi") == near(kPi));
  CHECK(ev("e") == near(std::exp(1.0)));
  CHECK(ev("2*pi") == near(2 * kPi));
  CHECK(ev("e^2") == near(std::exp(2.0)));
  CHECK(ev("cos(pi)") == near(-1.0));
  // a variable with the name of a constant wins
  CHECK(ev("e+1", {"e"}, {10.0}) == near(11.0));
  CHECK(ev("pi*2", {"x", "pi"}, {0.0, 3.0}) == near(6.0));
  CHECK(Expr::parse("pi*x", {"x"}).uses(0));
  CHECK(Expr::parse("2*pi", {"x"}).is_constant());
}

TEST_CASE("Expr: variables") {
  const Expr e = Expr::parse("3+r*cos(p)", {"r", "p"});
  CHECK(e.text() == "3+r*cos(p)");
  CHECK(e.num_vars() == 2);
  CHECK_FALSE(e.is_constant());
  CHECK(e.uses(0));
  CHECK(e.uses(1));
  CHECK_FALSE(e.uses(2));
  CHECK(e.eval({2.0, 0.5}) == near(3 + 2 * std::cos(0.5)));
  const double x[2] = {-1.0, kPi};
  CHECK(e.eval(x) == near(4.0));

  const Expr f = Expr::parse("z - 2*x", {"x", "y", "z"});
  CHECK(f.uses(0));
  CHECK_FALSE(f.uses(1));
  CHECK(f.uses(2));
  CHECK(f.eval({1.0, 100.0, 5.0}) == near(3.0));

  const Expr g = Expr::parse("q_1 + q2", {"q2", "q_1"});
  CHECK(g.eval({1.0, 10.0}) == near(11.0));

  // a variable the expression cancels out still counts as used
  const Expr h = Expr::parse("x - x", {"x"});
  CHECK_FALSE(h.is_constant());
  CHECK(h.eval({4.0}) == near(0.0));
}

TEST_CASE("Expr: default, constant and copies") {
  const Expr z;
  CHECK(z.text() == "0");
  CHECK(z.num_vars() == 0);
  CHECK(z.is_constant());
  CHECK_FALSE(z.uses(0));
  CHECK(z.eval(nullptr) == near(0.0));

  const Expr c = Expr::constant(2.5);
  CHECK(c.text() == "2.5");
  CHECK(c.eval(nullptr) == near(2.5));
  CHECK(Expr::constant(0.1).text() == "0.1");
  CHECK(Expr::constant(-3).text() == "-3");
  CHECK(Expr::parse(Expr::constant(1e-7).text(), {}).eval(nullptr) == near(1e-7));
  double g = -1.0, h = -1.0;
  CHECK(c.eval_d2(nullptr, &g, &h) == near(2.5));

  const Expr a = Expr::parse("x*2", {"x"});
  Expr b = a;
  CHECK(b.text() == "x*2");
  CHECK(b.eval({4.0}) == near(8.0));
  b = Expr::constant(1.0);
  CHECK(a.eval({4.0}) == near(8.0));

  // constant subexpressions are folded without changing the value
  const Expr k = Expr::parse("x + 2*3 - sqrt(4)", {"x"});
  CHECK(k.eval({1.0}) == near(5.0));
  CHECK(Expr::parse("1 + 2*3 - sqrt(4)", {"x"}).is_constant());
}

TEST_CASE("Expr: domain edges follow C") {
  CHECK(std::isnan(ev("sqrt(-1)")));
  CHECK(std::isnan(ev("sqrt(x)", {"x"}, {-1.0})));
  CHECK(std::isnan(ev("asin(x)", {"x"}, {2.0})));
  CHECK(std::isnan(ev("log(x)", {"x"}, {-1.0})));
  CHECK(ev("log(x)", {"x"}, {0.0}) == -std::numeric_limits<double>::infinity());
  CHECK(ev("1/x", {"x"}, {0.0}) == std::numeric_limits<double>::infinity());
  CHECK(ev("x^0", {"x"}, {0.0}) == near(1.0));
  CHECK(ev("min(x, 1)", {"x"}, {std::nan("")}) == near(1.0));  // like fmin
  CHECK(ev("max(1, x)", {"x"}, {std::nan("")}) == near(1.0));  // like fmax

  // |x|' = 0 at 0
  const Expr a = Expr::parse("abs(x)", {"x"});
  const Derivs da = derivs(a, {0.0});
  CHECK(da.g2[0] == near(0.0));
  CHECK(da.h[0] == near(0.0));
  const Derivs dn = derivs(a, {-2.0});
  CHECK(dn.g2[0] == near(-1.0));

  // sqrt'(0) = inf; a variable sqrt does not read gets 0, not NaN
  const Expr s = Expr::parse("sqrt(x) + y", {"x", "y"});
  double g[2], h[4];
  s.eval_d1(std::vector<double>{0.0, 1.0}.data(), g);
  CHECK(g[0] == std::numeric_limits<double>::infinity());
  CHECK(g[1] == near(1.0));
  s.eval_d2(std::vector<double>{0.0, 1.0}.data(), g, h);
  CHECK(h[1] == near(0.0));
  CHECK(h[3] == near(0.0));
}

TEST_CASE("Expr: first and second derivatives of every function") {
  struct Case {
    std::string name;
    std::function<double(double)> f, d1, d2;
    double x;
  };
  const std::vector<Case> cases = {
      {"sin", [](double x) { return std::sin(x); }, [](double x) { return std::cos(x); },
       [](double x) { return -std::sin(x); }, 0.7},
      {"cos", [](double x) { return std::cos(x); }, [](double x) { return -std::sin(x); },
       [](double x) { return -std::cos(x); }, 0.7},
      {"tan", [](double x) { return std::tan(x); },
       [](double x) { return 1 / (std::cos(x) * std::cos(x)); },
       [](double x) { return 2 * std::sin(x) / std::pow(std::cos(x), 3); }, 0.7},
      {"asin", [](double x) { return std::asin(x); },
       [](double x) { return 1 / std::sqrt(1 - x * x); },
       [](double x) { return x / std::pow(1 - x * x, 1.5); }, 0.4},
      {"acos", [](double x) { return std::acos(x); },
       [](double x) { return -1 / std::sqrt(1 - x * x); },
       [](double x) { return -x / std::pow(1 - x * x, 1.5); }, 0.4},
      {"atan", [](double x) { return std::atan(x); }, [](double x) { return 1 / (1 + x * x); },
       [](double x) { return -2 * x / ((1 + x * x) * (1 + x * x)); }, 0.4},
      {"sqrt", [](double x) { return std::sqrt(x); }, [](double x) { return 0.5 / std::sqrt(x); },
       [](double x) { return -0.25 / std::pow(x, 1.5); }, 2.0},
      {"exp", [](double x) { return std::exp(x); }, [](double x) { return std::exp(x); },
       [](double x) { return std::exp(x); }, 1.3},
      {"log", [](double x) { return std::log(x); }, [](double x) { return 1 / x; },
       [](double x) { return -1 / (x * x); }, 1.3},
      {"abs", [](double x) { return std::fabs(x); }, [](double x) { return x > 0 ? 1.0 : -1.0; },
       [](double) { return 0.0; }, -1.3},
  };
  for (const Case& c : cases) {
    // f(2x): first derivative 2 f'(2x), second 4 f''(2x)
    const double u = 2 * c.x;
    check_derivs(c.name + "(2*x)", {"x"}, {c.x}, c.f(u), {2 * c.d1(u)}, {4 * c.d2(u)});
  }
}

TEST_CASE("Expr: gradients and Hessians of operators") {
  const double r = 2.0, p = 0.6;
  check_derivs("3+r*cos(p)", {"r", "p"}, {r, p}, 3 + r * std::cos(p),
               {std::cos(p), -r * std::sin(p)},
               {0, -std::sin(p), -std::sin(p), -r * std::cos(p)});

  const double x = 1.5, y = -0.8, z = 0.4;
  // x^2 y + y^3 z - x z
  check_derivs("x^2*y + y^3*z - x*z", {"x", "y", "z"}, {x, y, z},
               x * x * y + y * y * y * z - x * z,
               {2 * x * y - z, x * x + 3 * y * y * z, y * y * y - x},
               {2 * y, 2 * x, -1, 2 * x, 6 * y * z, 3 * y * y, -1, 3 * y * y, 0});

  // x / y
  check_derivs("x/y", {"x", "y"}, {x, y}, x / y, {1 / y, -x / (y * y)},
               {0, -1 / (y * y), -1 / (y * y), 2 * x / (y * y * y)});

  // atan2(y, x)
  {
    const double r2 = x * x + y * y, r4 = r2 * r2;
    check_derivs("atan2(y, x)", {"x", "y"}, {x, y}, std::atan2(y, x), {-y / r2, x / r2},
                 {2 * x * y / r4, (y * y - x * x) / r4, (y * y - x * x) / r4, -2 * x * y / r4});
  }

  // x^y with both variable
  {
    const double a = 1.7, b = 2.3, f = std::pow(a, b), l = std::log(a);
    check_derivs("x^y", {"x", "y"}, {a, b}, f, {b * std::pow(a, b - 1), f * l},
                 {b * (b - 1) * std::pow(a, b - 2), std::pow(a, b - 1) * (1 + b * l),
                  std::pow(a, b - 1) * (1 + b * l), f * l * l});
  }

  // constant base, constant exponent, constant numerator, constant minuend
  {
    const double t = 0.9, l2 = std::log(2.0);
    check_derivs("2^t", {"t"}, {t}, std::pow(2.0, t), {std::pow(2.0, t) * l2},
                 {std::pow(2.0, t) * l2 * l2});
    check_derivs("t^3.5", {"t"}, {t}, std::pow(t, 3.5), {3.5 * std::pow(t, 2.5)},
                 {3.5 * 2.5 * std::pow(t, 1.5)});
    check_derivs("5/t", {"t"}, {t}, 5 / t, {-5 / (t * t)}, {10 / (t * t * t)});
    check_derivs("1-t^2", {"t"}, {t}, 1 - t * t, {-2 * t}, {-2});
    check_derivs("(t-4)/2 + t*3 - -t", {"t"}, {t}, (t - 4) / 2 + 4 * t, {4.5}, {0});
  }

  // exp(x y) sin(z)
  {
    const double E = std::exp(x * y), S = std::sin(z), C = std::cos(z);
    check_derivs("exp(x*y)*sin(z)", {"x", "y", "z"}, {x, y, z}, E * S,
                 {y * E * S, x * E * S, E * C},
                 {y * y * E * S, (1 + x * y) * E * S, y * E * C,  //
                  (1 + x * y) * E * S, x * x * E * S, x * E * C,  //
                  y * E * C, x * E * C, -E * S});
  }

  // min and max pick a branch
  check_derivs("min(x,y)*max(x,y)", {"x", "y"}, {x, y}, x * y, {y, x}, {0, 1, 1, 0});
  check_derivs("max(x, 1)", {"x"}, {0.5}, 1.0, {0.0}, {0.0});

  // a shared subexpression read twice by the same operation
  check_derivs("sin(x)*sin(x)", {"x"}, {x}, std::sin(x) * std::sin(x), {std::sin(2 * x)},
               {2 * std::cos(2 * x)});

  // a variable not used by the expression has zero derivatives
  check_derivs("y^2", {"x", "y"}, {x, y}, y * y, {0, 2 * y}, {0, 0, 0, 2});
  check_derivs("7", {"x"}, {x}, 7, {0}, {0});
  check_derivs("x", {"x", "y"}, {x, y}, x, {1, 0}, {0, 0, 0, 0});
}

TEST_CASE("Expr: derivatives in more than four variables") {
  const std::vector<std::string> v{"a", "b", "c", "d", "f", "g", "unused"};
  const std::vector<double> x{0.3, -1.2, 0.8, 2.0, -0.5, 1.1, 9.0};
  const double a = x[0], b = x[1], c = x[2], d = x[3], f = x[4], g = x[5];
  const std::string text = "a*b + c*d + f*g + a*g + sin(c)*f + d^2 + b*c*f";
  const double value =
      a * b + c * d + f * g + a * g + std::sin(c) * f + d * d + b * c * f;
  const std::vector<double> grad{b + g,     a + c * f,         d + std::cos(c) * f + b * f,
                                 c + 2 * d, g + std::sin(c) + b * c, f + a, 0};
  // Hessian, symmetric, 7 x 7 (row "unused" is zero)
  std::vector<double> H(49, 0.0);
  auto set = [&](int i, int j, double val) { H[i * 7 + j] = H[j * 7 + i] = val; };
  set(0, 1, 1);
  set(0, 5, 1);
  set(1, 2, f);
  set(1, 4, c);
  set(2, 2, -std::sin(c) * f);
  set(2, 3, 1);
  set(2, 4, std::cos(c) + b);
  set(3, 3, 2);
  set(4, 5, 1);
  check_derivs(text, v, x, value, grad, H);
}

TEST_CASE("Expr: long expressions") {
  // 40 terms computed before they are summed: more registers than fit on the stack
  std::string text = "0";
  double value = 0, grad = 0, hess = 0;
  const double x = 0.7;
  for (int i = 1; i <= 40; ++i) {
    text = "sin(" + std::to_string(i) + "*x) + (" + text + ")";
    value += std::sin(i * x);
    grad += i * std::cos(i * x);
    hess -= i * i * std::sin(i * x);
  }
  check_derivs(text, {"x"}, {x}, value, {grad}, {hess});

  // a long flat sum
  std::string flat = "x";
  for (int i = 0; i < 1000; ++i) flat += "+x";
  check_derivs(flat, {"x"}, {x}, 1001 * x, {1001}, {0});
}

TEST_CASE("Expr: error: empty expression") {
  for (const std::string text : {"", "   "}) {
    const ExprError e = parse_error(text);
    CHECK(e.position() == 0);
    CHECK_THAT(e.what(), Catch::Contains("empty expression"));
  }
}

TEST_CASE("Expr: error: unknown variable") {
  const ExprError e = parse_error("qq+1", {"r", "p"});
  CHECK(e.position() == 0);
  CHECK_THAT(e.what(), Catch::StartsWith("unknown variable 'qq' in \"qq+1\" at column 1"));
  CHECK_THAT(e.what(), Catch::Contains("r, p"));
  CHECK(parse_error("2*x + y", {"x"}).position() == 6);
}

TEST_CASE("Expr: error: unexpected character") {
  const ExprError e = parse_error("(1+2))");
  CHECK(e.position() == 5);
  CHECK(std::string(e.what()) == "unexpected ')' in \"(1+2))\" at column 6");
  CHECK(parse_error("1 $ 2").position() == 2);
  CHECK(parse_error("2x", {"x"}).position() == 1);
  CHECK_THAT(parse_error("2x", {"x"}).what(), Catch::Contains("unexpected 'x'"));
  CHECK(parse_error("1 2").position() == 2);
  CHECK(parse_error("1..2").position() == 2);
  CHECK(parse_error("*3").position() == 0);
  CHECK(parse_error("3*/2").position() == 2);
  CHECK(parse_error("()").position() == 1);
  CHECK_THAT(parse_error("1 + \xC2\xB5").what(), Catch::Contains("'\xC2\xB5'"));
}

TEST_CASE("Expr: error: unexpected end") {
  const ExprError e = parse_error("1+");
  CHECK(e.position() == 2);
  CHECK_THAT(e.what(), Catch::Contains("unexpected end of expression"));
  CHECK_THAT(e.what(), Catch::Contains("at column 3"));
  CHECK(parse_error("sin(").position() == 4);
  CHECK(parse_error("2^").position() == 2);
  CHECK(parse_error("-").position() == 1);
}

TEST_CASE("Expr: error: missing closing parenthesis") {
  const ExprError e = parse_error("(1+2");
  CHECK(e.position() == 4);
  CHECK_THAT(e.what(), Catch::Contains("expected ')'"));
  const ExprError f = parse_error("(1+2 3");
  CHECK(f.position() == 5);
  CHECK_THAT(f.what(), Catch::Contains("unexpected '3', expected ')'"));
  CHECK(parse_error("atan2(1 2)").position() == 8);
}

TEST_CASE("Expr: error: unknown function") {
  const ExprError e = parse_error("2*foo(x)", {"x"});
  CHECK(e.position() == 2);
  CHECK_THAT(e.what(), Catch::StartsWith("unknown function 'foo'"));
  const ExprError v = parse_error("x(2)", {"x"});
  CHECK(v.position() == 0);
  CHECK_THAT(v.what(), Catch::Contains("'x' is a variable, not a function"));
}

TEST_CASE("Expr: error: function without arguments") {
  const ExprError e = parse_error("1 + sin x", {"x"});
  CHECK(e.position() == 4);
  CHECK_THAT(e.what(), Catch::Contains("function 'sin'"));
  // a variable may have the name of a function
  CHECK(ev("sin + sin(sin)", {"sin"}, {0.5}) == near(0.5 + std::sin(0.5)));
}

TEST_CASE("Expr: error: wrong number of arguments") {
  const ExprError e = parse_error("sin(1, 2)");
  CHECK(e.position() == 0);
  CHECK_THAT(e.what(), Catch::StartsWith("function 'sin' takes 1 argument, got 2"));
  const ExprError f = parse_error("x + atan2(x)", {"x"});
  CHECK(f.position() == 4);
  CHECK_THAT(f.what(), Catch::StartsWith("function 'atan2' takes 2 arguments, got 1"));
  CHECK(parse_error("min()").position() == 0);
  CHECK(parse_error("max(1,2,3)").position() == 0);
}

TEST_CASE("Expr: error: number out of range") {
  const ExprError e = parse_error("2*1e999");
  CHECK(e.position() == 2);
  CHECK_THAT(e.what(), Catch::Contains("out of range"));
}

TEST_CASE("Expr: error: nested too deeply") {
  const std::string deep = std::string(100000, '(') + "1" + std::string(100000, ')');
  const ExprError e = parse_error(deep);
  CHECK(e.position() < 1000);
  CHECK_THAT(e.what(), Catch::Contains("nested too deeply"));
  CHECK(parse_error(std::string(100000, '-') + "1").position() < 1000);
  CHECK(ev(std::string(50, '(') + "1" + std::string(50, ')')) == near(1.0));
}

TEST_CASE("Expr: ExprError is a runtime_error") {
  CHECK_THROWS_AS(Expr::parse("1+", {}), std::runtime_error);
}
