// Point membership in a sweep by the paths of points: the trajectory test and its intersections.
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <Bnd_Box.hxx>
#include <BndLib_Add3dCurve.hxx>
#include <ElCLib.hxx>
#include <ElSLib.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Line.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <IntCurvesFace_Intersector.hxx>
#include <TColgp_Array1OfPnt.hxx>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>

#include "base/internal.hpp"
#include "varieties/tube_fit.hpp"
#include "verdict/solid_rays.hpp"

namespace sweep::occt {

namespace {

using Clock = std::chrono::steady_clock;

/// The paths back through a motion of world points, in the frame of the body the motion moves:
/// y(t) = M(t)^-1 x, t in [lo, hi]. Under a slide or a turn from `start` they are
/// start^-1 exp(-xi q) x, q in [0, T]: segments and circles. Otherwise (helices too, unless their
/// fit below fails: then each point's helix is fitted) y(t) = A(t) (x - c) + y_c(t) is affine in x: A and the path of c are fitted once as one
/// B-spline of twelve values (a least-squares fit is linear in its samples, so the path of any x is
/// the B-spline of the poles A_i (x - c) + b_i), to within the tolerance over a region about c that
/// grows when a point lies beyond it.
class BackwardPaths {
 public:
  BackwardPaths(const StageMotion& m, const Eigen::AlignedBox3d& body_box, double tol) : m_(m), tol_(tol) {
    double radius = 0;
    for (int k = 0; k < 8; ++k)
      radius = std::max(radius, body_box.corner(Eigen::AlignedBox3d::CornerType(k)).norm());
    screw_ = m.as_screw(radius);
    if (screw_) {
      moved_start_ = !screw_->start.isApprox(Eigen::Isometry3d::Identity(), 0.0);
      if (moved_start_) from_start_ = to_trsf(screw_->start.inverse());
      // segments and circles in closed form; a helix is fitted once for all points like any other
      // path (fitting each point's own helix took most of the time of a screw-swept part), or
      // point by point where that fit does not reach the tolerance (many turns)
      const bool helix = screw_->joint.type != JointType::Prismatic && screw_->joint.pitch != 0;
      if (!helix) return;
    }
    // the region of the swept points: about the body's centre at the start, as far as it goes
    const Eigen::Vector3d b = body_box.center();
    c_ = m.transform(m.lo()) * b;
    double reach = 0;
    const int n = Settings::path_reach_samples;
    for (int k = 0; k <= n; ++k)
      reach = std::max(reach, (m.transform(m.lo() + (m.hi() - m.lo()) * k / n) * b - c_).norm());
    fit_for(reach + 0.5 * body_box.diagonal().norm());
  }

  /// Where the path of x starts: M(lo)^-1 x.
  Eigen::Vector3d start_point(const Eigen::Vector3d& x) const {
    if (screw_ && !moved_start_) return x;  // (a screw's start is the body's frame)
    return m_.body_point(m_.lo(), x);
  }

  /// The path of x (null when x does not move: a point on a revolute joint's axis).
  Handle(Geom_Curve) operator()(const Eigen::Vector3d& x) {
    // the fit's error at x is at most its error per unit of |x - c|_1 and per the path of c
    if (fitted_ && !(fit_.error * (1 + (x - c_).lpNorm<1>()) <= tol_)) fit_for((x - c_).norm() * 2);
    if (!fitted_) {
      Handle(Geom_Curve) c = screw_path(x);
      if (!c.IsNull() && moved_start_) c->Transform(from_start_);
      return c;
    }
    const int np = int(fit_.poles.rows());
    TColgp_Array1OfPnt poles(1, np);
    const Eigen::Vector3d d = x - c_;
    for (int i = 0; i < np; ++i) {
      const Eigen::RowVectorXd& row = fit_.poles.row(i);
      const Eigen::Vector3d y = row.segment<3>(0).transpose() * d(0) + row.segment<3>(3).transpose() * d(1) +
                                row.segment<3>(6).transpose() * d(2) + row.segment<3>(9).transpose();
      poles.SetValue(i + 1, to_pnt(y));
    }
    TColStd_Array1OfReal knots(1, int(fit_.knots.size()));
    TColStd_Array1OfInteger mults(1, int(fit_.knots.size()));
    knots_of(fit_, knots, mults);
    return new Geom_BSplineCurve(poles, knots, mults, degree);
  }

 private:
  static constexpr int degree = 7;

