#include "sweep/membership.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <queue>
#include <random>
#include <vector>

#include "sweep/entity.hpp"
#include "sweep/error.hpp"
#include "sweep/settings.hpp"

namespace sweep {
namespace {

using Eigen::Vector3d;

/// The boxes of a depth-first branch and bound over k coordinates (joint values, then entity
/// parameters), k lows then k highs each, in one array: the last box is the next to visit.
class BoxStack {
 public:
  explicit BoxStack(std::size_t k) : k_(k) {}
  void push(const std::vector<double>& lo, const std::vector<double>& hi) {
    values_.insert(values_.end(), lo.begin(), lo.end());
    values_.insert(values_.end(), hi.begin(), hi.end());
  }
  bool empty() const { return values_.empty(); }
  const double* top_lo() const { return &values_[values_.size() - 2 * k_]; }
  const double* top_hi() const { return top_lo() + k_; }
  void pop() { values_.resize(values_.size() - 2 * k_); }
  /// Replaces the last box by its two halves split at coordinate `i`'s midpoint, the lower half
  /// last (visited first).
  void split_top(std::size_t i) {
    const std::size_t at = values_.size() - 2 * k_;
    values_.resize(values_.size() + 2 * k_);
    std::copy(values_.begin() + at, values_.begin() + at + 2 * k_, values_.begin() + at + 2 * k_);
    const double mid = 0.5 * (values_[at + i] + values_[at + k_ + i]);
    values_[at + i] = mid;                // the upper half, below
    values_[at + 2 * k_ + k_ + i] = mid;  // the lower half, on top
  }

