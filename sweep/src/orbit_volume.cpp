// The volume of a one-joint sweep integrated over the space of orbits (see orbit.hpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>

#include "orbit_internal.hpp"
#include "sweep/error.hpp"

namespace sweep {
namespace {

using orbit_detail::Span;
using orbit_detail::Spans;
/// What decides the shape of the measure near an orbit: the surfaces bounding the body's spans on
/// it and how their extensions overlap. The measure is smooth wherever this stays the same.
using Signature = std::vector<int>;

/// Orbits of one joint as a two-parameter family (alpha, beta), with their density.
class OrbitSpace {
 public:
  OrbitSpace(const orbit_detail::LabeledSolid& body, const ScrewJoint& j, double T) : body_(body), j_(j), T_(T) {
    const Eigen::AlignedBox3d box = body.bounds();
    SWEEP_ASSERT(box.min().maxCoeff() > -1e299 && box.max().minCoeff() < 1e299, "an unbounded orbit solid");
    w_ = j.direction.normalized();
    // a generic direction for alpha: orbits that start on a face of an axis-aligned body make
    // spans that appear and vanish with rounding
    const Eigen::Vector3d u = w_.unitOrthogonal(), v = w_.cross(u);
    e1_ = std::cos(0.5) * u + std::sin(0.5) * v;
    e2_ = w_.cross(e1_);
    origin_ = j.type == JointType::Prismatic ? Eigen::Vector3d::Zero() : j.point;
    double rmax = 0, zlo = 1e300, zhi = -1e300, u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d p = box.corner(Eigen::AlignedBox3d::CornerType(k)) - origin_;
      const double z = p.dot(w_);
      rmax = std::max(rmax, (p - z * w_).norm());
      zlo = std::min(zlo, z);
      zhi = std::max(zhi, z);
      u0 = std::min(u0, p.dot(e1_));
      u1 = std::max(u1, p.dot(e1_));
      v0 = std::min(v0, p.dot(e2_));
      v1 = std::max(v1, p.dot(e2_));
    }
    const double pad = 1e-9 * std::max({rmax, zhi - zlo, 1e-300});
    switch (j.type) {
      case JointType::Revolute:
        a0_ = 0, a1_ = rmax + pad, b0_ = zlo - pad, b1_ = zhi + pad;
        t0_ = -M_PI, t1_ = M_PI;
        weight_ = 1;  // times alpha (the radius)
        break;
      case JointType::Prismatic:
        a0_ = u0 - pad, a1_ = u1 + pad, b0_ = v0 - pad, b1_ = v1 + pad;
        t0_ = zlo - pad, t1_ = zhi + pad;
        weight_ = 1;
        break;
      case JointType::Helical: {
        SWEEP_ASSERT(j.pitch != 0, "a helical joint without pitch");
        // polar coordinates (radius, angle) in the plane through the axis point: a body off the
        // axis projects along the helices to a curved band that lines of one Cartesian family
        // would graze over long stretches
        a0_ = 0, a1_ = rmax + pad, b0_ = -M_PI, b1_ = M_PI;
        const double ta = (zlo - pad) / j.pitch, tb = (zhi + pad) / j.pitch;
        t0_ = std::min(ta, tb), t1_ = std::max(ta, tb);
        weight_ = std::abs(j.pitch);
        break;
      }
    }
  }
  double a0() const { return a0_; }
  double a1() const { return a1_; }
  double b0() const { return b0_; }
  double b1() const { return b1_; }

  /// The density-weighted measure of the swept part of orbit (alpha, beta), and its signature.
  double measure(double alpha, double beta, Signature* sig) const {
    const Spans body = body_.on_curve_labeled(orbit_of(j_, start(alpha, beta)), t0_, t1_, 0.0);
    if (sig) {
      sig->clear();
      for (const auto& s : body) {
        sig->push_back(s.lo_id);
        sig->push_back(s.hi_id);
      }
    }
    if (body.empty()) return 0.0;
    // the body's spans extended by the motion, merged
    std::vector<std::pair<double, double>> ext;
    for (const auto& s : body) {
      if (!ext.empty() && s.lo <= ext.back().second) {
        ext.back().second = std::max(ext.back().second, s.hi + T_);
        if (sig) sig->push_back(-2);  // this span joins the previous one's extension
      } else {
        ext.push_back({s.lo, s.hi + T_});
      }
    }
    double length = 0;
    if (j_.type != JointType::Revolute) {
      for (const auto& e : ext) length += e.second - e.first;
      return weight_ * length * (j_.type == JointType::Helical ? alpha : 1.0);
    }
    if (T_ >= 2 * M_PI) return alpha * 2 * M_PI;
    // on the circle: fold the parts beyond pi back by a turn, and merge again
    Intervals folded;
    for (const auto& e : ext) {
      if (e.second <= M_PI) {
        folded.push_back(e);
      } else if (e.first >= M_PI) {
        folded.push_back({e.first - 2 * M_PI, e.second - 2 * M_PI});
      } else {
        folded.push_back({e.first, M_PI});
        folded.push_back({-M_PI, e.second - 2 * M_PI});
      }
    }
    const Intervals circle = unite(folded, {});
    if (sig) sig->push_back(-3 - int(circle.size()));
    length = std::min(total_length(circle), 2 * M_PI);
    if (sig && length >= 2 * M_PI) sig->push_back(-100);
    return alpha * length;
  }

