#pragma once
/// @file swept_box.hpp
/// A box that contains the whole swept set, computed from the entity's box and the motion alone.
#include <Eigen/Geometry>

#include "sweep/motion.hpp"

namespace sweep {

/// A box containing T(q) x for every x in `body` (a box in the entity's frame, before `home`) and
/// every q in the joint box. One joint: the boxes of the corners' orbits, sampled with the bound
/// on their curvature added. Chains: the corners at a grid of joint values, widened by what a point
/// can move between grid values (its speed bound times half the step, summed over the joints).
Eigen::AlignedBox3d swept_box(const Eigen::AlignedBox3d& body, const Motion& motion);

}  // namespace sweep
