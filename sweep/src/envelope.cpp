#include "sweep/envelope.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cubic_spline.hpp"
#include "sweep/settings.hpp"
#include "sweep/variety.hpp"

namespace sweep {

using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

/// A track's arcs resampled at equal fractions of their length, every point a root of the grazing
/// function at its instant, and what evaluating the sheet between them needs.
class Sheet {
 public:
  Sheet(PatchPtr face, std::shared_ptr<const StageMotion> motion, const GrazingTrack& track)
      : face_(std::move(face)), motion_(std::move(motion)), t_(track.t), closed_(track.closed) {
    period_ = parameter_periods(*face_);
    scale_ = Vector2d(face_->hi(0) - face_->lo(0), face_->hi(1) - face_->lo(1));
    for (int e = 0; e < 2; ++e) end_side_[e] = track.end_sides[e];
    std::size_t most = 0;
    for (const auto& arc : track.arcs) most = std::max(most, arc.size());
    m_ = int(std::clamp<std::size_t>(most, 16, 256));
    for (std::size_t k = 0; k < t_.size(); ++k) rows_.push_back(spline_through(resampled(track.arcs[k], t_[k])));
  }

  /// The sheet's point at (s, t) in the face's parameters (of the domain's cover), with its
  /// derivatives in s and t.
  struct Jet {
    Vector2d x, xs, xt;
  };

  /// The body point of the sheet at (s, t): the root of the grazing function at t on the line from
  /// the interpolated point across the interpolated arc. An open arc's ends are found first, and the
  /// interpolated arc is moved to run between them (by the ends' offsets, blended linearly in s): the
  /// rows are interpolated in t, and where an arc shrinks fast (as the square root of the time left
  /// before it vanishes on a side) the interpolated arc overshoots its ends, and its roots then lie
  /// on the grazing curve's continuation outside the face.
  Jet at(double s, double t) const {
    const PoseJet pose = motion_->pose(t);
    Jet guess = interpolated(s, t);
    if (!closed_ && s > 0 && s < 1) {
      const Jet g0 = interpolated(0, t), g1 = interpolated(1, t);
      const Jet e0 = root_of(0, t, g0, pose), e1 = root_of(1, t, g1, pose);
      guess.x += (1 - s) * (e0.x - g0.x) + s * (e1.x - g1.x);
      guess.xs += (e1.x - g1.x) - (e0.x - g0.x);
      guess.xt += (1 - s) * (e0.xt - g0.xt) + s * (e1.xt - g1.xt);
    }
    return root_of(s, t, guess, pose);
  }

  const PatchPtr& face() const { return face_; }
  const StageMotion& motion() const { return *motion_; }
  const Vector2d& period() const { return period_; }
  bool closed() const { return closed_; }

 private:
  /// The root of the grazing function at the pose on the line from `guess` (the sheet's point at s
  /// before Newton) across the arc. Near an open arc's end on a side of the domain the line turns
  /// smoothly to run along the side (over the first of the m_ intervals), so the end stays on the
  /// side and the map stays smooth. The derivatives are those of the root as the guess moves and g
  /// changes with t (the line's own turning, times the root's tiny distance from the guess, left
  /// out).
  Jet root_of(double s, double t, const Jet& guess, const PoseJet& pose) const {
    // across the interpolated arc (where two arcs cross, the gradient vanishes and turns with the
    // point, so it would not say which arc to follow); along the gradient where the arc has no length
    Vector2d dir(-guess.xs.y(), guess.xs.x());
    if (!(dir.norm() > Settings::envelope_arc_degenerate * scale_.norm())) dir = gradient(guess.x, pose);
    if (!(dir.squaredNorm() > 0)) return guess;
    dir.normalize();
    if (!closed_) {
      const double d = std::min(s, 1 - s) * m_;  // from the nearer end, in intervals
      const int side = end_side_[s <= 0.5 ? 0 : 1];
      if (d < 1 && side >= 0 && side < 4) {
        Vector2d along = (side == 0 || side == 2) ? Vector2d(1, 0) : Vector2d(0, 1);
        if (along.dot(dir) < 0) along = -along;
        const double w = std::max(d, 0.0) * std::max(d, 0.0) * (3 - 2 * std::max(d, 0.0));  // smoothstep
        dir = (w * dir + (1 - w) * along).normalized();
      }
    }
    Jet out;
    // the end of an arc at a crossing is the saddle of g there: across the arc, g vanishes along
    // the other arc too, so no root on the line says where the end is
    const bool at_crossing = !closed_ && (s <= 0 || s >= 1) &&
                             ends_at_crossing(s <= 0.5 ? 0 : 1, guess.x, interpolated(0.5, t).x, pose);
    out.x = at_crossing ? onto_saddle(guess.x, pose) : onto_line(guess.x, dir, pose);
    const Vector2d grad = gradient(out.x, pose), w = wrapped_parameters(*face_, out.x, period_);
    const double across = grad.dot(dir);
    if (!(std::abs(across) > 0)) return {out.x, guess.xs, guess.xt};
    out.xs = guess.xs - grad.dot(guess.xs) / across * dir;
    out.xt = guess.xt - (grad.dot(guess.xt) + grazing_rate(*face_, pose, w.x(), w.y())) / across * dir;
    return out;
  }

