// Orbit intervals, the orbit-space volume of one-joint sweeps, the swept-set box and the mesh index.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "sweep/mesh_index.hpp"
#include "sweep/orbit.hpp"
#include "sweep/swept_box.hpp"

using Eigen::Vector3d;
using namespace sweep;

namespace {

ScrewJoint joint(JointType type, const Vector3d& point, const Vector3d& dir, double pitch_per_turn = 0) {
  ScrewJoint j;
  j.type = type;
  j.point = point;
  j.direction = dir.normalized();
  j.pitch = pitch_per_turn / (2 * M_PI);
  return j;
}

/// A frame turned off every axis and moved off the origin.
Eigen::Isometry3d tilted_frame() {
  Eigen::Isometry3d F = Eigen::Isometry3d::Identity();
  F.linear() = Eigen::AngleAxisd(0.7, Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
  F.translation() = Vector3d(0.2, -0.3, 0.1);
  return F;
}

std::vector<std::pair<std::string, OrbitSolidPtr>> primitives() {
  return {{"box", orbit_box(Vector3d(0.3, -0.2, 0.1), Vector3d(1.4, 0.9, 0.8))},
          {"sphere", orbit_sphere(Vector3d(0.7, 0.2, -0.3), 0.6)},
          {"cylinder", orbit_cylinder(Vector3d(0.2, 0.1, 0), Vector3d(1, 2, 2).normalized(), 0.4, 1.3)},
          {"cone", orbit_cone(Vector3d(-0.2, 0.4, 0.1), Vector3d(-1, 0.5, 2).normalized(), 0.7, 0.1, 1.1)},
          {"pointed cone", orbit_cone(Vector3d(0.1, 0, 0), Vector3d(0, 1, 0), 0.5, 0.0, 0.9)},
          {"torus", orbit_torus(Vector3d(0.5, -0.1, 0.2), Vector3d(1, -1, 3).normalized(), 0.8, 0.25)},
          {"elliptic cylinder", orbit_elliptic_cylinder(tilted_frame(), 0.9, 0.3, 1.2)},
          {"box minus cylinder",
           orbit_difference(orbit_box(Vector3d(0, 0, 0), Vector3d(2, 1, 0.5)),
                            orbit_cylinder(Vector3d(1, 0.5, -1), Vector3d(0, 0, 1), 0.3, 3))}};
}

}  // namespace

TEST_CASE("Orbit intervals: union, intersection and difference of interval sets") {
  const Intervals a{{0, 1}, {2, 3}}, b{{0.5, 2.5}};
  CHECK(unite(a, b) == Intervals{{0, 3}});
  CHECK(intersect(a, b) == Intervals{{0.5, 1}, {2, 2.5}});
  CHECK(subtract(a, b) == Intervals{{0, 0.5}, {2.5, 3}});
  CHECK(total_length(a) == Approx(2.0));
}

TEST_CASE("Orbit intervals: the orbit of a point is the joint's motion of it") {
  const Vector3d y(1.3, -0.4, 0.7);
  for (const auto& j : {joint(JointType::Revolute, Vector3d(0.2, 0.1, 0), Vector3d(1, 1, 2)),
                        joint(JointType::Helical, Vector3d(-1, 0, 0.5), Vector3d(0, 1, 1), 0.8),
                        joint(JointType::Prismatic, Vector3d::Zero(), Vector3d(1, -2, 0.5))}) {
    const OrbitCurve o = orbit_of(j, y);
    for (double t : {-2.0, -0.3, 0.0, 0.9, 4.0}) {
      CAPTURE(to_string(j.type), t);
      CHECK((o.at(t) - j.transform(t) * y).norm() == Approx(0.0).margin(1e-12));
      CHECK((o.shifted(0.7).at(t) - o.at(t + 0.7)).norm() == Approx(0.0).margin(1e-12));
    }
  }
}

TEST_CASE("Orbit intervals: every primitive's intervals agree with its inside test along random orbits") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  const std::vector<ScrewJoint> joints{joint(JointType::Revolute, Vector3d(0.1, 0.2, 0), Vector3d(0.3, 1, 0.2)),
                                       joint(JointType::Helical, Vector3d(0, -0.3, 0), Vector3d(1, 0.2, 0.4), 0.7),
                                       joint(JointType::Prismatic, Vector3d::Zero(), Vector3d(0.4, 1, -0.7))};
  for (const auto& [name, solid] : primitives()) {
    int inside = 0, checked = 0;
    for (const auto& j : joints)
      for (int k = 0; k < 60; ++k) {
        const OrbitCurve o = orbit_of(j, Vector3d(u(rng), u(rng), u(rng)));
        const Intervals iv = solid->on_curve(o, -4, 4);
        for (int m = 0; m < 200; ++m) {
          const double t = -4 + 8 * (m + 0.5) / 200;
          bool in_iv = false, near_end = false;
          for (const auto& s : iv) {
            in_iv = in_iv || (t >= s.first && t <= s.second);
            near_end = near_end || std::abs(t - s.first) < 1e-9 || std::abs(t - s.second) < 1e-9;
          }
          if (near_end) continue;
          CAPTURE(name, to_string(j.type), t);
          REQUIRE(in_iv == solid->contains(o.at(t)));
          inside += in_iv;
          ++checked;
        }
      }
    CAPTURE(name);
    CHECK(inside > 100);  // the orbits did meet the solid
    CHECK(checked > 30000);
  }
}

