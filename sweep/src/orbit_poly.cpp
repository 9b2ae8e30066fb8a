// Polynomials in (t, cos t, sin t) along orbits, their certified negative sets, and labelled spans.
#include <algorithm>
#include <cmath>

#include "orbit_internal.hpp"
#include "sweep/error.hpp"

namespace sweep::orbit_detail {

TrigPoly TrigPoly::linear(double c0, double a, double b, double d) {
  TrigPoly p;
  p.c[0][0] = c0;
  p.c[0][1] = a;
  p.s[0][1] = b;
  p.c[1][0] = d;
  p.kmax = d != 0 ? 1 : 0;
  p.nmax = (a != 0 || b != 0) ? 1 : 0;
  return p;
}

namespace {

TrigPoly combine(const TrigPoly& a, const TrigPoly& b, double sign) {
  TrigPoly r;
  r.kmax = std::max(a.kmax, b.kmax);
  r.nmax = std::max(a.nmax, b.nmax);
  for (int k = 0; k <= r.kmax; ++k)
    for (int n = 0; n <= r.nmax; ++n) {
      r.c[k][n] = a.c[k][n] + sign * b.c[k][n];
      r.s[k][n] = a.s[k][n] + sign * b.s[k][n];
    }
  return r;
}

}  // namespace

TrigPoly operator+(const TrigPoly& a, const TrigPoly& b) { return combine(a, b, 1.0); }
TrigPoly operator-(const TrigPoly& a, const TrigPoly& b) { return combine(a, b, -1.0); }
TrigPoly operator-(const TrigPoly& a) { return a * -1.0; }
TrigPoly operator+(const TrigPoly& a, double k) {
  TrigPoly r = a;
  r.c[0][0] += k;
  return r;
}
TrigPoly operator-(const TrigPoly& a, double k) { return a + (-k); }
TrigPoly operator*(const TrigPoly& a, double k) {
  TrigPoly r = a;
  for (int i = 0; i <= r.kmax; ++i)
    for (int n = 0; n <= r.nmax; ++n) {
      r.c[i][n] *= k;
      r.s[i][n] *= k;
    }
  return r;
}

TrigPoly operator*(const TrigPoly& a, const TrigPoly& b) {
  TrigPoly r;
  r.kmax = std::min(TrigPoly::K, a.kmax + b.kmax);
  r.nmax = std::min(TrigPoly::N, a.nmax + b.nmax);
  SWEEP_ASSERT(a.kmax + b.kmax <= TrigPoly::K && a.nmax + b.nmax <= TrigPoly::N, "orbit polynomial degree");
  // cos p cos q = (cos(p+q) + cos(p-q)) / 2, sin p sin q = (cos(p-q) - cos(p+q)) / 2,
  // cos p sin q = (sin(p+q) - sin(p-q)) / 2, sin p cos q = (sin(p+q) + sin(p-q)) / 2
  for (int i = 0; i <= a.kmax; ++i)
    for (int p = 0; p <= a.nmax; ++p) {
      const double ac = a.c[i][p], as = a.s[i][p];
      if (ac == 0 && as == 0) continue;
      for (int k = 0; k <= b.kmax; ++k)
        for (int q = 0; q <= b.nmax; ++q) {
          const double bc = b.c[k][q], bs = b.s[k][q];
          if (bc == 0 && bs == 0) continue;
          const int e = i + k, sum = p + q, diff = std::abs(p - q), sgn = p >= q ? 1 : -1;
          r.c[e][sum] += 0.5 * (ac * bc - as * bs);
          r.c[e][diff] += 0.5 * (ac * bc + as * bs);
          r.s[e][sum] += 0.5 * (ac * bs + as * bc);
          // sin(p - q) terms: from cos p sin q (-), sin p cos q (+)
          r.s[e][diff] += 0.5 * sgn * (as * bc - ac * bs);
        }
    }
  for (int e = 0; e <= r.kmax; ++e) r.s[e][0] = 0;  // sin(0 t)
  return r;
}

void TrigPoly::eval(double t, double* g, double* dg) const {
  double cn[N + 1], sn[N + 1], tk[K + 2];
  cn[0] = 1;
  sn[0] = 0;
  const double c1 = std::cos(t), s1 = std::sin(t);
  for (int n = 1; n <= nmax; ++n) {
    cn[n] = cn[n - 1] * c1 - sn[n - 1] * s1;
    sn[n] = sn[n - 1] * c1 + cn[n - 1] * s1;
  }
  tk[0] = 1;
  for (int k = 1; k <= kmax; ++k) tk[k] = tk[k - 1] * t;
  double v = 0, dv = 0;
  for (int k = 0; k <= kmax; ++k)
    for (int n = 0; n <= nmax; ++n) {
      const double trig = c[k][n] * cn[n] + s[k][n] * sn[n];
      const double dtrig = n * (s[k][n] * cn[n] - c[k][n] * sn[n]);
      v += tk[k] * trig;
      dv += tk[k] * dtrig + (k > 0 ? k * tk[k - 1] * trig : 0.0);
    }
  *g = v;
  if (dg) *dg = dv;
}

double TrigPoly::operator()(double t) const {
  double g;
  eval(t, &g, nullptr);
  return g;
}

namespace {

/// w^0 .. w^K
void powers(double w, double* out) {
  out[0] = 1;
  for (int k = 1; k <= TrigPoly::K; ++k) out[k] = out[k - 1] * w;
}

}  // namespace

double TrigPoly::second_derivative_bound(double w) const {
  double wk[K + 1];
  powers(w, wk);
  double bound = 0;
  for (int k = 0; k <= kmax; ++k)
    for (int n = 0; n <= nmax; ++n) {
      const double m = std::abs(c[k][n]) + std::abs(s[k][n]);
      if (m == 0) continue;
      // (t^k trig(n t))'' = k (k-1) t^(k-2) trig + 2 k n t^(k-1) trig' + n^2 t^k trig''
      const double b = (k >= 2 ? k * (k - 1) * wk[k - 2] : 0.0) + (k >= 1 ? 2.0 * k * n * wk[k - 1] : 0.0) +
                       double(n * n) * wk[k];
      bound += m * b;
    }
  return bound;
}

double TrigPoly::magnitude(double w) const {
  double wk[K + 1];
  powers(w, wk);
  double m = 0;
  for (int k = 0; k <= kmax; ++k)
    for (int n = 0; n <= nmax; ++n) m += (std::abs(c[k][n]) + std::abs(s[k][n])) * wk[k];
  return m;
}

namespace {

/// A root of g in [a, b] where g(a) and g(b) have opposite signs (Illinois false position).
double refine_root(const TrigPoly& g, double a, double b, double ga, double gb) {
  int side = 0;
  for (int it = 0; it < 200 && b - a > 4e-16 * (std::abs(a) + std::abs(b) + 1e-300); ++it) {
    double m = (a * gb - b * ga) / (gb - ga);
    if (!(m > a && m < b)) m = 0.5 * (a + b);
    const double gm = g(m);
    if (gm == 0) return m;
    if ((gm < 0) == (gb < 0)) {
      b = m;
      gb = gm;
      if (side == -1) ga *= 0.5;
      side = -1;
    } else {
      a = m;
      ga = gm;
      if (side == 1) gb *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (a + b);
}

}  // namespace

std::vector<double> sign_changes(const TrigPoly& g, double a, double b) {
  const double w = std::max(std::abs(a), std::abs(b));
  const double K = g.second_derivative_bound(w);
  // values below this are rounding: a cell that cannot leave it is decided by its centre's sign
  const double noise = 1e-13 * g.magnitude(w);
  const double hmin = 1e-13 * (b - a);
  std::vector<double> roots;
  std::vector<std::pair<double, double>> stack{{a, b}};
  while (!stack.empty()) {
    const auto [x0, x1] = stack.back();
    stack.pop_back();
    const double m = 0.5 * (x0 + x1), h = 0.5 * (x1 - x0);
    double gm, dm;
    g.eval(m, &gm, &dm);
    const double spread = std::abs(dm) * h + 0.5 * K * h * h;
    if (std::abs(gm) > spread) continue;  // no root in the cell
    if (spread <= noise && std::abs(gm) <= noise) continue;  // flat within rounding
    if (std::abs(dm) > K * h || h < hmin) {
      // g' keeps its sign: at most one root, where the ends differ
      const double g0 = g(x0), g1 = g(x1);
      if ((g0 < 0) != (g1 < 0)) roots.push_back(refine_root(g, x0, x1, g0, g1));
      continue;
    }
    stack.push_back({m, x1});
    stack.push_back({x0, m});
  }
  std::sort(roots.begin(), roots.end());
  return roots;
}

Spans negative_set(const TrigPoly& g, double a, double b, double shift, int id) {
  const std::vector<double> roots = sign_changes(g, a, b);
  std::vector<double> cuts{a};
  for (double r : roots)
    if (r > cuts.back() && r < b) cuts.push_back(r);
  cuts.push_back(b);
  Spans out;
  const double shortest = 1e-13 * (b - a);  // spans below this are rounding (a touching orbit)
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double lo = cuts[k], hi = cuts[k + 1];
    if (hi - lo < shortest || !(g(0.5 * (lo + hi)) < 0)) continue;
    const int lid = k == 0 ? -1 : id, hid = k + 2 == cuts.size() ? -1 : id;
    if (!out.empty() && out.back().hi == lo + shift) {
      out.back().hi = hi + shift;
      out.back().hi_id = hid;
    } else {
      out.push_back({lo + shift, hi + shift, lid, hid});
    }
  }
  return out;
}

Spans unite(const Spans& a, const Spans& b) {
  Spans v = a;
  v.insert(v.end(), b.begin(), b.end());
  std::sort(v.begin(), v.end(), [](const Span& x, const Span& y) { return x.lo < y.lo; });
  Spans out;
  for (const auto& s : v) {
    if (!out.empty() && s.lo <= out.back().hi) {
      if (s.hi > out.back().hi) {
        out.back().hi = s.hi;
        out.back().hi_id = s.hi_id;
      }
    } else {
      out.push_back(s);
    }
  }
  return out;
}

Spans intersect(const Spans& a, const Spans& b) {
  Spans out;
  std::size_t i = 0, k = 0;
  while (i < a.size() && k < b.size()) {
    const Span& x = a[i];
    const Span& y = b[k];
    Span r{std::max(x.lo, y.lo), std::min(x.hi, y.hi), x.lo >= y.lo ? x.lo_id : y.lo_id,
           x.hi <= y.hi ? x.hi_id : y.hi_id};
    if (r.lo <= r.hi) out.push_back(r);
    (x.hi < y.hi ? i : k) += 1;
  }
  return out;
}

Spans subtract(const Spans& a, const Spans& b) {
  Spans out;
  for (Span s : a) {
    bool alive = true;
    for (const auto& c : b) {
      if (c.hi <= s.lo || c.lo >= s.hi) continue;
      if (c.lo > s.lo) out.push_back({s.lo, c.lo, s.lo_id, c.lo_id});
      s.lo = c.hi;
      s.lo_id = c.hi_id;
      if (s.lo >= s.hi) {
        alive = false;
        break;
      }
    }
    if (alive && s.lo < s.hi) out.push_back(s);
  }
  return out;
}

Spans join_adjacent(const Spans& a, const Spans& b) {
  Spans out = a;
  for (const auto& s : b) {
    if (!out.empty() && out.back().hi == s.lo && out.back().hi_id == -1 && s.lo_id == -1) {
      out.back().hi = s.hi;
      out.back().hi_id = s.hi_id;
    } else {
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace sweep::orbit_detail