  /// A bound of measure() over the domain.
  double max_measure() const {
    if (j_.type == JointType::Revolute) return std::max(std::abs(a0_), std::abs(a1_)) * 2 * M_PI;
    return weight_ * (t1_ - t0_ + T_) * (j_.type == JointType::Helical ? a1_ : 1.0);
  }

  /// True when orbit (alpha, beta) keeps farther than h from the body.
  bool misses(double alpha, double beta, double h) const {
    return body_.on_curve_labeled(orbit_of(j_, start(alpha, beta)), t0_, t1_, h).empty();
  }

 private:
  Eigen::Vector3d start(double alpha, double beta) const {
    switch (j_.type) {
      case JointType::Revolute: return origin_ + alpha * e1_ + beta * w_;
      case JointType::Helical: return origin_ + alpha * (std::cos(beta) * e1_ + std::sin(beta) * e2_);
      default: return origin_ + alpha * e1_ + beta * e2_;
    }
  }
  const orbit_detail::LabeledSolid& body_;
  ScrewJoint j_;
  double T_;
  Eigen::Vector3d w_, e1_, e2_, origin_;
  double a0_ = 0, a1_ = 0, b0_ = 0, b1_ = 0, t0_ = 0, t1_ = 0, weight_ = 1;
};

/// Where a piecewise-constant signature changes on [x0, x1] (ends' signatures given): the
/// transition points, located by bisection to `eps`. At most `budget` points are located (a
/// signature that flickers with rounding on a set of orbits of measure zero would otherwise be
/// bisected without end).
void transitions(const std::function<Signature(double)>& sig, double x0, const Signature& s0, double x1,
                 const Signature& s1, double eps, std::vector<double>& out, int& budget) {
  if (s0 == s1 || budget <= 0) return;
  const double m = 0.5 * (x0 + x1);
  if (x1 - x0 <= eps || !(m > x0 && m < x1)) {
    out.push_back(m);
    --budget;
    return;
  }
  const Signature sm = sig(m);
  transitions(sig, x0, s0, m, sm, eps, out, budget);
  transitions(sig, m, sm, x1, s1, eps, out, budget);
}

/// Double-exponential (tanh-sinh) quadrature of f on [p, q], refined by halving the step until two
/// levels agree to `tol` (absolute); *err receives the last difference. f(x, tol_x) is given the
/// absolute accuracy its value needs at that node (nodes near the ends weigh little).
double tanh_sinh(const std::function<double(double, double)>& f, double p, double q, double tol, double* err) {
  const double half = 0.5 * (q - p);
  *err = 0;
  if (half <= 0) return 0;
  const double tmax = 3.15;
  double h = 0.5, sum = 0;
  auto term = [&](double t) {
    const double u = 0.5 * M_PI * std::sinh(t);
    const double e = std::exp(-2 * std::abs(u));
    const double dist = 2 * half * e / (1 + e);  // distance from the nearer end
    const double ch = std::cosh(u);
    const double wgt = half * 0.5 * M_PI * std::cosh(t) / (ch * ch);
    if (!(wgt > 0)) return 0.0;
    // each of about 2 tmax / h nodes may err by tol / (that many) in the sum h * sum(wgt f)
    const double node_tol = tol / (wgt * 2 * tmax);
    return wgt * f(t < 0 ? p + dist : q - dist, node_tol);
  };
  for (int i = -6; i <= 6; ++i) sum += term(i * h);
  double estimate = h * sum;
  for (int level = 1; level <= 5; ++level) {
    h *= 0.5;  // the new nodes are the odd multiples of h
    for (int i = 1; i * h <= tmax; i += 2) sum += term(i * h) + term(-i * h);
    const double next = h * sum;
    *err = std::abs(next - estimate);
    estimate = next;
    // (differences below rounding in the sum are not an error)
    if (level >= 2 && *err <= std::max(tol, 1e-12 * std::abs(next))) break;
  }
  return estimate;
}

/// A function of one variable that is smooth between the points where its signature changes.
struct Piecewise {
  /// f(x, tol): its value to absolute accuracy tol, and its signature when the pointer is given
  std::function<double(double, double, Signature*)> f;
  /// true when f vanishes on the whole of [x0, x1] (may answer false when unsure); empty: never sure
  std::function<bool(double, double)> empty_on;
  /// an upper bound of |f|
  double bound = 0;
};

/// The points of [a, b] where the signature changes, from a scan of n + 1 points. Cells with an
/// empty signature at both ends are split until empty_on certifies them, or until what f could
/// reach on them is below `tol`.
std::vector<double> breakpoints(const Piecewise& F, double a, double b, int n, double tol,
                                const std::vector<double>& seeds = {}) {
  auto sig = [&](double x) {
    Signature s;
    F.f(x, 1e300, &s);
    return s;
  };
  std::vector<std::pair<double, Signature>> pts;
  // (an orbit that touches the body all along, as on the plane of a face, keeps every cell near it
  // uncertified: the refinement has a budget too)
  int budget = 200;
  const double smallest = std::max(0.1 * tol / std::max(F.bound, 1e-300), 1e-15 * (b - a));
  std::function<void(double, const Signature&, double, const Signature&)> scan =
      [&](double x0, const Signature& s0, double x1, const Signature& s1) {
        if (s0.empty() && s1.empty() && F.empty_on && budget > 0 && x1 - x0 > smallest && !F.empty_on(x0, x1)) {
          --budget;
          const double m = 0.5 * (x0 + x1);
          const Signature sm = sig(m);
          scan(x0, s0, m, sm);
          pts.push_back({m, sm});
          scan(m, sm, x1, s1);
        }
      };
  // the scan: a uniform grid and the seeds (points where the function was not empty nearby)
  std::vector<double> xs;
  for (int i = 1; i <= n; ++i) xs.push_back(a + (b - a) * i / n);
  for (double x : seeds)
    if (x > a && x < b) xs.push_back(x);
  std::sort(xs.begin(), xs.end());
  Signature prev = sig(a);
  pts.push_back({a, prev});
  for (double x : xs) {
    if (x <= pts.back().first) continue;
    const Signature s = sig(x);
    scan(pts.back().first, prev, x, s);
    pts.push_back({x, s});
    prev = s;
  }
  std::vector<double> cuts{a};
  // breakpoints are located to where a misplaced one cannot cost more than tol
  const double eps = std::max(1e-14 * (b - a), 0.1 * tol / std::max(F.bound, 1e-300) / 8);
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    int flicker = 6;
    transitions(sig, pts[i].first, pts[i].second, pts[i + 1].first, pts[i + 1].second, eps, cuts, flicker);
  }
  cuts.push_back(b);
  return cuts;
}

