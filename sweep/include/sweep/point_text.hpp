#pragma once
// A point as messages write it.
#include <Eigen/Core>
#include <string>

namespace sweep {

/// "(x, y, z)" with `digits` significant digits.
std::string point_text(const Eigen::Vector3d& p, int digits = 6);

}  // namespace sweep
