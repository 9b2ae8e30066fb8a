#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "sweep/error.hpp"
#include "sweep/kinematics.hpp"

using namespace sweep::kinematics;
using sweep::InputError;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string example_path(const std::string& name) {
  return std::string(SWEEP_SOURCE_DIR) + "/examples/joints/" + name;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

NumericFrame unit_frame() { return NumericFrame{}; }

Twist random_screw(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Twist t;
  for (int i = 0; i < 6; ++i) t[i] = u(rng);
  return t;
}

Eigen::Isometry3d random_motion(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Quaterniond q(u(rng), u(rng), u(rng), u(rng));
  q.normalize();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = Vec3(u(rng), u(rng), u(rng)) * 50.0;
  return T;
}

/// The same assembly moved rigidly by T.
Assembly moved(Assembly a, const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d R = T.linear();
  for (auto& c : a.constraints) {
    for (Axis* ax : {&c.axis1, &c.axis2}) {
      ax->point = T * ax->point;
      ax->direction = R * ax->direction;
    }
    for (Plane* pl : {&c.plane1, &c.plane2}) {
      pl->point = T * pl->point;
      pl->normal = R * pl->normal;
    }
    c.point1 = T * c.point1;
    c.point2 = T * c.point2;
  }
  return a;
}

/// The constraints in a shuffled order; symmetric constraints also get their two sides swapped.
Assembly reordered(Assembly a, std::mt19937& rng) {
  std::shuffle(a.constraints.begin(), a.constraints.end(), rng);
  for (auto& c : a.constraints) {
    if (rng() % 2) continue;
    switch (c.type) {
      case ConstraintType::Coaxial:
        std::swap(c.axis1, c.axis2);
        break;
      case ConstraintType::Coplanar:
      case ConstraintType::Align:
        std::swap(c.plane1, c.plane2);
        break;
      case ConstraintType::Spherical:
        std::swap(c.point1, c.point2);
        break;
      default:
        continue;
    }
    std::swap(c.parts[0], c.parts[1]);
  }
  return a;
}

ScrewBasis transformed(const ScrewBasis& b, const Eigen::Isometry3d& T) {
  ScrewBasis out(6, b.cols());
  for (Eigen::Index j = 0; j < b.cols(); ++j) out.col(j) = transform_twist(T, b.col(j));
  return out;
}

std::vector<Wrench> concat(std::vector<Wrench> a, const std::vector<Wrench>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

/// Expects parse_assembly(text) to throw InputError at `pointer`, with `words` in the message.
void require_input_error(const std::string& text, const std::string& pointer, const std::string& words) {
  try {
    parse_assembly(text);
    FAIL("no InputError for " << pointer);
  } catch (const InputError& e) {
    CAPTURE(e.what());
    CHECK(e.pointer() == pointer);
    CHECK(std::string(e.what()).find(words) != std::string::npos);
  }
}

const char* kRevolute = R"({
  "assembly": 1,
  "parts": ["ground", "crank", "rod", "slider"],
  "ground": "ground",
  "constraints": [
    { "type": "coaxial",  "parts": ["ground", "crank"],
      "axis1": { "point": [0, 0, 0], "direction": [0, 0, 1] },
      "axis2": { "point": [0, 0, 5], "direction": [0, 0, -1] } },
    { "type": "coplanar", "parts": ["ground", "crank"],
      "plane1": { "point": [0, 0, 0], "normal": [0, 0, 1] },
      "plane2": { "point": [1, 0, 0], "normal": [0, 0, -1] } }
  ]
})";

/// kRevolute with `from` replaced by `to` (once).
std::string edited(const std::string& from, const std::string& to) {
  std::string s = kRevolute;
  const auto pos = s.find(from);
  REQUIRE(pos != std::string::npos);
  return s.replace(pos, from.size(), to);
}

Joint joint_of(const std::vector<Wrench>& w) { return recognize_joint(w, unit_frame()); }

/// A pin joint along z at (x, y) between parts a and b: coaxial + coplanar, as JSON constraints.
std::string pin(const char* a, const char* b, double x, double y) {
  std::ostringstream os;
  const std::string parts = std::string(R"("parts": [")") + a + R"(", ")" + b + R"("])";
  os << R"({ "type": "coaxial", )" << parts << R"(, "axis1": {"point": [)" << x << ", " << y
     << R"(, 0], "direction": [0, 0, 1]}, "axis2": {"point": [)" << x << ", " << y
     << R"(, 1], "direction": [0, 0, 1]} }, { "type": "coplanar", )" << parts << R"(, "plane1": {"point": [)"
     << x << ", " << y << R"(, 0.5], "normal": [0, 0, 1]}, "plane2": {"point": [)" << x + 1 << ", " << y
     << R"(, 0.5], "normal": [0, 0, -1]} })";
  return os.str();
}

}  // namespace

// ---------------------------------------------------------------------------------------------