  double g(const Vector2d& x, const PoseJet& pose) const {
    const Vector2d w = wrapped_parameters(*face_, x, period_);
    return grazing_value(*face_, pose, w.x(), w.y());
  }

  /// The gradient of g in the face's parameters (central differences).
  Vector2d gradient(const Vector2d& x, const PoseJet& pose) const {
    const double hu = Settings::envelope_gradient_step * scale_.x(), hv = Settings::envelope_gradient_step * scale_.y();
    return Vector2d((g(x + Vector2d(hu, 0), pose) - g(x - Vector2d(hu, 0), pose)) / (2 * hu),
                    (g(x + Vector2d(0, hv), pose) - g(x - Vector2d(0, hv), pose)) / (2 * hv));
  }

  /// Newton steps along the gradient of g from x to a root (the root of least distance to first order).
  Vector2d onto_set(const Vector2d& x, const PoseJet& pose) const {
    const Vector2d grad = gradient(x, pose);
    return grad.squaredNorm() > 0 ? onto_line(x, grad.normalized(), pose) : x;
  }

  /// Whether end e of the arc (at `end`, `middle` a point of the arc away from its ends) is where it
  /// crosses another arc: inside the domain, or on a side along which g vanishes too (a grazing
  /// seam), where the gradient of g vanishes against its size in the arc's middle.
  bool ends_at_crossing(int e, const Vector2d& end, const Vector2d& middle, const PoseJet& pose) const {
    if (end_side_[e] == 4) return true;
    if (end_side_[e] < 0) return false;
    return gradient(end, pose).norm() < Settings::envelope_saddle_gradient * gradient(middle, pose).norm();
  }

  /// Newton steps from x to a zero of the gradient of g (the saddle where two arcs cross), each at
  /// most Settings::envelope_newton_step of the domain; x itself when the Hessian is singular.
  Vector2d onto_saddle(const Vector2d& x, const PoseJet& pose) const {
    const double most = Settings::envelope_newton_step * scale_.norm();
    const Vector2d h(Settings::envelope_hessian_step * scale_.x(), Settings::envelope_hessian_step * scale_.y());
    Vector2d p = x;
    for (int it = 0; it < 30; ++it) {
      const Vector2d grad = gradient(p, pose);
      Eigen::Matrix2d hess;
      hess.col(0) = (gradient(p + Vector2d(h.x(), 0), pose) - gradient(p - Vector2d(h.x(), 0), pose)) / (2 * h.x());
      hess.col(1) = (gradient(p + Vector2d(0, h.y()), pose) - gradient(p - Vector2d(0, h.y()), pose)) / (2 * h.y());
      if (!(std::abs(hess.determinant()) > 0)) break;
      Vector2d step = -hess.fullPivLu().solve(grad);
      if (!step.allFinite()) break;
      if (step.norm() > most) step *= most / step.norm();
      p += step;
      if (step.norm() < Settings::envelope_newton_stop * scale_.norm()) break;
    }
    return p;
  }

  /// Newton steps from x along the unit direction `dir` (in the face's parameters) to a root of g,
  /// each at most Settings::envelope_newton_step of the domain (so that a flat stretch of g does not throw the point
  /// onto another arc).
  Vector2d onto_line(const Vector2d& x, const Vector2d& dir, const PoseJet& pose) const {
    const double h = Settings::envelope_gradient_step * scale_.norm(), most = Settings::envelope_newton_step * scale_.norm();
    double lambda = 0;
    for (int it = 0; it < 60; ++it) {
      const Vector2d p = x + lambda * dir;
      const double d = (g(p + h * dir, pose) - g(p - h * dir, pose)) / (2 * h);
      if (!(std::abs(d) > 0)) break;
      const double step = std::clamp(-g(p, pose) / d, -most, most);
      lambda += step;
      if (std::abs(step) < Settings::envelope_newton_stop * scale_.norm()) break;
    }
    return x + lambda * dir;
  }

