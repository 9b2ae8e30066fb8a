#include "sweep/expr.hpp"

#include "sweep/interval.hpp"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <utility>

// Expressions are parsed by recursive descent into a DAG (constants folded, common subexpressions
// shared), then flattened into a register tape: one instruction per operation, registers reused
// once a value is dead. The same tape is interpreted over plain doubles (eval) and over truncated
// Taylor numbers (Jet<1,N>: value and gradient; Jet<2,N>: value, gradient and Hessian), which gives
// exact derivatives by forward-mode automatic differentiation.

namespace sweep {
namespace {

constexpr double kPi = 3.141592653589793238462643383279502884;
constexpr double kE = 2.718281828459045235360287471352662498;
constexpr int kMaxDepth = 200;          ///< nesting limit of the parser (no stack overflow)
constexpr std::size_t kStackRegs = 32;  ///< registers kept on the stack; more go to the heap

enum class Op : std::uint8_t {
  Const, Var,                            // Var only appears in the DAG, never on the tape
  Neg, Add, Sub, Mul, Div, Pow,
  AddK, KSub, MulK, DivK, KDiv, PowK, KPow, Sq,  // one operand and the constant k
  Sin, Cos, Tan, Asin, Acos, Atan, Atan2, Sqrt, Exp, Log, Abs, Min, Max,
};

int arity(Op op) {
  switch (op) {
    case Op::Const: case Op::Var: return 0;
    case Op::Add: case Op::Sub: case Op::Mul: case Op::Div: case Op::Pow:
    case Op::Atan2: case Op::Min: case Op::Max: return 2;
    default: return 1;
  }
}

struct Instr {
  Op op;
  std::uint32_t dst, a, b;
  double k;
};

// ---------------------------------------------------------------------------------------------
// Numbers: double and truncated Taylor polynomials in N variables (order 1 or 2).

template <int O, int N>
struct Jet;
template <int N>
struct Jet<1, N> {
  double v;
  double g[N];
};
template <int N>
struct Jet<2, N> {
  static constexpr int kH = N * (N + 1) / 2;  ///< upper triangle of the Hessian, row by row
  double v;
  double g[N];
  double h[kH];
};

template <class T>
struct Lift;
template <>
struct Lift<double> {
  static double of(double k) { return k; }
};
template <int O, int N>
struct Lift<Jet<O, N>> {
  static Jet<O, N> of(double k) {
    Jet<O, N> r;
    r.v = k;
    for (double& x : r.g) x = 0.0;
    if constexpr (O >= 2)
      for (double& x : r.h) x = 0.0;
    return r;
  }
};

/// f * x, but 0 when x is 0: a function of an argument that does not depend on a variable does not
/// depend on it either, even where f' is infinite (sqrt at 0).
inline double times(double f, double x) { return x == 0.0 ? 0.0 : f * x; }

/// r = f(a) with f(a.v) = f0, f'(a.v) = f1, f''(a.v) = f2.
template <int O, int N>
Jet<O, N> chain(const Jet<O, N>& a, double f0, double f1, double f2) {
  Jet<O, N> r;
  r.v = f0;
  for (int i = 0; i < N; ++i) r.g[i] = times(f1, a.g[i]);
  if constexpr (O >= 2) {
    int k = 0;
    for (int i = 0; i < N; ++i)
      for (int j = i; j < N; ++j, ++k) r.h[k] = times(f1, a.h[k]) + times(f2, a.g[i] * a.g[j]);
  }
  return r;
}

/// r = f(a, b) with value f0, first partials fa, fb and second partials faa, fab, fbb.
template <int O, int N>
Jet<O, N> chain(const Jet<O, N>& a, const Jet<O, N>& b, double f0, double fa, double fb,
                double faa, double fab, double fbb) {
  Jet<O, N> r;
  r.v = f0;
  for (int i = 0; i < N; ++i) r.g[i] = times(fa, a.g[i]) + times(fb, b.g[i]);
  if constexpr (O >= 2) {
    int k = 0;
    for (int i = 0; i < N; ++i)
      for (int j = i; j < N; ++j, ++k)
        r.h[k] = times(fa, a.h[k]) + times(fb, b.h[k]) + times(faa, a.g[i] * a.g[j]) +
                 times(fab, a.g[i] * b.g[j] + a.g[j] * b.g[i]) + times(fbb, b.g[i] * b.g[j]);
  }
  return r;
}

/// r = s * a.
template <int O, int N>
Jet<O, N> affine(const Jet<O, N>& a, double s) {
  Jet<O, N> r;
  r.v = s * a.v;
  for (int i = 0; i < N; ++i) r.g[i] = s * a.g[i];
  if constexpr (O >= 2)
    for (int k = 0; k < Jet<O, N>::kH; ++k) r.h[k] = s * a.h[k];
  return r;
}

// Min/max follow C fmin/fmax (a NaN argument loses); ties pick the first argument.
inline bool pick_first_min(double a, double b) { return a <= b || std::isnan(b); }
inline bool pick_first_max(double a, double b) { return a >= b || std::isnan(b); }
/// log for the derivative of a power with respect to its exponent: 0 at 0 (d/dy 0^y = 0).
inline double log_or_zero(double x) { return x == 0.0 ? 0.0 : std::log(x); }

// Operations on double: the reference semantics (C library), also used for constant folding.
inline double op_neg(double a) { return -a; }
inline double op_add(double a, double b) { return a + b; }
inline double op_sub(double a, double b) { return a - b; }
inline double op_mul(double a, double b) { return a * b; }
inline double op_div(double a, double b) { return a / b; }
inline double op_pow(double a, double b) { return std::pow(a, b); }
inline double op_addk(double a, double k) { return a + k; }
inline double op_ksub(double k, double a) { return k - a; }
inline double op_mulk(double a, double k) { return a * k; }
inline double op_divk(double a, double k) { return a / k; }
inline double op_kdiv(double k, double a) { return k / a; }
inline double op_powk(double a, double k) { return std::pow(a, k); }
inline double op_kpow(double k, double a) { return std::pow(k, a); }
inline double op_sq(double a) { return a * a; }
inline double op_sin(double a) { return std::sin(a); }
inline double op_cos(double a) { return std::cos(a); }
inline double op_tan(double a) { return std::tan(a); }
inline double op_asin(double a) { return std::asin(a); }
inline double op_acos(double a) { return std::acos(a); }
inline double op_atan(double a) { return std::atan(a); }
inline double op_atan2(double y, double x) { return std::atan2(y, x); }
inline double op_sqrt(double a) { return std::sqrt(a); }
inline double op_exp(double a) { return std::exp(a); }
inline double op_log(double a) { return std::log(a); }
inline double op_abs(double a) { return std::fabs(a); }
inline double op_min(double a, double b) { return pick_first_min(a, b) ? a : b; }
inline double op_max(double a, double b) { return pick_first_max(a, b) ? a : b; }

// The same operations on jets.
template <int O, int N>
Jet<O, N> op_neg(const Jet<O, N>& a) { return affine(a, -1.0); }

template <int O, int N>
Jet<O, N> op_add(const Jet<O, N>& a, const Jet<O, N>& b) {
  Jet<O, N> r;
  r.v = a.v + b.v;
  for (int i = 0; i < N; ++i) r.g[i] = a.g[i] + b.g[i];
  if constexpr (O >= 2)
    for (int k = 0; k < Jet<O, N>::kH; ++k) r.h[k] = a.h[k] + b.h[k];
  return r;
}

template <int O, int N>
Jet<O, N> op_sub(const Jet<O, N>& a, const Jet<O, N>& b) {
  Jet<O, N> r;
  r.v = a.v - b.v;
  for (int i = 0; i < N; ++i) r.g[i] = a.g[i] - b.g[i];
  if constexpr (O >= 2)
    for (int k = 0; k < Jet<O, N>::kH; ++k) r.h[k] = a.h[k] - b.h[k];
  return r;
}

template <int O, int N>
Jet<O, N> op_mul(const Jet<O, N>& a, const Jet<O, N>& b) {
  Jet<O, N> r;
  r.v = a.v * b.v;
  for (int i = 0; i < N; ++i) r.g[i] = a.v * b.g[i] + b.v * a.g[i];
  if constexpr (O >= 2) {
    int k = 0;
    for (int i = 0; i < N; ++i)
      for (int j = i; j < N; ++j, ++k)
        r.h[k] = a.v * b.h[k] + b.v * a.h[k] + a.g[i] * b.g[j] + a.g[j] * b.g[i];
  }
  return r;
}

// c = a / b from a = c * b: c' = (a' - c b') / b, c'' = (a'' - c b'' - c' b'^T - b' c'^T) / b.
template <int O, int N>
Jet<O, N> op_div(const Jet<O, N>& a, const Jet<O, N>& b) {
  Jet<O, N> r;
  r.v = a.v / b.v;
  for (int i = 0; i < N; ++i) r.g[i] = (a.g[i] - r.v * b.g[i]) / b.v;
  if constexpr (O >= 2) {
    int k = 0;
    for (int i = 0; i < N; ++i)
      for (int j = i; j < N; ++j, ++k)
        r.h[k] = (a.h[k] - r.v * b.h[k] - r.g[i] * b.g[j] - r.g[j] * b.g[i]) / b.v;
  }
  return r;
}

// x^y for a non-constant exponent. The partials in y use log x (0 at x = 0, NaN for x < 0).
template <int O, int N>
Jet<O, N> op_pow(const Jet<O, N>& a, const Jet<O, N>& b) {
  const double x = a.v, y = b.v;
  const double f = std::pow(x, y), f1 = std::pow(x, y - 1.0), lx = log_or_zero(x);
  const double fxx = O >= 2 ? y * (y - 1.0) * std::pow(x, y - 2.0) : 0.0;
  return chain(a, b, f, y * f1, f * lx, fxx, f1 * (1.0 + y * lx), f * lx * lx);
}

template <int O, int N>
Jet<O, N> op_addk(const Jet<O, N>& a, double k) {
  Jet<O, N> r = a;
  r.v = a.v + k;
  return r;
}
template <int O, int N>
Jet<O, N> op_ksub(double k, const Jet<O, N>& a) {
  Jet<O, N> r = affine(a, -1.0);
  r.v = k - a.v;
  return r;
}
template <int O, int N>
Jet<O, N> op_mulk(const Jet<O, N>& a, double k) { return affine(a, k); }
template <int O, int N>
Jet<O, N> op_divk(const Jet<O, N>& a, double k) {
  Jet<O, N> r;
  r.v = a.v / k;
  for (int i = 0; i < N; ++i) r.g[i] = a.g[i] / k;
  if constexpr (O >= 2)
    for (int kk = 0; kk < Jet<O, N>::kH; ++kk) r.h[kk] = a.h[kk] / k;
  return r;
}
template <int O, int N>
Jet<O, N> op_kdiv(double k, const Jet<O, N>& a) {
  const double x = a.v, f = k / x, f1 = -f / x;
  return chain(a, f, f1, -2.0 * f1 / x);
}
template <int O, int N>
Jet<O, N> op_powk(const Jet<O, N>& a, double k) {
  const double x = a.v;
  const double f2 = O >= 2 ? k * (k - 1.0) * std::pow(x, k - 2.0) : 0.0;
  return chain(a, std::pow(x, k), k * std::pow(x, k - 1.0), f2);
}
template <int O, int N>
Jet<O, N> op_kpow(double k, const Jet<O, N>& a) {
  const double f = std::pow(k, a.v), lk = log_or_zero(k);
  return chain(a, f, f * lk, f * lk * lk);
}
template <int O, int N>
Jet<O, N> op_sq(const Jet<O, N>& a) { return chain(a, a.v * a.v, 2.0 * a.v, 2.0); }
template <int O, int N>
Jet<O, N> op_sin(const Jet<O, N>& a) {
  const double s = std::sin(a.v);
  return chain(a, s, std::cos(a.v), -s);
}
template <int O, int N>
Jet<O, N> op_cos(const Jet<O, N>& a) {
  const double c = std::cos(a.v);
  return chain(a, c, -std::sin(a.v), -c);
}
template <int O, int N>
Jet<O, N> op_tan(const Jet<O, N>& a) {
  const double t = std::tan(a.v), d = 1.0 + t * t;
  return chain(a, t, d, 2.0 * t * d);
}
template <int O, int N>
Jet<O, N> op_asin(const Jet<O, N>& a) {
  const double x = a.v, f1 = 1.0 / std::sqrt(1.0 - x * x);
  return chain(a, std::asin(x), f1, x * f1 * f1 * f1);
}
template <int O, int N>
Jet<O, N> op_acos(const Jet<O, N>& a) {
  const double x = a.v, f1 = 1.0 / std::sqrt(1.0 - x * x);
  return chain(a, std::acos(x), -f1, -x * f1 * f1 * f1);
}
template <int O, int N>
Jet<O, N> op_atan(const Jet<O, N>& a) {
  const double x = a.v, d = 1.0 / (1.0 + x * x);
  return chain(a, std::atan(x), d, -2.0 * x * d * d);
}
template <int O, int N>
Jet<O, N> op_atan2(const Jet<O, N>& a, const Jet<O, N>& b) {
  const double y = a.v, x = b.v, r2 = x * x + y * y, r4 = r2 * r2;
  return chain(a, b, std::atan2(y, x), x / r2, -y / r2, -2.0 * x * y / r4, (y * y - x * x) / r4,
               2.0 * x * y / r4);
}
template <int O, int N>
Jet<O, N> op_sqrt(const Jet<O, N>& a) {
  const double x = a.v, s = std::sqrt(x), f1 = 0.5 / s;
  return chain(a, s, f1, -0.5 * f1 / x);
}
template <int O, int N>
Jet<O, N> op_exp(const Jet<O, N>& a) {
  const double e = std::exp(a.v);
  return chain(a, e, e, e);
}
template <int O, int N>
Jet<O, N> op_log(const Jet<O, N>& a) {
  const double f1 = 1.0 / a.v;
  return chain(a, std::log(a.v), f1, -f1 * f1);
}
template <int O, int N>
Jet<O, N> op_abs(const Jet<O, N>& a) {
  const double x = a.v;
  return chain(a, std::fabs(x), x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0), 0.0);
}
template <int O, int N>
Jet<O, N> op_min(const Jet<O, N>& a, const Jet<O, N>& b) {
  return pick_first_min(a.v, b.v) ? a : b;
}
template <int O, int N>
Jet<O, N> op_max(const Jet<O, N>& a, const Jet<O, N>& b) {
  return pick_first_max(a.v, b.v) ? a : b;
}

// ---------------------------------------------------------------------------------------------
// Enclosures: an interval for the value and one for the derivative in one variable, over a box of
// arguments. Where a function is not differentiable (abs at 0, min and max where the arguments
// cross) the derivative interval holds both one-sided derivatives, so it still bounds the slope.
// `defined` is false when some point of the box may give NaN (an operation leaving its domain, or
// an unbounded operand): the intervals then hold the values where the expression is defined, and
// min and max, which drop a NaN argument, also hold the other argument.

struct IJet {
  Interval v, d;
  bool defined = true;
};
template <>
struct Lift<IJet> {
  /// A constant folded to NaN or an infinity (sqrt(-1), 1/0) is nowhere defined: its enclosure is
  /// the whole line, so that min and max, which drop it at a point, still hold the other operand.
  static IJet of(double k) {
    if (!std::isfinite(k)) return {Interval::entire(), Interval::point(0.0), false};
    return {Interval::point(k), Interval::point(0.0), true};
  }
};

/// f' * d, but 0 when d is 0 (as times() above: f' may be unbounded where d vanishes).
inline Interval times(Interval f, Interval d) { return d.is_zero() ? d : f * d; }
inline Interval pt(double k) { return Interval::point(k); }
inline bool bounded(Interval a) { return std::isfinite(a.lo) && std::isfinite(a.hi); }

/// The result of an operation whose operands were all defined (`ok`) and bounded.
inline IJet result(Interval v, Interval d, bool ok) { return {v, d, ok && bounded(v)}; }
inline IJet ichain(const IJet& a, Interval f0, Interval f1, bool domain = true) {
  return result(f0, times(f1, a.d), a.defined && domain);
}

inline IJet op_neg(const IJet& a) { return {-a.v, -a.d, a.defined}; }
inline IJet op_add(const IJet& a, const IJet& b) { return result(a.v + b.v, a.d + b.d, a.defined && b.defined); }
inline IJet op_sub(const IJet& a, const IJet& b) { return result(a.v - b.v, a.d - b.d, a.defined && b.defined); }
inline IJet op_mul(const IJet& a, const IJet& b) {
  return result(a.v * b.v, times(b.v, a.d) + times(a.v, b.d), a.defined && b.defined);
}
inline IJet op_div(const IJet& a, const IJet& b) {
  const Interval c = a.v / b.v;
  return result(c, (a.d - times(c, b.d)) / b.v, a.defined && b.defined);
}
inline IJet op_pow(const IJet& a, const IJet& b) {
  const Interval f = pow(a.v, b.v);
  return result(f, times(b.v * pow(a.v, b.v - pt(1.0)), a.d) + times(f * log(a.v), b.d),
                a.defined && b.defined && a.v.lo > 0);
}
/// An operation with a constant folded to NaN or an infinity (0^-2): nowhere a bound.
inline IJet nowhere() { return {Interval::entire(), Interval::entire(), false}; }
inline IJet op_addk(const IJet& a, double k) { return std::isfinite(k) ? result(a.v + pt(k), a.d, a.defined) : nowhere(); }
inline IJet op_ksub(double k, const IJet& a) { return std::isfinite(k) ? result(pt(k) - a.v, -a.d, a.defined) : nowhere(); }
inline IJet op_mulk(const IJet& a, double k) {
  return std::isfinite(k) ? result(a.v * pt(k), a.d * pt(k), a.defined) : nowhere();
}
inline IJet op_divk(const IJet& a, double k) {
  return std::isfinite(k) ? result(a.v / pt(k), a.d / pt(k), a.defined) : nowhere();
}
inline IJet op_kdiv(double k, const IJet& a) {
  return std::isfinite(k) ? ichain(a, pt(k) / a.v, -pt(k) / sq(a.v)) : nowhere();
}
inline IJet op_powk(const IJet& a, double k) {
  if (!std::isfinite(k)) return nowhere();
  const bool integer = k == std::floor(k);
  return ichain(a, pow_const(a.v, k), pt(k) * pow_const(a.v, k - 1.0), integer || a.v.lo >= 0);
}
inline IJet op_kpow(double k, const IJet& a) {
  if (!std::isfinite(k)) return nowhere();
  const Interval f = const_pow(k, a.v);
  return ichain(a, f, f * pt(log_or_zero(k)));
}
inline IJet op_sq(const IJet& a) { return ichain(a, sq(a.v), pt(2.0) * a.v); }
inline IJet op_sin(const IJet& a) { return ichain(a, sin(a.v), cos(a.v), bounded(a.v)); }
inline IJet op_cos(const IJet& a) { return ichain(a, cos(a.v), -sin(a.v), bounded(a.v)); }
inline IJet op_tan(const IJet& a) {
  const Interval t = tan(a.v);
  return ichain(a, t, pt(1.0) + sq(t));
}
inline bool in_unit(Interval a) { return a.lo >= -1 && a.hi <= 1; }
inline IJet op_asin(const IJet& a) {
  return ichain(a, asin(a.v), pt(1.0) / sqrt(pt(1.0) - sq(a.v)), in_unit(a.v));
}
inline IJet op_acos(const IJet& a) {
  return ichain(a, acos(a.v), pt(-1.0) / sqrt(pt(1.0) - sq(a.v)), in_unit(a.v));
}
inline IJet op_atan(const IJet& a) { return ichain(a, atan(a.v), pt(1.0) / (pt(1.0) + sq(a.v)), bounded(a.v)); }
inline IJet op_atan2(const IJet& a, const IJet& b) {
  // y = a, x = b: d atan2 = (x dy - y dx) / (x^2 + y^2)
  return result(atan2(a.v, b.v), (times(b.v, a.d) - times(a.v, b.d)) / (sq(a.v) + sq(b.v)),
                a.defined && b.defined && bounded(a.v) && bounded(b.v));
}
inline IJet op_sqrt(const IJet& a) {
  const Interval s = sqrt(a.v);
  return ichain(a, s, pt(0.5) / s, a.v.lo >= 0);
}
inline IJet op_exp(const IJet& a) {
  const Interval e = exp(a.v);
  return ichain(a, e, e);
}
inline IJet op_log(const IJet& a) { return ichain(a, log(a.v), pt(1.0) / a.v, a.v.lo > 0); }
inline IJet op_abs(const IJet& a) {
  const Interval sign = a.v.lo > 0 ? pt(1.0) : (a.v.hi < 0 ? pt(-1.0) : Interval{-1.0, 1.0});
  return ichain(a, abs(a.v), sign);
}
/// min or max of a and b as `pick` gives it for defined operands; where one may be NaN the other
/// may be the result (C fmin and fmax drop a NaN).
template <class Pick>
IJet min_or_max(const IJet& a, const IJet& b, bool a_only, bool b_only, Pick pick) {
  IJet r{pick(a.v, b.v), a_only ? a.d : (b_only ? b.d : hull(a.d, b.d)), a.defined && b.defined};
  if (!a.defined) r = {hull(r.v, b.v), hull(r.d, b.d), false};
  if (!b.defined) r = {hull(r.v, a.v), hull(r.d, a.d), false};
  return r;
}
inline IJet op_min(const IJet& a, const IJet& b) {
  return min_or_max(a, b, a.v.hi < b.v.lo, b.v.hi < a.v.lo, [](Interval x, Interval y) { return min(x, y); });
}
inline IJet op_max(const IJet& a, const IJet& b) {
  return min_or_max(a, b, a.v.lo > b.v.hi, b.v.lo > a.v.hi, [](Interval x, Interval y) { return max(x, y); });
}

/// Runs `n` instructions over the register file `r`.
template <class T>
void run(const Instr* tape, std::size_t n, T* r) {
  for (const Instr* in = tape; in != tape + n; ++in) {
    const std::uint32_t a = in->a, b = in->b;
    T& d = r[in->dst];
    switch (in->op) {
      case Op::Const: d = Lift<T>::of(in->k); break;
      case Op::Var: break;
      case Op::Neg: d = op_neg(r[a]); break;
      case Op::Add: d = op_add(r[a], r[b]); break;
      case Op::Sub: d = op_sub(r[a], r[b]); break;
      case Op::Mul: d = op_mul(r[a], r[b]); break;
      case Op::Div: d = op_div(r[a], r[b]); break;
      case Op::Pow: d = op_pow(r[a], r[b]); break;
      case Op::AddK: d = op_addk(r[a], in->k); break;
      case Op::KSub: d = op_ksub(in->k, r[a]); break;
      case Op::MulK: d = op_mulk(r[a], in->k); break;
      case Op::DivK: d = op_divk(r[a], in->k); break;
      case Op::KDiv: d = op_kdiv(in->k, r[a]); break;
      case Op::PowK: d = op_powk(r[a], in->k); break;
      case Op::KPow: d = op_kpow(in->k, r[a]); break;
      case Op::Sq: d = op_sq(r[a]); break;
      case Op::Sin: d = op_sin(r[a]); break;
      case Op::Cos: d = op_cos(r[a]); break;
      case Op::Tan: d = op_tan(r[a]); break;
      case Op::Asin: d = op_asin(r[a]); break;
      case Op::Acos: d = op_acos(r[a]); break;
      case Op::Atan: d = op_atan(r[a]); break;
      case Op::Atan2: d = op_atan2(r[a], r[b]); break;
      case Op::Sqrt: d = op_sqrt(r[a]); break;
      case Op::Exp: d = op_exp(r[a]); break;
      case Op::Log: d = op_log(r[a]); break;
      case Op::Abs: d = op_abs(r[a]); break;
      case Op::Min: d = op_min(r[a], r[b]); break;
      case Op::Max: d = op_max(r[a], r[b]); break;
    }
  }
}

/// The value of one operation on constants, computed by the interpreter itself.
double fold(Op op, double a, double b, double k) {
  double r[3] = {a, b, 0.0};
  const Instr in{op, 2, 0, 1, k};
  run(&in, 1, r);
  return r[2];
}

/// Calls f(registers) with `n` registers, on the stack when they fit.
template <class T, class F>
auto with_registers(std::size_t n, F&& f) {
  if (n <= kStackRegs) {
    T stack[kStackRegs];
    return f(stack);
  }
  std::vector<T> heap(n);
  return f(heap.data());
}

// ---------------------------------------------------------------------------------------------
// DAG with constant folding and shared subexpressions.

struct Node {
  Op op;
  std::uint32_t a, b;  ///< operands (node ids); for Var, a is the variable index
  double k;            ///< Const value, or the constant of a K operation
};

struct NodeKey {
  Op op;
  std::uint32_t a, b;
  std::uint64_t k;
  bool operator==(const NodeKey& o) const { return op == o.op && a == o.a && b == o.b && k == o.k; }
};
struct NodeKeyHash {
  std::size_t operator()(const NodeKey& key) const {
    std::uint64_t h = static_cast<std::uint64_t>(key.op);
    h = h * 0x9E3779B97F4A7C15ull ^ key.a;
    h = h * 0x9E3779B97F4A7C15ull ^ key.b;
    h = h * 0x9E3779B97F4A7C15ull ^ key.k;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

class Builder {
 public:
  std::vector<Node> nodes;

  std::uint32_t constant(double k) { return add({Op::Const, 0, 0, k}); }
  std::uint32_t variable(std::uint32_t i) { return add({Op::Var, i, 0, 0.0}); }
  bool is_const(std::uint32_t n) const { return nodes[n].op == Op::Const; }
  double value(std::uint32_t n) const { return nodes[n].k; }

  std::uint32_t unary(Op op, std::uint32_t a, double k = 0.0) {
    if (is_const(a)) return constant(fold(op, value(a), 0.0, k));
    return add({op, a, 0, k});
  }

  std::uint32_t binary(Op op, std::uint32_t a, std::uint32_t b) {
    const bool ca = is_const(a), cb = is_const(b);
    if (ca && cb) return constant(fold(op, value(a), value(b), 0.0));
    if (ca || cb) {
      const double ka = ca ? value(a) : 0.0, kb = cb ? value(b) : 0.0;
      switch (op) {
        case Op::Add: return cb ? unary(Op::AddK, a, kb) : unary(Op::AddK, b, ka);
        case Op::Sub:  // a - k == a + (-k) exactly
          return cb ? unary(Op::AddK, a, -kb) : unary(Op::KSub, b, ka);
        case Op::Mul: return cb ? unary(Op::MulK, a, kb) : unary(Op::MulK, b, ka);
        case Op::Div: return cb ? unary(Op::DivK, a, kb) : unary(Op::KDiv, b, ka);
        case Op::Pow:
          if (ca) return unary(Op::KPow, b, ka);
          if (kb == 1.0) return a;              // pow(x, 1) == x
          if (kb == 0.0) return constant(1.0);  // pow(x, 0) == 1, even for NaN
          if (kb == 2.0) return unary(Op::Sq, a);
          return unary(Op::PowK, a, kb);
        default: break;  // atan2, min, max keep a Const operand
      }
    }
    return add({op, a, b, 0.0});
  }

 private:
  std::unordered_map<NodeKey, std::uint32_t, NodeKeyHash> index_;

  std::uint32_t add(const Node& n) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &n.k, sizeof bits);
    const NodeKey key{n.op, n.a, n.b, bits};
    const auto it = index_.find(key);
    if (it != index_.end()) return it->second;
    const auto id = static_cast<std::uint32_t>(nodes.size());
    nodes.push_back(n);
    index_.emplace(key, id);
    return id;
  }
};

// ---------------------------------------------------------------------------------------------
// Parser.

struct Function {
  const char* name;
  Op op;
  int arity;
};
constexpr Function kFunctions[] = {
    {"sin", Op::Sin, 1},   {"cos", Op::Cos, 1},   {"tan", Op::Tan, 1},     {"asin", Op::Asin, 1},
    {"acos", Op::Acos, 1}, {"atan", Op::Atan, 1}, {"atan2", Op::Atan2, 2}, {"sqrt", Op::Sqrt, 1},
    {"exp", Op::Exp, 1},   {"log", Op::Log, 1},   {"abs", Op::Abs, 1},     {"min", Op::Min, 2},
    {"max", Op::Max, 2},
};

const Function* find_function(const std::string& name) {
  for (const Function& f : kFunctions)
    if (name == f.name) return &f;
  return nullptr;
}

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_name_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_name_char(char c) { return is_name_start(c) || is_digit(c); }
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

class Parser {
 public:
  Parser(const std::string& text, const std::vector<std::string>& variables)
      : s_(text), vars_(variables) {
    used.assign(variables.size(), 0);
  }