TEST_CASE("Kinematics: reciprocal product and screw conventions") {
  const Vec3 p(1, 2, 3), s(0, 0, 2);
  const Twist rot = revolute_twist(p, s);
  CHECK(rot.head<3>().isApprox(Vec3(0, 0, 1)));
  CHECK(rot.tail<3>().isApprox(p.cross(Vec3(0, 0, 1))));
  // A force meeting the axis does no work on the rotation; a parallel force neither; a skew one does.
  CHECK(reciprocal_product(rot, force_wrench(p + Vec3(0, 0, 7), Vec3(1, 1, 0))) == Approx(0.0).margin(1e-12));
  CHECK(reciprocal_product(rot, force_wrench(Vec3(5, 5, 5), Vec3(0, 0, 1))) == Approx(0.0).margin(1e-12));
  CHECK(std::abs(reciprocal_product(rot, force_wrench(p + Vec3(1, 0, 0), Vec3(0, 1, 0)))) == Approx(1.0));
  // A couple does no work on a translation, and a force does none on a perpendicular translation.
  CHECK(reciprocal_product(prismatic_twist(Vec3(1, 0, 0)), couple_wrench(Vec3(1, 0, 0))) ==
        Approx(0.0).margin(1e-12));
  CHECK(reciprocal_product(prismatic_twist(Vec3(1, 0, 0)), force_wrench(p, Vec3(0, 1, 0))) ==
        Approx(0.0).margin(1e-12));
  // Pitch of a helical twist; swap twice is the identity.
  CHECK(twist_pitch(helical_twist(p, s, 0.25)) == Approx(0.25));
  const Twist t(1, 2, 3, 4, 5, 6);
  CHECK(swap_triplets(t) == Twist(4, 5, 6, 1, 2, 3));
  CHECK(swap_triplets(swap_triplets(t)) == t);

  SECTION("the reciprocal product is invariant under rigid motions") {
    std::mt19937 rng(7);
    for (int k = 0; k < 20; ++k) {
      const Twist a = random_screw(rng);
      const Wrench w = random_screw(rng);
      const Eigen::Isometry3d T = random_motion(rng);
      CHECK(reciprocal_product(transform_twist(T, a), transform_wrench(T, w)) ==
            Approx(reciprocal_product(a, w)).margin(1e-9));
    }
  }
}

TEST_CASE("Kinematics: basic constraints are the derivatives of dot-1, dot-2 and distance") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto rv = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  for (int k = 0; k < 20; ++k) {
    const Vec3 ai = rv(), aj = rv(), pi = rv(), pj = rv();
    const Twist t = random_screw(rng);  // motion of body j, body i fixed
    const Vec3 w = t.head<3>(), v = t.tail<3>();
    // dot-1: d/dt (a_i . a_j) with a_j' = w x a_j
    const double d1 = ai.dot(w.cross(aj));
    CHECK(d1 == Approx(-ai.cross(aj).norm() * reciprocal_product(t, dot1_wrench(ai, aj))).margin(1e-12));
    // dot-2: d/dt (a_i . (P_j - P_i)) with P_j' = v + w x P_j
    const double d2 = ai.dot(v + w.cross(pj));
    CHECK(d2 == Approx(ai.norm() * reciprocal_product(t, dot2_wrench(ai, pj))).margin(1e-12));
    // dot-2 with body i moving instead: a_i' = w x a_i, P_i' = v + w x P_i.
    const double d2i = w.cross(ai).dot(pj - pi) - ai.dot(v + w.cross(pi));
    CHECK(d2i == Approx(-ai.norm() * reciprocal_product(t, dot2_wrench(ai, pj))).margin(1e-12));
    // distance: d/dt |P_j - P_i|^2 / 2
    const auto dw = distance_wrenches(pi, pj, 1e-9);
    REQUIRE(dw.size() == 1);
    const double d3 = (pj - pi).dot(v + w.cross(pj));
    CHECK(d3 == Approx((pj - pi).norm() * reciprocal_product(t, dw[0])).margin(1e-12));
  }
  // Coincident points: three forces through the point.
  const auto three = distance_wrenches(Vec3(1, 2, 3), Vec3(1, 2, 3), 1e-9);
  REQUIRE(three.size() == 3);
  CHECK(joint_of(three).kind == JointKind::Spherical);
  // dot-1 of parallel vectors is not a basic constraint.
  CHECK_THROWS_AS(dot1_wrench(Vec3(0, 0, 1), Vec3(0, 0, -2)), sweep::InternalError);
}

