#include "sweep/variety.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

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
  /// The root of g on the segment from a to b, where g(a) = ga and g(b) = gb have opposite signs
  /// (Illinois regula falsi).
  Vector2d root(Vector2d a, Vector2d b, double ga, double gb) const {
    Vector2d x = a;
    for (int it = 0; it < 100; ++it) {
      const double f = ga / (ga - gb);
      x = a + f * (b - a);
      const double gx = at(x);
      if (gx == 0 || (b - a).norm() < 1e-15 * (span_[0] + span_[1])) break;
      if ((gx < 0) == (ga < 0)) {
        a = x;
        ga = gx;
        gb *= 0.5;
      } else {
        b = x;
        gb = gx;
        ga *= 0.5;
      }
    }
    return x;
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

}  // namespace

GrazingSet grazing_set(const Patch& face, const StageMotion& motion, double t, int n) {
  GrazingSet out;
  const PoseJet pose = motion.pose(t);
  GrazingField field(face, pose);
  auto grid_point = [&](int i, int j) {
    return Vector2d(face.lo(0) + (face.hi(0) - face.lo(0)) * i / n, face.lo(1) + (face.hi(1) - face.lo(1)) * j / n);
  };
  std::vector<double> g((n + 1) * (n + 1));
  double scale = 0;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const Vector2d s = grid_point(i, j);
      g[j * (n + 1) + i] = grazing_value(face, pose, s.x(), s.y());
      scale = std::max(scale, std::abs(g[j * (n + 1) + i]));
    }
  if (!(scale > 0)) return out;  // the face does not move, or grazes everywhere
  find_vanishing_sides(face, pose, n, scale, out, field);
  // on a side where g vanishes, its grid values are read just inside instead
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      if ((field.vanishing_[3] && i == 0) || (field.vanishing_[1] && i == n) || (field.vanishing_[0] && j == 0) ||
          (field.vanishing_[2] && j == n))
        g[j * (n + 1) + i] = field.at(grid_point(i, j));
  auto value = [&](int i, int j) { return g[j * (n + 1) + i]; };
  // crossings on grid edges: horizontal edge (i, j)-(i+1, j) has id j n + i, vertical edge
  // (i, j)-(i, j+1) has id H + i n + j
  const int H = n * (n + 1);
  std::map<int, Vector2d> crossing;
  auto edge_crossing = [&](int id, int i0, int j0, int i1, int j1) {
    const double a = value(i0, j0), b = value(i1, j1);
    if ((a < 0) == (b < 0)) return false;
    if (!crossing.count(id)) crossing[id] = field.root(grid_point(i0, j0), grid_point(i1, j1), a, b);
    return true;
  };
  std::map<int, std::vector<int>> links;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::array<int, 4> ids = {j * n + i, H + (i + 1) * n + j, (j + 1) * n + i, H + i * n + j};
      std::vector<int> hit;
      if (edge_crossing(ids[0], i, j, i + 1, j)) hit.push_back(ids[0]);
      if (edge_crossing(ids[1], i + 1, j, i + 1, j + 1)) hit.push_back(ids[1]);
      if (edge_crossing(ids[2], i, j + 1, i + 1, j + 1)) hit.push_back(ids[2]);
      if (edge_crossing(ids[3], i, j, i, j + 1)) hit.push_back(ids[3]);
      if (hit.size() == 4) {
        // a saddle: the centre's sign tells which corners are joined across the cell
        const bool centre_like_first = (field.at(0.5 * (grid_point(i, j) + grid_point(i + 1, j + 1))) < 0) ==
                                       (value(i, j) < 0);
        if (centre_like_first) hit = {ids[0], ids[1], ids[2], ids[3]};
        else hit = {ids[0], ids[3], ids[2], ids[1]};
      }
      for (std::size_t k = 0; k + 1 < hit.size(); k += 2) {
        links[hit[k]].push_back(hit[k + 1]);
        links[hit[k + 1]].push_back(hit[k]);
      }
    }
  // chains: open ones from their ends first, then the closed ones
  std::map<int, bool> used;
  auto walk = [&](int start) {
    std::vector<Vector2d> line{crossing[start]};
    used[start] = true;
    int prev = -1, at = start;
    while (true) {
      int next = -1;
      for (int m : links[at])
        if (m != prev && !used[m]) next = m;
      if (next < 0) {
        for (int m : links[at])
          if (m == start && m != prev && line.size() > 2) line.push_back(crossing[start]);
        break;
      }
      used[next] = true;
      line.push_back(crossing[next]);
      prev = at;
      at = next;
    }
    out.curves.push_back(std::move(line));
  };
  for (const auto& [id, next] : links)
    if (next.size() == 1 && !used[id]) walk(id);
  for (const auto& [id, next] : links)
    if (!used[id]) walk(id);
  return out;
}

}  // namespace sweep