  Builder builder;
  std::vector<char> used;

  std::uint32_t parse() {
    skip();
    if (p_ == s_.size()) fail(0, "empty expression");
    const std::uint32_t root = sum();
    skip();
    if (p_ != s_.size()) unexpected();
    return root;
  }

 private:
  const std::string& s_;
  const std::vector<std::string>& vars_;
  std::size_t p_ = 0;
  int depth_ = 0;

  /// Throws "<problem> in "<text>" at column <pos+1><hint>".
  [[noreturn]] void fail(std::size_t pos, const std::string& problem,
                         const std::string& hint = "") const {
    const std::string where = " in \"" + s_ + "\" at column " + std::to_string(pos + 1);
    throw ExprError(problem + where + hint, pos);
  }

  /// The token starting at p, as written (a number, a name, or one character).
  std::string token_at(std::size_t p) const {
    std::size_t q = p + 1;
    const char c = s_[p];
    if (is_digit(c) || c == '.') {
      while (q < s_.size() && (is_digit(s_[q]) || s_[q] == '.')) ++q;
    } else if (is_name_start(c)) {
      while (q < s_.size() && is_name_char(s_[q])) ++q;
    } else if (static_cast<unsigned char>(c) >= 0xC0) {  // whole UTF-8 sequence
      while (q < s_.size() && (static_cast<unsigned char>(s_[q]) & 0xC0) == 0x80) ++q;
    }
    return s_.substr(p, q - p);
  }