TEST_CASE("Kinematics: degree of constraint of the six geometry constraints") {
  const Axis z{Vec3(0, 0, 0), Vec3(0, 0, 1)};
  const Axis z2{Vec3(0, 0, 4), Vec3(0, 0, -1)};
  const Plane xy{Vec3(0, 0, 0), Vec3(0, 0, 1)};
  const Plane xy2{Vec3(3, 1, 0), Vec3(0, 0, -1)};
  struct Case {
    ConstraintType type;
    std::vector<Wrench> w;
    int dof;
    JointKind kind;
  };
  const std::vector<Case> cases = {
      {ConstraintType::Coaxial, coaxial_wrenches(z, z2), 2, JointKind::Cylindrical},
      {ConstraintType::Coplanar, coplanar_wrenches(xy, xy2), 3, JointKind::Planar},
      {ConstraintType::Spherical, spherical_wrenches(Vec3(1, 1, 1), Vec3(1, 1, 1)), 3, JointKind::Spherical},
      {ConstraintType::Align, align_wrenches(xy, Plane{Vec3(0, 0, 9), Vec3(0, 0, 1)}), 4,
       JointKind::Unrecognized},
      {ConstraintType::LineSurfaceDistance,
       line_surface_distance_wrenches(Axis{Vec3(0, 0, 2), Vec3(1, 0, 0)}, xy), 4, JointKind::Unrecognized},
      {ConstraintType::PointOnLine, point_on_line_wrenches(Vec3(0, 0, 3), z), 4, JointKind::Unrecognized},
  };
  for (const auto& c : cases) {
    CAPTURE(to_string(c.type));
    CHECK(static_cast<int>(c.w.size()) == degree_of_constraint(c.type));
    const Joint j = joint_of(c.w);
    CHECK(j.rank == degree_of_constraint(c.type));
    CHECK(j.redundant == 0);
    CHECK(j.dof == c.dof);
    CHECK(j.kind == c.kind);
    CHECK(j.dof + j.rank == 6);
    // Every twist of the basis is reciprocal to every wrench.
    for (Eigen::Index k = 0; k < j.twists.cols(); ++k)
      for (const auto& w : c.w) CHECK(reciprocal_product(j.twists.col(k), w) == Approx(0.0).margin(1e-9));
  }
}

TEST_CASE("Kinematics: planar from one coplanar (paper example 1)") {
  const Joint j =
      joint_of(coplanar_wrenches(Plane{Vec3(0, 0, 2), Vec3(0, 0, 1)}, Plane{Vec3(5, 1, 2), Vec3(0, 0, -3)}));
  CHECK(j.kind == JointKind::Planar);
  CHECK(j.dof == 3);
  CHECK(j.redundant == 0);
  CHECK(j.direction.isApprox(Vec3(0, 0, 1)));
  // Planar basis: rotation about z, translations along x and y.
  ScrewBasis expected(6, 3);
  expected << revolute_twist(Vec3(7, 7, 0), Vec3(0, 0, 1)), prismatic_twist(Vec3(1, 0, 0)),
      prismatic_twist(Vec3(0, 1, 0));
  CHECK(same_twist_space(j.twists, expected, unit_frame()));
}

TEST_CASE("Kinematics: prismatic from two coplanar (paper example 2)") {
  const auto w =
      concat(coplanar_wrenches(Plane{Vec3(0, 0, 0), Vec3(0, 0, 1)}, Plane{Vec3(1, 0.5, 0), Vec3(0, 0, -1)}),
             coplanar_wrenches(Plane{Vec3(0, 1, 0), Vec3(0, 1, 0)}, Plane{Vec3(3, 1, 0.5), Vec3(0, -1, 0)}));
  const Joint j = joint_of(w);
  CHECK(j.kind == JointKind::Prismatic);
  CHECK(j.dof == 1);
  CHECK(j.components == 6);
  CHECK(j.rank == 5);
  CHECK(j.redundant == 1);  // the couple about x appears in both constraints
  CHECK(j.direction.x() == Approx(1.0));
  CHECK(j.direction.y() == Approx(0.0).margin(1e-12));
  CHECK(j.direction.z() == Approx(0.0).margin(1e-12));
}

TEST_CASE("Kinematics: revolute from coaxial+coplanar") {
  // Paper section 4.3: rank(coaxial) = 4, rank(coplanar) = 3, rank of both together = 5.
  const Axis a1{Vec3(1, 2, 0), Vec3(0, 0, 1)}, a2{Vec3(1, 2, 5), Vec3(0, 0, -1)};
  const Plane p1{Vec3(0, 0, 0), Vec3(0, 0, 1)}, p2{Vec3(4, 4, 0), Vec3(0, 0, -1)};
  CHECK(joint_of(coaxial_wrenches(a1, a2)).rank == 4);
  CHECK(joint_of(coplanar_wrenches(p1, p2)).rank == 3);
  const Joint j = joint_of(concat(coaxial_wrenches(a1, a2), coplanar_wrenches(p1, p2)));
  CHECK(j.kind == JointKind::Revolute);
  CHECK(j.dof == 1);
  CHECK(j.components == 7);
  CHECK(j.rank == 5);
  CHECK(j.redundant == 2);
  CHECK(j.point.x() == Approx(1.0));
  CHECK(j.point.y() == Approx(2.0));
  CHECK(j.point.z() == Approx(0.0).margin(1e-12));
  CHECK(j.direction.z() == Approx(1.0));
  REQUIRE(j.twists.cols() == 1);
  CHECK(j.twists.col(0).isApprox(revolute_twist(Vec3(1, 2, 0), Vec3(0, 0, 1))));

  SECTION("the file of the example") {
    const Assembly a = load_assembly(example_path("revolute.json"));
    const Analysis an = analyze(a);
    REQUIRE(an.joints.size() == 1);
    CHECK(an.joints[0].joint.kind == JointKind::Revolute);
    CHECK(an.joints[0].joint.redundant == 2);
    CHECK(an.part_dof[1] == 1);
  }
}