  Handle(Geom_Curve) screw_path(const Eigen::Vector3d& x) const {
    const ScrewJoint& j = screw_->joint;
    const double T = j.hi;
    if (j.type == JointType::Prismatic) {
      Handle(Geom_Line) l = new Geom_Line(to_pnt(x), gp_Dir(to_vec(-j.direction)));
      return new Geom_TrimmedCurve(l, 0.0, T);
    }
    const Eigen::Vector3d foot = j.point + j.direction * j.direction.dot(x - j.point);
    const double r = (x - foot).norm();
    if (j.pitch == 0) {
      if (r < Settings::path_on_axis) return nullptr;
      gp_Ax2 ax(to_pnt(foot), gp_Dir(to_vec(-j.direction)), gp_Dir(to_vec((x - foot) / r)));
      Handle(Geom_Circle) c = new Geom_Circle(ax, r);
      return new Geom_TrimmedCurve(c, 0.0, T);
    }
    const int fewest = Settings::helix_path_min_samples;
    const int n = std::max(fewest, int(std::ceil(T / (M_PI / Settings::helix_path_samples_per_half_turn))));
    TColgp_Array1OfPnt pts(1, n + 1);
    for (int k = 0; k <= n; ++k) pts.SetValue(k + 1, to_pnt(j.transform(-T * k / n) * x));
    GeomAPI_PointsToBSpline fit(pts, 3, 8, GeomAbs_C2, tol_);
    return Handle(Geom_Curve)(fit.Curve().get());
  }

  /// Fits A(t) and the path of c, spans doubled until points within `reach` of c are within the
  /// tolerance; fitted_ tells whether a fit of up to Settings::path_fit_spans_max spans
  /// (Settings::screw_path_fit_spans_max for a screw) is. @throws ComputeError when none is and the
  /// motion is no screw (whose paths have a way out).
  void fit_for(double reach) {
    const double lo = m_.lo(), L = m_.hi() - lo;
    const auto row = [&](double u) {
      const Eigen::Isometry3d B = m_.transform(std::min(lo + u, m_.hi())).inverse();
      Eigen::RowVectorXd r(12);
      for (int k = 0; k < 3; ++k) r.segment<3>(3 * k) = B.linear().col(k).transpose();
      r.segment<3>(9) = (B * c_).transpose();
      return r;
    };
    // (a screw's helices have a way out, point by point; a dense fit of 1024 spans takes seconds)
    const int most = screw_ ? Settings::screw_path_fit_spans_max : Settings::path_fit_spans_max;
    for (int spans = Settings::path_fit_spans_first; spans <= most; spans *= 2) {
      fit_ = fit_bspline(row, 12, L, degree, spans, 1);
      fitted_ = fit_.error * (1 + std::sqrt(3.0) * reach) <= tol_;
      if (fitted_) return;
    }
    if (!screw_)
      throw ComputeError("the motion's inverse poses could not be fitted within " + std::to_string(tol_) +
                         " for the paths of the membership test");
  }