  /// Fails at the current token: "unexpected end of expression" or "unexpected 'x'".
  [[noreturn]] void unexpected(const std::string& expected = "") const {
    const std::string tail = expected.empty() ? "" : ", expected " + expected;
    if (p_ >= s_.size()) fail(s_.size(), "unexpected end of expression" + tail);
    fail(p_, "unexpected '" + token_at(p_) + "'" + tail);
  }

  void skip() {
    while (p_ < s_.size() && is_space(s_[p_])) ++p_;
  }
  bool accept(char c) {
    skip();
    if (p_ < s_.size() && s_[p_] == c) {
      ++p_;
      return true;
    }
    return false;
  }
  void expect(char c, const char* what) {
    if (!accept(c)) unexpected(what);
  }

  std::uint32_t sum() {
    std::uint32_t lhs = product();
    for (;;) {
      if (accept('+')) lhs = builder.binary(Op::Add, lhs, product());
      else if (accept('-')) lhs = builder.binary(Op::Sub, lhs, product());
      else return lhs;
    }
  }

  std::uint32_t product() {
    std::uint32_t lhs = unary();
    for (;;) {
      if (accept('*')) lhs = builder.binary(Op::Mul, lhs, unary());
      else if (accept('/')) lhs = builder.binary(Op::Div, lhs, unary());
      else return lhs;
    }
  }

