#pragma once
// A seeded generator of one-joint sweeps of primitives (box, sphere, cylinder, cone, torus, elliptic
// cylinder) about axes through, beside and away from the entity, oblique or not, for revolute
// ranges up to 720 degrees, prismatic strokes and helical pitches from overlapping to far-apart
// turns, 0.25 to 3 turns. Case i has entity kind i % 6 and joint kind (i / 6) % 3, so every 18
// consecutive cases hold each pair once. Each case is a spec text (degrees), so it goes through
// the parser as a user's file does.
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

namespace sweep::testing {

struct RandomCase {
  std::string name;  ///< kind, joint type and index
  std::string spec;  ///< the spec's JSON
};

/// The entity kinds and joint types of the generator, in the order case indices cycle through them.
inline const char* const kRandomKinds[] = {"box", "sphere", "cylinder", "cone", "torus", "elliptic_cylinder"};
inline const char* const kRandomJoints[] = {"revolute", "prismatic", "helical"};
inline constexpr int kRandomKindCount = 6;
/// Case i's entity kind (an index into kRandomKinds) and joint type (into kRandomJoints).
inline int random_case_kind(int index) { return index % kRandomKindCount; }
inline int random_case_joint(int index) { return (index / kRandomKindCount) % 3; }

/// A number as the specs print it (six decimals).
inline std::string fixed6(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6f", v);
  return b;
}

/// How far from the origin a joint's axis point is drawn: through the entity's region, beside it
/// or away from it. `uni()` draws from the case's stream in [0, 1).
template <class Uni>
double random_axis_reach(Uni& uni) {
  return uni() < 0.4 ? 0.5 : (uni() < 0.5 ? 1.5 : 3.0);
}

/// The end of a joint's JSON after its direction: its range, and a helical joint's pitch, as the
/// generators draw them (revolute 20 to 340 degrees, one in ten 720; prismatic strokes 0.3 to 3;
/// helical 0.25 to 3 turns of pitch 0.3 to 1.5, overlapping, or 2 to 5, apart). `in(a, b)` and
/// `uni()` draw from the case's stream.
template <class In, class Uni>
std::string random_joint_range(const std::string& type, In& in, Uni& uni) {
  if (type == "revolute") {
    const double deg = uni() < 0.1 ? 720.0 : in(20, 340);
    return ", \"range\": [0, " + fixed6(deg) + "]}";
  }
  if (type == "prismatic") return ", \"range\": [0, " + fixed6(in(0.3, 3)) + "]}";
  const double turns = in(0.25, 3);
  const double pitch = uni() < 0.5 ? in(0.3, 1.5) : in(2, 5);
  return ", \"pitch\": " + fixed6(pitch) + ", \"range\": [0, " + fixed6(360 * turns) + "]}";
}

inline RandomCase random_one_joint_case(std::uint64_t seed, int index) {
  std::mt19937_64 rng(seed * 1000003ULL + std::uint64_t(index));
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  auto in = [&](double a, double b) { return a + (b - a) * uni(rng); };
  auto u = [&]() { return uni(rng); };
  // (every draw in a statement of its own, so that every compiler draws alike; z before y before
  // x, and the later fields of an entity first, is the order the tables in tests/data were made in)
  auto vec = [&](double s) {
    const double z = in(-s, s), y = in(-s, s), x = in(-s, s);
    char b[96];
    std::snprintf(b, sizeof b, "[%.6f, %.6f, %.6f]", x, y, z);
    return std::string(b);
  };
  const auto num = fixed6;
  auto unit = [&]() {
    for (;;) {
      const double x = in(-1, 1), y = in(-1, 1), z = in(-1, 1), n = std::sqrt(x * x + y * y + z * z);
      if (n > 0.2 && n <= 1) {
        char b[96];
        std::snprintf(b, sizeof b, "[%.6f, %.6f, %.6f]", x / n, y / n, z / n);
        return std::string(b);
      }
    }
  };
  const std::string kind = kRandomKinds[random_case_kind(index)];
  std::string entity;
  if (kind == "box") {
    const double x = in(-1, 0.5), y = in(-1, 0.5), z = in(-1, 0.5);
    const double dz = in(0.3, 1.5), dy = in(0.3, 1.5), dx = in(0.3, 1.5);
    entity = "{\"kind\": \"box\", \"min\": [" + num(x) + ", " + num(y) + ", " + num(z) + "], \"max\": [" +
             num(x + dx) + ", " + num(y + dy) + ", " + num(z + dz) + "]}";
  } else if (kind == "sphere") {
    const double radius = in(0.3, 1.2);
    const std::string center = vec(1);
    entity = "{\"kind\": \"sphere\", \"center\": " + center + ", \"radius\": " + num(radius) + "}";
  } else if (kind == "cylinder") {
    const double height = in(0.5, 2), radius = in(0.2, 0.8);
    const std::string axis = unit(), base = vec(1);
    entity = "{\"kind\": \"cylinder\", \"base\": " + base + ", \"axis\": " + axis + ", \"radius\": " + num(radius) +
             ", \"height\": " + num(height) + "}";
  } else if (kind == "cone") {
    const bool pointed = uni(rng) < 0.3;
    const double height = in(0.5, 2);
    const double radius2 = pointed ? 0.0 : in(0.1, 0.6);
    const double radius1 = in(0.3, 0.9);
    const std::string axis = unit(), base = vec(1);
    entity = "{\"kind\": \"cone\", \"base\": " + base + ", \"axis\": " + axis + ", \"radius1\": " + num(radius1) +
             ", \"radius2\": " + num(radius2) + ", \"height\": " + num(height) + "}";
  } else if (kind == "elliptic_cylinder") {
    const double a = in(0.3, 1.0);
    const double height = in(0.5, 2), ratio = in(0.25, 0.9);
    const std::string axis = unit(), base = vec(1);
    entity = "{\"kind\": \"elliptic_cylinder\", \"base\": " + base + ", \"axis\": " + axis + ", \"a\": " + num(a) +
             ", \"b\": " + num(a * ratio) + ", \"height\": " + num(height) + "}";
  } else {
    const double minor = in(0.15, 0.5);
    const double major = minor + in(0.3, 1.2);
    const std::string axis = unit(), center = vec(1);
    entity = "{\"kind\": \"torus\", \"center\": " + center + ", \"axis\": " + axis + ", \"major\": " + num(major) +
             ", \"minor\": " + num(minor) + "}";
  }
  // the axis: through the entity's region, beside it or away from it
  const double reach = random_axis_reach(u);
  const std::string point = vec(reach);
  const std::string direction = uni(rng) < 0.3 ? "[0, 0, 1]" : unit();
  const std::string type = kRandomJoints[random_case_joint(index)];
  const std::string joint = "{\"type\": \"" + type + "\", \"point\": " + point + ", \"direction\": " + direction +
                            random_joint_range(type, in, u);
  RandomCase c;
  c.name = kind + "_" + type + "_" + std::to_string(index);
  c.spec = "{\"sweep\": 1, \"name\": \"" + c.name + "\", \"angles\": \"deg\", \"entity\": " + entity +
           ", \"motion\": {\"kind\": \"axes\", \"joints\": [" + joint + "]}}";
  return c;
}

}  // namespace sweep::testing

