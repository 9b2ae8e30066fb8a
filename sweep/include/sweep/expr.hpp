#pragma once
/// @file expr.hpp
/// Expressions of SPEC.md ("3+r*cos(p)", "q-90") compiled once and evaluated fast, with exact
/// first and second derivatives by forward-mode automatic differentiation.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace sweep {

struct Interval;  // sweep/interval.hpp

/// A syntax error or an unknown name. `position` is the 0-based offset of the offending character
/// in the expression text; what() quotes the expression and marks the position.
class ExprError : public std::runtime_error {
 public:
  ExprError(const std::string& message, std::size_t position)
      : std::runtime_error(message), position_(position) {}
  std::size_t position() const { return position_; }

 private:
  std::size_t position_;
};

/// A compiled expression over named variables.
/// Grammar: numbers, + - * / ^ (right-associative, binds tighter than unary minus: -x^2 = -(x^2)),
/// unary minus/plus, parentheses, functions sin cos tan asin acos atan atan2 sqrt exp log abs min max,
/// constants pi and e, and the variables given at parse time.
class Expr {
 public:
  Expr();  ///< the constant 0
  /// @throws ExprError on a syntax error, unknown variable or function, or wrong argument count.
  static Expr parse(const std::string& text, const std::vector<std::string>& variables);
  static Expr constant(double value);

  /// Value at `vars` (num_vars() entries, in the order given to parse()).
  double eval(const double* vars) const;
  double eval(const std::vector<double>& vars) const { return eval(vars.data()); }
  /// Value and gradient (num_vars() entries written to grad).
  double eval_d1(const double* vars, double* grad) const;
  /// Value, gradient and Hessian (row-major num_vars() x num_vars()).
  double eval_d2(const double* vars, double* grad, double* hess) const;
  /// Encloses the value and the derivative in variable `var` over the box `vars` (num_vars()
  /// intervals): at every point of the box both lie in the intervals written, rounding included.
  /// Where the expression is not differentiable (abs, min, max) the derivative interval bounds its
  /// one-sided slopes; where an operation has no finite bound the interval is the whole line.
  /// Returns false when some point of the box may leave an operation's domain (the expression may
  /// be NaN there, or finite through infinite intermediates); the intervals are then the whole line.
  bool enclose_d1(const Interval* vars, std::size_t var, Interval& value, Interval& derivative) const;

  const std::string& text() const;
  std::size_t num_vars() const;
  /// True when the expression uses none of its variables.
  bool is_constant() const;
  /// True when variable i occurs in the expression.
  bool uses(std::size_t i) const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

}  // namespace sweep
