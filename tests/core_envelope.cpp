// Envelope sheets of grazing tracks (sweep/envelope.hpp), checked against closed forms that do not
// use them: a ball's sheets are its tube (on the moved sphere, across the centre's velocity, of
// area 2 pi r times the centre's path length), and a cylinder translated along a turning direction
// sweeps two strips whose areas follow from the lines' speeds.
#include <catch2/catch.hpp>

#include <cmath>

#include "sweep/envelope.hpp"
#include "sweep/settings.hpp"
#include "util/core_entities.hpp"

using Eigen::Vector2d;
using Eigen::Vector3d;
using namespace sweep;

namespace {

using sweep_test::entity_of;
using sweep_test::texpr;

/// The 4-point Gauss-Legendre rule on [0, 1].
const double gauss_x[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
const double gauss_w[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};

/// The area of a sheet by the 4-point rule on the intervals between its track's instants (where its
/// parametrization is smooth) and on n panels along s.
double area_of(const Patch& p, const std::vector<double>& instants, int n) {
  double area = 0;
  const double ds = (p.hi(0) - p.lo(0)) / n;
  for (std::size_t b = 0; b + 1 < instants.size(); ++b) {
    const double dt = instants[b + 1] - instants[b];
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          const PatchPoint q = p.eval(p.lo(0) + (a + gauss_x[i]) * ds, instants[b] + gauss_x[j] * dt);
          area += gauss_w[i] * gauss_w[j] * ds * dt * q.xu.cross(q.xv).norm();
        }
  }
  return area;
}

}  // namespace

TEST_CASE("Envelope: a ball's sheets are its tube about the centre's path", "[variety]") {
  // a path that is no screw: along (t, t^2, sin t) while turning about an axis that tilts with t
  const Expr tr[3] = {texpr("t"), texpr("t^2"), texpr("sin(t)")};
  auto path = std::make_shared<PathMotion>(
      0, 2, tr, std::vector<PathRotation>{{{texpr("0.3"), texpr("1"), texpr("t")}, texpr("0.7*t")}});
  const Vector3d c(0.3, -0.2, 0.5);
  const double r = 0.2;
  const EntityPtr ball = entity_of(R"({"kind": "sphere", "center": [0.3, -0.2, 0.5], "radius": 0.2})");
  // the centre's path: its length, and its curvature below 1 / r (so the tube does not fold)
  double length = 0, curvature = 0;
  for (int k = 0; k < 2000; ++k)
    for (int i = 0; i < 4; ++i) {
      const double t = 2 * (k + gauss_x[i]) / 2000;
      const PoseJet P = path->pose(t);
      const Vector3d v = P.dR * c + P.dp, a = P.ddR * c + P.ddp;
      length += gauss_w[i] * 2.0 / 2000 * v.norm();
      curvature = std::max(curvature, v.cross(a).norm() / std::pow(v.norm(), 3));
    }
  REQUIRE(curvature * r < 0.9);

  const GrazingFamily f = grazing_family(*ball->faces()[0], *path);
  REQUIRE(f.complete);
  double area = 0, covered = 0;
  for (const GrazingTrack& track : f.tracks) {
    if (track.t.size() < 2) continue;
    const PatchPtr sheet = envelope_patch(ball->faces()[0], path, track, "the ball's envelope");
    covered += sheet->hi(1) - sheet->lo(1);
    area += area_of(*sheet, track.t, 128);
    for (double s : {0.0, 0.13, 0.5, 0.77, 1.0})
      for (double fraction : {0.0, 0.31, 0.5, 0.94, 1.0}) {
        const double t = sheet->lo(1) + fraction * (sheet->hi(1) - sheet->lo(1));
        const PoseJet P = path->pose(t);
        const Vector3d centre = P.R * c + P.p, v = P.dR * c + P.dp;
        const PatchPoint q = sheet->eval(s, t);
        CHECK(std::abs((q.x - centre).norm() - r) < 1e-12);
        CHECK(std::abs((q.x - centre).dot(v.normalized())) < 1e-9);
        // derivatives: those of the map, by differences of exact points
        const double h = 1e-6;
        if (s > h && s < 1 - h && t > sheet->lo(1) + h && t < sheet->hi(1) - h) {
          CHECK((q.xu - (sheet->eval(s + h, t).x - sheet->eval(s - h, t).x) / (2 * h)).norm() < 1e-6 * q.xu.norm());
          CHECK((q.xv - (sheet->eval(s, t + h).x - sheet->eval(s, t - h).x) / (2 * h)).norm() < 1e-6 * q.xv.norm());
        }
        // the sheet's normal is the sphere's there
        INFO("s " << s << " t " << t);
        CHECK(q.xu.cross(q.xv).normalized().cross((q.x - centre).normalized()).norm() < 1e-6);
      }
  }
  CHECK(covered == Approx(2.0).margin(1e-6));
  CHECK(area == Approx(2 * M_PI * r * length).epsilon(1e-6));
}

