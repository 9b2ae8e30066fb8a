#include "sweep/envelope.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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
    for (std::size_t k = 0; k < t_.size(); ++k) rows_.push_back(resampled(track.arcs[k], t_[k]));
  }

  /// The body point of the sheet at (s, t), in the face's parameters (of the domain's cover): the
  /// root of the grazing function at t on the line from the interpolated point along the gradient
  /// there. Near an open arc's end on a side of the domain the line turns smoothly to run along the
  /// side (over the first of the m_ intervals), so the end stays on the side and the map stays smooth.
  Vector2d at(double s, double t) const {
    const PoseJet pose = motion_->pose(t);
    const Vector2d guess = interpolated(s, t);
    Vector2d dir = gradient(guess, pose);
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
    return onto_line(guess, dir, pose);
  }

  const PatchPtr& face() const { return face_; }
  const StageMotion& motion() const { return *motion_; }
  const Vector2d& period() const { return period_; }
  bool closed() const { return closed_; }

 private:
  double g(const Vector2d& x, const PoseJet& pose) const {
    const Vector2d w = wrapped_parameters(*face_, x, period_);
    return grazing_value(*face_, pose, w.x(), w.y());
  }

  /// The gradient of g in the face's parameters (central differences).
  Vector2d gradient(const Vector2d& x, const PoseJet& pose) const {
    const double hu = 1e-7 * scale_.x(), hv = 1e-7 * scale_.y();
    return Vector2d((g(x + Vector2d(hu, 0), pose) - g(x - Vector2d(hu, 0), pose)) / (2 * hu),
                    (g(x + Vector2d(0, hv), pose) - g(x - Vector2d(0, hv), pose)) / (2 * hv));
  }

  /// Newton steps along the gradient of g from x to a root (the root of least distance to first order).
  Vector2d onto_set(const Vector2d& x, const PoseJet& pose) const {
    const Vector2d grad = gradient(x, pose);
    return grad.squaredNorm() > 0 ? onto_line(x, grad.normalized(), pose) : x;
  }

  /// Newton steps from x along the unit direction `dir` (in the face's parameters) to a root of g.
  Vector2d onto_line(const Vector2d& x, const Vector2d& dir, const PoseJet& pose) const {
    const double h = 1e-7 * scale_.norm();
    double lambda = 0;
    for (int it = 0; it < 40; ++it) {
      const Vector2d p = x + lambda * dir;
      const double d = (g(p + h * dir, pose) - g(p - h * dir, pose)) / (2 * h);
      if (!(std::abs(d) > 0)) break;
      const double step = -g(p, pose) / d;
      lambda += step;
      if (std::abs(step) < 1e-15 * scale_.norm()) break;
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
      row = placed(along, pose, [this, &row](std::size_t seg, double f) {
        return cubic_on(row, closed_, double(seg - 1) + f);
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
        row.push_back(i == 0 ? pts.front() : pts[segments]);
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

  /// The cubic through a row's points (Catmull-Rom) at x in [0, n - 1] (closed: [0, n), periodic);
  /// an open row is extended past its ends linearly (so the end slopes are one-sided differences).
  static Vector2d cubic_on(const std::vector<Vector2d>& r, bool closed, double x) {
    const int n = int(r.size());
    const int i = std::clamp(int(std::floor(x)), 0, closed ? n - 1 : n - 2);
    const double f = x - i;
    auto p = [&](int j) -> Vector2d {
      if (closed) return r[std::size_t(((j % n) + n) % n)];
      if (j < 0) return 2 * r[0] - r[1];
      if (j > n - 1) return 2 * r[std::size_t(n - 1)] - r[std::size_t(n - 2)];
      return r[std::size_t(j)];
    };
    return hermite(p(i), p(i + 1), 0.5 * (p(i + 1) - p(i - 1)), 0.5 * (p(i + 2) - p(i)), f);
  }

  Vector3d point(const Vector2d& x) const {
    const Vector2d w = wrapped_parameters(*face_, x, period_);
    return face_->eval(w.x(), w.y()).x;
  }

  /// Row k's point at fraction s.
  Vector2d row_at(std::size_t k, double s) const { return cubic_on(rows_[k], closed_, s * m_); }

  /// The sheet's body point at (s, t) before Newton: cubic in t through the rows' points at s.
  Vector2d interpolated(double s, double t) const {
    const int n = int(t_.size());
    int k = int(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
    k = std::clamp(k, 0, n - 2);
    const double h = t_[std::size_t(k + 1)] - t_[std::size_t(k)], f = (t - t_[std::size_t(k)]) / h;
    auto row = [&](int j) { return row_at(std::size_t(std::clamp(j, 0, n - 1)), s); };
    auto time = [&](int j) { return t_[std::size_t(std::clamp(j, 0, n - 1))]; };
    const Vector2d a = row(k), b = row(k + 1);
    // slopes from the neighbouring rows, scaled to this interval
    const Vector2d da = (row(k + 1) - row(k - 1)) / (time(k + 1) - time(k - 1)) * h;
    const Vector2d db = (row(k + 2) - row(k)) / (time(k + 2) - time(k)) * h;
    return hermite(a, b, da, db, f);
  }

  static Vector2d hermite(const Vector2d& a, const Vector2d& b, const Vector2d& da, const Vector2d& db, double f) {
    const double f2 = f * f, f3 = f2 * f;
    return (2 * f3 - 3 * f2 + 1) * a + (f3 - 2 * f2 + f) * da + (-2 * f3 + 3 * f2) * b + (f3 - f2) * db;
  }

  PatchPtr face_;
  std::shared_ptr<const StageMotion> motion_;
  std::vector<double> t_;
  bool closed_;
  int end_side_[2] = {-1, -1};
  int m_ = 16;
  Vector2d period_, scale_;
  std::vector<std::vector<Vector2d>> rows_;
};

}  // namespace

PatchPtr envelope_patch(const PatchPtr& face, std::shared_ptr<const StageMotion> motion, const GrazingTrack& track,
                        const std::string& what) {
  if (track.t.size() < 2 || track.arcs.size() != track.t.size())
    throw std::invalid_argument("envelope_patch: a track needs arcs at two instants at least");
  auto sheet = std::make_shared<const Sheet>(face, std::move(motion), track);
  const double t0 = track.t.front(), t1 = track.t.back();
  auto world = [sheet](double s, double t) {
    const Vector2d x = wrapped_parameters(*sheet->face(), sheet->at(s, t), sheet->period());
    return sheet->motion().transform(t) * sheet->face()->eval(x.x(), x.y()).x;
  };
  auto map = [sheet, world, t0, t1](const double* st) {
    const double s = st[0], t = st[1], hs = 1e-6, ht = 1e-6 * (t1 - t0);
    // central differences, one-sided (second order) at the ends of an open range
    auto diff = [](const std::function<Vector3d(double)>& f, double x, double h, double lo, double hi, bool periodic) {
      if (periodic || (x - h >= lo && x + h <= hi)) return Vector3d((f(x + h) - f(x - h)) / (2 * h));
      const double d = x - h < lo ? h : -h;
      return Vector3d((-3 * f(x) + 4 * f(x + d) - f(x + 2 * d)) / (2 * d));
    };
    PatchPoint p;
    p.x = world(s, t);
    p.xu = diff([&](double a) { return world(a, t); }, s, hs, 0, 1, sheet->closed());
    p.xv = diff([&](double b) { return world(s, b); }, t, ht, t0, t1, false);
    return p;
  };
  return std::make_shared<Patch>(2, std::vector<double>{0.0, t0}, std::vector<double>{1.0, t1}, std::move(map),
                                 PatchForm{}, what);
}

}  // namespace sweep
