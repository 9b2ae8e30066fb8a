// The examples of seed 000 (examples/paper): each spec's chain reproduces the paper's printed
// position vector xi(q), and Monte Carlo membership in the image of (q, s) -> M(q) Gamma(s)
// (the independent volume check for points, curves and surfaces) agrees with exact volumes.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <random>

#include "sweep/membership.hpp"
#include "sweep/spec.hpp"

namespace {

using Eigen::Vector3d;
using sweep::Spec;

Spec paper_spec(const std::string& name) { return sweep::load_spec(SWEEP_SOURCE_DIR "/examples/paper/" + name); }

/// Largest distance, over random joint and entity parameters in their ranges, between the spec's
/// motion applied to its entity and the paper's formula xi(q1..qn, s...).
double largest_gap(const Spec& spec, const std::function<Vector3d(const std::vector<double>&)>& xi) {
  auto pe = sweep::ParametricEntity::make(spec.entity);
  REQUIRE(pe);
  const sweep::Motion& m = spec.motion.motion;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  REQUIRE(spec.motion.dh.size() == m.dof());
  for (int k = 0; k < 200; ++k) {
    // q as the paper writes it (the DH variable), and the joint coordinates it gives (theta or d)
    std::vector<double> q, coord;
    for (const auto& row : spec.motion.dh) {
      q.push_back(row.lo + (row.hi - row.lo) * u(rng));
      coord.push_back((row.type == sweep::JointType::Prismatic ? row.d : row.theta).eval(&q.back()));
    }
    std::vector<double> s;
    for (std::size_t i = 0; i < pe->num_params(); ++i) s.push_back(pe->lo(i) + (pe->hi(i) - pe->lo(i)) * u(rng));
    std::vector<double> all = q;
    all.insert(all.end(), s.begin(), s.end());
    worst = std::max(worst, (m.transform(coord) * pe->eval(s.data()) - xi(all)).norm());
  }
  return worst;
}

/// Extends `box` over sampled image points, 5 % larger on each side; returns the image's size.
double sampled_box(const Spec& spec, Eigen::AlignedBox3d& box) {
  auto pe = sweep::ParametricEntity::make(spec.entity);
  const sweep::Motion& m = spec.motion.motion;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 20000; ++k) {
    std::vector<double> q, s;
    for (const auto& j : m.joints) q.push_back(j.lo + (j.hi - j.lo) * u(rng));
    for (std::size_t i = 0; i < pe->num_params(); ++i) s.push_back(pe->lo(i) + (pe->hi(i) - pe->lo(i)) * u(rng));
    box.extend(m.transform(q) * pe->eval(s.data()));
  }
  const double size = box.sizes().maxCoeff();
  box.extend(box.min() - Vector3d::Constant(0.05 * size));
  box.extend(box.max() + Vector3d::Constant(0.05 * size));
  return size;
}

sweep::MonteCarloResult image_volume(const Spec& spec, std::size_t samples) {
  auto pe = sweep::ParametricEntity::make(spec.entity);
  Eigen::AlignedBox3d box;
  const double size = sampled_box(spec, box);
  return sweep::monte_carlo_volume(
      [&](const Vector3d& x) { return sweep::in_swept_image(*pe, spec.motion.motion, x, 1e-9 * size, size); }, box,
      samples, 11);
}

}  // namespace

TEST_CASE("Paper 4.1: the DH table reproduces eq. (16)") {
  const double gap = largest_gap(paper_spec("sec4_1_curve_three_revolutes.json"), [](const std::vector<double>& q) {
    const double c1 = std::cos(q[0]), s1 = std::sin(q[0]), c2 = std::cos(q[1]), s2 = std::sin(q[1]);
    const double c3 = std::cos(q[2]), s3 = std::sin(q[2]), c4 = std::cos(q[3]), s4 = std::sin(q[3]);
    return Vector3d(5 * c1 * c2 * c3 * c4 - 5 * c1 * s2 * s3 * c4 + 5 * s1 * s4 + 7 * c1 * c2 * s3 + 7 * c1 * s2 * c3 +
                        20 * c1 * c2,
                    5 * s1 * c2 * c3 * c4 - 5 * s1 * s2 * s3 * c4 - 5 * c1 * s4 + 7 * s1 * c2 * s3 + 7 * s1 * s2 * c3 +
                        20 * s1 * c2,
                    5 * s2 * c3 * c4 + 5 * c2 * s3 * c4 + 7 * s2 * s3 - 7 * c2 * c3 + 20 * s2 + 30);
  });
  CHECK(gap < 1e-11);
}

TEST_CASE("Paper 4.2: the DH table reproduces the printed matrices (q2 in 1T2)") {
  const double r3 = std::sqrt(3.0) / 2;  // the printed 0.866
  auto T = [&](double q, double d, double a) {
    Eigen::Matrix4d M;
    M << std::cos(q), -0.5 * std::sin(q), r3 * std::sin(q), a * std::cos(q), std::sin(q), 0.5 * std::cos(q),
        -r3 * std::cos(q), a * std::sin(q), 0, r3, 0.5, d, 0, 0, 0, 1;
    return M;
  };
  const double gap = largest_gap(paper_spec("sec4_2_curve_three_skew_revolutes.json"), [&](const std::vector<double>& q) {
    const Eigen::Vector4d g(3 * std::cos(q[3]) + 0.866 * std::sin(q[3]), 3 * std::sin(q[3]) - 0.866 * std::cos(q[3]), 3.5,
                            1);
    return Vector3d((T(q[0], 10, 10) * T(q[1], 8, 12) * T(q[2], 16, 20) * g).head<3>());
  });
  CHECK(gap < 1e-11);
}

