#pragma once
/// @file grazing_family.hpp
/// The grazing set of a face over the whole range of a motion (000, 001): traced at sampled
/// instants (variety.hpp's grazing_set), the instants where its structure changes found by
/// bisection (events: an arc appears or vanishes, an arc's end moves onto another side of the
/// face's domain, arcs cross, a side starts or stops grazing all along), and between events each
/// arc followed from one instant to the next along the set's drift. The swept tracks are the
/// envelope sheets of the face; the events are where those sheets begin, end or meet.
#include <Eigen/Core>
#include <vector>

#include "sweep/entity.hpp"
#include "sweep/settings.hpp"
#include "sweep/stage_motion.hpp"

namespace sweep {

/// How the structure of a grazing set changes at an event.
enum class GrazingChange {
  Appears,      ///< more arcs after than before (a loop is born, an arc enters the domain)
  Vanishes,     ///< fewer arcs after than before
  MeetsSide,    ///< as many arcs, but an arc's end moves onto another side of the domain (or its corner)
  Crosses,      ///< arcs meet inside the domain (where two branches cross), or part there
  SideGrazes,   ///< a side of the domain starts or stops grazing all along
};
const char* to_string(GrazingChange c);

/// An instant where the structure of the traced grazing set changes; it lies in [before, after],
/// the last instant traced with the old structure and the first with the new, at most the
/// resolution apart.
struct GrazingEvent {
  double before = 0, after = 0;
  GrazingChange change = GrazingChange::Appears;
  double t() const { return 0.5 * (before + after); }
};

/// One arc of the grazing set followed over an interval of t on which the set keeps its structure.
/// `arcs[k]` is the arc at `t[k]` in the face's parameters, oriented as the arc at t[k - 1] and, when
/// closed, starting at the point nearest to where the start of that arc drifted.
struct GrazingTrack {
  std::vector<double> t;
  std::vector<std::vector<Eigen::Vector2d>> arcs;
  bool closed = false;
  /// The sides of the domain its ends lie on (0: v = lo, 1: u = hi, 2: v = hi, 3: u = lo), 4 inside
  /// the domain (a crossing), -1 for a closed arc.
  int end_sides[2] = {-1, -1};
};

/// The grazing set of a face over [motion.lo(), motion.hi()].
struct GrazingFamily {
  std::vector<GrazingEvent> events;
  /// Every arc between consecutive events (and the range's ends), in order of t.
  std::vector<GrazingTrack> tracks;
  /// The sides that graze all along (variety.hpp's GrazingSet::sides) over intervals of t:
  /// (side, t first, t last) as traced.
  struct SideSpan {
    int side = 0;
    double t0 = 0, t1 = 0;
  };
  std::vector<SideSpan> sides;
  /// False when the events were more than Settings::grazing_events_max (tracks and sides then stop
  /// at the last one found).
  bool complete = true;
};

/// The grazing set of `face` over the motion's range: traced (grazing_set, about n x n cells) at `samples` + 1
/// evenly spaced instants and at the bisection points of events, each event located to
/// Settings::grazing_event_resolution times the range. Events are those of the traced sets: a
/// feature smaller than a grid cell is seen when it grows past one.
GrazingFamily grazing_family(const Patch& face, const StageMotion& motion, int samples = Settings::grazing_instants,
                             int n = Settings::grazing_grid);

}  // namespace sweep