  // Every level of nesting goes through here, so the depth limit is checked once.
  std::uint32_t unary() {
    struct Guard {
      int& d;
      ~Guard() { --d; }
    } guard{++depth_};
    skip();
    if (depth_ > kMaxDepth) fail(p_, "expression nested too deeply");
    if (accept('-')) return builder.unary(Op::Neg, unary());
    if (accept('+')) return unary();
    return power();
  }

  // base ^ exponent: right-associative, and the exponent may carry a sign (2^-1).
  std::uint32_t power() {
    const std::uint32_t base = primary();
    if (accept('^')) return builder.binary(Op::Pow, base, unary());
    return base;
  }

  std::uint32_t primary() {
    skip();
    if (p_ >= s_.size()) unexpected();
    const char c = s_[p_];
    if (is_digit(c) || (c == '.' && p_ + 1 < s_.size() && is_digit(s_[p_ + 1]))) return number();
    if (is_name_start(c)) return name();
    if (accept('(')) {
      const std::uint32_t e = sum();
      expect(')', "')'");
      return e;
    }
    unexpected();
  }

  std::uint32_t number() {
    const std::size_t start = p_;
    while (p_ < s_.size() && is_digit(s_[p_])) ++p_;
    if (p_ < s_.size() && s_[p_] == '.') {
      ++p_;
      while (p_ < s_.size() && is_digit(s_[p_])) ++p_;
    }
    if (p_ < s_.size() && (s_[p_] == 'e' || s_[p_] == 'E')) {  // exponent only if digits follow
      std::size_t q = p_ + 1;
      if (q < s_.size() && (s_[q] == '+' || s_[q] == '-')) ++q;
      if (q < s_.size() && is_digit(s_[q])) {
        p_ = q;
        while (p_ < s_.size() && is_digit(s_[p_])) ++p_;
      }
    }
    double v = 0.0;
    const char* first = s_.data() + start;
    const char* last = s_.data() + p_;
    const auto res = std::from_chars(first, last, v);  // locale independent
    if (res.ec == std::errc::result_out_of_range)
      fail(start, "number '" + s_.substr(start, p_ - start) + "' is out of range");
    if (res.ec != std::errc() || res.ptr != last)
      fail(start, "malformed number '" + s_.substr(start, p_ - start) + "'");
    return builder.constant(v);
  }