namespace {

/// A one-joint sweep whose volume has a closed form.
struct ClosedFormCase {
  const char* name;
  OrbitSolidPtr body;
  ScrewJoint j;
  double T, exact;
};

std::vector<ClosedFormCase> closed_form_cases() {
  const double r = 0.5, d = 2.0;
  return {
      {"box a quarter turn about an outside axis", orbit_box(Vector3d(1, 0, 0), Vector3d(2, 1, 1)),
       joint(JointType::Revolute, Vector3d::Zero(), Vector3d::UnitZ()), M_PI / 2, M_PI + 1},
      {"ball extruded along a diagonal (capsule)", orbit_sphere(Vector3d::Zero(), 1),
       joint(JointType::Prismatic, Vector3d::Zero(), Vector3d(1, 1, 1)), 5, 4.0 / 3 * M_PI + 5 * M_PI},
      {"cylinder a half turn about a diameter", orbit_cylinder(Vector3d(0, 0, -1), Vector3d::UnitZ(), 1, 2),
       joint(JointType::Revolute, Vector3d::Zero(), Vector3d::UnitX()), M_PI, 10 * M_PI / 3},
      {"ball turned 100 degrees about an axis beside it (Pappus)", orbit_sphere(Vector3d(d, 0, 0), r),
       joint(JointType::Revolute, Vector3d::Zero(), Vector3d::UnitZ()), 100 * M_PI / 180,
       100 * M_PI / 180 * d * M_PI * r * r + 4.0 / 3 * M_PI * r * r * r},
      {"ball screw-swept two turns with turns apart (tube formula)", orbit_sphere(Vector3d(5, 0, 0), 1),
       joint(JointType::Helical, Vector3d::Zero(), Vector3d::UnitZ(), 3), 4 * M_PI,
       M_PI * 2 * std::sqrt(std::pow(10 * M_PI, 2) + 9) + 4.0 / 3 * M_PI},
      {"torus turned about its own axis (itself)", orbit_torus(Vector3d(0, 0, 0.3), Vector3d::UnitZ(), 2, 0.5),
       joint(JointType::Revolute, Vector3d::Zero(), Vector3d::UnitZ()), 1.0, 2 * M_PI * M_PI * 2 * 0.25},
      {"elliptic cylinder slid along its a axis", orbit_elliptic_cylinder(tilted_frame(), 0.9, 0.3, 1.2),
       joint(JointType::Prismatic, Vector3d::Zero(), tilted_frame().linear().col(0)), 2,
       M_PI * 0.9 * 0.3 * 1.2 + 2 * (2 * 0.3 * 1.2)},
      {"elliptic cylinder a half turn about its axis", orbit_elliptic_cylinder(tilted_frame(), 0.9, 0.3, 1.2),
       joint(JointType::Revolute, tilted_frame().translation(), tilted_frame().linear().col(2)), M_PI,
       M_PI * 0.9 * 0.9 * 1.2},
      {"box extruded obliquely", orbit_box(Vector3d(0, 0, 0), Vector3d(1, 2, 3)),
       joint(JointType::Prismatic, Vector3d::Zero(), Vector3d(1, 1, 0)), 2,
       6 + 2 * (3 * (1 + 2) / std::sqrt(2.0))},
  };
}

}  // namespace

TEST_CASE("Orbit volume: one-joint sweeps against closed forms") {
  for (const auto& c : closed_form_cases()) {
    CAPTURE(c.name);
    double err = 0;
    const double v = joint_sweep_volume(*c.body, c.j, c.T, 1e-10, &err);
    CHECK(v == Approx(c.exact).epsilon(1e-8));
    CHECK(err < 1e-7 * c.exact);
  }
}