 private:
  std::size_t k_;
  std::vector<double> values_;
};

}  // namespace

std::unique_ptr<SignedDistance> make_signed_distance(const EntitySpec& e) {
  const EntityPtr entity = make_entity(e);
  return entity ? entity->distance_bound() : nullptr;
}

bool in_swept_set(const SignedDistance& sd, const Motion& motion, const Vector3d& x,
                  double resolution) {
  return swept_set_membership(sd, motion, x, resolution, 500000) == 1;
}

namespace {

/// y(c) = M(c)^-1 x for a chain M(q) = J_0(q_0) ... J_{n-1}(q_{n-1}) home, and how far y(q) can be
/// from it over the box of half-widths w about c. The inverses K_i = J_i^-1 apply to x outermost
/// first; turning q_i moves the point z_i that K_i takes (x after K_0 ... K_{i-1}) along a circle
/// or helix about joint i's axis at speed sqrt(r^2 + pitch^2), r its distance from the axis, and
/// every map after it is rigid. Over the box z_i is at most the moves of the joints before it
/// from its place at c, so joint i moves y by at most w_i sqrt((r_i(c) + move_<i)^2 + pitch_i^2)
/// (w_i for a prismatic joint). `moves` receives each joint's share.
Vector3d back_through(const Motion& motion, const Eigen::Isometry3d& home_inverse, const double* c, const double* w,
                      Vector3d z, double* moves) {
  double before = 0.0;
  for (std::size_t i = 0; i < motion.joints.size(); ++i) {
    const ScrewJoint& j = motion.joints[i];
    if (j.type == JointType::Prismatic) {
      moves[i] = w[i];
      before += moves[i];
      z -= j.direction * c[i];
      continue;
    }
    const Vector3d v = z - j.point - j.direction * (j.pitch * c[i]);
    const double r = (v - j.direction.dot(v) * j.direction).norm() + before;
    moves[i] = w[i] * std::sqrt(r * r + j.pitch * j.pitch);
    before += moves[i];
    const double cs = std::cos(c[i]), sn = std::sin(c[i]);
    z = j.point + v * cs - j.direction.cross(v) * sn + j.direction * (j.direction.dot(v) * (1 - cs));
  }
  return home_inverse * z;
}

}  // namespace

int swept_set_membership(const SignedDistance& sd, const Motion& motion, const Vector3d& x, double resolution,
                         std::size_t budget) {
  const std::size_t n = motion.dof();
  SWEEP_ASSERT(n >= 1, "motion without joints");
  // Branch and bound over the joint box. For a sub-box with half-widths w_i around centre c, the
  // body-frame point y(q) = M(q)^-1 x moves at most the sum of back_through()'s moves from y(c);
  // sd is 1-Lipschitz.
  const Eigen::Isometry3d home_inverse = motion.home.inverse();
  std::vector<double> w(n), moves(n);
  // The sub-boxes, 2n values each (lo then hi) in one pool; a box's slot is reused once it is split.
  std::vector<double> pool;
  std::vector<std::size_t> free_slots;
  auto new_slot = [&]() -> std::size_t {
    if (!free_slots.empty()) {
      const std::size_t k = free_slots.back();
      free_slots.pop_back();
      return k;
    }
    pool.resize(pool.size() + 2 * n);
    return pool.size() / (2 * n) - 1;
  };
  // Best first: the sub-box whose lower bound of the distance (d at the centre minus the move) is
  // smallest is split next, so a point inside is found along the way to the distance's minimum.
  struct Open {
    double bound;
    std::size_t split, slot;
    bool operator<(const Open& o) const { return bound > o.bound; }
  };
  std::priority_queue<Open> open;
  std::vector<double> c(n);
  // a loose bound cannot tell a sub-box smaller than its slack from one that reaches the solid
  const double slack = sd.slack();
  bool uncertain = false;
  // 1: x is in, 0: the sub-box may hold it (pushed), -1: discarded (its slot freed)
  auto visit = [&](std::size_t slot) -> int {
    const double* lo = &pool[2 * n * slot];
    const double* hi = lo + n;
    for (std::size_t i = 0; i < n; ++i) {
      c[i] = 0.5 * (lo[i] + hi[i]);
      w[i] = 0.5 * (hi[i] - lo[i]);
    }
    const Vector3d y = back_through(motion, home_inverse, c.data(), w.data(), x, moves.data());
    double move = 0.0, widest = -1.0;
    std::size_t split = 0;
    for (std::size_t i = 0; i < n; ++i) {
      move += moves[i];
      if (moves[i] > widest) { widest = moves[i]; split = i; }
    }
    const double d = sd.below(y, move);
    if (d <= 0.0) return 1;
    const bool out = d > move || move < resolution;  // out, or within resolution of the boundary: out
    if (!out && move < slack) uncertain = true;
    if (out || uncertain) {
      free_slots.push_back(slot);
      return -1;
    }
    open.push({d - move, split, slot});
    return 0;
  };
  const std::size_t root = new_slot();
  for (std::size_t i = 0; i < n; ++i) {
    pool[2 * n * root + i] = motion.joints[i].lo;
    pool[2 * n * root + n + i] = motion.joints[i].hi;
  }
  if (visit(root) == 1) return 1;
  if (uncertain) return -1;
  for (std::size_t iterations = 0; !open.empty(); ++iterations) {
    if (iterations >= budget) return -1;
    const Open top = open.top();
    open.pop();
    // the box's lower half keeps its slot, the upper half takes a new one
    const std::size_t half = new_slot();
    double* box = &pool[2 * n * top.slot];
    double* upper = &pool[2 * n * half];
    std::copy(box, box + 2 * n, upper);
    const double mid = 0.5 * (box[top.split] + box[n + top.split]);
    box[n + top.split] = mid;
    upper[top.split] = mid;
    if (visit(top.slot) == 1 || visit(half) == 1) return 1;
    // a sub-box the bound cannot decide: x is within its slack of the boundary, or in; the rest of
    // the search could only tell the second, at the cost of the whole budget
    if (uncertain) return -1;
  }
  return 0;
}

std::unique_ptr<ParametricEntity> ParametricEntity::make(const EntitySpec& e) {
  if (e.kind != EntityKind::Point && e.kind != EntityKind::Curve && e.kind != EntityKind::Surface) return nullptr;
  auto p = std::make_unique<ParametricEntity>();
  p->placement_ = e.placement;
  if (e.kind == EntityKind::Point) {
    p->at_ = e.at;
    return p;
  }
  p->xyz_ = e.xyz;
  for (const auto& r : e.params) {
    p->lo_.push_back(r.lo);
    p->hi_.push_back(r.hi);
  }
  // Largest Frobenius norm of the stacked Hessians on a grid over the parameter box.
  const std::size_t k = p->lo_.size();
  const int steps = k == 1 ? 512 : 96;
  double hmax = 0.0;
  std::vector<double> s(k), grad(k), hess(k * k);
  const int total = k == 1 ? steps + 1 : (steps + 1) * (steps + 1);
  for (int idx = 0; idx < total; ++idx) {
    s[0] = p->lo_[0] + (p->hi_[0] - p->lo_[0]) * double(idx % (steps + 1)) / steps;
    if (k == 2) s[1] = p->lo_[1] + (p->hi_[1] - p->lo_[1]) * double(idx / (steps + 1)) / steps;
    double sum = 0.0;
    for (const auto& f : p->xyz_) {
      f.eval_d2(s.data(), grad.data(), hess.data());
      for (double h : hess) sum += h * h;
    }
    hmax = std::max(hmax, std::sqrt(sum));
  }
  p->hessian_bound_ = 2.0 * hmax;
  return p;
}

Vector3d ParametricEntity::eval(const double* s, Vector3d* jac) const {
  if (lo_.empty()) return placement_ * at_;
  Vector3d v;
  double grad[2];
  for (int c = 0; c < 3; ++c) {
    v[c] = xyz_[c].eval_d1(s, grad);
    if (jac)
      for (std::size_t j = 0; j < lo_.size(); ++j) jac[j][c] = grad[j];
  }
  if (jac)
    for (std::size_t j = 0; j < lo_.size(); ++j) jac[j] = placement_.linear() * jac[j];
  return placement_ * v;
}

double ParametricEntity::move_bound(const double* c, const double* w, double* each) const {
  if (lo_.empty()) return 0.0;
  Vector3d jac[2];
  eval(c, jac);
  return move_bound_at(jac, w, each);
}

double ParametricEntity::move_bound_at(const Vector3d* jac, const double* w, double* each) const {
  if (lo_.empty()) return 0.0;
  double first = 0.0, w2 = 0.0;
  for (std::size_t j = 0; j < lo_.size(); ++j) {
    const double fj = jac[j].norm() * w[j], wj2 = w[j] * w[j];
    if (each) each[j] = fj + 0.5 * hessian_bound_ * wj2;
    first += fj;
    w2 += wj2;
  }
  return first + 0.5 * hessian_bound_ * w2;
}

namespace {

/// dP/dz for P = M(q) Gamma(s), z the joints then the entity parameters, into J (3 x z's size):
/// joint i's velocity field, carried by the outer joints, at P; then Gamma's derivatives `dg` turned
/// by M(q). `joint_pose[i]` is joint i's transform at q_i.
void image_jacobian(const Motion& motion, const std::vector<Eigen::Isometry3d>& joint_pose, const Vector3d& P,
                    const Vector3d* dg, Eigen::MatrixXd& J) {
  const std::size_t n = motion.dof();
  Eigen::Isometry3d A = Eigen::Isometry3d::Identity();
  for (std::size_t i = 0; i < n; ++i) {
    J.col(i) = A.linear() * motion.joints[i].velocity(A.inverse() * P);
    A = A * joint_pose[i];
  }
  const Eigen::Matrix3d R = (A * motion.home).linear();
  for (std::size_t m = n; m < std::size_t(J.cols()); ++m) J.col(m) = R * dg[m - n];
}

/// Projected, damped Gauss-Newton for M(q) Gamma(s) = x over the boxes, from z (joints then
/// entity parameters). True when the residual falls below `eps`; false as soon as an iteration
/// leaves more than Settings::membership_newton_stall of the residual (the caller's search then
/// splits the box and starts again from the halves' centres).
bool solve_image(const ParametricEntity& e, const Motion& motion, const Vector3d& x, std::vector<double> z,
                 const std::vector<double>& lo, const std::vector<double>& hi, double eps) {
  const std::size_t n = motion.dof(), k = z.size();
  Eigen::MatrixXd J(3, k);
  std::vector<Eigen::Isometry3d> joint_pose(n);
  auto residual = [&](const std::vector<double>& zz, bool with_jacobian) {
    Vector3d dg[2];
    const Vector3d g = e.eval(zz.data() + n, with_jacobian ? dg : nullptr);
    const Vector3d P = motion.transform(std::vector<double>(zz.begin(), zz.begin() + n)) * g;
    if (with_jacobian) {
      for (std::size_t i = 0; i < n; ++i) joint_pose[i] = motion.joints[i].transform(zz[i]);
      image_jacobian(motion, joint_pose, P, dg, J);
    }
    return Vector3d(P - x);
  };
  Vector3d F = residual(z, true);
  double f = F.norm();
  for (int it = 0; it < 40; ++it) {
    if (f < eps) return true;
    const Eigen::Matrix3d JJ = J * J.transpose();
    const double mu = Settings::image_newton_damping * std::max(JJ.trace(), 1e-300);
    const Eigen::VectorXd step = -J.transpose() * (JJ + mu * Eigen::Matrix3d::Identity()).ldlt().solve(F);
    double t = 1.0;
    bool improved = false;
    for (int h = 0; h < 12 && !improved; ++h, t *= 0.5) {
      std::vector<double> z2(k);
      for (std::size_t i = 0; i < k; ++i) z2[i] = std::clamp(z[i] + t * step[i], lo[i], hi[i]);
      const Vector3d F2 = residual(z2, false);
      if (F2.norm() < f) {
        z = std::move(z2);
        improved = true;
      }
    }
    if (!improved) return false;
    F = residual(z, true);
    const double before = f;
    f = F.norm();
    if (f >= eps && f > Settings::membership_newton_stall * before) return false;  // stalled
  }
  return f < eps;
}

/// A lower bound of |M(q) Gamma(s) - x| over the box of centre c and half widths w (joints, then
/// entity parameters), from the first-order model at the centre and a bound on the remainder:
///   |P(c) + J d - x| >= |u . (P(c) - x)| - sum_i |u . J_i| w_i  for unit u (the residual's
///   direction, and the normal of J's range, which is what matters at a fold);
///   |remainder| <= 1/2 sum_ij |d2P/dz_i dz_j| w_i w_j, where with joints outermost first a joint i
///   outside (or equal to) joint j turns joint j's velocity, so |d2P/dq_i dq_j| <= [i turns] S_j,
///   S_j the bound on joint j's speed over the box (`speed`); with an entity parameter a it is
///   [i turns] G_a (G_a bounds |dGamma/ds_a| over the box), and between parameters the map's
///   Hessian bound.
/// `P` is the image of the centre, `joint_pose` the joints' transforms there and `dg` Gamma's
/// derivatives there.
double second_order_gap(const ParametricEntity& e, const Motion& motion, const Vector3d& x, const Vector3d& P,
                        const std::vector<Eigen::Isometry3d>& joint_pose, const std::vector<double>& c,
                        const std::vector<double>& w, const std::vector<double>& speed, const Vector3d* dg) {
  const std::size_t n = motion.dof(), k = c.size(), m = k - n;
  Eigen::MatrixXd J(3, k);
  image_jacobian(motion, joint_pose, P, dg, J);
  // the remainder
  double ws = 0;
  for (std::size_t a = 0; a < m; ++a) ws += w[n + a];
  double rem = e.hessian_bound() * ws * ws;
  for (std::size_t i = 0; i < n; ++i) {
    if (!motion.joints[i].is_rotation()) continue;
    double inner = speed[i] * w[i];  // joint i with itself, then with the joints inside it (twice)
    for (std::size_t j = i + 1; j < n; ++j) inner += 2 * speed[j] * w[j];
    for (std::size_t a = 0; a < m; ++a) inner += 2 * (dg[a].norm() + e.hessian_bound() * ws) * w[n + a];
    rem += w[i] * inner;
  }
  rem *= 0.5;
  // the linear model's distance from x, along the residual and along the normal of J's range
  const Vector3d F = P - x;
  double best = 0;
  auto along = [&](const Vector3d& u) {
    double lb = std::abs(u.dot(F));
    for (std::size_t i = 0; i < k; ++i) lb -= std::abs(u.dot(J.col(i))) * w[i];
    best = std::max(best, lb);
  };
  if (F.norm() > 0) along(F.normalized());
  // (the bound holds for any unit u: the closed-form eigenvector of J J^T's least eigenvalue serves)
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> normal;
  normal.computeDirect(J * J.transpose());
  along(normal.eigenvectors().col(0));
  return best - rem;
}

}  // namespace

bool in_swept_image(const ParametricEntity& e, const Motion& motion, const Vector3d& x, double resolution,
                    double scale) {
  return swept_image_membership(e, motion, x, resolution, scale, 200000) == 1;
}

int swept_image_membership(const ParametricEntity& e, const Motion& motion, const Vector3d& x, double resolution,
                           double scale, std::size_t budget, bool undecided_past_budget, bool second_order) {
  const std::size_t n = motion.dof(), m = e.num_params(), k = n + m;
  SWEEP_ASSERT(n >= 1, "motion without joints");
  std::vector<double> lo(k), hi(k);
  for (std::size_t i = 0; i < n; ++i) {
    lo[i] = motion.joints[i].lo;
    hi[i] = motion.joints[i].hi;
  }
  for (std::size_t j = 0; j < m; ++j) {
    lo[n + j] = e.lo(j);
    hi[n + j] = e.hi(j);
  }
  const double eps = Settings::image_newton_residual * scale;
  BoxStack stack(k);
  stack.push(lo, hi);
  std::vector<double> c(k), w(k), speed(n);
  std::vector<Eigen::Isometry3d> joint_pose(n);
  std::size_t iterations = 0;
  bool unresolved = false;
  while (!stack.empty()) {
    for (std::size_t i = 0; i < k; ++i) {
      c[i] = 0.5 * (stack.top_lo()[i] + stack.top_hi()[i]);
      w[i] = 0.5 * (stack.top_hi()[i] - stack.top_lo()[i]);
    }
    // P(q, s) = E_1(q_1) ... E_n(q_n) home Gamma(s). With Q_i = E_{i+1} ... E_n home Gamma, the speed
    // |dP/dq_i| is the distance of Q_i from joint i's axis (with the pitch); over the box Q_i moves
    // at most by what the inner joints and the entity parameters move it. Innermost first.
    double each[2] = {0.0, 0.0};
    Vector3d dg[2] = {Vector3d::Zero(), Vector3d::Zero()};
    const Vector3d g = e.eval(c.data() + n, dg);
    double move = e.move_bound_at(dg, w.data() + n, each);
    double split_move = -1.0;
    std::size_t split = 0;
    for (std::size_t j = 0; j < m; ++j)
      if (each[j] > split_move) { split_move = each[j]; split = n + j; }
    Vector3d Q = motion.home * g;
    for (std::size_t i = n; i-- > 0;) {
      const ScrewJoint& j = motion.joints[i];
      speed[i] = 1.0;
      if (j.is_rotation()) {
        const Vector3d rel = Q - j.point;
        const double r = (rel - rel.dot(j.direction) * j.direction).norm() + move;
        speed[i] = std::sqrt(r * r + j.pitch * j.pitch);
      }
      const double mv = w[i] * speed[i];
      if (mv > split_move) { split_move = mv; split = i; }
      move += mv;
      joint_pose[i] = j.transform(c[i]);
      Q = joint_pose[i] * Q;
    }
    const double gap = (Q - x).norm();
    if (gap > move || (second_order && second_order_gap(e, motion, x, Q, joint_pose, c, w, speed, dg) > 0)) {
      stack.pop();
      continue;
    }
    if (gap < 0.5 * move && solve_image(e, motion, x, c, lo, hi, eps)) return 1;
    if (move < resolution) {  // no exclusion and no solve within the resolution
      unresolved = true;
      stack.pop();
      continue;
    }
    if (++iterations > budget) {
      if (undecided_past_budget) return -1;
      stack.pop();
      continue;
    }
    stack.split_top(split);
  }
  return unresolved && undecided_past_budget ? -1 : 0;
}

MonteCarloResult monte_carlo_volume(const std::function<bool(const Vector3d&)>& inside,
                                    const Eigen::AlignedBox3d& box, std::size_t samples,
                                    std::uint64_t seed, const std::function<bool(const Vector3d&)>& compare) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::size_t hits = 0, mismatches = 0;
  const Vector3d lo = box.min(), ext = box.sizes();
  for (std::size_t k = 0; k < samples; ++k) {
    Vector3d p(lo.x() + ext.x() * u(rng), lo.y() + ext.y() * u(rng), lo.z() + ext.z() * u(rng));
    const bool in = inside(p);
    if (in) ++hits;
    if (compare && compare(p) != in) ++mismatches;
  }
  const double vbox = ext.prod();
  const double f = samples ? double(hits) / double(samples) : 0.0;
  MonteCarloResult r;
  r.samples = samples;
  r.volume = vbox * f;
  r.stderr_ = samples ? vbox * std::sqrt(f * (1.0 - f) / double(samples)) : 0.0;
  r.mismatches = mismatches;
  r.mismatch_volume = samples ? vbox * double(mismatches) / double(samples) : 0.0;
  return r;
}