  const StageMotion& m_;
  double tol_;
  std::optional<ScrewSegment> screw_;
  bool fitted_ = false;  ///< paths come from fit_ (else from the screw, point by point)
  bool moved_start_ = false;  ///< the screw's start is not the identity: its paths are carried back
  gp_Trsf from_start_;        ///< by start^-1
  Eigen::Vector3d c_ = Eigen::Vector3d::Zero();
  Fit fit_;
};

}  // namespace

std::vector<double> circle_torus_angles(const gp_Circ& c, const gp_Torus& tor, bool* solved) {
  using C = std::complex<double>;
  using Trig = std::array<C, 5>;  // coefficients of exp(i k w), k = -2..2
  const gp_Ax3& ax = tor.Position();
  const Eigen::Vector3d O = to_eigen(ax.Location()), Z = to_eigen(gp_Vec(ax.Direction()));
  const Eigen::Vector3d Cc = to_eigen(c.Location()), Xc = to_eigen(gp_Vec(c.XAxis().Direction())),
                        Yc = to_eigen(gp_Vec(c.YAxis().Direction()));
  const double rho = c.Radius(), R = tor.MajorRadius(), r = tor.MinorRadius();
  const Eigen::Vector3d d0 = Cc - O;
  // g0 + g1 cos w + g2 sin w
  auto trig = [](double g0, double g1, double g2) {
    Trig t{};
    t[2] = g0;
    t[3] = C(g1, -g2) / 2.0;
    t[1] = std::conj(t[3]);
    return t;
  };
  auto mul = [](const Trig& a, const Trig& b) {  // both of degree 1 at most
    Trig t{};
    for (int i = 1; i <= 3; ++i)
      for (int k = 1; k <= 3; ++k) t[i + k - 2] += a[i] * b[k];
    return t;
  };
  // |d|^2 and d . z along the circle, d = P(w) - O
  const Trig q = trig(d0.squaredNorm() + rho * rho, 2 * rho * d0.dot(Xc), 2 * rho * d0.dot(Yc));
  const Trig a = trig(d0.dot(Z), rho * Xc.dot(Z), rho * Yc.dot(Z));
  Trig sq = q;
  sq[2] += R * R - r * r;
  const Trig s2 = mul(sq, sq), a2 = mul(a, a);
  Trig F{};
  double scale = 0;
  for (int k = 0; k < 5; ++k) {
    F[k] = s2[k] - 4 * R * R * q[k] + 4 * R * R * a2[k];
    scale = std::max(scale, std::abs(F[k]));
  }
  std::vector<double> angles;
  *solved = std::abs(F[4]) > Settings::circle_torus_leading * scale;
  if (!*solved) return angles;
  // z^2 F = sum F[m] z^m: the roots of this quartic are its companion matrix's eigenvalues
  Eigen::Matrix4cd comp = Eigen::Matrix4cd::Zero();
  for (int m = 0; m < 4; ++m) comp(m, 3) = -F[m] / F[4];
  for (int m = 1; m < 4; ++m) comp(m, m - 1) = 1.0;
  const Eigen::ComplexEigenSolver<Eigen::Matrix4cd> es(comp, false);
  if (es.info() != Eigen::Success) {
    *solved = false;
    return angles;
  }
  for (int k = 0; k < 4; ++k) {
    const C z = es.eigenvalues()(k);
    // a root off the unit circle by more than rounding (a double root is found to about the
    // square root of the machine precision) is a point where the circle misses the torus
    if (std::abs(std::abs(z) - 1.0) > Settings::circle_torus_root_rounding) continue;
    double w = std::arg(z);
    if (w < 0) w += 2 * M_PI;
    angles.push_back(w);
  }
  std::sort(angles.begin(), angles.end());
  return angles;
}

/// Membership by the trajectory: x is swept when y(0) is in the body, or y(t) meets its boundary.
/// An intersector per face is set up once for all points: it meets the trajectories, and the
/// rays that decide whether y(0) is in the body (OCCT's solid classifier decides where a ray
/// cannot).
struct TrajectoryMembership::Impl {
  Impl(const TopoDS_Shape& body, bool solid, const StageMotion& m, double tol)
      : solid_(solid), paths_(m, box_of(body), tol), tol_(tol) {
    if (solid_) cls_.Load(body);
    inter_ = face_hits(body, tol);
  }
  /// Whether x is swept: the trajectory meets the body's boundary, or lies wholly inside it (then
  /// so does y(0)). Either test can come first; the order that has been cheaper so far does (the
  /// answer does not depend on it).
  bool operator()(const Eigen::Vector3d& x) {
    if (!solid_) return meets_boundary(x);
    const double classify_first = classify_.cost() + (1 - classify_.success()) * intersect_.cost();
    const double intersect_first = intersect_.cost() + (1 - intersect_.success()) * classify_.cost();
    if (classify_first < intersect_first) return inside_at_start(x) || meets_boundary(x);
    return meets_boundary(x) || inside_at_start(x);
  }

  /// Running cost and success rate of one test.
  struct Stats {
    double seconds = 0, runs = 0, successes = 0;
    double cost() const { return (seconds + Settings::membership_cost_prior) / (runs + 1); }
    double success() const { return (successes + 1) / (runs + 2); }
    bool record(Clock::time_point t0, bool ok) {
      seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      runs += 1;
      successes += ok;
      return ok;
    }
  };

  /// Whether the path of x starts inside the body: y(lo) = M(lo)^-1 x.
  bool inside_at_start(const Eigen::Vector3d& world) {
    const auto t0 = Clock::now();
    const Eigen::Vector3d x = paths_.start_point(world);
    const int by_ray = sweep::occt::ray_inside(inter_, x, tol_);
    if (by_ray >= 0) return classify_.record(t0, by_ray == 1);
    cls_.Perform(to_pnt(x), tol_);
    return classify_.record(t0, cls_.State() == TopAbs_IN);
  }

