#include "sweep/grazing_family.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <optional>
#include <tuple>

#include "sweep/settings.hpp"
#include "sweep/variety.hpp"

namespace sweep {

using Eigen::Vector2d;

const char* to_string(GrazingChange c) {
  switch (c) {
    case GrazingChange::Appears: return "an arc appears";
    case GrazingChange::Vanishes: return "an arc vanishes";
    case GrazingChange::MeetsSide: return "an arc's end moves onto another side";
    case GrazingChange::Crosses: return "arcs cross";
    case GrazingChange::SideGrazes: return "a side starts or stops grazing";
  }
  return "";
}

namespace {

/// An arc's shape for the structure of a set: closed, or the sides of its two ends (smaller first).
using ArcKind = std::tuple<bool, int, int>;

/// The structure of a grazing set: its arcs' kinds and its grazing sides, each sorted.
struct Structure {
  std::vector<ArcKind> arcs;
  std::vector<int> sides;
  bool operator==(const Structure& o) const { return arcs == o.arcs && sides == o.sides; }
  bool operator!=(const Structure& o) const { return !(*this == o); }
  int inner_ends() const {
    int k = 0;
    for (const ArcKind& a : arcs) k += (std::get<1>(a) == 4) + (std::get<2>(a) == 4);
    return k;
  }
};

bool is_closed(const std::vector<Vector2d>& arc) { return arc.size() > 2 && arc.front() == arc.back(); }

/// The side of the domain a point lies on (0: v = lo, 1: u = hi, 2: v = hi, 3: u = lo), 4 inside.
int side_of(const Patch& face, const Vector2d& s) {
  const double eu = Settings::grazing_side_rounding * (face.hi(0) - face.lo(0)),
               ev = Settings::grazing_side_rounding * (face.hi(1) - face.lo(1));
  if (std::abs(s.y() - face.lo(1)) <= ev) return 0;
  if (std::abs(s.x() - face.hi(0)) <= eu) return 1;
  if (std::abs(s.y() - face.hi(1)) <= ev) return 2;
  if (std::abs(s.x() - face.lo(0)) <= eu) return 3;
  return 4;
}

ArcKind kind_of(const Patch& face, const std::vector<Vector2d>& arc) {
  if (is_closed(arc)) return {true, -1, -1};
  const int a = side_of(face, arc.front()), b = side_of(face, arc.back());
  return {false, std::min(a, b), std::max(a, b)};
}

/// The grazing set at one instant with its structure.
struct Instant {
  double t = 0;
  GrazingSet set;
  Structure structure;
  bool starts_span = false;  ///< the first instant after an event (or the range's start)
};

Instant trace(const Patch& face, const StageMotion& motion, double t, int n) {
  Instant in;
  in.t = t;
  in.set = grazing_set(face, motion, t, n);
  for (const auto& arc : in.set.curves) in.structure.arcs.push_back(kind_of(face, arc));
  std::sort(in.structure.arcs.begin(), in.structure.arcs.end());
  in.structure.sides = in.set.sides;
  std::sort(in.structure.sides.begin(), in.structure.sides.end());
  return in;
}

GrazingChange change_between(const Structure& a, const Structure& b) {
  if (a.sides != b.sides) return GrazingChange::SideGrazes;
  if (a.inner_ends() != b.inner_ends()) return GrazingChange::Crosses;
  if (b.arcs.size() > a.arcs.size()) return GrazingChange::Appears;
  if (b.arcs.size() < a.arcs.size()) return GrazingChange::Vanishes;
  return GrazingChange::MeetsSide;
}

/// The instants traced over the range: evenly spaced ones and the two sides of every event, each
/// event located by bisection between the last instant of the old structure and the next sample.
std::vector<Instant> traced_instants(const Patch& face, const StageMotion& motion, int samples, int n,
                                     GrazingFamily& out) {
  const double lo = motion.lo(), hi = motion.hi(), resolution = Settings::grazing_event_resolution * (hi - lo);
  std::vector<Instant> seq{trace(face, motion, lo, n)};
  seq.back().starts_span = true;
  for (int i = 1; i <= samples && out.complete; ++i) {
    const Instant next = trace(face, motion, i == samples ? hi : lo + (hi - lo) * i / samples, n);
    while (seq.back().structure != next.structure) {
      if (int(out.events.size()) >= Settings::grazing_events_max) {
        out.complete = false;
        break;
      }
      Instant a = seq.back(), b = next;
      while (b.t - a.t > resolution) {
        Instant m = trace(face, motion, 0.5 * (a.t + b.t), n);
        (m.structure == a.structure ? a : b) = std::move(m);
      }
      out.events.push_back({a.t, b.t, change_between(a.structure, b.structure)});
      a.starts_span = false;
      if (a.t > seq.back().t) seq.push_back(std::move(a));
      b.starts_span = true;
      seq.push_back(std::move(b));
    }
    if (out.complete && next.t > seq.back().t) seq.push_back(next);
  }
  return seq;
}

/// The instants with every span between events traced at least Settings::grazing_span_intervals + 1
/// times (instants added evenly where the range's samples leave a span short): the sheets
/// interpolate their arcs in t, and a short span between close events may hold no sample at all.
std::vector<Instant> filled_spans(const Patch& face, const StageMotion& motion, std::vector<Instant> seq, int n) {
  std::vector<Instant> out;
  const int want = Settings::grazing_span_intervals;
  for (std::size_t a = 0; a < seq.size();) {
    std::size_t b = a + 1;
    while (b < seq.size() && !seq[b].starts_span) ++b;
    const double t0 = seq[a].t, t1 = seq[b - 1].t;
    const Structure structure = seq[a].structure;
    std::vector<Instant> span(std::make_move_iterator(seq.begin() + std::ptrdiff_t(a)),
                              std::make_move_iterator(seq.begin() + std::ptrdiff_t(b)));
    if (int(span.size()) < want + 1 && t1 > t0) {
      for (int k = 1; k < want; ++k) {
        const double t = t0 + (t1 - t0) * k / want;
        bool near = false;
        for (const Instant& in : span) near = near || std::abs(in.t - t) < 0.25 * (t1 - t0) / want;
        if (near) continue;
        Instant in = trace(face, motion, t, n);
        if (in.structure != structure) continue;  // (an event the bisection did not separate)
        span.push_back(std::move(in));
      }
      std::sort(span.begin() + 1, span.end(), [](const Instant& x, const Instant& y) { return x.t < y.t; });
    }
    for (auto& in : span) out.push_back(std::move(in));
    a = b;
  }
  return out;
}

/// Where the points of an arc (at most 32 of them) go in time dt along the drift at `pose`.
std::vector<Vector2d> drifted(const Patch& face, const PoseJet& pose, double dt, const std::vector<Vector2d>& arc,
                              const Vector2d& period) {
  std::vector<Vector2d> out;
  const std::size_t step = std::max<std::size_t>(1, arc.size() / 32);
  for (std::size_t k = 0; k < arc.size(); k += step) {
    const Vector2d w = wrapped_parameters(face, arc[k], period);
    out.push_back(arc[k] + dt * grazing_drift(face, pose, w.x(), w.y()));
  }
  return out;
}

/// How far the points `from` lie from the polyline `to` shifted by `shift`, at worst, in the domain
/// scaled to the unit square.
double distance_to(const std::vector<Vector2d>& from, const std::vector<Vector2d>& to, const Vector2d& shift,
                   const Vector2d& scale) {
  double worst = 0;
  for (const Vector2d& p : from) {
    double best = std::numeric_limits<double>::infinity();
    for (const Vector2d& q : to) best = std::min(best, (p - q - shift).cwiseQuotient(scale).norm());
    worst = std::max(worst, best);
  }
  return worst;
}

/// `arc` oriented as `prev` after its drift (and, closed, starting nearest to prev's start).
std::vector<Vector2d> oriented_as(const std::vector<Vector2d>& prev, std::vector<Vector2d> arc, const Vector2d& scale) {
  auto d = [&scale](const Vector2d& a, const Vector2d& b) { return (a - b).cwiseQuotient(scale).norm(); };
  if (!is_closed(arc)) {
    if (d(prev.front(), arc.back()) + d(prev.back(), arc.front()) < d(prev.front(), arc.front()) + d(prev.back(), arc.back()))
      std::reverse(arc.begin(), arc.end());
    return arc;
  }
  arc.pop_back();
  std::size_t first = 0;
  for (std::size_t k = 1; k < arc.size(); ++k)
    if (d(arc[k], prev.front()) < d(arc[first], prev.front())) first = k;
  std::rotate(arc.begin(), arc.begin() + std::ptrdiff_t(first), arc.end());
  // the same direction: prev's second point lies nearer the arc's second than its last
  if (arc.size() > 2 && d(prev[1], arc.back()) < d(prev[1], arc[1])) std::reverse(arc.begin() + 1, arc.end());
  arc.push_back(arc.front());
  return arc;
}

bool same_kind(const GrazingTrack& tr, const ArcKind& k) {
  if (std::get<0>(k) != tr.closed) return false;
  return tr.closed || (std::get<1>(k) == std::min(tr.end_sides[0], tr.end_sides[1]) &&
                       std::get<2>(k) == std::max(tr.end_sides[0], tr.end_sides[1]));
}

/// The arcs of `next` matched to the tracks of a span (their last arcs traced at one instant before
/// it): each track gets the arc of the same kind nearest to where its last arc drifted, shifted by
/// the whole periods that bring it nearest.
void extend_tracks(const Patch& face, const StageMotion& motion, const Instant& next, std::vector<GrazingTrack>& span,
                   const Vector2d& scale, const Vector2d& period) {
  const double prev_t = span.front().t.back(), dt = next.t - prev_t;
  const PoseJet pose = motion.pose(prev_t);
  struct Pair {
    double cost;
    std::size_t track, arc;
    Vector2d shift;
  };
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < span.size(); ++i) {
    const std::vector<Vector2d> moved = drifted(face, pose, dt, span[i].arcs.back(), period);
    // the whole periods between the arc's cover and the domain, and one either way
    const Vector2d base = span[i].arcs.back().front() - wrapped_parameters(face, span[i].arcs.back().front(), period);
    for (std::size_t j = 0; j < next.set.curves.size(); ++j) {
      if (!same_kind(span[i], kind_of(face, next.set.curves[j]))) continue;
      Pair best{std::numeric_limits<double>::infinity(), i, j, Vector2d::Zero()};
      for (int a = -1; a <= 1; ++a)
        for (int b = -1; b <= 1; ++b) {
          if ((a != 0 && period.x() == 0) || (b != 0 && period.y() == 0)) continue;
          const Vector2d shift = base + Vector2d(a * period.x(), b * period.y());
          const double c = distance_to(moved, next.set.curves[j], shift, scale);
          if (c < best.cost) best = {c, i, j, shift};
        }
      pairs.push_back(best);
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.cost < b.cost; });
  std::vector<char> track_done(span.size(), 0), arc_done(next.set.curves.size(), 0);
  for (const Pair& p : pairs) {
    if (track_done[p.track] || arc_done[p.arc]) continue;
    track_done[p.track] = arc_done[p.arc] = 1;
    GrazingTrack& tr = span[p.track];
    std::vector<Vector2d> arc = next.set.curves[p.arc];
    for (Vector2d& s : arc) s += p.shift;
    tr.t.push_back(next.t);
    tr.arcs.push_back(oriented_as(tr.arcs.back(), std::move(arc), scale));
  }
}

/// A track per arc of the instant that starts a span.
std::vector<GrazingTrack> start_tracks(const Patch& face, const Instant& in) {
  std::vector<GrazingTrack> span;
  for (const auto& arc : in.set.curves) {
    GrazingTrack tr;
    tr.t.push_back(in.t);
    tr.arcs.push_back(arc);
    tr.closed = is_closed(arc);
    if (!tr.closed) {
      tr.end_sides[0] = side_of(face, arc.front());
      tr.end_sides[1] = side_of(face, arc.back());
    }
    span.push_back(std::move(tr));
  }
  return span;
}

/// The grazing sides as spans of t: a side's span runs over consecutive instants that have it.
void collect_side_spans(const std::vector<Instant>& seq, GrazingFamily& out) {
  for (int side = 0; side < 4; ++side) {
    bool open = false;
    for (const Instant& in : seq) {
      const bool has = std::find(in.set.sides.begin(), in.set.sides.end(), side) != in.set.sides.end();
      if (has && !open) out.sides.push_back({side, in.t, in.t});
      if (has) out.sides.back().t1 = in.t;
      open = has;
    }
  }
}


/// The parameters of the point of side `side` at w along it.
Vector2d side_parameters(const Patch& face, int side, double w) {
  switch (side) {
    case 0: return {w, face.lo(1)};
    case 1: return {face.hi(0), w};
    case 2: return {w, face.hi(1)};
    default: return {face.lo(0), w};
  }
}

/// The parameter along side `side` of a point on it.
double along_side(int side, const Vector2d& x) { return side == 0 || side == 2 ? x.x() : x.y(); }

/// Where an arc with both ends on one side of the domain shrinks to a point of that side (it
/// vanishes there, or appears from it read backwards): the double root of g along the side, g = 0
/// and dg/dw = 0 in (w, t), by Newton from `w0` at `t0`. Empty when Newton does not converge, or
/// the side has no length (a pole), or the root is not a double one.
std::optional<std::pair<double, double>> side_double_root(const Patch& face, const StageMotion& motion, int side,
                                                          double w0, double t0) {
  const double wlo = side == 0 || side == 2 ? face.lo(0) : face.lo(1), whi = side == 0 || side == 2 ? face.hi(0) : face.hi(1);
  const double hw = Settings::side_root_step * (whi - wlo);
  auto G = [&](double w, const PoseJet& P) {
    const Vector2d x = side_parameters(face, side, w);
    return grazing_value(face, P, x.x(), x.y());
  };
  auto Gt = [&](double w, const PoseJet& P) {
    const Vector2d x = side_parameters(face, side, w);
    return grazing_rate(face, P, x.x(), x.y());
  };
  double w = w0, t = t0, scale = 0;
  for (int it = 0; it < 50; ++it) {
    const PoseJet P = motion.pose(t);
    const double g = G(w, P), gp = G(w + hw, P), gm = G(w - hw, P);
    const double gw = (gp - gm) / (2 * hw), gww = (gp - 2 * g + gm) / (hw * hw);
    const double gt = Gt(w, P), gwt = (Gt(w + hw, P) - Gt(w - hw, P)) / (2 * hw);
    scale = std::max({scale, std::abs(gt), std::abs(gww) * (whi - wlo)});
    Eigen::Matrix2d J;
    J << gw, gt, gww, gwt;
    const Eigen::Vector2d F(g, gw);
    if (!(std::abs(J.determinant()) > 0)) return std::nullopt;
    const Eigen::Vector2d step = -J.inverse() * F;
    if (!step.allFinite()) return std::nullopt;
    w += std::clamp(step.x(), -0.1 * (whi - wlo), 0.1 * (whi - wlo));
    t += step.y();
    if (std::abs(step.x()) <= Settings::side_root_stop * (whi - wlo) &&
        std::abs(step.y()) <= Settings::side_root_time_stop * (1 + std::abs(t))) {
      const PoseJet Q = motion.pose(t);
      const double gww_end = (G(w + hw, Q) - 2 * G(w, Q) + G(w - hw, Q)) / (hw * hw);
      // a double root, of a function that does vary along the side (not a pole)
      if (!(scale > 0) || !(std::abs(gww_end) * (whi - wlo) > Settings::side_root_curvature * scale)) return std::nullopt;
      return std::make_pair(w, t);
    }
  }
  return std::nullopt;
}

/// Tracks whose arc, with both ends on one side, appears at their first instant or vanishes after
/// their last one are carried to the instant where it is a point of that side. The traced sets see
/// an arc only once it spans a node of the grid, and such an arc grows as the square root of the
/// time since it appeared: the sheet would start (or end) short of the arc's point by up to a grid
/// cell, with a gap the sweeps of the side's edge do not close.
void exact_side_events(const Patch& face, const StageMotion& motion, GrazingFamily& f) {
  const double lo = motion.lo(), hi = motion.hi(), reach = Settings::grazing_event_reach * (hi - lo);
  for (GrazingTrack& tr : f.tracks) {
    if (tr.closed || tr.t.size() < 2 || tr.end_sides[0] != tr.end_sides[1] || tr.end_sides[0] < 0 || tr.end_sides[0] > 3)
      continue;
    const int side = tr.end_sides[0];
    for (const bool start : {true, false}) {
      const double t_end = start ? tr.t.front() : tr.t.back();
      const bool at_event = std::any_of(f.events.begin(), f.events.end(), [&](const GrazingEvent& e) {
        return start ? e.change == GrazingChange::Appears && e.after == t_end
                     : e.change == GrazingChange::Vanishes && e.before == t_end;
      });
      if (!at_event) continue;
      const std::vector<Vector2d>& arc = start ? tr.arcs.front() : tr.arcs.back();
      const double wa = along_side(side, arc.front()), wb = along_side(side, arc.back());
      const auto root = side_double_root(face, motion, side, 0.5 * (wa + wb), t_end);
      if (!root) continue;
      const auto [w, t] = *root;
      const bool inside = w > std::min(wa, wb) && w < std::max(wa, wb);
      const bool before = start ? t < t_end && t >= std::max(lo, t_end - reach) : t > t_end && t <= std::min(hi, t_end + reach);
      if (!inside || !before) continue;
      const Vector2d x = side_parameters(face, side, w);
      if (start) {
        tr.t.insert(tr.t.begin(), t);
        tr.arcs.insert(tr.arcs.begin(), std::vector<Vector2d>{x, x});
      } else {
        tr.t.push_back(t);
        tr.arcs.push_back(std::vector<Vector2d>{x, x});
      }
    }
  }
}

}  // namespace

GrazingFamily grazing_family(const Patch& face, const StageMotion& motion, int samples, int n) {
  GrazingFamily out;
  const std::vector<Instant> seq =
      filled_spans(face, motion, traced_instants(face, motion, std::max(samples, 1), n, out), n);
  const Vector2d scale(face.hi(0) - face.lo(0), face.hi(1) - face.lo(1)), period = parameter_periods(face);
  std::vector<GrazingTrack> span;
  for (const Instant& in : seq) {
    if (in.starts_span) {
      for (auto& tr : span) out.tracks.push_back(std::move(tr));
      span = start_tracks(face, in);
    } else if (!span.empty()) {
      extend_tracks(face, motion, in, span, scale, period);
    }
  }
  for (auto& tr : span) out.tracks.push_back(std::move(tr));
  exact_side_events(face, motion, out);
  collect_side_spans(seq, out);
  return out;
}

}  // namespace sweep