TEST_CASE("Kinematics: cylindrical from coaxial") {
  const Joint j =
      joint_of(coaxial_wrenches(Axis{Vec3(1, 2, 0), Vec3(1, 1, 0)}, Axis{Vec3(3, 4, 0), Vec3(-1, -1, 0)}));
  CHECK(j.kind == JointKind::Cylindrical);
  CHECK(j.dof == 2);
  CHECK(j.redundant == 0);
  CHECK(j.direction.x() == Approx(std::sqrt(0.5)));
  CHECK(j.direction.y() == Approx(std::sqrt(0.5)));
  // point of the axis nearest to the origin
  CHECK(j.point.x() == Approx(-0.5));
  CHECK(j.point.y() == Approx(0.5));
  CHECK(j.point.z() == Approx(0.0).margin(1e-12));
}

TEST_CASE("Kinematics: spherical from spherical") {
  const Joint j = joint_of(spherical_wrenches(Vec3(1, 2, 3), Vec3(1, 2, 3)));
  CHECK(j.kind == JointKind::Spherical);
  CHECK(j.dof == 3);
  CHECK(j.point.x() == Approx(1.0));
  CHECK(j.point.y() == Approx(2.0));
  CHECK(j.point.z() == Approx(3.0));
}

TEST_CASE("Kinematics: helical with pitch from align+point_on_line+line_surface_distance") {
  // A force along (0, 1, 2) through (-1, 0, 0) is reciprocal to the screw about z with pitch 1/2.
  const auto w =
      concat(concat(align_wrenches(Plane{Vec3(0, 0, 0), Vec3(0, 0, 1)}, Plane{Vec3(0, 0, 3), Vec3(0, 0, -1)}),
                    point_on_line_wrenches(Vec3(0, 0, 0), Axis{Vec3(0, 0, 1), Vec3(0, 0, 1)})),
             line_surface_distance_wrenches(Axis{Vec3(-1, 0, 0), Vec3(0, 2, -1)},
                                            Plane{Vec3(-1, -1, -2), Vec3(0, 1, 2)}));
  const Joint j = joint_of(w);
  CHECK(j.kind == JointKind::Helical);
  CHECK(j.dof == 1);
  CHECK(j.pitch == Approx(0.5));
  CHECK(j.redundant == 1);
  CHECK(j.point.norm() == Approx(0.0).margin(1e-9));
  CHECK(j.direction.z() == Approx(1.0));

  SECTION("a helical twist given directly, off the origin, negative pitch") {
    ScrewBasis t(6, 1);
    t.col(0) = helical_twist(Vec3(3, -2, 7), Vec3(1, 1, 1), -0.3);
    const Joint h = classify_twists(t, unit_frame());
    CHECK(h.kind == JointKind::Helical);
    CHECK(h.pitch == Approx(-0.3));
    CHECK(((h.point - Vec3(3, -2, 7)).cross(Vec3(1, 1, 1).normalized())).norm() == Approx(0.0).margin(1e-9));
  }
  SECTION("the file of the example") {
    const Assembly a = load_assembly(example_path("helical.json"));
    const Analysis an = analyze(a);
    REQUIRE(an.joints.size() == 1);
    CHECK(an.joints[0].joint.kind == JointKind::Helical);
    CHECK(an.joints[0].joint.pitch * 2 * kPi == Approx(kPi));
  }
}

