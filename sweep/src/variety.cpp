#include "sweep/variety.hpp"

#include "sweep/contour.hpp"

#include <algorithm>
#include <cmath>

namespace sweep {

using Eigen::Vector2d;
using Eigen::Vector3d;

PatchPtr moved_patch(const PatchPtr& patch, std::shared_ptr<const StageMotion> motion, double t,
                     const std::string& what) {
  const Eigen::Isometry3d M = motion->transform(t);
  PatchForm form = patch->form();
  form.origin = M * form.origin;
  form.axis = M.linear() * form.axis;
  form.ref = M.linear() * form.ref;
  auto map = [patch, M](const double* s) {
    const PatchPoint p = patch->eval(s);
    return PatchPoint{M * p.x, M.linear() * p.xu, M.linear() * p.xv};
  };
  std::vector<double> lo, hi;
  for (int k = 0; k < patch->dim(); ++k) {
    lo.push_back(patch->lo(k));
    hi.push_back(patch->hi(k));
  }
  auto out = std::make_shared<Patch>(patch->dim(), lo, hi, std::move(map), form, what, patch->orientation());
  out->fixed = patch->fixed;
  out->fixed.push_back({"t", t});
  out->trimmed = patch->trimmed;
  return out;
}

PatchPtr swept_curve(const PatchPtr& curve, std::shared_ptr<const StageMotion> motion, const std::string& what) {
  auto map = [curve, motion](const double* s) {
    const PatchPoint c = curve->eval(s);
    const PoseJet P = motion->pose(s[1]);
    return PatchPoint{P.R * c.x + P.p, P.R * c.xu, P.dR * c.x + P.dp};
  };
  auto out = std::make_shared<Patch>(2, std::vector<double>{curve->lo(0), motion->lo()},
                                     std::vector<double>{curve->hi(0), motion->hi()}, std::move(map), PatchForm{},
                                     what);
  out->fixed = curve->fixed;
  return out;
}

double grazing_value(const Patch& face, const PoseJet& P, double u, double v) {
  const PatchPoint p = face.eval(u, v);
  const Vector3d w = P.R.transpose() * (P.dR * p.x + P.dp);
  return p.xu.cross(p.xv).dot(w);
}

double grazing_rate(const Patch& face, const PoseJet& P, double u, double v) {
  const PatchPoint p = face.eval(u, v);
  const Vector3d dw = P.dR.transpose() * (P.dR * p.x + P.dp) + P.R.transpose() * (P.ddR * p.x + P.ddp);
  return p.xu.cross(p.xv).dot(dw);
}

Vector2d grazing_drift(const Patch& face, const PoseJet& P, double u, double v, double h) {
  const double hu = h * (face.hi(0) - face.lo(0)), hv = h * (face.hi(1) - face.lo(1));
  const Vector2d grad((grazing_value(face, P, u + hu, v) - grazing_value(face, P, u - hu, v)) / (2 * hu),
                      (grazing_value(face, P, u, v + hv) - grazing_value(face, P, u, v - hv)) / (2 * hv));
  const double g2 = grad.squaredNorm();
  if (!(g2 > 0)) return Vector2d::Zero();
  return -grazing_rate(face, P, u, v) * grad / g2;
}

std::vector<double> grazing_roots_on_circle(const Patch& face, const PoseJet& pose, double v, double scale,
                                            bool* whole) {
  const double u0 = face.lo(0);
  const double g0 = grazing_value(face, pose, u0, v), g1 = grazing_value(face, pose, u0 + M_PI / 2, v),
               g2 = grazing_value(face, pose, u0 + M_PI, v);
  const double C = 0.5 * (g0 + g2), A = 0.5 * (g0 - g2), B = g1 - C, rho = std::hypot(A, B);
  if (whole) *whole = rho <= 1e-12 * scale && std::abs(C) <= 1e-12 * scale;
  if (rho <= 1e-12 * scale || std::abs(C) > rho) return {};
  const double phi = std::atan2(B, A), half = std::acos(std::clamp(-C / rho, -1.0, 1.0));
  auto into = [u0](double u) { return u0 + std::fmod(std::fmod(u, 2 * M_PI) + 2 * M_PI, 2 * M_PI); };
  if (half == 0.0) return {into(phi)};
  std::vector<double> out{into(phi - half), into(phi + half)};
  std::sort(out.begin(), out.end());
  return out;
}

namespace {

/// g over the face at one pose, read just inside the domain on the sides along which it vanishes
/// (there its sign is the one of the face beside the side, not rounding's).
class GrazingField {
 public:
  GrazingField(const Patch& face, const PoseJet& pose) : face_(face), pose_(pose) {
    for (int k = 0; k < 2; ++k) span_[k] = face.hi(k) - face.lo(k);
  }
  double at(Vector2d s) const {
    const double in = 1e-7;
    if (vanishing_[3]) s.x() = std::max(s.x(), face_.lo(0) + in * span_[0]);
    if (vanishing_[1]) s.x() = std::min(s.x(), face_.hi(0) - in * span_[0]);
    if (vanishing_[0]) s.y() = std::max(s.y(), face_.lo(1) + in * span_[1]);
    if (vanishing_[2]) s.y() = std::min(s.y(), face_.hi(1) - in * span_[1]);
    return grazing_value(face_, pose_, s.x(), s.y());
  }
  bool vanishing_[4] = {false, false, false, false};

