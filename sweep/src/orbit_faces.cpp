// A solid bounded by faces on orbit surfaces, met by orbits at its faces' crossings (see orbit.hpp).
#include <algorithm>
#include <cmath>

#include "orbit_internal.hpp"
#include "sweep/error.hpp"
#include "sweep/orbit.hpp"

namespace sweep {

namespace {

using orbit_detail::Span;
using orbit_detail::Spans;

/// True when curve o keeps outside box b over [lo, hi], in windows of a quarter turn at most.
bool keeps_out(const OrbitCurve& o, double lo, double hi, const Eigen::AlignedBox3d& b) {
  const bool turns = o.a.squaredNorm() + o.b.squaredNorm() > 0;
  const int pieces = turns ? std::max(1, int(std::ceil((hi - lo) / (0.5 * M_PI)))) : 1;
  for (int p = 0; p < pieces; ++p) {
    const double mid = lo + (hi - lo) * (p + 0.5) / pieces, w = 0.5 * (hi - lo) / pieces;
    if (!orbit_detail::curve_misses_box(o.shifted(mid), w, b)) return false;
  }
  return true;
}

class FaceSolid : public orbit_detail::LabeledSolid {
 public:
  FaceSolid(std::vector<OrbitFace> faces, std::function<bool(const Eigen::Vector3d&)> inside,
            const Eigen::AlignedBox3d& bounds)
      : faces_(std::move(faces)), inside_(std::move(inside)), bounds_(bounds) {
    SWEEP_ASSERT(!faces_.empty() && !bounds_.isEmpty(), "a solid bounded by faces needs faces and a box");
    ids_ = orbit_detail::new_surface_ids(int(faces_.size()));
  }

  Spans on_curve_labeled(const OrbitCurve& o, double lo, double hi, double margin) const override {
    Eigen::AlignedBox3d grown = bounds_;
    grown.min().array() -= margin;
    grown.max().array() += margin;
    if (keeps_out(o, lo, hi, grown)) return {};
    // (with a margin, the whole range holds every point within it of the solid)
    if (margin > 0) return {{lo, hi, -1, -1}};
    std::vector<std::pair<double, int>> cuts;
    for (std::size_t k = 0; k < faces_.size(); ++k)
      for (double t : surface_crossings(faces_[k].surface, o, lo, hi, faces_[k].box))
        if (faces_[k].holds(o.at(t))) cuts.push_back({t, ids_ + int(k)});
    std::sort(cuts.begin(), cuts.end());
    cuts.insert(cuts.begin(), {lo, -1});
    cuts.push_back({hi, -1});
    Spans out;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      const double a = cuts[k].first, b = cuts[k + 1].first;
      if (!(b > a) || !inside_(o.at(0.5 * (a + b)))) continue;
      if (!out.empty() && out.back().hi == a) {
        out.back().hi = b;
        out.back().hi_id = cuts[k + 1].second;
      } else {
        out.push_back({a, b, cuts[k].second, cuts[k + 1].second});
      }
    }
    return out;
  }
  bool contains(const Eigen::Vector3d& p) const override { return bounds_.contains(p) && inside_(p); }
  Eigen::AlignedBox3d bounds() const override { return bounds_; }

 private:
  std::vector<OrbitFace> faces_;
  std::function<bool(const Eigen::Vector3d&)> inside_;
  Eigen::AlignedBox3d bounds_;
  int ids_ = 0;
};

}  // namespace

OrbitSolidPtr orbit_faces(std::vector<OrbitFace> faces, std::function<bool(const Eigen::Vector3d&)> inside,
                          const Eigen::AlignedBox3d& bounds) {
  return std::make_shared<FaceSolid>(std::move(faces), std::move(inside), bounds);
}

}  // namespace sweep