TEST_CASE("Kinematics: fixed and unrecognized joints") {
  const Axis a1{Vec3(0, 0, 0), Vec3(0, 0, 1)}, a2{Vec3(0, 0, 5), Vec3(0, 0, -1)};
  const Plane p1{Vec3(0, 0, 0), Vec3(0, 0, 1)}, p2{Vec3(1, 0, 0), Vec3(0, 0, -1)};
  SECTION("a revolute blocked by a point on a line off the axis is fixed") {
    const auto w = concat(concat(coaxial_wrenches(a1, a2), coplanar_wrenches(p1, p2)),
                          point_on_line_wrenches(Vec3(2, 0, 0), Axis{Vec3(2, 0, 1), Vec3(0, 0, 1)}));
    const Joint j = joint_of(w);
    CHECK(j.kind == JointKind::Fixed);
    CHECK(j.dof == 0);
    CHECK(j.twists.cols() == 0);
    CHECK(j.rank == 6);
    CHECK(j.redundant == 3);
  }
  SECTION("coplanar plus a perpendicular align leaves two translations") {
    const auto w = concat(coplanar_wrenches(p1, p2), align_wrenches(Plane{Vec3(0, 0, 0), Vec3(0, 1, 0)},
                                                                    Plane{Vec3(0, 3, 0), Vec3(0, 1, 0)}));
    const Joint j = joint_of(w);
    CHECK(j.kind == JointKind::Unrecognized);
    CHECK(j.dof == 2);
    CHECK(j.redundant == 1);
    // reduced row echelon form: translations along x and y
    REQUIRE(j.twists.cols() == 2);
    CHECK(j.twists.col(0).isApprox(prismatic_twist(Vec3(1, 0, 0))));
    CHECK(j.twists.col(1).isApprox(prismatic_twist(Vec3(0, 1, 0))));
  }
  SECTION("point on line has four dof") {
    const Joint j = joint_of(point_on_line_wrenches(Vec3(0, 0, 3), a1));
    CHECK(j.kind == JointKind::Unrecognized);
    CHECK(j.dof == 4);
  }
}

TEST_CASE("Kinematics: twist sum along serial chains, intersection over parallel paths") {
  // A planar four-bar: ground pins at (0,0) and (4,0), crank tip (1,2), rocker tip (4,3).
  const std::string text = R"({ "assembly": 1, "parts": ["ground", "crank", "coupler", "rocker"],
    "ground": "ground", "constraints": [)" +
                           pin("ground", "crank", 0, 0) + "," + pin("crank", "coupler", 1, 2) + "," +
                           pin("coupler", "rocker", 4, 3) + "," + pin("ground", "rocker", 4, 0) + "]}";
  const Assembly a = parse_assembly(text);
  const Analysis an = analyze(a);
  const NumericFrame& f = an.frame;
  auto T = [&](const char* x, const char* y) {
    const int j = an.find_joint(a.part_index(x), a.part_index(y));
    REQUIRE(j >= 0);
    return an.joints[static_cast<std::size_t>(j)].joint.twists;
  };
  CHECK(an.mobility == 1);
  CHECK(an.loop_redundant == 3);  // a planar loop of four revolutes in space
  for (const char* p : {"crank", "coupler", "rocker"}) {
    CAPTURE(p);
    CHECK(an.part_dof[static_cast<std::size_t>(a.part_index(p))] == 1);
  }
  // coupler: two serial paths, each a sum of two revolutes, intersected
  const ScrewBasis left = twist_sum(T("ground", "crank"), T("crank", "coupler"), f);
  const ScrewBasis right = twist_sum(T("ground", "rocker"), T("coupler", "rocker"), f);
  CHECK(twist_dimension(left, f) == 2);
  CHECK(twist_dimension(right, f) == 2);
  const ScrewBasis both = twist_intersection(left, right, f);
  CHECK(twist_dimension(both, f) == 1);
  CHECK(same_twist_space(both, an.part_twists[static_cast<std::size_t>(a.part_index("coupler"))], f));
  // crank: its own revolute intersected with the three-joint path around the loop
  const ScrewBasis around =
      twist_sum(twist_sum(T("ground", "rocker"), T("coupler", "rocker"), f), T("crank", "coupler"), f);
  CHECK(same_twist_space(twist_intersection(T("ground", "crank"), around, f),
                         an.part_twists[static_cast<std::size_t>(a.part_index("crank"))], f));

  SECTION("opened loop: a serial chain is the sum of its joints") {
    Assembly open = a;
    open.constraints.resize(6);
    const Analysis ao = analyze(open);
    CHECK(ao.mobility == 3);
    CHECK(ao.loop_redundant == 0);
    const ScrewBasis chain = twist_sum(left, T("coupler", "rocker"), f);
    CHECK(twist_dimension(chain, f) == 3);
    CHECK(same_twist_space(chain, ao.part_twists[static_cast<std::size_t>(a.part_index("rocker"))], f));
  }
}

