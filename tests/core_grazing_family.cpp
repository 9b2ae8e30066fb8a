// Grazing sets followed over a motion's range (sweep/grazing_family.hpp): fixed under a screw,
// events where seed 001's rolling cylinder says its grazing set changes, and arcs followed
// without swapping where a translation turns.
#include <catch2/catch.hpp>

#include <cmath>

#include "sweep/grazing_family.hpp"
#include "sweep/variety.hpp"
#include "util/core_entities.hpp"

using Eigen::Vector2d;
using Eigen::Vector3d;
using namespace sweep;

namespace {

using sweep_test::entity_of;
using sweep_test::texpr;

EntityPtr unit_cylinder() {
  return entity_of(R"({"kind": "cylinder", "base": [0, 0, -1], "axis": [0, 0, 1], "radius": 0.5, "height": 2})");
}

/// The instants of the events of `f`.
std::vector<double> event_times(const GrazingFamily& f) {
  std::vector<double> t;
  for (const GrazingEvent& e : f.events) t.push_back(e.t());
  return t;
}

/// Whether an arc is a single point (where an arc appears from or vanishes into a side).
bool is_point(const std::vector<Vector2d>& arc) {
  for (const Vector2d& x : arc)
    if (x != arc.front()) return false;
  return true;
}

/// Every track's instants are increasing, lie between the range's ends and events (an end where
/// the arc is a point of a side aside: the traced events are where the grid first or last sees the
/// arc), and its arcs are as many as its instants.
void check_tracks_well_formed(const GrazingFamily& f, double lo, double hi) {
  for (const GrazingTrack& tr : f.tracks) {
    REQUIRE(tr.t.size() == tr.arcs.size());
    REQUIRE(!tr.t.empty());
    CHECK(tr.t.front() >= lo);
    CHECK(tr.t.back() <= hi);
    for (std::size_t k = 1; k < tr.t.size(); ++k) CHECK(tr.t[k] > tr.t[k - 1]);
    const std::size_t first = is_point(tr.arcs.front()) && tr.t.size() > 1 ? 1 : 0;
    const std::size_t last = is_point(tr.arcs.back()) && tr.t.size() > 1 ? tr.t.size() - 2 : tr.t.size() - 1;
    for (const GrazingEvent& e : f.events) CHECK((tr.t[last] <= e.before || tr.t[first] >= e.after));
  }
}

}  // namespace

TEST_CASE("Grazing family: under a screw the arcs stay the same body curves, with no event", "[variety]") {
  const EntityPtr cyl =
      entity_of(R"({"kind": "cylinder", "base": [1, 0.2, 0], "axis": [1, 0.3, 0.4], "radius": 0.4, "height": 1.5})");
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = Vector3d(0, 0.5, 0);
  j.direction = Vector3d(0.2, 0, 1).normalized();
  j.pitch = 0.3;
  j.lo = 0;
  j.hi = 4;
  const ScrewStage screw(j);
  const Patch& side = *cyl->faces()[0];
  const GrazingFamily f = grazing_family(side, screw, 16);
  CHECK(f.complete);
  CHECK(f.events.empty());
  const GrazingSet first = grazing_set(side, screw, 0.0);
  REQUIRE(!first.curves.empty());
  REQUIRE(f.tracks.size() == first.curves.size());
  check_tracks_well_formed(f, 0, 4);
  for (const GrazingTrack& tr : f.tracks) {
    REQUIRE(tr.t.size() == 17);
    for (const auto& arc : tr.arcs) {
      REQUIRE(arc.size() == tr.arcs[0].size());
      for (std::size_t k = 0; k < arc.size(); ++k) CHECK((arc[k] - tr.arcs[0][k]).norm() < 1e-9);
    }
  }
}

