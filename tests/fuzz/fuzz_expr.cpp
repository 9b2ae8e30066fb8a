// libFuzzer target: expression text either compiles or throws ExprError; a compiled expression
// evaluates with its derivatives at a few points without undefined behaviour, and its interval
// enclosure over a box holds the values and slopes at points of the box, and where it says the
// expression is defined on the box no point gives NaN (a miss traps).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sweep/expr.hpp"
#include "sweep/interval.hpp"

namespace {

/// The enclosure in t over t in [-0.5, 1.5], q in [0.25, 0.75] against 9 x 3 points of the box.
void check_enclosure(const sweep::Expr& e) {
  const sweep::Interval box[2] = {{-0.5, 1.5}, {0.25, 0.75}};
  sweep::Interval value, slope;
  const bool defined = e.enclose_d1(box, 0, value, slope);
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 2; ++j) {
      const double vars[2] = {-0.5 + 0.25 * i, 0.25 + 0.25 * j};
      double grad[2];
      const double v = e.eval_d1(vars, grad);
      if (defined && !std::isfinite(v)) __builtin_trap();
      if (std::isfinite(v) && !value.contains(v)) __builtin_trap();
      if (std::isfinite(v) && std::isfinite(grad[0]) && !slope.contains(grad[0])) __builtin_trap();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const sweep::Expr e = sweep::Expr::parse(text, {"t", "q"});
    for (const double t : {0.0, 0.5, -2.0, 1e300}) {
      const double vars[2] = {t, 1.0 - t};
      double grad[2], hess[4];
      (void)e.eval(vars);
      (void)e.eval_d1(vars, grad);
      (void)e.eval_d2(vars, grad, hess);
    }
    check_enclosure(e);
  } catch (const sweep::ExprError&) {
  }
  return 0;
}
