#pragma once
/// @file kinematics_internal.hpp
/// Helpers shared by the kinematics*.cpp files (not part of the public interface).
#include <Eigen/Core>
#include <utility>

#include "sweep/kinematics.hpp"

namespace sweep {
namespace kinematics {

/// Two unit vectors u, w with (u, w, d/|d|) orthonormal and right-handed. @pre d is not zero.
std::pair<Vec3, Vec3> perpendicular_pair(const Vec3& d);

namespace detail {

/// Number of singular values above the rank tolerance of `frame` (relative to the largest, >= 1).
int numeric_rank(const Eigen::VectorXd& singular_values, const NumericFrame& frame);
/// Orthonormal basis of the span of the columns (each normalized first when `normalize`).
Eigen::MatrixXd span_basis(const Eigen::MatrixXd& cols, const NumericFrame& frame, bool normalize = true);
/// Orthonormal basis of the Euclidean orthogonal complement of the span of the columns.
Eigen::MatrixXd complement_basis(const Eigen::MatrixXd& cols, const NumericFrame& frame);
/// Orthonormal basis of {x : a x = 0}; `rank` receives the rank of a.
Eigen::MatrixXd null_space(const Eigen::MatrixXd& a, const NumericFrame& frame, int* rank);
ScrewBasis to_local(const ScrewBasis& world, const NumericFrame& frame);
ScrewBasis to_world(const ScrewBasis& local, const NumericFrame& frame);
/// Sets entries that are rounding noise to exact zeros.
void clean(ScrewBasis& b, double scale);
/// Classifies an orthonormal local-frame basis of a twist space.
Joint classify_local(const ScrewBasis& local, const NumericFrame& frame);

}  // namespace detail
}  // namespace kinematics
}  // namespace sweep