TEST_CASE("Kinematics: hydraulic grab part mobilities") {
  const Assembly a = load_assembly(example_path("grab.json"));
  REQUIRE(a.parts.size() == 12);
  int coplanar = 0, coaxial = 0;
  for (const auto& c : a.constraints) {
    coplanar += c.type == ConstraintType::Coplanar;
    coaxial += c.type == ConstraintType::Coaxial;
  }
  CHECK(coplanar == 12);
  CHECK(coaxial == 15);

  const Analysis an = analyze(a);
  REQUIRE(an.joints.size() == 15);
  int revolute = 0, cylindrical = 0, redundant = 0;
  for (const auto& pj : an.joints) {
    revolute += pj.joint.kind == JointKind::Revolute;
    cylindrical += pj.joint.kind == JointKind::Cylindrical;
    redundant += pj.joint.redundant;
  }
  CHECK(revolute == 12);
  CHECK(cylindrical == 3);
  CHECK(redundant == 24);
  CHECK(an.over_constrained().size() == 12);
  CHECK(an.mobility == 3);
  CHECK(an.loop_redundant == 9);

  const std::vector<std::pair<const char*, int>> expected = {
      {"ground", 0},  {"boom", 1}, {"stick", 2},   {"jaw_left", 3}, {"jaw_right", 3}, {"link", 3},
      {"barrel1", 1}, {"rod1", 1}, {"barrel2", 2}, {"rod2", 2},     {"barrel3", 3},   {"rod3", 3}};
  for (const auto& [name, dof] : expected) {
    CAPTURE(name);
    CHECK(an.part_dof[static_cast<std::size_t>(a.part_index(name))] == dof);
  }
  // Every part moves in the plane of the linkage: each twist is a rotation about z or a
  // translation in xy.
  for (const auto& b : an.part_twists)
    for (Eigen::Index k = 0; k < b.cols(); ++k) {
      CHECK(b(0, k) == Approx(0.0).margin(1e-9));
      CHECK(b(1, k) == Approx(0.0).margin(1e-9));
      CHECK(b(5, k) == Approx(0.0).margin(1e-9));
    }

  SECTION("the committed DOT graph is up to date") {
    CHECK(report_dot(a, an) == read_text(example_path("grab.dot")));
  }
  SECTION("motion of a jaw: three revolutes from the ground, ranges from the file") {
    const sweep::Motion m = motion_for(a, an, a.part_index("jaw_left"), {});
    REQUIRE(m.joints.size() == 3);
    CHECK(m.joints[0].point.norm() == Approx(0.0).margin(1e-12));
    CHECK(m.joints[1].point.x() == Approx(4.0));
    CHECK(m.joints[1].point.y() == Approx(2.0));
    CHECK(m.joints[2].point.x() == Approx(4.3));
    CHECK(m.joints[2].point.y() == Approx(-1.0));
    for (const auto& j : m.joints) {
      CHECK(j.type == sweep::JointType::Revolute);
      CHECK(j.direction.z() == Approx(1.0));
    }
    CHECK(m.joints[0].lo == Approx(-20.0));
    CHECK(m.joints[0].hi == Approx(30.0));
    CHECK(m.joints[2].lo == Approx(0.0).margin(1e-12));
    CHECK(m.joints[2].hi == Approx(35.0));
    const auto mj = motion_json(m);
    CHECK(mj["kind"] == "axes");
    CHECK(mj["joints"].size() == 3);
  }
  SECTION("motion of a rod goes through revolutes, not through its cylinder") {
    RangeSpec r = resolve_range_key(a, "rod3", "--range");
    r.lo = -5;
    r.hi = 5;
    const sweep::Motion m = motion_for(a, an, a.part_index("rod3"), {r});
    REQUIRE(m.joints.size() == 4);
    CHECK(m.joints[3].point.x() == Approx(4.0));
    CHECK(m.joints[3].point.y() == Approx(-0.8));
    CHECK(m.joints[3].lo == Approx(-5.0));
    try {
      motion_for(a, an, a.part_index("rod3"), {});
      FAIL("no error for a joint without a range");
    } catch (const InputError& e) {
      CHECK(e.pointer() == "/ranges");
      CHECK(std::string(e.what()).find("jaw_left-rod3") != std::string::npos);
    }
  }
}

TEST_CASE("Kinematics: same classification after a rigid motion and after reordering constraints") {
  std::mt19937 rng(2024);
  for (const char* file : {"planar.json", "prismatic.json", "revolute.json", "cylindrical.json",
                           "spherical.json", "helical.json", "grab.json"}) {
    CAPTURE(file);
    const Assembly a = load_assembly(example_path(file));
    const Analysis ref = analyze(a);
    for (int trial = 0; trial < 4; ++trial) {
      CAPTURE(trial);
      const Eigen::Isometry3d T = random_motion(rng);
      const Assembly b = reordered(moved(a, T), rng);
      const Analysis an = analyze(b);
      REQUIRE(an.joints.size() == ref.joints.size());
      CHECK(an.mobility == ref.mobility);
      CHECK(an.loop_redundant == ref.loop_redundant);
      CHECK(an.part_dof == ref.part_dof);
      for (std::size_t j = 0; j < ref.joints.size(); ++j) {
        const Joint &x = ref.joints[j].joint, &y = an.joints[j].joint;
        CHECK(an.joints[j].parts == ref.joints[j].parts);
        CHECK(y.kind == x.kind);
        CHECK(y.dof == x.dof);
        CHECK(y.redundant == x.redundant);
        CHECK(y.pitch == Approx(x.pitch).margin(1e-9));
        CHECK(same_twist_space(transformed(x.twists, T), y.twists, an.frame));
      }
      for (std::size_t p = 0; p < a.parts.size(); ++p)
        CHECK(same_twist_space(transformed(ref.part_twists[p], T), an.part_twists[p], an.frame));
    }
  }
}