#include "sweep/orbit.hpp"
#include "sweep/spec.hpp"

namespace sweep::testing {

/// A one-joint sweep as the orbit integrals take it: the body where the joint's range starts, the
/// joint, and the range's length (a revolute's at most a turn).
struct JointSweep {
  OrbitSolidPtr body;
  ScrewJoint j;
  double T = 0;
};

/// The sweep of `body` (as orbit intervals, in the entity's frame) by the spec's one joint.
inline JointSweep joint_sweep_of(const Spec& spec, const OrbitSolidPtr& body) {
  const Motion& m = spec.motion.motion;
  JointSweep s;
  s.j = m.joints.at(0);
  s.T = std::min(s.j.hi - s.j.lo, s.j.type == JointType::Revolute ? 2 * M_PI : 1e300);
  s.body = orbit_placed(body, s.j.transform(s.j.lo) * m.home);
  return s;
}

/// The volume of a one-joint sweep of a primitive, integrated over orbit space from the entity's
/// orbit intervals (sweep/orbit.hpp): it never looks at a B-rep. *err: its error estimate.
inline double reference_volume(const Spec& spec, double rel_tol, double* err) {
  const JointSweep s = joint_sweep_of(spec, make_orbit_solid(spec.entity));
  return joint_sweep_volume(*s.body, s.j, s.T, rel_tol, err);
}

}  // namespace sweep::testing