  std::uint32_t name() {
    const std::size_t start = p_;
    while (p_ < s_.size() && is_name_char(s_[p_])) ++p_;
    const std::string id = s_.substr(start, p_ - start);
    skip();
    const bool call = p_ < s_.size() && s_[p_] == '(';
    const Function* fn = find_function(id);
    if (call) {
      if (!fn) {
        for (const std::string& v : vars_)
          if (v == id) fail(start, "'" + id + "' is a variable, not a function");
        fail(start, "unknown function '" + id + "'");
      }
      return call_function(*fn, start);
    }
    for (std::size_t i = 0; i < vars_.size(); ++i) {
      if (vars_[i] == id) {
        used[i] = 1;
        return builder.variable(static_cast<std::uint32_t>(i));
      }
    }
    if (id == "pi") return builder.constant(kPi);
    if (id == "e") return builder.constant(kE);
    if (fn) fail(start, "function '" + id + "' needs its arguments in parentheses");
    std::string known;
    for (const std::string& v : vars_) known += (known.empty() ? "" : ", ") + v;
    fail(start, "unknown variable '" + id + "'",
         known.empty() ? std::string(" (no variables here)") : " (variables: " + known + ")");
  }

  std::uint32_t call_function(const Function& fn, std::size_t start) {
    expect('(', "'('");
    std::vector<std::uint32_t> args;
    if (!accept(')')) {
      for (;;) {
        args.push_back(sum());
        if (accept(')')) break;
        expect(',', "',' or ')'");
      }
    }
    if (static_cast<int>(args.size()) != fn.arity)
      fail(start, std::string("function '") + fn.name + "' takes " + std::to_string(fn.arity) +
                      (fn.arity == 1 ? " argument" : " arguments") + ", got " +
                      std::to_string(args.size()));
    return fn.arity == 1 ? builder.unary(fn.op, args[0]) : builder.binary(fn.op, args[0], args[1]);
  }
};

std::string number_text(double v) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
  return std::string(buf, res.ptr);
}

}  // namespace