  /// Whether the trajectory circle c, over [0, T], meets the torus face classified by fc (see
  /// circle_torus_angles for *solved).
  static bool circle_meets_face(const gp_Circ& c, double T, const gp_Torus& tor, BRepTopAdaptor_FClass2d& fc,
                                bool* solved) {
    for (double w : circle_torus_angles(c, tor, solved)) {
      if (w > T + Settings::angle_resolution && w < 2 * M_PI - Settings::angle_resolution) continue;
      if (w > T) w = 0.0;
      double u, v;
      ElSLib::Parameters(tor, ElCLib::Value(w, c), u, v);
      const TopAbs_State st = fc.Perform(gp_Pnt2d(u, v));
      if (st == TopAbs_IN || st == TopAbs_ON) return true;
    }
    return false;
  }

  /// The parameter ranges of path c, each cut once its tangent has turned by more than
  /// Settings::trajectory_piece_turn (at the path's sampled points). OCCT's curve-face intersector
  /// samples the range it is given: over a whole helix of turns it stepped over a short chord
  /// through a cylinder face, which it found over a part of the path.
  static std::vector<std::pair<double, double>> path_pieces(const Geom_Curve& c) {
    const double a = c.FirstParameter(), b = c.LastParameter();
    std::vector<std::pair<double, double>> pieces;
    double from = a, turned = 0;
    gp_Pnt p;
    gp_Vec before;
    c.D1(a, p, before);
    const int n = Settings::trajectory_turn_samples;
    for (int k = 1; k <= n; ++k) {
      const double u = a + (b - a) * k / n;
      gp_Vec d;
      c.D1(u, p, d);
      if (before.Magnitude() > 0 && d.Magnitude() > 0) turned += before.Angle(d);
      before = d;
      if (turned > Settings::trajectory_piece_turn && k < n) {
        pieces.push_back({from, u});
        from = u;
        turned = 0;
      }
    }
    pieces.push_back({from, b});
    return pieces;
  }

  bool meets_boundary(const Eigen::Vector3d& x) {
    const auto t0 = Clock::now();
    Handle(Geom_Curve) c = paths_(x);
    if (c.IsNull()) return intersect_.record(t0, false);
    Handle(Geom_Circle) circle;
    if (auto tc = Handle(Geom_TrimmedCurve)::DownCast(c)) circle = Handle(Geom_Circle)::DownCast(tc->BasisCurve());
    const double T = c->LastParameter();
    for (const auto& [from, to] : path_pieces(*c)) {
      Handle(GeomAdaptor_Curve) curve = new GeomAdaptor_Curve(c, from, to);
      Bnd_Box box;
      BndLib_Add3dCurve::Add(*curve, 0.0, box);
      for (std::size_t k = 0; k < inter_.size(); ++k) {
        if (inter_[k].box.IsOut(box)) continue;
        if (circle && inter_[k].torus) {
          bool solved = false;
          const bool hit = circle_meets_face(circle->Circ(), T, *inter_[k].torus, *inter_[k].fc, &solved);
          if (solved) {
            if (!hit) continue;
            if (k > 0) std::rotate(inter_.begin(), inter_.begin() + k, inter_.begin() + k + 1);
            return intersect_.record(t0, true);
          }
        }
        inter_[k].inter->Perform(curve, from, to);
        if (!inter_[k].inter->IsDone() || inter_[k].inter->NbPnt() == 0) continue;
        // the face met goes first next time: neighbouring points tend to meet the same face
        if (k > 0) std::rotate(inter_.begin(), inter_.begin() + k, inter_.begin() + k + 1);
        return intersect_.record(t0, true);
      }
    }
    return intersect_.record(t0, false);
  }

  bool solid_;
  BackwardPaths paths_;
  double tol_;
  BRepClass3d_SolidClassifier cls_;
  std::vector<FaceHit> inter_;
  Stats classify_, intersect_;
};

TrajectoryMembership::TrajectoryMembership(const TopoDS_Shape& body, bool solid, const StageMotion& motion, double tol)
    : impl_(std::make_unique<Impl>(body, solid, motion, tol)) {}
TrajectoryMembership::~TrajectoryMembership() = default;
bool TrajectoryMembership::operator()(const Eigen::Vector3d& x) { return (*impl_)(x); }
int TrajectoryMembership::ray_inside(const Eigen::Vector3d& x) { return sweep::occt::ray_inside(impl_->inter_, x, impl_->tol_); }

}  // namespace sweep::occt