TEST_CASE("Orbit volume: shifted lattices agree with the closed forms within their own error estimate") {
  for (const auto& c : closed_form_cases()) {
    CAPTURE(c.name);
    double err = 0;
    const double v = joint_sweep_volume_lattice(*c.body, c.j, c.T, 100, 6, 7, &err);
    CAPTURE(v, err, c.exact);
    CHECK(std::abs(v - c.exact) <= 4 * err + 1e-12 * c.exact);
    CHECK(err < 1e-2 * c.exact);  // an estimate that says something
  }
  // the same shifts for the same seed, other shifts for another
  const ClosedFormCase c = closed_form_cases().at(2);
  double e1 = 0, e2 = 0;
  CHECK(joint_sweep_volume_lattice(*c.body, c.j, c.T, 40, 3, 11, &e1) ==
        joint_sweep_volume_lattice(*c.body, c.j, c.T, 40, 3, 11, &e2));
  CHECK(e1 == e2);
  CHECK(joint_sweep_volume_lattice(*c.body, c.j, c.T, 40, 3, 11) !=
        joint_sweep_volume_lattice(*c.body, c.j, c.T, 40, 3, 12));
}

TEST_CASE("Orbit volume: agrees with Monte Carlo membership on a torus moved along a direction in its plane") {
  const auto tor = orbit_torus(Vector3d::Zero(), Vector3d::UnitZ(), 2, 0.5);
  const ScrewJoint j = joint(JointType::Prismatic, Vector3d::Zero(), Vector3d::UnitX());
  const double v = joint_sweep_volume(*tor, j, 1.0, 1e-9);
  // the same set moved along -x and along +y
  CHECK(joint_sweep_volume(*tor, joint(JointType::Prismatic, Vector3d::Zero(), -Vector3d::UnitX()), 1.0, 1e-9) ==
        Approx(v).epsilon(1e-8));
  CHECK(joint_sweep_volume(*tor, joint(JointType::Prismatic, Vector3d::Zero(), Vector3d::UnitY()), 1.0, 1e-9) ==
        Approx(v).epsilon(1e-8));
  std::mt19937_64 rng(3);
  const Eigen::AlignedBox3d box(Vector3d(-2.6, -2.6, -0.6), Vector3d(3.6, 2.6, 0.6));
  std::uniform_real_distribution<double> u(0, 1);
  const int n = 200000;
  int in = 0;
  for (int k = 0; k < n; ++k)
    in += in_joint_sweep(*tor, j, 1.0, box.min() + Vector3d(u(rng), u(rng), u(rng)).cwiseProduct(box.sizes()));
  const double p = double(in) / n, mc = p * box.volume(), sigma = box.volume() * std::sqrt(p * (1 - p) / n);
  CHECK(std::abs(mc - v) < 4 * sigma);
}

TEST_CASE("Swept box: holds sampled points of one-joint and chain sweeps") {
  const Eigen::AlignedBox3d body(Vector3d(1, -0.5, 0), Vector3d(2, 0.5, 1));
  Motion one;
  one.joints = {joint(JointType::Helical, Vector3d(0.3, 0, 0), Vector3d(0.2, 0.1, 1), 1.5)};
  one.joints[0].lo = -1, one.joints[0].hi = 7;
  Motion chain;
  chain.joints = {joint(JointType::Revolute, Vector3d(0, 0, 0), Vector3d(0, 0, 1)),
                  joint(JointType::Prismatic, Vector3d::Zero(), Vector3d(1, 0, 0)),
                  joint(JointType::Revolute, Vector3d(3, 0, 0), Vector3d(0, 1, 0))};
  chain.joints[0].lo = 0, chain.joints[0].hi = 2;
  chain.joints[1].lo = -1, chain.joints[1].hi = 2;
  chain.joints[2].lo = -0.5, chain.joints[2].hi = 1;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (const Motion* m : {&one, &chain}) {
    const Eigen::AlignedBox3d box = swept_box(body, *m);
    for (int k = 0; k < 20000; ++k) {
      std::vector<double> q;
      for (const auto& j : m->joints) q.push_back(j.lo + (j.hi - j.lo) * u(rng));
      const Vector3d x = m->transform(q) * (body.min() + Vector3d(u(rng), u(rng), u(rng)).cwiseProduct(body.sizes()));
      REQUIRE(box.contains(x));
    }
  }
}