// -----------------------------------------------------------------------------------------------

namespace {

/// The compiled form of an expression (immutable once built).
struct Program {
  std::string text;
  std::size_t nvars = 0;
  std::vector<char> used;           ///< per variable: occurs in the text
  std::vector<std::size_t> active;  ///< used variables; active[k] lives in register k
  std::vector<Instr> tape;
  std::size_t nregs = 0;
  std::uint32_t result = 0;  ///< register of the result, unless constant
  bool constant = true;
  double value = 0.0;  ///< the result when constant
};

}  // namespace

struct Expr::Impl : Program {};

namespace {

/// Flattens the DAG below `root` into a register tape. Variables sit in registers 0..active-1;
/// every other value gets a register that is reused once its last reader has run.
void compile(Program& m, const std::vector<Node>& nodes, std::uint32_t root) {
  for (std::size_t i = 0; i < m.used.size(); ++i)
    if (m.used[i]) m.active.push_back(i);
  if (nodes[root].op == Op::Const) {
    m.value = nodes[root].k;
    return;
  }
  m.constant = false;
  std::vector<std::uint32_t> var_reg(m.nvars, 0);
  for (std::size_t k = 0; k < m.active.size(); ++k)
    var_reg[m.active[k]] = static_cast<std::uint32_t>(k);

  // Nodes are created after their operands, so one backward sweep marks what the root reads.
  std::vector<char> live(root + 1, 0);
  live[root] = 1;
  for (std::uint32_t n = root + 1; n-- > 0;) {
    if (!live[n]) continue;
    const int ar = arity(nodes[n].op);
    if (ar >= 1) live[nodes[n].a] = 1;
    if (ar >= 2) live[nodes[n].b] = 1;
  }
  std::vector<std::uint32_t> order;
  for (std::uint32_t n = 0; n <= root; ++n)
    if (live[n] && nodes[n].op != Op::Var) order.push_back(n);

  constexpr std::uint32_t kNever = 0xFFFFFFFFu;
  std::vector<std::uint32_t> last_use(root + 1, 0);
  for (std::uint32_t i = 0; i < order.size(); ++i) {
    const Node& nd = nodes[order[i]];
    const int ar = arity(nd.op);
    if (ar >= 1) last_use[nd.a] = i;
    if (ar >= 2) last_use[nd.b] = i;
  }
  last_use[root] = kNever;

  std::vector<std::uint32_t> reg(root + 1, 0), free_regs;
  std::uint32_t nregs = static_cast<std::uint32_t>(m.active.size());
  auto reg_of = [&](std::uint32_t n) {
    return nodes[n].op == Op::Var ? var_reg[nodes[n].a] : reg[n];
  };
  for (std::uint32_t i = 0; i < order.size(); ++i) {
    const std::uint32_t n = order[i];
    const Node& nd = nodes[n];
    const int ar = arity(nd.op);
    Instr in{nd.op, 0, 0, 0, nd.k};
    if (ar >= 1) in.a = reg_of(nd.a);
    if (ar >= 2) in.b = reg_of(nd.b);
    // Operands read for the last time free their registers; the result may take one of them.
    if (ar >= 1 && nodes[nd.a].op != Op::Var && last_use[nd.a] == i) free_regs.push_back(in.a);
    if (ar >= 2 && nd.b != nd.a && nodes[nd.b].op != Op::Var && last_use[nd.b] == i)
      free_regs.push_back(in.b);
    if (free_regs.empty()) {
      in.dst = nregs++;
    } else {
      in.dst = free_regs.back();
      free_regs.pop_back();
    }
    reg[n] = in.dst;
    m.tape.push_back(in);
  }
  m.nregs = nregs;
  m.result = reg_of(root);
}

/// One forward pass over jets; variable k (in active order) is seeded in jet slot seed(k) (< 0:
/// held constant).
template <int O, int N, class Seed>
Jet<O, N> jet_pass(const Program& m, const double* x, Seed seed) {
  using J = Jet<O, N>;
  return with_registers<J>(m.nregs, [&](J* r) {
    for (std::size_t k = 0; k < m.active.size(); ++k) {
      r[k] = Lift<J>::of(x[m.active[k]]);
      const int s = seed(k);
      if (s >= 0) r[k].g[s] = 1.0;
    }
    run(m.tape.data(), m.tape.size(), r);
    return r[m.result];
  });
}

/// Writes the gradient (and Hessian) entries of the variables seeded in a pass.
/// var[s] is the variable index seeded in slot s, or SIZE_MAX.
template <int O, int N>
void scatter(const Jet<O, N>& j, const std::size_t* var, std::size_t nvars, double* grad,
             double* hess) {
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  for (int s = 0; s < N; ++s)
    if (var[s] != kNone) grad[var[s]] = j.g[s];
  if constexpr (O >= 2) {
    int k = 0;
    for (int s = 0; s < N; ++s)
      for (int t = s; t < N; ++t, ++k)
        if (var[s] != kNone && var[t] != kNone)
          hess[var[s] * nvars + var[t]] = hess[var[t] * nvars + var[s]] = j.h[k];
  }
}

/// All active variables (at most four) in one pass.
template <int O, int N>
double single_pass(const Program& m, const double* x, double* grad, double* hess) {
  const Jet<O, N> j = jet_pass<O, N>(m, x, [](std::size_t k) { return static_cast<int>(k); });
  std::size_t var[N];
  for (int s = 0; s < N; ++s) var[s] = m.active[s];
  scatter(j, var, m.nvars, grad, hess);
  return j.v;
}

template <int O>
double derivatives(const Program& m, const double* x, double* grad, double* hess) {
  const std::size_t n = m.nvars, na = m.active.size();
  for (std::size_t i = 0; i < n; ++i) grad[i] = 0.0;
  if constexpr (O >= 2)
    for (std::size_t i = 0; i < n * n; ++i) hess[i] = 0.0;
  if (m.constant) return m.value;
  switch (na) {
    case 0: return jet_pass<O, 1>(m, x, [](std::size_t) { return -1; }).v;
    case 1: return single_pass<O, 1>(m, x, grad, hess);
    case 2: return single_pass<O, 2>(m, x, grad, hess);
    case 3: return single_pass<O, 3>(m, x, grad, hess);
    case 4: return single_pass<O, 4>(m, x, grad, hess);
    default: break;
  }
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  double v = 0.0;
  if constexpr (O == 1) {
    // Gradient in chunks of four variables.
    for (std::size_t c = 0; c * 4 < na; ++c) {
      const auto j = jet_pass<1, 4>(m, x, [c](std::size_t k) {
        return k / 4 == c ? static_cast<int>(k % 4) : -1;
      });
      std::size_t var[4];
      for (std::size_t s = 0; s < 4; ++s) var[s] = c * 4 + s < na ? m.active[c * 4 + s] : kNone;
      scatter(j, var, n, grad, hess);
      v = j.v;
    }
  } else {
    // Hessian in 2x2 blocks: a pass for each pair of blocks (p, q), p <= q, seeds both.
    const std::size_t nb = (na + 1) / 2;
    for (std::size_t p = 0; p < nb; ++p) {
      for (std::size_t q = p; q < nb; ++q) {
        const auto j = jet_pass<2, 4>(m, x, [p, q](std::size_t k) {
          if (k / 2 == p) return static_cast<int>(k % 2);
          if (k / 2 == q) return static_cast<int>(2 + k % 2);
          return -1;
        });
        std::size_t var[4];
        for (std::size_t s = 0; s < 2; ++s) {
          var[s] = 2 * p + s < na ? m.active[2 * p + s] : kNone;
          var[2 + s] = q != p && 2 * q + s < na ? m.active[2 * q + s] : kNone;
        }
        scatter(j, var, n, grad, hess);
        v = j.v;
      }
    }
  }
  return v;
}

}  // namespace