/// The integral over [a, b] to absolute accuracy tol: breakpoints first, then each piece by
/// tanh-sinh; a piece that does not converge (a breakpoint the scan missed) is split in two and
/// done again, up to `depth` times. Pieces too short to matter are left out.
double piecewise_integral(const Piecewise& F, double a, double b, int n, double tol, double* err, int depth = 3,
                          const std::vector<double>& seeds = {}, std::vector<double>* found = nullptr) {
  const std::vector<double> cuts = breakpoints(F, a, b, n, tol, seeds);
  double total = 0;
  *err = 0;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double p = cuts[k], q = cuts[k + 1];
    if (q <= p) continue;
    // a share of the tolerance by length and an equal share per piece (short pieces near a
    // breakpoint need no absurd accuracy)
    const double piece_tol = tol * (0.5 * (q - p) / (b - a) + 0.5 / double(cuts.size() - 1));
    if ((q - p) * F.bound <= 0.01 * tol) {  // it cannot matter
      *err += (q - p) * F.bound;
      continue;
    }
    Signature s;
    F.f(0.5 * (p + q), 1e300, &s);
    // (a piece is left out only when certified empty: a signature is a sample, and the scan can
    // miss a narrow part)
    if (s.empty() && F.empty_on && F.empty_on(p, q)) continue;
    if (found && !s.empty()) found->push_back(0.5 * (p + q));
    double e = 0;
    const double v = tanh_sinh([&](double x, double tx) { return F.f(x, tx, nullptr); }, p, q, piece_tol, &e);
    if (e > piece_tol && depth > 0) {
      double e1 = 0, e2 = 0;
      const double m = 0.5 * (p + q);
      total += piecewise_integral(F, p, m, 4, 0.5 * piece_tol, &e1, depth - 1);
      total += piecewise_integral(F, m, q, 4, 0.5 * piece_tol, &e2, depth - 1);
      *err += e1 + e2;
      continue;
    }
    total += v;
    *err += e;
  }
  return total;
}

}  // namespace