TEST_CASE("Mesh index: inside and distance for a closed cube") {
  std::vector<Triangle> tris;
  const Vector3d c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
  for (const auto& q : quads) {
    tris.push_back({c[q[0]], c[q[1]], c[q[2]]});
    tris.push_back({c[q[0]], c[q[2]], c[q[3]]});
  }
  const MeshIndex mesh(tris);
  CHECK(mesh.inside(Vector3d(0.5, 0.5, 0.5)));
  CHECK(mesh.inside(Vector3d(0.5, 0.5, 0.5)));  // a ray through the cube's diagonal edges is cast again
  CHECK(mesh.inside(Vector3d(0.01, 0.99, 0.5)));
  CHECK_FALSE(mesh.inside(Vector3d(1.01, 0.5, 0.5)));
  CHECK_FALSE(mesh.inside(Vector3d(-3, 7, 2)));
  CHECK(mesh.distance(Vector3d(0.5, 0.5, 0.5)) == Approx(0.5));
  CHECK(mesh.distance(Vector3d(2, 0.5, 0.5)) == Approx(1.0));
  CHECK(mesh.distance(Vector3d(2, 2, 0.5)) == Approx(std::sqrt(2.0)));
  CHECK(mesh.distance_below(Vector3d(2, 2, 0.5), 0.5) >= 0.5);
}

TEST_CASE("Mesh index: rays that avoid a region whose triangles are wrong") {
  // the unit cube without its top face's triangles: rays through the hole miss a crossing
  std::vector<Triangle> tris;
  const Vector3d c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int quads[5][4] = {{0, 3, 2, 1}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
  for (const auto& q : quads) {
    tris.push_back({c[q[0]], c[q[1]], c[q[2]]});
    tris.push_back({c[q[0]], c[q[2]], c[q[3]]});
  }
  const MeshIndex mesh(tris);
  const Vector3d centre(0.5, 0.5, 0.5), high(0.5, 0.5, 0.9);
  CHECK_FALSE(mesh.inside(high));  // two of the first three rays leave through the hole
  const std::vector<Eigen::AlignedBox3d> top{Eigen::AlignedBox3d(Vector3d(-0.01, -0.01, 0.99), Vector3d(1.01, 1.01, 1.01))};
  CHECK(mesh.inside_avoiding(high, top) == 1);
  CHECK(mesh.inside_avoiding(centre, top) == 1);
  CHECK(mesh.inside_avoiding(Vector3d(0.9, 0.1, 0.05), top) == 1);
  CHECK(mesh.inside_avoiding(Vector3d(0.5, 0.5, 1.0), top) == -1);  // in the region
  CHECK(mesh.inside_avoiding(Vector3d(2, 0.5, 0.5), top) == 0);
  CHECK(mesh.inside_avoiding(Vector3d(0.5, 0.5, 1.5), top) == 0);
  CHECK(mesh.inside_avoiding(Vector3d(0.5, 0.5, -0.5), top) == 0);
  // no region: the plain test's answers
  CHECK(mesh.inside_avoiding(Vector3d(0.9, 0.1, 0.05), {}) == int(mesh.inside(Vector3d(0.9, 0.1, 0.05))));
  // a region around the point's every ray: undecided
  std::vector<Eigen::AlignedBox3d> around;
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) {
      Eigen::Vector3d lo(-2, -2, -2), hi(3, 3, 3);
      (side < 0 ? hi : lo)[axis] = side < 0 ? -1.5 : 2.5;
      around.push_back(Eigen::AlignedBox3d(lo, hi));
    }
  CHECK(mesh.inside_avoiding(centre, around) == -1);
}

namespace {

std::vector<std::pair<std::string, OrbitSurface>> orbit_surfaces() {
  using K = OrbitSurface::Kind;
  Eigen::Isometry3d other = tilted_frame().inverse();
  other.translation() += Vector3d(0.1, 0.4, -0.2);
  std::vector<std::pair<std::string, OrbitSurface>> out;
  for (const auto& [name, kind] : std::vector<std::pair<std::string, K>>{
           {"plane", K::Plane}, {"cylinder", K::Cylinder}, {"cone", K::Cone}, {"sphere", K::Sphere}, {"torus", K::Torus}})
    for (const auto& frame : {tilted_frame(), other}) {
      OrbitSurface s;
      s.kind = kind;
      s.frame = frame;
      s.radius = kind == K::Torus ? 0.9 : kind == K::Cone ? 0.3 : 0.7;
      s.slope = 0.5;
      s.minor = 0.3;
      out.push_back({name, s});
    }
  return out;
}

}  // namespace