Expr::Expr() {
  static const std::shared_ptr<const Impl> zero = [] {
    auto m = std::make_shared<Impl>();
    m->text = "0";
    return m;
  }();
  impl_ = zero;
}

Expr Expr::parse(const std::string& text, const std::vector<std::string>& variables) {
  Parser parser(text, variables);
  const std::uint32_t root = parser.parse();
  auto m = std::make_shared<Impl>();
  m->text = text;
  m->nvars = variables.size();
  m->used = std::move(parser.used);
  compile(*m, parser.builder.nodes, root);
  Expr e;
  e.impl_ = std::move(m);
  return e;
}

Expr Expr::constant(double value) {
  auto m = std::make_shared<Impl>();
  m->text = number_text(value);
  m->value = value;
  Expr e;
  e.impl_ = std::move(m);
  return e;
}

double Expr::eval(const double* vars) const {
  const Impl& m = *impl_;
  if (m.constant) return m.value;
  const auto body = [&](double* r) {
    for (std::size_t k = 0; k < m.active.size(); ++k) r[k] = vars[m.active[k]];
    run(m.tape.data(), m.tape.size(), r);
    return r[m.result];
  };
  if (m.nregs > kStackRegs) return with_registers<double>(m.nregs, body);
  double r[kStackRegs];
  return body(r);
}

