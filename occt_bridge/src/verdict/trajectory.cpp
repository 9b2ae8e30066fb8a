// Point membership in a sweep by the paths of points: the trajectory test and its intersections.
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <Bnd_Box.hxx>
#include <BndLib_Add3dCurve.hxx>
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

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <optional>

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

  /// Under a screw, the path of x as an orbit curve over [0, orbit_end()]: the screw's orbit of x
  /// run backwards, carried back by the start's inverse.
  std::optional<OrbitCurve> orbit(const Eigen::Vector3d& x) const {
    if (!screw_) return std::nullopt;
    OrbitCurve o = orbit_of(screw_->joint, x);
    o.b = -o.b;  // a cos(-t) + b sin(-t) + d (-t)
    o.d = -o.d;
    return moved_start_ ? o.mapped(screw_->start.inverse()) : o;
  }
  double orbit_end() const { return screw_ ? screw_->joint.hi : 0.0; }

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

/// Membership by the trajectory: x is swept when y(0) is in the body, or y(t) meets its boundary.
/// An intersector per face is set up once for all points: it meets the trajectories, and the
/// rays that decide whether y(0) is in the body (OCCT's solid classifier decides where a ray
/// cannot).
struct TrajectoryMembership::Impl {
  Impl(const TopoDS_Shape& body, bool solid, const StageMotion& m, double tol, const Eigen::AlignedBox3d& body_box)
      : solid_(solid), paths_(m, body_box, tol), tol_(tol) {
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

  /// Whether the orbit path o of a screw meets face h (its implicit form set): at a root of the
  /// implicit function along o that lies on the face. Unknown when a root's point has no clear
  /// parameters on the surface.
  std::optional<bool> orbit_meets_face(const FaceHit& h, const OrbitCurve& o) const {
    double x0, y0, z0, x1, y1, z1;
    h.box.Get(x0, y0, z0, x1, y1, z1);
    const Eigen::AlignedBox3d region(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
    for (double t : surface_crossings(*h.implicit, o, 0.0, paths_.orbit_end(), region)) {
      const std::optional<bool> on = on_face(h, o.at(t), tol_);
      if (!on || *on) return on;
    }
    return false;
  }

  /// Whether OCCT's intersector finds a point of face h on path c over one of its pieces (each
  /// with its box).
  static bool curve_meets_face(FaceHit& h, const Handle(Geom_Curve)& c,
                               const std::vector<std::pair<double, double>>& pieces, const std::vector<Bnd_Box>& boxes) {
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (h.box.IsOut(boxes[i])) continue;
      Handle(GeomAdaptor_Curve) curve = new GeomAdaptor_Curve(c, pieces[i].first, pieces[i].second);
      h.inter->Perform(curve, pieces[i].first, pieces[i].second);
      if (h.inter->IsDone() && h.inter->NbPnt() > 0) return true;
    }
    return false;
  }

  /// Whether the path of x meets the body's boundary. Under a screw, faces on planes, quadrics and
  /// tori are met by the roots along the path's orbit; other faces by OCCT's intersector.
  bool meets_boundary(const Eigen::Vector3d& x) {
    const auto t0 = Clock::now();
    const std::optional<OrbitCurve> orbit = paths_.orbit(x);
    if (orbit && orbit->a.isZero(0.0) && orbit->b.isZero(0.0) && orbit->d.isZero(0.0))
      return intersect_.record(t0, false);  // a point on a revolute joint's axis does not move
    Handle(Geom_Curve) c;  // the path as an OCCT curve, made when a face needs it
    std::vector<std::pair<double, double>> pieces;
    std::vector<Bnd_Box> boxes;
    for (std::size_t k = 0; k < inter_.size(); ++k) {
      std::optional<bool> hit;
      if (orbit && inter_[k].implicit) hit = orbit_meets_face(inter_[k], *orbit);
      if (!hit) {
        if (c.IsNull()) {
          c = paths_(x);
          if (c.IsNull()) return intersect_.record(t0, false);
          pieces = path_pieces(*c);
          for (const auto& [from, to] : pieces) {
            boxes.emplace_back();
            BndLib_Add3dCurve::Add(GeomAdaptor_Curve(c, from, to), 0.0, boxes.back());
          }
        }
        hit = curve_meets_face(inter_[k], c, pieces, boxes);
      }
      if (!*hit) continue;
      // the face met goes first next time: neighbouring points tend to meet the same face
      if (k > 0) std::rotate(inter_.begin(), inter_.begin() + k, inter_.begin() + k + 1);
      return intersect_.record(t0, true);
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
    : impl_(std::make_unique<Impl>(body, solid, motion, tol, box_of(body))) {}
TrajectoryMembership::TrajectoryMembership(const TopoDS_Shape& body, bool solid, const StageMotion& motion, double tol,
                                           const Eigen::AlignedBox3d& body_box)
    : impl_(std::make_unique<Impl>(body, solid, motion, tol, body_box)) {}
TrajectoryMembership::~TrajectoryMembership() = default;
bool TrajectoryMembership::operator()(const Eigen::Vector3d& x) { return (*impl_)(x); }
int TrajectoryMembership::ray_inside(const Eigen::Vector3d& x) { return sweep::occt::ray_inside(impl_->inter_, x, impl_->tol_); }

}  // namespace sweep::occt