bool slides_along_itself(const EntitySpec& e, const Eigen::Isometry3d& G, const ScrewJoint& j, double T,
                         double scale, EntitySpec* reduced) {
  if (e.kind != EntityKind::Curve && e.kind != EntityKind::Surface) return false;
  const auto pe = ParametricEntity::make(e);
  if (!pe || !(T > 0)) return false;
  const std::size_t np = pe->num_params();
  const Eigen::Isometry3d A = j.transform(j.lo) * G;
  std::mt19937_64 rng(20261123);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  auto uniform = [&]() { return uni(rng); };
  std::vector<double> s(np);
  auto random_params = [&]() {
    for (std::size_t i = 0; i < np; ++i) s[i] = pe->lo(i) + (pe->hi(i) - pe->lo(i)) * uniform();
  };
  std::vector<Eigen::Vector3d> jac(np);
  for (std::size_t k = 0; k < np; ++k) {
    // the rate: the joint's velocity at a point is c times the point's derivative in s_k
    double c = 0;
    bool ok = true;
    for (int n = 0; n < 16 && ok; ++n) {
      random_params();
      const Eigen::Vector3d y = A * pe->eval(s.data(), jac.data());
      const Eigen::Vector3d g = A.linear() * jac[k], v = j.velocity(y);
      if (!(g.squaredNorm() > 0) || !(v.squaredNorm() > 0)) {
        ok = false;
        break;
      }
      const double ck = v.dot(g) / g.squaredNorm();
      if ((v - ck * g).norm() > Settings::parameter_shift_match * v.norm()) ok = false;
      if (n == 0) c = ck;
      else if (std::abs(ck - c) > Settings::parameter_shift_match * std::abs(c)) ok = false;
    }
    if (!ok || c == 0) continue;
    // the motion over the whole range is that shift
    for (int n = 0; n < 64 && ok; ++n) {
      random_params();
      const double t = T * uniform();
      const Eigen::Vector3d moved = j.transform(t) * (A * pe->eval(s.data()));
      s[k] += c * t;
      const Eigen::Vector3d shifted = A * pe->eval(s.data());
      if (!shifted.allFinite() || (moved - shifted).norm() > Settings::parameter_shift_match * scale) ok = false;
    }
    if (!ok) continue;
    *reduced = e;
    ParamRange& r = reduced->params[k];
    const double grow = std::abs(c) * T;
    double lo = c > 0 ? r.lo : r.lo - grow, hi = c > 0 ? r.hi + grow : r.hi;
    if (j.type == JointType::Revolute && hi - lo > 2 * M_PI * std::abs(c)) {
      if (c > 0) hi = lo + 2 * M_PI * std::abs(c);
      else lo = hi - 2 * M_PI * std::abs(c);
    }
    r.lo = lo;
    r.hi = hi;
    return true;
  }
  return false;
}

}  // namespace sweep
