#include "sweep/candidate_patches.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cstdio>

#include "sweep/envelope.hpp"
#include "sweep/error.hpp"
#include "sweep/grazing_family.hpp"
#include "sweep/settings.hpp"
#include "sweep/variety.hpp"

namespace sweep {
namespace {

std::string number(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

/// Side `side` of a face's domain as a curve patch (0: v = lo, 1: u = hi, 2: v = hi, 3: u = lo), in
/// the direction of its free parameter.
PatchPtr side_curve(const PatchPtr& face, int side, const std::string& what) {
  const bool along_u = side == 0 || side == 2;
  const double fixed = side == 0 ? face->lo(1) : side == 1 ? face->hi(0) : side == 2 ? face->hi(1) : face->lo(0);
  auto map = [face, along_u, fixed](const double* s) {
    const PatchPoint p = along_u ? face->eval(s[0], fixed) : face->eval(fixed, s[0]);
    return PatchPoint{p.x, along_u ? p.xu : p.xv, Eigen::Vector3d::Zero()};
  };
  const int k = along_u ? 0 : 1;
  return std::make_shared<Patch>(1, std::vector<double>{face->lo(k)}, std::vector<double>{face->hi(k)}, std::move(map),
                                 PatchForm{}, what);
}

/// The envelope sheets of the sides of a face's domain that graze all along over spans of t (a
/// seam line of a face grazing, not a pole), each seam once.
void add_side_sheets(const PatchPtr& face, int face_index, const std::shared_ptr<const StageMotion>& motion,
                     const GrazingFamily& family, std::vector<CandidatePatch>& out) {
  const Eigen::Vector2d period = parameter_periods(*face);
  const double size = (side_point(*face, 0, 0) - side_point(*face, 2, 0.5)).norm() +
                      (side_point(*face, 1, 0) - side_point(*face, 3, 0.5)).norm();
  static const char* names[4] = {"v = lo", "u = hi", "v = hi", "u = lo"};
  for (const GrazingFamily::SideSpan& span : family.sides) {
    const int side = span.side;
    if ((side == 1 && period.x() > 0) || (side == 2 && period.y() > 0)) continue;  // the seam's other side
    if (!(span.t1 - span.t0 > Settings::grazing_sliver * (motion->hi() - motion->lo()))) continue;
    double length = 0;
    for (int i = 1; i <= 8; ++i) length += (side_point(*face, side, i / 8.0) - side_point(*face, side, (i - 1) / 8.0)).norm();
    if (!(length > 1e-9 * size)) continue;  // a pole
    const std::string what = "the side " + std::string(names[side]) + " of " + face->what() +
                             " grazing all along, swept over t in [" + number(span.t0) + ", " + number(span.t1) + "]";
    const PatchPtr curve = side_curve(face, side, what);
    out.push_back({"interior",
                   patch_part(swept_curve(curve, motion, what), {curve->lo(0), span.t0}, {curve->hi(0), span.t1}), {},
                   {{"s", {curve->lo(0), curve->hi(0)}}, {"t", {span.t0, span.t1}}}, face_index});
  }
}

}  // namespace

bool has_trimmed_faces(const Entity& entity) {
  return std::any_of(entity.faces().begin(), entity.faces().end(), [](const PatchPtr& f) { return f->trimmed; });
}

std::vector<CandidatePatch> candidate_patches(const Entity& entity, const std::shared_ptr<const StageMotion>& motion,
                                              const std::function<void()>& check) {
  auto poll = [&check] {
    if (check) check();
  };
  std::vector<CandidatePatch> out;
  const double lo = motion->lo(), hi = motion->hi();
  const std::vector<PatchPtr>& faces = entity.faces();
  if (has_trimmed_faces(entity))
    throw ComputeError("the candidate patches of trimmed faces (B-rep solids) are not built yet: end copies and "
                       "envelope sheets take whole parameter boxes");
  for (double t : {lo, hi})
    for (std::size_t k = 0; k < faces.size(); ++k) {
      poll();
      const std::string when = t == lo ? "start" : "end";
      out.push_back({"limit", moved_patch(faces[k], motion, t, faces[k]->what() + " at the " + when + " of the motion"),
                     {{"t", t}}, {}, int(k)});
    }
  for (const PatchPtr& edge : entity.edges()) {
    poll();
    out.push_back({"boundary", swept_curve(edge, motion, edge->what() + " swept by the motion"), {},
                   {{"s", {edge->lo(0), edge->hi(0)}}, {"t", {lo, hi}}}});
  }
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const PatchPtr& face = faces[k];
    poll();
    const GrazingFamily family = grazing_family(*face, *motion);
    int arc = 0;
    for (const GrazingTrack& track : family.tracks) {
      // an instant between two events, or a sliver of the range between two
      if (track.t.size() < 2 || !(track.t.back() - track.t.front() > Settings::grazing_sliver * (hi - lo))) continue;
      poll();
      const std::string what = "grazing arc " + std::to_string(++arc) + " (n . v = 0) of " + face->what() +
                               " swept over t in [" + number(track.t.front()) + ", " + number(track.t.back()) + "]";
      out.push_back({"interior", envelope_patch(face, motion, track, what), {},
                     {{"s", {0.0, 1.0}}, {"t", {track.t.front(), track.t.back()}}}, int(k)});
    }
    add_side_sheets(face, int(k), motion, family, out);
  }
  return out;
}

std::optional<PatchPlane> patch_plane(const Patch& p, double tol, int n) {
  if (p.dim() != 2) return std::nullopt;
  std::vector<Eigen::Vector3d> pts;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b) {
      pts.push_back(p.eval(p.lo(0) + (p.hi(0) - p.lo(0)) * a / n, p.lo(1) + (p.hi(1) - p.lo(1)) * b / n).x);
      mean += pts.back();
    }
  mean /= double(pts.size());
  Eigen::MatrixXd m(pts.size(), 3);
  for (std::size_t k = 0; k < pts.size(); ++k) m.row(Eigen::Index(k)) = (pts[k] - mean).transpose();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeThinV);
  const Eigen::Vector3d sv = svd.singularValues();
  const double spread = sv(0) / std::sqrt(double(pts.size()));
  // (the points span a plane: their second direction spreads them well beyond the tolerance)
  if (!(sv(1) / std::sqrt(double(pts.size())) > 1e3 * tol) || !(spread > 0)) return std::nullopt;
  const Eigen::Vector3d normal = svd.matrixV().col(2).normalized();
  for (const auto& x : pts)
    if (!(std::abs(normal.dot(x - mean)) <= tol)) return std::nullopt;
  return PatchPlane{normal, normal.dot(mean)};
}

double patch_area(const Patch& p, int n) {
  static const double x[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
  static const double w[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};
  const double du = (p.hi(0) - p.lo(0)) / n, dv = (p.hi(1) - p.lo(1)) / n;
  double area = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          const PatchPoint q = p.eval(p.lo(0) + (a + x[i]) * du, p.lo(1) + (b + x[j]) * dv);
          area += w[i] * w[j] * du * dv * q.xu.cross(q.xv).norm();
        }
  return area;
}

}  // namespace sweep