TEST_CASE("Kinematics: examples/joints expected classification") {
  struct Expect {
    const char* file;
    const char* type;
    int dof, redundant;
  };
  for (const Expect& e :
       {Expect{"planar.json", "planar", 3, 0}, Expect{"prismatic.json", "prismatic", 1, 1},
        Expect{"revolute.json", "revolute", 1, 2}, Expect{"cylindrical.json", "cylindrical", 2, 0},
        Expect{"spherical.json", "spherical", 3, 0}, Expect{"helical.json", "helical", 1, 1}}) {
    CAPTURE(e.file);
    const Assembly a = load_assembly(example_path(e.file));
    const auto j = report_json(a, analyze(a));
    REQUIRE(j["joints"].size() == 1);
    CHECK(j["joints"][0]["type"] == e.type);
    CHECK(j["joints"][0]["dof"] == e.dof);
    CHECK(j["joints"][0]["redundant"] == e.redundant);
    REQUIRE(j["parts"].size() == 1);
    CHECK(j["parts"][0]["dof"] == e.dof);
  }
}

TEST_CASE("Kinematics: JSON report shape (SPEC.md)") {
  const Assembly a = parse_assembly(kRevolute);
  const auto j = report_json(a, analyze(a));
  REQUIRE(j["joints"].size() == 1);
  const auto& joint = j["joints"][0];
  CHECK(joint["parts"] == nlohmann::ordered_json({"ground", "crank"}));
  CHECK(joint["type"] == "revolute");
  CHECK(joint["dof"] == 1);
  REQUIRE(joint["twists"].size() == 1);
  const std::vector<double> expected = {0, 0, 1, 0, 0, 0};
  for (std::size_t i = 0; i < 6; ++i)
    CHECK(joint["twists"][0][i].get<double>() == Approx(expected[i]).margin(1e-12));
  CHECK(joint["redundant"] == 2);
  // Every part but the ground; the unconstrained ones are free.
  REQUIRE(j["parts"].size() == 3);
  CHECK(j["parts"][0]["name"] == "crank");
  CHECK(j["parts"][0]["dof"] == 1);
  CHECK(j["parts"][1]["dof"] == 6);
  CHECK(j["parts"][2]["dof"] == 6);
  // The compact text is valid JSON with the same content.
  const auto again = nlohmann::ordered_json::parse(format_json(j));
  CHECK(again["joints"][0]["type"] == "revolute");
  CHECK(again["parts"][0]["dof"] == 1);
}

TEST_CASE("Kinematics: geometry within the tolerance still classifies, beyond it is an error") {
  // Off by 1e-8 in direction and position: well inside the default 1e-6 relative tolerance.
  const Assembly a =
      parse_assembly(edited(R"("axis2": { "point": [0, 0, 5], "direction": [0, 0, -1] })",
                            R"("axis2": { "point": [1e-8, 0, 5], "direction": [1e-8, 0, -1] })"));
  const Analysis an = analyze(a);
  REQUIRE(an.joints.size() == 1);
  CHECK(an.joints[0].joint.kind == JointKind::Revolute);
  CHECK(an.joints[0].joint.redundant == 2);
  // The file may loosen the tolerance (model units).
  const std::string loose = edited(R"("point": [0, 0, 5])", R"("point": [0.001, 0, 5])");
  CHECK_THROWS_AS(parse_assembly(loose), InputError);
  std::string with_tol = loose;
  with_tol.replace(with_tol.find(R"("ground": "ground")"), 18, R"("ground": "ground", "tolerance": 0.01)");
  const Assembly b = parse_assembly(with_tol);
  CHECK(analyze(b).joints[0].joint.kind == JointKind::Revolute);
}

TEST_CASE("Kinematics: constraint-level ranges") {
  const std::string text = edited(R"("type": "coplanar", "parts": ["ground", "crank"],)",
                                  R"("type": "coplanar", "parts": ["ground", "crank"], "range": [-30, 60],)");
  const Assembly a = parse_assembly(text);
  const sweep::Motion m = motion_for(a, analyze(a), a.part_index("crank"), {});
  REQUIRE(m.joints.size() == 1);
  CHECK(m.joints[0].lo == Approx(-30.0));
  CHECK(m.joints[0].hi == Approx(60.0));
  // A second, different range for the same joint is a conflict.
  std::string conflict = text;
  conflict.replace(conflict.find(R"("ground": "ground")"), 18,
                   R"("ground": "ground", "ranges": {"crank-ground": [0, 1]})");
  require_input_error(conflict, "/ranges/crank-ground", "conflicts");
}

