// libFuzzer target: expression text either compiles or throws ExprError; a compiled expression
// evaluates with its derivatives at a few points without undefined behaviour.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sweep/expr.hpp"

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
  } catch (const sweep::ExprError&) {
  }
  return 0;
}