  /// `arc` at m_ + 1 (closed: m_) points at equal fractions of its length in space, each moved onto
  /// the grazing set at t; an open arc's ends are kept. Placed first along the traced polyline, then
  /// twice again along the cubic through the placed points, so that the fractions no longer follow
  /// the polyline's uneven points (they would make the sheet's parametrization jitter from one
  /// instant to the next).
  std::vector<Vector2d> resampled(const std::vector<Vector2d>& arc, double t) const {
    const PoseJet pose = motion_->pose(t);
    std::vector<Vector2d> row = placed(arc, pose, [&arc](std::size_t seg, double f) {
      return Vector2d(arc[seg - 1] + f * (arc[seg] - arc[seg - 1]));
    }, arc.size() - 1);
    for (int pass = 0; pass < 2; ++pass) {
      std::vector<Vector2d> along = row;
      if (closed_) along.push_back(row.front());
      const detail::CubicSpline2 cubic = spline_through(row);
      row = placed(along, pose, [this, &cubic](std::size_t seg, double f) {
        return cubic((double(seg - 1) + f) / m_);
      }, along.size() - 1);
    }
    return row;
  }

  /// Points at equal fractions of the length of the polyline `pts` (segments 1..segments), each
  /// where `between(segment, fraction)` puts it, moved onto the grazing set.
  template <class Between>
  std::vector<Vector2d> placed(const std::vector<Vector2d>& pts, const PoseJet& pose, Between between,
                               std::size_t segments) const {
    std::vector<double> length{0.0};
    for (std::size_t i = 1; i <= segments; ++i) length.push_back(length.back() + (point(pts[i]) - point(pts[i - 1])).norm());
    const int count = closed_ ? m_ : m_ + 1;
    std::vector<Vector2d> row;
    std::size_t seg = 1;
    for (int i = 0; i < count; ++i) {
      if (!closed_ && (i == 0 || i == m_)) {
        const Vector2d end = i == 0 ? pts.front() : pts[segments];
        row.push_back(ends_at_crossing(i == 0 ? 0 : 1, end, pts[segments / 2], pose) ? onto_saddle(end, pose) : end);
        continue;
      }
      const double target = length.back() * i / m_;
      while (seg < segments && length[seg] < target) ++seg;
      const double span = length[seg] - length[seg - 1];
      const double f = std::clamp(span > 0 ? (target - length[seg - 1]) / span : 0.0, 0.0, 1.0);
      row.push_back(onto_set(between(seg, f), pose));
    }
    return row;
  }

  /// The spline through a row's points at s = i / m_ (closed: periodic in s with period 1).
  detail::CubicSpline2 spline_through(std::vector<Vector2d> row) const {
    if (closed_) row.push_back(row.front());
    std::vector<double> knots;
    for (std::size_t i = 0; i < row.size(); ++i) knots.push_back(double(i) / m_);
    return detail::CubicSpline2(std::move(knots), std::move(row), closed_);
  }

  Vector3d point(const Vector2d& x) const {
    const Vector2d w = wrapped_parameters(*face_, x, period_);
    return face_->eval(w.x(), w.y()).x;
  }

  /// The sheet's body point at (s, t) before Newton, with its derivatives: the spline in t through
  /// the rows' points at s.
  Jet interpolated(double s, double t) const {
    std::vector<Vector2d> at_s, along_s;
    for (const auto& row : rows_) {
      at_s.push_back(row(s));
      along_s.push_back(row.derivative(s));
    }
    const detail::CubicSpline2 in_t(t_, std::move(at_s), false), ds_in_t(t_, std::move(along_s), false);
    return {in_t(t), ds_in_t(t), in_t.derivative(t)};
  }

  PatchPtr face_;
  std::shared_ptr<const StageMotion> motion_;
  std::vector<double> t_;
  bool closed_;
  int end_side_[2] = {-1, -1};
  int m_ = 16;
  Vector2d period_, scale_;
  std::vector<detail::CubicSpline2> rows_;
};

}  // namespace

PatchPtr envelope_patch(const PatchPtr& face, std::shared_ptr<const StageMotion> motion, const GrazingTrack& track,
                        const std::string& what) {
  if (track.t.size() < 2 || track.arcs.size() != track.t.size())
    throw std::invalid_argument("envelope_patch: a track needs arcs at two instants at least");
  auto sheet = std::make_shared<const Sheet>(face, std::move(motion), track);
  const double t0 = track.t.front(), t1 = track.t.back();
  auto map = [sheet](const double* st) {
    const double t = st[1];
    const auto j = sheet->at(st[0], t);
    const Vector2d w = wrapped_parameters(*sheet->face(), j.x, sheet->period());
    const PatchPoint y = sheet->face()->eval(w.x(), w.y());
    const PoseJet P = sheet->motion().pose(t);
    PatchPoint p;
    p.x = P.R * y.x + P.p;
    p.xu = P.R * (y.xu * j.xs.x() + y.xv * j.xs.y());
    p.xv = P.dR * y.x + P.dp + P.R * (y.xu * j.xt.x() + y.xv * j.xt.y());
    return p;
  };
  return std::make_shared<Patch>(2, std::vector<double>{0.0, t0}, std::vector<double>{1.0, t1}, std::move(map),
                                 PatchForm{}, what);
}

}  // namespace sweep