double joint_sweep_volume(const OrbitSolid& body_in, const ScrewJoint& j, double T, double rel_tol, double* error) {
  const auto* body = dynamic_cast<const orbit_detail::LabeledSolid*>(&body_in);
  SWEEP_ASSERT(body, "joint_sweep_volume needs an orbit solid of orbit.cpp");
  const OrbitSpace space(*body, j, T);
  // the absolute tolerance's scale: the volume of the body's box
  const Eigen::AlignedBox3d box = body->bounds();
  const double scale = box.volume() > 0 ? box.volume() : 1.0;
  const double tol = rel_tol * scale;
  const int n_inner = 24, n_outer = 24;
  auto inner_function = [&space](double beta) {
    Piecewise F;
    F.f = [&space, beta](double alpha, double, Signature* s) { return space.measure(alpha, beta, s); };
    // orbits within h of orbit alpha lie within h of it: none meets the body when it keeps h away
    F.empty_on = [&space, beta](double a0, double a1) { return space.misses(0.5 * (a0 + a1), beta, 0.5 * (a1 - a0)); };
    F.bound = space.max_measure();
    return F;
  };
  // Where the inner function was not empty at the values of beta done so far: a part of the body's
  // projection shrinks continuously to where it vanishes, so the nearest beta's points seed the
  // scan (a narrow part between the scan's grid points is found so).
  std::map<double, std::vector<double>> seen;
  auto seeds_near = [&seen](double beta) {
    std::vector<double> out;
    auto it = seen.lower_bound(beta);
    if (it != seen.end()) out.insert(out.end(), it->second.begin(), it->second.end());
    if (it != seen.begin()) {
      --it;
      out.insert(out.end(), it->second.begin(), it->second.end());
    }
    return out;
  };
  Piecewise outer;
  outer.bound = space.max_measure() * (space.a1() - space.a0());
  outer.f = [&](double beta, double tol_beta, Signature* sig) {
    const Piecewise F = inner_function(beta);
    if (sig) {
      // the signatures of the inner function's pieces, in order (how empty stretches were cut up
      // does not matter)
      sig->clear();
      const std::vector<double> cuts = breakpoints(F, space.a0(), space.a1(), n_inner, tol, seeds_near(beta));
      std::vector<double> found;
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
        Signature s;
        F.f(0.5 * (cuts[k] + cuts[k + 1]), 1e300, &s);
        if (s.empty()) continue;
        found.push_back(0.5 * (cuts[k] + cuts[k + 1]));
        sig->insert(sig->end(), s.begin(), s.end());
        sig->push_back(-1000);
      }
      if (!found.empty()) seen[beta] = found;
      return 0.0;
    }
    double e = 0;
    std::vector<double> found;
    const double v = piecewise_integral(F, space.a0(), space.a1(), n_inner, tol_beta, &e, 3, seeds_near(beta), &found);
    if (!found.empty()) seen[beta] = found;
    return v;
  };
  double err = 0;
  const double v = piecewise_integral(outer, space.b0(), space.b1(), n_outer, 0.5 * tol, &err, 6);
  if (error) *error = err;
  return v;
}

double joint_sweep_volume_lattice(const OrbitSolid& body_in, const ScrewJoint& j, double T, int n, int shifts,
                                  std::uint64_t seed, double* error) {
  const auto* body = dynamic_cast<const orbit_detail::LabeledSolid*>(&body_in);
  SWEEP_ASSERT(body, "joint_sweep_volume_lattice needs an orbit solid of orbit.cpp");
  SWEEP_ASSERT(n > 0 && shifts > 1, "a lattice needs points and at least two shifts");
  const OrbitSpace space(*body, j, T);
  const double da = (space.a1() - space.a0()) / n, db = (space.b1() - space.b0()) / n;
  std::uint64_t state = seed;
  auto uniform = [&state] {  // splitmix64: the same shifts on every compiler
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return double((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  double sum = 0, sum2 = 0;
  for (int s = 0; s < shifts; ++s) {
    const double oa = uniform(), ob = uniform();
    double total = 0;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        total += space.measure(space.a0() + (a + oa) * da, space.b0() + (b + ob) * db, nullptr);
    const double v = total * da * db;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / shifts;
  if (error) *error = std::sqrt(std::max(0.0, sum2 / shifts - mean * mean) / (shifts - 1));
  return mean;
}

}  // namespace sweep
