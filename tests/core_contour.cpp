// The zero set of a function of two parameters traced on a grid (sweep/contour.hpp).
#include <catch2/catch.hpp>

#include <cmath>

#include "sweep/contour.hpp"

using Eigen::Vector2d;

TEST_CASE("A circle's implicit function gives one closed chain of exact roots", "[contour]") {
  const double r = 0.7;
  const sweep::ContourFunction f = [&](const Vector2d& p) { return p.squaredNorm() - r * r; };
  const auto chains = sweep::contour_chains(f, -1.1, 1.3, -0.9, 1.2, 31, 29, 1e-12);
  REQUIRE(chains.size() == 1);
  const auto dense = sweep::densified(f, chains[0]);
  CHECK(dense.size() > chains[0].size());
  CHECK((chains[0].front() - chains[0].back()).norm() < 1e-12);  // closed
  double turned = 0;
  for (std::size_t k = 0; k < dense.size(); ++k) {
    CHECK(std::abs(dense[k].norm() - r) < 1e-12);
    if (k > 0) turned += std::remainder(std::atan2(dense[k].y(), dense[k].x()) - std::atan2(dense[k - 1].y(), dense[k - 1].x()), 2 * M_PI);
  }
  CHECK(std::abs(std::abs(turned) - 2 * M_PI) < 1e-9);  // once around
}

TEST_CASE("Two crossing branches meet at the saddle inside a cell, open branches end on the sides", "[contour]") {
  const Vector2d c(0.013, -0.021);  // inside a cell, not on a grid line
  const sweep::ContourFunction f = [&](const Vector2d& p) { return (p.x() - c.x()) * (p.y() - c.y()); };
  const auto chains = sweep::contour_chains(f, -1, 1, -1, 1, 20, 20, 1e-12);
  REQUIRE(chains.size() == 4);
  for (const auto& ch : chains) {
    // between the saddle and a side of the square, every point on one of the two lines
    const bool saddle_first = (ch.front() - c).norm() < 1e-9;
    CHECK((saddle_first || (ch.back() - c).norm() < 1e-9));
    const Vector2d e = saddle_first ? ch.back() : ch.front();
    CHECK(std::abs(std::max(std::abs(e.x()), std::abs(e.y())) - 1) < 1e-12);
    for (const auto& p : ch) CHECK(std::min(std::abs(p.x() - c.x()), std::abs(p.y() - c.y())) < 1e-12);
  }
}

TEST_CASE("A function without a zero, or flat to the given level, has no chains", "[contour]") {
  const sweep::ContourFunction pos = [](const Vector2d& p) { return 1 + p.squaredNorm(); };
  CHECK(sweep::contour_chains(pos, -1, 1, -1, 1, 10, 10, 1e-12).empty());
  const sweep::ContourFunction flat = [](const Vector2d& p) { return 1e-14 * p.x(); };
  CHECK(sweep::contour_chains(flat, -1, 1, -1, 1, 10, 10, 1e-12).empty());
  CHECK(sweep::root_in_unit([](double t) { return t * t - 0.5; }, -0.5, 0.5) == Approx(std::sqrt(0.5)).epsilon(1e-14));
}