TEST_CASE("Envelope: a cylinder translated along a turning direction sweeps strips of the lines' speeds", "[variety]") {
  // p(t) = (sin t, -cos t, 0.3 t): the velocity (cos t, sin t, 0.3) grazes the lateral face on the
  // lines u = t +- pi/2, which move round the face at 0.5 per unit t: in space the line u = t + pi/2
  // moves across itself at 1 - 0.5, the other at 1 + 0.5, so over t in [0, 2] the strips of height 2
  // have areas 2 and 6
  const Expr tr[3] = {texpr("sin(t)"), texpr("-cos(t)"), texpr("0.3*t")};
  auto path = std::make_shared<PathMotion>(0, 2, tr, std::vector<PathRotation>{});
  const EntityPtr cyl =
      entity_of(R"({"kind": "cylinder", "base": [0, 0, -1], "axis": [0, 0, 1], "radius": 0.5, "height": 2})");
  const GrazingFamily f = grazing_family(*cyl->faces()[0], *path, 24);
  REQUIRE(f.tracks.size() == 2);
  std::vector<double> areas;
  for (const GrazingTrack& track : f.tracks) {
    const PatchPtr sheet = envelope_patch(cyl->faces()[0], path, track, "a strip");
    areas.push_back(area_of(*sheet, track.t, 128));
    for (double s : {0.0, 0.4, 1.0})
      for (double t : {0.0, 0.7, 1.5707963, 2.0}) {
        const Vector3d x = sheet->eval(s, t).x - Vector3d(std::sin(t), -std::cos(t), 0.3 * t);
        CHECK(std::abs(std::hypot(x.x(), x.y()) - 0.5) < 1e-12);
        CHECK(std::abs(x.x() * std::cos(t) + x.y() * std::sin(t)) < 1e-9);  // across the velocity
        CHECK(std::abs(std::abs(x.z()) - 1) * (s == 0.0 || s == 1.0) < 1e-12);  // the ends on the rims
      }
  }
  std::sort(areas.begin(), areas.end());
  CHECK(areas[0] == Approx(2).epsilon(1e-7));
  CHECK(areas[1] == Approx(6).epsilon(1e-7));
  CHECK_THROWS(envelope_patch(cyl->faces()[0], path, GrazingTrack{}, "empty"));
}

TEST_CASE("Envelope: a box face's sheets between close events stay on the face and on its grazing lines", "[variety]") {
  // the wandering path turns the grazing line of the box's min y face through a corner twice in
  // its first 0.06 of t: short tracks, which the range's instants alone leave with one or two
  const EntityPtr box = entity_of(R"({"kind": "box", "min": [-0.3, -0.2, -0.5], "max": [0.3, 0.2, 0.5]})");
  REQUIRE(box);
  const PathMotion path = sweep_test::wandering_path();
  auto motion = std::make_shared<const PathMotion>(path);
  const PatchPtr face = box->faces()[2];  // min y
  REQUIRE(std::abs(face->eval(0.5 * (face->lo(0) + face->hi(0)), 0.5 * (face->lo(1) + face->hi(1))).x.y() + 0.2) < 1e-12);
  const GrazingFamily f = grazing_family(*face, *motion);
  int short_tracks = 0;
  for (const GrazingTrack& tr : f.tracks) {
    if (!(tr.t.back() - tr.t.front() > 1e-6)) continue;
    CHECK(int(tr.t.size()) >= Settings::grazing_span_intervals + 1);
    short_tracks += tr.t.back() - tr.t.front() < 0.1;
    const PatchPtr sheet = envelope_patch(face, motion, tr, "sheet");
    double off_face = 0, off_line = 0;
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; j <= 20; ++j) {
        const double t = tr.t.front() + (tr.t.back() - tr.t.front()) * j / 20;
        const Vector3d y = motion->transform(t).inverse() * sheet->eval(i / 20.0, t).x;
        off_face = std::max({off_face, std::abs(y.y() + 0.2), std::abs(y.x()) - 0.3, std::abs(y.z()) - 0.5});
        // on the grazing line: the velocity at the point lies in the face's plane
        const PoseJet P = motion->pose(t);
        const Vector3d v = P.R.transpose() * (P.dR * y + P.dp);
        off_line = std::max(off_line, std::abs(v.y()) / v.norm());
      }
    CHECK(off_face < 1e-12);
    CHECK(off_line < 1e-9);
  }
  CHECK(short_tracks >= 1);
}