 private:
  const Patch& face_;
  const PoseJet& pose_;
  double span_[2];
};

/// The sides of the domain along which g vanishes to rounding: sampled at 4n points against the
/// largest |g| of the grid.
void find_vanishing_sides(const Patch& face, const PoseJet& pose, int n, double scale, GrazingSet& out,
                          GrazingField& field) {
  for (int side = 0; side < 4; ++side) {
    bool zero = true;
    for (int i = 0; i <= 4 * n && zero; ++i) {
      const double f = double(i) / (4 * n);
      const double u = side == 1 ? face.hi(0) : side == 3 ? face.lo(0) : face.lo(0) + (face.hi(0) - face.lo(0)) * f;
      const double v = side == 0 ? face.lo(1) : side == 2 ? face.hi(1) : face.lo(1) + (face.hi(1) - face.lo(1)) * f;
      zero = std::abs(grazing_value(face, pose, u, v)) <= 1e-11 * scale;
    }
    if (zero) {
      out.sides.push_back(side);
      field.vanishing_[side] = true;
    }
  }
}

/// An odd number of grid intervals near n (at least 3): a face's lines of symmetry (its half and
/// quarter turns) then fall inside grid cells, not on grid lines where g is zero at every node.
int odd_below(int n) { return std::max(3, n % 2 ? n - 2 : n - 3); }

}  // namespace

GrazingSet grazing_set(const Patch& face, const StageMotion& motion, double t, int n) {
  GrazingSet out;
  const PoseJet pose = motion.pose(t);
  GrazingField field(face, pose);
  double scale = 0;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      scale = std::max(scale, std::abs(grazing_value(face, pose, face.lo(0) + (face.hi(0) - face.lo(0)) * i / n,
                                                     face.lo(1) + (face.hi(1) - face.lo(1)) * j / n)));
  if (!(scale > 0)) return out;  // the face does not move, or grazes everywhere
  find_vanishing_sides(face, pose, n, scale, out, field);
  // the zero set, traced with the values read just inside vanishing sides; branches meet at a
  // saddle where g is flat (Settings::grazing_crossing): they cross there
  out.curves = contour_chains([&field](const Vector2d& s) { return field.at(s); }, face.lo(0), face.hi(0), face.lo(1),
                              face.hi(1), odd_below(n), odd_below(n - 2), Settings::grazing_crossing * scale);
  return out;
}

}  // namespace sweep
