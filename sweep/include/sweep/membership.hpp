#pragma once
/// @file membership.hpp
/// Point membership in a swept set, independent of any B-rep: x is in the sweep of solid B under
/// the motion M(q), q in the joint box, when some q puts M(q)^-1 x inside B. For primitive solids the
/// test uses an exact (or 1-Lipschitz lower-bound) signed distance and a certified branch-and-bound
/// over the joint box: a sub-box is discarded only when the distance at its centre exceeds what the
/// motion can move a point within it.
#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <memory>
#include <random>

#include "sweep/motion.hpp"
#include "sweep/spec.hpp"

namespace sweep {

/// A solid given by a signed distance function (negative inside) that is 1-Lipschitz, or by a
/// bound on one: |d(p)| at most the distance from p to the boundary, a negative value only inside.
class SignedDistance {
 public:
  virtual ~SignedDistance() = default;
  virtual double operator()(const Eigen::Vector3d& p) const = 0;
  /// 0 for a bound whose sign is exact everywhere. Otherwise the distance from the boundary
  /// within which the bound may give a tiny positive value for a point inside: a search cannot
  /// tell points that near the boundary from points out of the solid.
  virtual double slack() const { return 0; }
  /// A cheaper bound for a search that only asks whether it exceeds `limit`: negative exactly where
  /// operator() is (a bound there too), equal to operator() where that is in [0, limit), above
  /// `limit` elsewhere (a bound that looks for the nearest of many features stops sooner).
  virtual double below(const Eigen::Vector3d& p, double limit) const {
    (void)limit;
    return (*this)(p);
  }
};

/// Signed distance of a primitive solid entity (sphere, box, cylinder, cone, torus) with its
/// placement applied; nullptr for other kinds.
std::unique_ptr<SignedDistance> make_signed_distance(const EntitySpec& entity);

/// True when x is in the swept set of `sd` under `motion` over its joint box. `resolution` is the
/// length below which the search stops and decides by the sign at the best joint value.
bool in_swept_set(const SignedDistance& sd, const Motion& motion, const Eigen::Vector3d& x,
                  double resolution);

/// The same search with at most `budget` sub-boxes split: 1 when x is in the swept set, 0 when it
/// is out (or within `resolution` of the boundary), -1 when the budget ran out first or when the
/// search met a sub-box whose move is below sd.slack() and that the bound does not exclude (x may
/// then be out within the slack of the boundary, or in).
int swept_set_membership(const SignedDistance& sd, const Motion& motion, const Eigen::Vector3d& x,
                         double resolution, std::size_t budget);

/// A point, curve or surface given by its parametric map Gamma(s) over a box of s (0, 1 or 2
/// parameters), with its placement applied.
class ParametricEntity {
 public:
  /// nullptr for entity kinds other than point, curve and surface.
  static std::unique_ptr<ParametricEntity> make(const EntitySpec& entity);
  std::size_t num_params() const { return lo_.size(); }
  double lo(std::size_t j) const { return lo_[j]; }
  double hi(std::size_t j) const { return hi_[j]; }
  /// Gamma(s) and, when `jac` is given, its 3 x num_params() derivative (column-major 3-vectors).
  Eigen::Vector3d eval(const double* s, Eigen::Vector3d* jac = nullptr) const;
  /// Upper bound of |Gamma(s) - Gamma(c)| over |s_j - c_j| <= w_j: the first-order term at c plus a
  /// second-order term from the largest Hessian norm, sampled on a grid over the parameter box and
  /// doubled. When `each` is given, it receives the bound for each parameter varying alone.
  double move_bound(const double* c, const double* w, double* each = nullptr) const;
  /// The same bound from `jac`, Gamma's derivative at the centre as eval() gives it.
  double move_bound_at(const Eigen::Vector3d* jac, const double* w, double* each = nullptr) const;
  /// The bound on the second derivatives of Gamma that move_bound uses.
  double hessian_bound() const { return hessian_bound_; }

 private:
  std::array<Expr, 3> xyz_;
  Eigen::Vector3d at_ = Eigen::Vector3d::Zero();
  Eigen::Isometry3d placement_ = Eigen::Isometry3d::Identity();
  std::vector<double> lo_, hi_;
  double hessian_bound_ = 0.0;
};

/// When screw joint j, moving over [j.lo, j.lo + T], carries a curve or surface entity (placed by
/// G) along itself with a parametrisation that shifts one parameter at a constant rate,
///   M(j.lo + t) G Gamma(s) = M(j.lo) G Gamma(s + c t e_k)   for all s in the box and t in [0, T],
/// the image of the stage is the same entity with parameter k's range extended by c T (to at most
/// one period, 2 pi |c|, for a revolute joint), placed by M(j.lo) G: that entity goes in *reduced.
/// Checked on random samples to 1e-9 of `scale`. False when no parameter does this.
bool slides_along_itself(const EntitySpec& e, const Eigen::Isometry3d& G, const ScrewJoint& j, double T,
                         double scale, EntitySpec* reduced);

/// True when x is in the image of (q, s) -> M(q) Gamma(s) over the joint box and the parameter
/// box. A branch and bound over both boxes discards a sub-box when the gap |M(c) Gamma(s_c) - x|
/// exceeds what the motion and the map can move within it, or when the first-order model at the
/// centre stays farther from x than the second-order remainder allows (which, near a fold of the
/// map where the swept set's boundary lies, discards far larger sub-boxes than the gap alone);
/// membership is proved by a projected Gauss-Newton solve of M(q) Gamma(s) = x started in a
/// surviving sub-box, converging to 1e-10 of `scale` inside the boxes. Sub-boxes smaller than `resolution` that no solve reaches count as
/// outside (only points within about `resolution` of the boundary are at stake).
bool in_swept_image(const ParametricEntity& entity, const Motion& motion, const Eigen::Vector3d& x,
                    double resolution, double scale);

/// The same search splitting at most `budget` sub-boxes: 1 in, 0 out; past the budget, or with a
/// sub-box below the resolution that neither the bounds exclude nor a solve proves, -1
/// (undecided) when `undecided_past_budget`, else those sub-boxes are counted as outside (what
/// in_swept_image does, with a budget of 200000).
/// `second_order` off leaves sub-boxes to the first-order test alone (the same answers, more boxes).
int swept_image_membership(const ParametricEntity& entity, const Motion& motion, const Eigen::Vector3d& x,
                           double resolution, double scale, std::size_t budget, bool undecided_past_budget = true,
                           bool second_order = true);

/// Monte Carlo estimate of a volume from a membership test inside an axis-aligned box. With
/// `compare` (a second membership, e.g. a computed solid's), the samples where the two disagree
/// are counted too: `mismatch_volume` estimates the volume of the symmetric difference.
struct MonteCarloResult {
  double volume = 0.0;
  double stderr_ = 0.0;
  std::size_t samples = 0;
  std::size_t mismatches = 0;
  double mismatch_volume = 0.0;
};
MonteCarloResult monte_carlo_volume(const std::function<bool(const Eigen::Vector3d&)>& inside,
                                    const Eigen::AlignedBox3d& box, std::size_t samples,
                                    std::uint64_t seed = 12345,
                                    const std::function<bool(const Eigen::Vector3d&)>& compare = {});

}  // namespace sweep