TEST_CASE("Envelope: seed 001's circle sheets end exactly where the circle crosses the grazing seam lines", "[variety]") {
  // the circle z = (4 / pi) cos(pi t) of the rolling cylinder's lateral face grazes for t in
  // [0.2125, 0.7875]; its halves end where it crosses the lines x = +-0.5 (one of them the face's
  // seam), at saddles of g, where no root across the arc says where the end is
  const EntityPtr cyl = entity_of(R"({"kind": "cylinder", "base": [0, 0, -1], "axis": [0, 0, 1], "radius": 0.5, "height": 2})");
  REQUIRE(cyl);
  const Expr tr[3] = {texpr("0"), texpr("4*t"), texpr("0")};
  auto motion = std::make_shared<const PathMotion>(0, 1, tr, std::vector<PathRotation>{{{texpr("1"), texpr("0"), texpr("0")}, texpr("pi*t")}});
  const PatchPtr face = cyl->faces()[0];
  const GrazingFamily f = grazing_family(*face, *motion);
  int circles = 0;
  for (const GrazingTrack& track : f.tracks) {
    if (track.t.size() < 2) continue;  // an instant between two events
    const PatchPtr sheet = envelope_patch(face, motion, track, "sheet");
    const double tm = 0.5 * (track.t.front() + track.t.back());
    const Vector3d mid = motion->transform(tm).inverse() * sheet->eval(0.5, tm).x;
    if (std::abs(std::abs(mid.x()) - 0.5) < 1e-9) continue;  // a line x = +-0.5
    ++circles;
    double off = 0;
    for (int i = 0; i <= 20; ++i)
      for (int j = 0; j <= 20; ++j) {
        const double t = track.t.front() + (track.t.back() - track.t.front()) * j / 20;
        const Vector3d y = motion->transform(t).inverse() * sheet->eval(i / 20.0, t).x;
        off = std::max({off, std::abs(std::hypot(y.x(), y.y()) - 0.5), std::abs(y.z() - 4 / M_PI * std::cos(M_PI * t))});
      }
    CHECK(off < 1e-10);
  }
  CHECK(circles == 2);
}

TEST_CASE("Envelope: seed 001's cap sheets stay on the caps up to where their grazing chords vanish at the rim", "[variety]") {
  // on the caps of the rolling cylinder the grazing line is the chord y = (4 / pi) sin(pi t), until
  // it leaves the disk of radius 0.5 (t near 0.128 and 0.872): there the chord shrinks like a square
  // root of the time left, faster than the rows of the track say between their instants
  const EntityPtr cyl = entity_of(R"({"kind": "cylinder", "base": [0, 0, -1], "axis": [0, 0, 1], "radius": 0.5, "height": 2})");
  REQUIRE(cyl);
  const Expr tr[3] = {texpr("0"), texpr("4*t"), texpr("0")};
  auto motion = std::make_shared<const PathMotion>(0, 1, tr, std::vector<PathRotation>{{{texpr("1"), texpr("0"), texpr("0")}, texpr("pi*t")}});
  int sheets = 0;
  for (std::size_t k = 1; k < cyl->faces().size(); ++k) {
    const PatchPtr face = cyl->faces()[k];
    for (const GrazingTrack& track : grazing_family(*face, *motion).tracks) {
      // (as candidate_patches: slivers of the range between two events left out)
      if (track.t.size() < 2 || !(track.t.back() - track.t.front() > Settings::grazing_sliver)) continue;
      ++sheets;
      const PatchPtr sheet = envelope_patch(face, motion, track, "sheet");
      double outside = 0, off_chord = 0;
      for (int j = 0; j <= 2000; ++j) {
        const double t = track.t.front() + (track.t.back() - track.t.front()) * j / 2000;
        for (int i = 0; i <= 24; ++i) {
          const Vector3d y = motion->transform(t).inverse() * sheet->eval(i / 24.0, t).x;
          outside = std::max({outside, std::hypot(y.x(), y.y()) - 0.5, std::abs(std::abs(y.z()) - 1)});
          off_chord = std::max(off_chord, std::abs(std::abs(y.y()) - 4 / M_PI * std::sin(M_PI * t)));
        }
      }
      INFO("a sheet of face " << k << " over t in [" << track.t.front() << ", " << track.t.back() << "]");
      CHECK(outside < 1e-10);
      CHECK(off_chord < 1e-10);
    }
  }
  CHECK(sheets == 4);
}