TEST_CASE("Paper 4.3: the DH table reproduces the printed matrices") {
  const double gap = largest_gap(paper_spec("sec4_3_surface_revolve_two_extrusions.json"), [](const std::vector<double>& q) {
    Eigen::Matrix4d T1, T2, T3;
    T1 << 1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, q[0] + 10, 0, 0, 0, 1;
    T2 << 1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, q[1] + 7, 0, 0, 0, 1;
    T3 << std::sin(q[2]), 0, std::cos(q[2]), 0, -std::cos(q[2]), 0, std::sin(q[2]), 0, 0, -1, 0, 0, 0, 0, 0, 1;
    const Eigen::Vector4d g(5 * std::cos(q[4]), 5 + q[3], 5 * std::sin(q[4]), 1);
    return Vector3d((T1 * T2 * T3 * g).head<3>());
  });
  CHECK(gap < 1e-11);
}

TEST_CASE("Paper 4.4: the DH table reproduces eq. (23)") {
  const double gap = largest_gap(paper_spec("sec4_4_point_three_revolutes.json"), [](const std::vector<double>& q) {
    const double r = 10 * std::cos(q[1]) + 5 * std::cos(q[1] + q[2]);
    return Vector3d(r * std::cos(q[0]), r * std::sin(q[0]), 10 * std::sin(q[1]) + 5 * std::sin(q[1] + q[2]));
  });
  CHECK(gap < 1e-11);
}

TEST_CASE("Paper 4.6: the DH table reproduces the printed xi(q*)") {
  const double gap =
      largest_gap(paper_spec("sec4_6_hemisphere_two_revolutes_prismatic.json"), [](const std::vector<double>& q) {
        const double c1 = std::cos(q[0]), s1 = std::sin(q[0]), c2 = std::cos(q[1]), s2 = std::sin(q[1]), q3 = q[2];
        const double c4 = std::cos(q[3]), s4 = std::sin(q[3]), c5 = std::cos(q[4]), s5 = std::sin(q[4]);
        return Vector3d(-5 * s5 * c1 * s2 * s4 - 5 * s5 * s1 * c4 + 5 * c1 * c2 * c5 + 15 * c1 * c2 + q3 * c1 * c2,
                        -5 * s5 * s1 * s2 * s4 + 5 * s5 * c1 * c4 + 5 * s1 * c2 * c5 + 15 * s1 * c2 + q3 * s1 * c2,
                        5 * c2 * s4 * s5 + 5 * s2 * c5 + 15 * s2 + q3 * s2 + 25);
      });
  CHECK(gap < 1e-11);
}

TEST_CASE("Monte Carlo: samples where two memberships disagree estimate their symmetric difference") {
  const Eigen::AlignedBox3d box(Vector3d(-2, -2, -2), Vector3d(2, 2, 2));
  const auto ball = [](double r) { return [r](const Vector3d& x) { return x.norm() < r; }; };
  const std::size_t n = 200000;
  const auto same = sweep::monte_carlo_volume(ball(1.0), box, n, 7, ball(1.0));
  CHECK(same.mismatches == 0);
  CHECK(same.mismatch_volume == 0.0);
  // the shell between radii 1 and 1.1: 4/3 pi (1.331 - 1)
  const auto shell = sweep::monte_carlo_volume(ball(1.0), box, n, 7, ball(1.1));
  const double exact = 4.0 / 3.0 * M_PI * (1.331 - 1.0), f = exact / 64.0;
  CHECK(std::abs(shell.mismatch_volume - exact) < 4.5 * 64.0 * std::sqrt(f * (1 - f) / double(n)));
  // the volume itself is that of the first membership
  CHECK(std::abs(shell.volume - 4.0 / 3.0 * M_PI) < 4.5 * shell.stderr_);
}

TEST_CASE("Monte Carlo membership of swept points and surfaces matches exact volumes") {
  struct Case {
    const char* file;
    double exact;
    std::size_t samples;
  };
  for (const Case& c : {Case{"/examples/chains/point_two_revolutes_extrude.json", 6 * M_PI, 20000},
                        Case{"/examples/hemisphere_extrude.json", 125 * M_PI, 20000},
                        Case{"/examples/paper/sec4_4_point_three_revolutes.json", 9617.133396244355, 8000}}) {
    const Spec spec = sweep::load_spec(std::string(SWEEP_SOURCE_DIR) + c.file);
    const auto mc = image_volume(spec, c.samples);
    INFO(c.file << ": " << mc.volume << " +- " << mc.stderr_ << " against " << c.exact);
    CHECK(mc.stderr_ < 0.02 * c.exact);
    CHECK(std::abs(mc.volume - c.exact) < 4 * mc.stderr_);
  }
}

