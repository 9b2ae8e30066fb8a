// Points, parametric curves and parametric surfaces as entities: the entity is its own patch;
// a surface's edges are the sides of its parameter box that neither collapse to a point nor meet
// the opposite side (a closed parameter).
#include <algorithm>
#include <cmath>

#include "entity_internal.hpp"

namespace sweep::entity_detail {

using Eigen::Vector3d;

namespace {

/// A box that holds the image of the parameter box: a grid of cells, each enlarged by what the
/// map can move within it (its first-order part per axis, the second-order part of
/// ParametricEntity::move_bound in every axis).
Eigen::AlignedBox3d image_box(const ParametricEntity& pe) {
  const std::size_t k = pe.num_params();
  Eigen::AlignedBox3d box;
  if (k == 0) {
    const Vector3d p = pe.eval(nullptr);
    return Eigen::AlignedBox3d(p, p);
  }
  const int n = k == 1 ? 512 : 96;
  double w[2] = {0.5 * (pe.hi(0) - pe.lo(0)) / n, k > 1 ? 0.5 * (pe.hi(1) - pe.lo(1)) / n : 0.0};
  for (int i = 0; i < n; ++i)
    for (int m = 0; m < (k > 1 ? n : 1); ++m) {
      const double c[2] = {pe.lo(0) + (2 * i + 1) * w[0], k > 1 ? pe.lo(1) + (2 * m + 1) * w[1] : 0.0};
      Vector3d jac[2] = {Vector3d::Zero(), Vector3d::Zero()};
      const Vector3d p = pe.eval(c, jac);
      // the first-order term along each axis, and the second-order rest of move_bound in every one
      const Vector3d first = jac[0].cwiseAbs() * w[0] + jac[1].cwiseAbs() * w[1];
      const double second = pe.move_bound(c, w) - jac[0].norm() * w[0] - jac[1].norm() * w[1];
      const Vector3d reach = first + Vector3d::Constant(std::max(second, 0.0));
      box.extend(p - reach);
      box.extend(p + reach);
    }
  return box;
}

PatchPtr own_patch(const std::shared_ptr<const ParametricEntity>& pe, const char* what) {
  const int k = int(pe->num_params());
  std::vector<double> lo, hi;
  for (int j = 0; j < k; ++j) {
    lo.push_back(pe->lo(j));
    hi.push_back(pe->hi(j));
  }
  auto map = [pe, k](const double* s) {
    Vector3d jac[2] = {Vector3d::Zero(), Vector3d::Zero()};
    PatchPoint p;
    p.x = pe->eval(s, k > 0 ? jac : nullptr);
    p.xu = jac[0];
    p.xv = jac[1];
    return p;
  };
  return std::make_shared<Patch>(k, lo, hi, std::move(map), PatchForm{}, what);
}

/// Side `side` of the surface's parameter box (0: v = lo, 1: u = hi, 2: v = hi, 3: u = lo) as a
/// curve patch over its free parameter, increasing.
PatchPtr side_patch(const std::shared_ptr<const ParametricEntity>& pe, int side) {
  const int free = side % 2 == 0 ? 0 : 1, fixed = 1 - free;
  const double at = side == 0 || side == 3 ? pe->lo(fixed) : pe->hi(fixed);
  auto map = [pe, free, fixed, at](const double* t) {
    double s[2];
    s[free] = t[0];
    s[fixed] = at;
    Vector3d jac[2];
    const Vector3d x = pe->eval(s, jac);
    return PatchPoint{x, jac[free], Vector3d::Zero()};
  };
  static const char* names[4] = {"the side v = lo of the surface", "the side u = hi of the surface",
                                 "the side v = hi of the surface", "the side u = lo of the surface"};
  auto p = std::make_shared<Patch>(1, std::vector<double>{pe->lo(free)}, std::vector<double>{pe->hi(free)},
                                   std::move(map), PatchForm{}, names[side]);
  p->fixed.push_back({fixed == 0 ? "u" : "v", at});
  return p;
}

}  // namespace

std::shared_ptr<BuiltEntity> make_parametric(const EntitySpec& e) {
  std::shared_ptr<const ParametricEntity> pe = ParametricEntity::make(e);
  if (!pe) return nullptr;
  auto s = std::make_shared<BuiltEntity>();
  s->kind_ = e.kind;
  s->dimension_ = int(pe->num_params());
  s->box_ = image_box(*pe);
  s->faces_.push_back(own_patch(pe, s->dimension_ == 0 ? "the point" : s->dimension_ == 1 ? "the curve" : "the surface"));
  if (s->dimension_ < 2) return s;
  // sides that collapse (a pole) or that run back along their opposite side (a closed parameter)
  // are no edges
  const double tol = 1e-9 * std::max(1.0, s->box_.sizes().maxCoeff());
  for (int k : bounding_sides(*s->faces_[0], tol)) s->edges_.push_back(side_patch(pe, k));
  return s;
}

}  // namespace sweep::entity_detail