double Expr::eval_d1(const double* vars, double* grad) const {
  return derivatives<1>(*impl_, vars, grad, nullptr);
}

double Expr::eval_d2(const double* vars, double* grad, double* hess) const {
  return derivatives<2>(*impl_, vars, grad, hess);
}

bool Expr::enclose_d1(const Interval* vars, std::size_t var, Interval& value, Interval& derivative) const {
  const Impl& m = *impl_;
  if (m.constant) {
    value = std::isfinite(m.value) ? Interval::point(m.value) : Interval::entire();
    derivative = Interval::point(0.0);
    return std::isfinite(m.value);
  }
  const IJet r = with_registers<IJet>(m.nregs, [&](IJet* reg) {
    for (std::size_t k = 0; k < m.active.size(); ++k)
      reg[k] = {vars[m.active[k]], Interval::point(m.active[k] == var ? 1.0 : 0.0), bounded(vars[m.active[k]])};
    run(m.tape.data(), m.tape.size(), reg);
    return reg[m.result];
  });
  // a box where an operation may leave its domain may also hold points whose value is finite
  // through infinite intermediates (log(2)^(log(0)^e) = 0): no bound holds there
  value = r.defined ? r.v : Interval::entire();
  derivative = r.defined ? r.d : Interval::entire();
  return r.defined;
}

const std::string& Expr::text() const { return impl_->text; }
std::size_t Expr::num_vars() const { return impl_->nvars; }
bool Expr::is_constant() const { return impl_->active.empty(); }
bool Expr::uses(std::size_t i) const { return i < impl_->used.size() && impl_->used[i]; }

}  // namespace sweep