TEST_CASE("Orbit surfaces: crossings of random orbits agree with the sign of the surface's function between samples") {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  const std::vector<ScrewJoint> joints{joint(JointType::Revolute, Vector3d(0.1, 0.2, 0), Vector3d(0.3, 1, 0.2)),
                                       joint(JointType::Helical, Vector3d(0, -0.3, 0), Vector3d(1, 0.2, 0.4), 0.7),
                                       joint(JointType::Prismatic, Vector3d::Zero(), Vector3d(0.4, 1, -0.7))};
  const Eigen::AlignedBox3d everywhere(Vector3d::Constant(-1e3), Vector3d::Constant(1e3));
  for (const auto& [name, s] : orbit_surfaces()) {
    int found = 0, brackets = 0;
    for (const auto& j : joints)
      for (int k = 0; k < 40; ++k) {
        const OrbitCurve o = orbit_of(j, Vector3d(u(rng), u(rng), u(rng)));
        const std::vector<double> roots = surface_crossings(s, o, -4, 4, everywhere);
        REQUIRE(std::is_sorted(roots.begin(), roots.end()));
        found += int(roots.size());
        for (double r : roots) {
          CAPTURE(name, to_string(j.type), r);
          REQUIRE(r >= -4);
          REQUIRE(r <= 4);
          // f changes sign across the root
          const double before = s.value(o.at(r - 1e-7)), after = s.value(o.at(r + 1e-7));
          CHECK((before < 0) != (after < 0));
        }
        // between samples, an odd number of roots where f's signs differ, an even number elsewhere
        const int n = 2000;
        int wrong = 0;
        double first_wrong = 0;
        for (int m = 0; m < n; ++m) {
          const double t0 = -4 + 8.0 * m / n, t1 = -4 + 8.0 * (m + 1) / n;
          const double f0 = s.value(o.at(t0)), f1 = s.value(o.at(t1));
          if (std::abs(f0) < 1e-9 || std::abs(f1) < 1e-9) continue;  // a root at a sample
          const auto in = std::count_if(roots.begin(), roots.end(), [&](double r) { return r > t0 && r < t1; });
          if ((in % 2 == 1) != ((f0 < 0) != (f1 < 0)) && wrong++ == 0) first_wrong = t0;
          brackets += (f0 < 0) != (f1 < 0);
        }
        CAPTURE(name, to_string(j.type), first_wrong);
        CHECK(wrong == 0);
      }
    CAPTURE(name);
    CHECK(brackets > 15);  // the orbits did cross the surface
    CHECK(found >= brackets);
  }
}

TEST_CASE("Orbit surfaces: a circle that dips 1e-8 deep into a sphere crosses it twice, and a region away from the dip is not searched") {
  // the circle of radius 1 about the z axis, and the unit sphere about (2 - delta, 0, 0): inside it
  // where cos t > 1 - delta / 2
  const double delta = 1e-8;
  const OrbitCurve circle = orbit_of(joint(JointType::Revolute, Vector3d::Zero(), Vector3d::UnitZ()), Vector3d::UnitX());
  OrbitSurface sphere;
  sphere.kind = OrbitSurface::Kind::Sphere;
  sphere.frame.translation() = Vector3d(2 - delta, 0, 0);
  sphere.radius = 1;
  const Eigen::AlignedBox3d everywhere(Vector3d::Constant(-10), Vector3d::Constant(10));
  const double t = std::acos(1 - delta / 2);
  const std::vector<double> roots = surface_crossings(sphere, circle, -3, 3.5, everywhere);
  REQUIRE(roots.size() == 2);
  CHECK(roots[0] == Approx(-t).epsilon(1e-6));
  CHECK(roots[1] == Approx(t).epsilon(1e-6));
  // two turns later, the same crossings
  const std::vector<double> later = surface_crossings(sphere, circle, 10, 14, everywhere);
  REQUIRE(later.size() == 2);
  CHECK(later[0] == Approx(4 * M_PI - t).epsilon(1e-9));
  CHECK(later[1] == Approx(4 * M_PI + t).epsilon(1e-9));
  const Eigen::AlignedBox3d far_side(Vector3d(-1.5, -1.5, -1), Vector3d(-0.5, 1.5, 1));
  CHECK(surface_crossings(sphere, circle, -3, 3.5, far_side).empty());
}
