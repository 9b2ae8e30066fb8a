#pragma once
/// @file contour.hpp
/// The zero set of a function of two parameters, traced on a grid: every point is a root of the
/// function on a grid line (found by bracketing, to rounding), and where two branches cross inside
/// a cell they are joined at the saddle of the function. Grazing curves (n . v = 0 on a face) and
/// the crossings of a swept face with the face it touches are such zero sets.
#include <Eigen/Core>
#include <functional>
#include <vector>

namespace sweep {

using ContourFunction = std::function<double(const Eigen::Vector2d&)>;

/// Root of f on [0, 1] given f(0) and f(1) of opposite signs (Illinois false position, bisection
/// where it stalls), to 1e-15.
double root_in_unit(const std::function<double(double)>& f, double f0, double f1);

/// Root of f on the segment p..q, whose ends have values fp and fq of opposite signs.
Eigen::Vector2d root_on_segment(const ContourFunction& f, const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                                double fp, double fq);

/// The zero set of f over the rectangle [u0, u1] x [v0, v1], traced on an nu x nv grid: chains of
/// roots between points where branches end (the rectangle's sides, crossings) and closed loops
/// (first point repeated last). Empty when |f| <= flat at every grid node.
std::vector<std::vector<Eigen::Vector2d>> contour_chains(const ContourFunction& f, double u0, double u1, double v0,
                                                         double v1, int nu, int nv, double flat);

/// The chain with a root of f inserted between consecutive points, on the line through the
/// chord's midpoint across the chord (where f changes sign along it).
std::vector<Eigen::Vector2d> densified(const ContourFunction& f, const std::vector<Eigen::Vector2d>& chain);

}  // namespace sweep
