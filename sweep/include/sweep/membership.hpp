#pragma once
/// @file membership.hpp
/// Point membership in a swept set, independent of any B-rep: x is in the sweep of solid B under
/// the motion M(q), q in the joint box, when some q puts M(q)^-1 x inside B. For primitive solids the
/// test uses an exact (or 1-Lipschitz lower-bound) signed distance and a certified branch-and-bound
/// over the joint box: a sub-box is discarded only when the distance at its centre exceeds what the
/// motion can move a point within it.
#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <random>

#include "sweep/motion.hpp"
#include "sweep/spec.hpp"

namespace sweep {

/// A solid given by a signed distance function (negative inside) that is 1-Lipschitz.
class SignedDistance {
 public:
  virtual ~SignedDistance() = default;
  virtual double operator()(const Eigen::Vector3d& p) const = 0;
};

/// Signed distance of a primitive solid entity (sphere, box, cylinder, cone, torus) with its
/// placement applied; nullptr for other kinds.
std::unique_ptr<SignedDistance> make_signed_distance(const EntitySpec& entity);

/// True when x is in the swept set of `sd` under `motion` over its joint box. `resolution` is the
/// length below which the search stops and decides by the sign at the best joint value.
bool in_swept_set(const SignedDistance& sd, const Motion& motion, const Eigen::Vector3d& x,
                  double resolution);

/// Monte Carlo estimate of a volume from a membership test inside an axis-aligned box.
struct MonteCarloResult {
  double volume = 0.0;
  double stderr_ = 0.0;
  std::size_t samples = 0;
};
MonteCarloResult monte_carlo_volume(const std::function<bool(const Eigen::Vector3d&)>& inside,
                                    const Eigen::AlignedBox3d& box, std::size_t samples,
                                    std::uint64_t seed = 12345);

}  // namespace sweep