TEST_CASE("Kinematics: motion errors") {
  SECTION("a cylindrical joint cannot drive a motion") {
    const Assembly a = load_assembly(example_path("cylindrical.json"));
    const Analysis an = analyze(a);
    try {
      motion_for(a, an, a.part_index("rod"), {});
      FAIL("no error");
    } catch (const InputError& e) {
      CHECK(e.pointer() == "/constraints/0");
      CHECK(std::string(e.what()).find("cylindrical") != std::string::npos);
    }
  }
  SECTION("the ground and unconnected parts") {
    const Assembly a = parse_assembly(kRevolute);
    const Analysis an = analyze(a);
    CHECK_THROWS_AS(motion_for(a, an, a.ground, {}), InputError);
    CHECK_THROWS_AS(motion_for(a, an, a.part_index("slider"), {}), InputError);
  }
  SECTION("range keys") {
    const Assembly a = parse_assembly(kRevolute);
    CHECK(resolve_range_key(a, "crank-ground", "k").joint == std::array<int, 2>{{0, 1}});
    CHECK(resolve_range_key(a, "crank", "k").part == 1);
    CHECK_THROWS_AS(resolve_range_key(a, "rod-slider", "k"), InputError);  // not constrained
    CHECK_THROWS_AS(resolve_range_key(a, "ground", "k"), InputError);
  }
}

TEST_CASE("Kinematics: bad input errors name the JSON pointer") {
  SECTION("unknown part") {
    require_input_error(edited(R"("parts": ["ground", "crank"],
      "axis1")",
                               R"("parts": ["ground", "crankk"],
      "axis1")"),
                        "/constraints/0/parts/1", "unknown part \"crankk\"");
  }
  SECTION("a part constrained with itself") {
    require_input_error(edited(R"("parts": ["ground", "crank"],
      "plane1")",
                               R"("parts": ["crank", "crank"],
      "plane1")"),
                        "/constraints/1/parts", "itself");
  }
  SECTION("degenerate axis direction") {
    require_input_error(edited(R"("direction": [0, 0, -1])", R"("direction": [0, 0, 0])"),
                        "/constraints/0/axis2/direction", "degenerate");
  }
  SECTION("zero normal") {
    require_input_error(edited(R"("normal": [0, 0, 1])", R"("normal": [0, 0, 0])"),
                        "/constraints/1/plane1/normal", "normal");
  }
  SECTION("unknown constraint type") {
    require_input_error(edited(R"("type": "coplanar")", R"("type": "glued")"), "/constraints/1/type",
                        "unknown constraint type \"glued\"");
  }
  SECTION("missing field") {
    require_input_error(edited(R"("axis1": { "point": [0, 0, 0], "direction": [0, 0, 1] },)", ""),
                        "/constraints/0/axis1", "missing");
  }
  SECTION("ground not among the parts") {
    require_input_error(edited(R"("ground": "ground")", R"("ground": "floor")"), "/ground",
                        "not among the parts");
  }
  SECTION("unknown field") {
    require_input_error(edited(R"("ground": "ground")", R"("ground": "ground", "grund": 1)"), "/grund",
                        "unknown field");
  }
  SECTION("field of another constraint type") {
    require_input_error(edited(R"("type": "coaxial",  "parts": ["ground", "crank"],)",
                               R"("type": "coaxial",  "parts": ["ground", "crank"], "plane1": {},)"),
                        "/constraints/0/plane1", "unknown field");
  }
  SECTION("point not an array of three numbers") {
    require_input_error(edited(R"("point": [0, 0, 5])", R"("point": [0, 5])"), "/constraints/0/axis2/point",
                        "3 numbers");
  }
  SECTION("axes that are not coaxial at the assembled position") {
    require_input_error(edited(R"("point": [0, 0, 5])", R"("point": [0, 0.5, 5])"),
                        "/constraints/0/axis2/point", "not on the line");
  }
  SECTION("planes that are not coplanar") {
    require_input_error(edited(R"("point": [1, 0, 0])", R"("point": [1, 0, 0.1])"),
                        "/constraints/1/plane2/point", "not in plane1");
  }
  SECTION("unsupported version") {
    require_input_error(edited(R"("assembly": 1)", R"("assembly": 2)"), "/assembly", "version");
  }
  SECTION("duplicate part") {
    require_input_error(edited(R"("rod", "slider")", R"("rod", "rod")"), "/parts/3", "duplicate");
  }
  SECTION("range with a name that is neither a part nor a joint") {
    require_input_error(
        edited(R"("ground": "ground")", R"("ground": "ground", "ranges": {"ground-rod": [0, 1]})"),
        "/ranges/ground-rod", "neither");
  }
  SECTION("range with lo > hi") {
    require_input_error(edited(R"("ground": "ground")", R"("ground": "ground", "ranges": {"crank": [1, 0]})"),
                        "/ranges/crank", "lo <= hi");
  }
  SECTION("invalid JSON has a line and column") {
    try {
      parse_assembly("{\n  \"assembly\": 1,\n  \"parts\": [\n}");
      FAIL("no error");
    } catch (const InputError& e) {
      CHECK(e.pointer().empty());
      CHECK(e.line() == 4);
    }
  }
  SECTION("unreadable file") {
    CHECK_THROWS_AS(load_assembly(example_path("no_such_file.json")), InputError);
  }
}