TEST_CASE("Membership in a swept curve: inside and outside points of a torus sector") {
  // A circle of radius 1 about (3, 0, 0) in the xz plane, revolved 180 degrees about z: the
  // surface of a half torus, whose image is a surface (no volume): points on it are members,
  // points off it by 1e-3 are not.
  Spec spec = sweep::parse_spec(R"J({"sweep": 1, "entity": {"kind": "curve", "params": {"t": [0, 6.283185307179586]},
      "xyz": ["3+cos(t)", "0", "sin(t)"]}, "motion": {"kind": "axes", "joints": [
      {"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, 3.141592653589793]}]}})J",
                                ".");
  auto pe = sweep::ParametricEntity::make(spec.entity);
  REQUIRE(pe);
  const sweep::Motion& m = spec.motion.motion;
  for (double phi : {0.3, 1.5, 3.0})
    for (double t : {0.1, 2.0, 4.0}) {
      const double r = 3 + std::cos(t);
      const Vector3d on(r * std::cos(phi), r * std::sin(phi), std::sin(t));
      CHECK(sweep::in_swept_image(*pe, m, on, 1e-9, 5.0));
      const Vector3d off = on + 1e-3 * Vector3d(std::cos(t) * std::cos(phi), std::cos(t) * std::sin(phi), std::sin(t));
      CHECK_FALSE(sweep::in_swept_image(*pe, m, off, 1e-9, 5.0));
    }
  // beyond the range of the joint
  CHECK_FALSE(sweep::in_swept_image(*pe, m, Vector3d(4, -0.2, 0), 1e-9, 5.0));
}

TEST_CASE("Membership in a swept image: the second-order exclusion gives the first-order answers") {
  // random chains of two or three joints of every kind, a point, a curve or a surface, and points
  // near the image (image points moved by 1e-6 to 1e-2 of the size in random directions) and far off
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const char* entities[3] = {R"J("kind": "point", "at": [0.3, -0.2, 0.5])J",
                             R"J("kind": "curve", "params": {"s": [0, 2]}, "xyz": ["1+0.5*cos(s)", "0.5*sin(s)", "0.2*s"])J",
                             R"J("kind": "surface", "params": {"u": [0, 1], "v": [0, 1]}, "xyz": ["u", "v", "0.3*u*v"])J"};
  const char* types[3] = {"revolute", "prismatic", "helical"};
  int compared = 0, decided_out = 0;
  for (int trial = 0; trial < 24; ++trial) {
    std::string joints;
    const int n = trial % 3 == 0 ? 3 : 2;
    for (int i = 0; i < n; ++i) {
      const double lo = u(rng), len = 0.5 + 2 * std::abs(u(rng));
      const std::string type = types[std::abs(int(3 * u(rng))) % 3];
      joints += std::string(i ? ", " : "") + "{\"type\": \"" + type +
                "\", \"point\": [" + std::to_string(u(rng)) + ", " + std::to_string(u(rng)) + ", " +
                std::to_string(u(rng)) + "], \"direction\": [" + std::to_string(u(rng)) + ", " +
                std::to_string(u(rng)) + ", " + std::to_string(u(rng) + 0.01) + "]" +
                (type == "helical" ? ", \"pitch\": 1.3" : "") + ", \"range\": [" +
                std::to_string(lo) + ", " + std::to_string(lo + len) + "]}";
    }
    const Spec spec = sweep::parse_spec(std::string("{\"sweep\": 1, \"entity\": {") + entities[trial % 3] +
                                            "}, \"motion\": {\"kind\": \"axes\", \"joints\": [" + joints + "]}}",
                                        ".");
    auto pe = sweep::ParametricEntity::make(spec.entity);
    REQUIRE(pe);
    const sweep::Motion& m = spec.motion.motion;
    for (int k = 0; k < 20; ++k) {
      std::vector<double> q, s;
      for (const auto& j : m.joints) q.push_back(j.lo + (j.hi - j.lo) * 0.5 * (1 + u(rng)));
      for (std::size_t i = 0; i < pe->num_params(); ++i) s.push_back(pe->lo(i) + (pe->hi(i) - pe->lo(i)) * 0.5 * (1 + u(rng)));
      const Vector3d on = m.transform(q) * pe->eval(s.data());
      const double off = std::pow(10.0, -6 + 4 * 0.5 * (1 + u(rng))) * 5.0;
      const Vector3d x = k % 5 == 4 ? Vector3d(9, 9, 9) : on + off * Vector3d(u(rng), u(rng), u(rng)).normalized();
      const int second = sweep::swept_image_membership(*pe, m, x, 1e-9, 5.0, 200000, true, true);
      const int first = sweep::swept_image_membership(*pe, m, x, 1e-9, 5.0, 200000, true, false);
      INFO("trial " << trial << " point " << k);
      if (first < 0) continue;  // the first-order search ran out of boxes
      CHECK(second == first);
      ++compared;
      decided_out += first == 0;
    }
  }
  CHECK(compared >= 300);
  CHECK(decided_out >= 60);
}