TEST_CASE("Grazing family: seed 001's rolling cylinder changes where the circle and the cap lines enter and leave",
          "[variety]") {
  // x -> (0, 4t, 0) + R_x(pi t) x: the rim circle z = 4 cos(pi t) / pi is on the lateral face for
  // |z| <= 1, the caps' line y = 4 sin(pi t) / pi on the caps for y <= 0.5
  const Expr tr[3] = {texpr("0"), texpr("4*t"), texpr("0")};
  const PathMotion rolling(0, 1, tr, {PathRotation{{texpr("1"), texpr("0"), texpr("0")}, texpr("pi*t")}});
  const EntityPtr cyl = unit_cylinder();
  const double circle_in = std::acos(M_PI / 4) / M_PI, line_out = std::asin(M_PI / 8) / M_PI;

  const GrazingFamily lateral = grazing_family(*cyl->faces()[0], rolling);
  CHECK(lateral.complete);
  check_tracks_well_formed(lateral, 0, 1);
  const std::vector<double> lt = event_times(lateral);
  REQUIRE(lt.size() >= 2);
  CHECK(lt.front() == Approx(circle_in).margin(1e-7));
  CHECK(lt.back() == Approx(1 - circle_in).margin(1e-7));
  // before the circle enters, the set is the two lines x = +-0.5: the one at u = pi a track from
  // z = -1 to 1, the other the face's seam, whose sides graze all along
  int lines = 0;
  for (const GrazingTrack& t : lateral.tracks)
    if (t.t.front() == 0.0) {
      ++lines;
      CHECK(t.t.back() < circle_in);
      for (const auto& arc : t.arcs)
        for (const Vector2d& s : arc) CHECK(std::abs(cyl->faces()[0]->eval(s.x(), s.y()).x.x() + 0.5) < 1e-9);
    }
  CHECK(lines == 1);
  int seam = 0;
  for (const auto& side : lateral.sides)
    if ((side.side == 1 || side.side == 3) && side.t0 == 0.0 && side.t1 == 1.0) ++seam;
  CHECK(seam == 2);

  for (std::size_t k = 1; k < cyl->faces().size(); ++k) {
    const GrazingFamily cap = grazing_family(*cyl->faces()[k], rolling);
    CHECK(cap.complete);
    check_tracks_well_formed(cap, 0, 1);
    // the line leaves the cap at line_out and comes back at 1 - line_out (events at the range's
    // very ends, where the line passes the cap's centre, aside)
    std::vector<double> inner;
    for (double t : event_times(cap))
      if (t > 1e-6 && t < 1 - 1e-6) inner.push_back(t);
    REQUIRE(inner.size() == 2);
    // (seen once the line reaches a node of the rim, at most half a cell, 2 pi / 61 / 2, from where
    // it touches the rim: 0.5 (1 - cos 0.0515) = 6.6e-4 below the rim, at 4 cos(pi t) = 3.7 a unit t)
    CHECK(inner[0] == Approx(line_out).margin(2e-4));
    CHECK(inner[1] == Approx(1 - line_out).margin(2e-4));
    int points = 0;
    for (const GrazingTrack& t : cap.tracks) {
      const bool early = t.t.back() <= line_out + 1e-12, late = t.t.front() >= 1 - line_out - 1e-12;
      CHECK((early || late));
      // the line leaves the cap, and comes back, at the rim's point (0, 0.5): tracks end there
      for (const bool front : {true, false}) {
        const std::vector<Vector2d>& arc = front ? t.arcs.front() : t.arcs.back();
        if (t.arcs.size() < 2 || !is_point(arc)) continue;
        ++points;
        CHECK(std::abs(std::min(std::abs((front ? t.t.front() : t.t.back()) - line_out),
                                std::abs((front ? t.t.front() : t.t.back()) - (1 - line_out)))) < 1e-12);
        const Vector3d x = cyl->faces()[k]->eval(arc.front().x(), arc.front().y()).x;
        CHECK((x.head<2>() - Eigen::Vector2d(0, 0.5)).norm() < 1e-9);
      }
      for (std::size_t i = 0; i < t.t.size(); ++i)
        for (const Vector2d& s : t.arcs[i])
          // (the centre is a pole, where the set is read 1e-7 of the radius inside)
          if (s.y() > 1e-6) CHECK(std::abs(cyl->faces()[k]->eval(s.x(), s.y()).x.y() - 4 * std::sin(M_PI * t.t[i]) / M_PI) < 1e-9);
    }
    CHECK(points == 2);
  }
}

TEST_CASE("Grazing family: the lines of a cylinder translated along a turning direction are followed without swapping",
          "[variety]") {
  // p(t) = (sin t, -cos t, 0.3 t): the velocity (cos t, sin t, 0.3) grazes the lateral face on the
  // lines u = t + pi/2 and u = t - pi/2 (mod 2 pi); the first crosses the seam u = 0 at t = pi/2
  const Expr tr[3] = {texpr("sin(t)"), texpr("-cos(t)"), texpr("0.3*t")};
  const PathMotion path(0, 2, tr, {});
  const EntityPtr cyl = unit_cylinder();
  const GrazingFamily f = grazing_family(*cyl->faces()[0], path, 24);
  CHECK(f.complete);
  check_tracks_well_formed(f, 0, 2);
  // the lines keep their structure (each from z = -1 to 1), so no event, though the first crosses
  // the seam: it is followed across it, a whole period off the domain
  CHECK(f.events.empty());
  REQUIRE(f.tracks.size() == 2);
  int followed = 0;
  for (const GrazingTrack& t : f.tracks) {
    // the branch of the first arc, kept at every instant: u - t is +-pi/2 mod 2 pi
    auto branch = [](double u, double t) {
      const double d = std::remainder(u - t, 2 * M_PI);
      return std::abs(d - M_PI / 2) < 1e-7 ? 1 : std::abs(d + M_PI / 2) < 1e-7 ? -1 : 0;
    };
    const int b = branch(t.arcs[0][0].x(), t.t[0]);
    CHECK(b != 0);
    for (std::size_t i = 0; i < t.t.size(); ++i)
      for (const Vector2d& s : t.arcs[i]) CHECK(branch(s.x(), t.t[i]) == b);
    // continuous across the seam: the line moves by dt = 1/12 in u from one instant to the next
    for (std::size_t i = 1; i < t.t.size(); ++i)
      CHECK(std::abs(t.arcs[i][0].x() - t.arcs[i - 1][0].x() - (t.t[i] - t.t[i - 1])) < 1e-7);
    // oriented alike: every arc runs the way the first does along z
    for (const auto& arc : t.arcs) CHECK((arc.back().y() - arc.front().y()) * (t.arcs[0].back().y() - t.arcs[0].front().y()) > 0);
    if (t.t.size() == 25) ++followed;
  }
  CHECK(followed == 2);
}
