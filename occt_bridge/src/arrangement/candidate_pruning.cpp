// Candidates left out of a stage's arrangement: the same face reached twice, and faces found
// inside the swept set at sampled points; and those taken back where the boundary needs them.
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Curve2d.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <sstream>

#include "arrangement/stage_sweep.hpp"
#include "base/stop.hpp"

namespace sweep::occt {

namespace {

/// Whether sampled points of face a's interior lie on face b (within Settings::duplicate_face_distance
/// of the model size).
bool lies_on(const TopoDS_Face& a, const TopoDS_Face& b, double size) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(a, u0, u1, v0, v1);
  BRepAdaptor_Surface SA(a);
  BRepTopAdaptor_FClass2d fa(a, Settings::face_sample_classifier_tolerance);
  Handle(Geom_Surface) gb = BRep_Tool::Surface(b);
  BRepTopAdaptor_FClass2d fb(b, Settings::face_sample_classifier_tolerance);
  int n = 0;
  for (int i = 0; i < 5; ++i)
    for (int k = 0; k < 5; ++k) {
      gp_Pnt2d uv(u0 + (u1 - u0) * (i + 0.5) / 5, v0 + (v1 - v0) * (k + 0.5) / 5);
      if (fa.Perform(uv) != TopAbs_IN) continue;
      gp_Pnt p = SA.Value(uv.X(), uv.Y());
      GeomAPI_ProjectPointOnSurf proj(p, gb);
      if (proj.NbPoints() == 0 || proj.LowerDistance() > Settings::duplicate_face_distance * size) return false;
      double pu, pv;
      proj.LowerDistanceParameters(pu, pv);
      if (fb.Perform(gp_Pnt2d(pu, pv)) == TopAbs_OUT) return false;
      ++n;
    }
  return n >= 3;
}

/// Calls visit(point, outward normal) at the points of a 7 x 7 grid inside face f, while it
/// returns true; the number of points visited.
int visit_face_samples(const TopoDS_Face& f,
                       const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&)>& visit) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  BRepTopAdaptor_FClass2d fc(f, Settings::face_sample_classifier_tolerance);
  BRepAdaptor_Surface S(f);
  const int n = 7;
  int visited = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      gp_Pnt2d uv(u0 + (u1 - u0) * (a + 0.5) / n, v0 + (v1 - v0) * (b + 0.5) / n);
      if (fc.Perform(uv) != TopAbs_IN) continue;
      BRepLProp_SLProps props(S, uv.X(), uv.Y(), 1, Settings::normal_resolution);
      if (!props.IsNormalDefined()) continue;
      Eigen::Vector3d nn = to_eigen(gp_Vec(props.Normal()));
      if (f.Orientation() == TopAbs_REVERSED) nn = -nn;
      ++visited;
      check_stop();
      if (!visit(to_eigen(props.Value()), nn)) return visited;
    }
  return visited;
}

/// Whether the face of the body at an end of the range (variety lo or hi) is inside the swept
/// set by the sign of n . v alone: a solid at the start of the range is inside the set wherever
/// the motion carries it forward (n . v > 0: the space in front is swept next, the space behind is
/// the solid), and at the end wherever it came from behind (n . v < 0); over a whole turn both.
/// Its pieces (split at the grazing curves) with one strict sign need no membership test.
bool internal_by_sign(const StageInput& in, LimitIds limits, int id, const TopoDS_Face& f, double delta) {
  if (in.dim != 3 || (id != limits.lo && id != limits.hi)) return false;
  const bool full_turn = in.full_turn();
  bool all_pos = true, all_neg = true;
  const int sampled = visit_face_samples(f, [&](const Eigen::Vector3d& p, const Eigen::Vector3d& nn) {
    // how far the range moves the point along the normal, at least Settings::prune_sign_reach times
    // the offset of the membership tests (a face the motion barely leaves is tested)
    const double c = nn.dot(in.j().velocity(p)) * in.T();
    all_pos = all_pos && c > Settings::prune_sign_reach * delta;
    all_neg = all_neg && c < -Settings::prune_sign_reach * delta;
    return true;
  });
  return sampled >= 4 && ((full_turn && (all_pos || all_neg)) || (!full_turn && id == limits.lo && all_pos) ||
                          (!full_turn && id == limits.hi && all_neg));
}

}  // namespace

void drop_duplicate_candidates(Candidates& cand, double size) {
  std::vector<TopoDS_Face> uniq;
  std::vector<std::pair<double, Bnd_Box>> props;
  std::vector<char> keep(cand.faces.size(), 0);
  for (std::size_t fi = 0; fi < cand.faces.size(); ++fi) {
    const TopoDS_Face& f = cand.faces[fi];
    GProp_GProps g;
    BRepGProp::SurfaceProperties(f, g);
    Bnd_Box b;
    BRepBndLib::Add(f, b);
    bool dup = false;
    for (std::size_t k = 0; k < uniq.size() && !dup; ++k) {
      if (std::abs(props[k].first - g.Mass()) > Settings::area_relative_tolerance * std::max(g.Mass(), 1e-300))
        continue;
      double a[6], c[6];
      props[k].second.Get(a[0], a[1], a[2], a[3], a[4], a[5]);
      b.Get(c[0], c[1], c[2], c[3], c[4], c[5]);
      bool same_box = true;
      for (int m = 0; m < 6; ++m)
        same_box = same_box && std::abs(a[m] - c[m]) <= Settings::duplicate_box_tolerance * size;
      if (!same_box) continue;
      dup = lies_on(f, uniq[k], size) && lies_on(uniq[k], f, size);
    }
    if (!dup) {
      uniq.push_back(f);
      props.push_back({g.Mass(), b});
      keep[fi] = 1;
    }
  }
  cand.keep_only(keep);
}

DroppedFaces prune_internal_candidates(const StageInput& in, LimitIds limits, double fit_err, Candidates& cand) {
  // A quick test with a comfortable offset; a sample that fails it (near the boundary, or at a
  // point where an internal face touches the boundary) is tested again with the trajectory test
  // at an offset just above the geometric error.
  const double delta = Settings::prune_offset * in.size;
  const double fine = std::max(Settings::prune_fine_offset * in.size, Settings::prune_fine_fit_errors * fit_err);
  std::vector<char> internal_face(cand.faces.size(), 0);
  parallel_for(cand.faces.size(), [&]() -> std::function<void(std::size_t)> {
    const auto quick = stage_membership(in);
    const auto traj = stage_trajectory_membership(in, Settings::prune_trajectory_tolerance);
    return [&, quick, traj](std::size_t fi) {
      const TopoDS_Face& f = cand.faces[fi];
      if (internal_by_sign(in, limits, cand.ids[fi], f, delta)) {
        internal_face[fi] = 1;
        return;
      }
      bool internal = true;
      const int tested = visit_face_samples(f, [&](const Eigen::Vector3d& p, const Eigen::Vector3d& nn) {
        internal = (quick(p + delta * nn) && quick(p - delta * nn)) || (traj(p + fine * nn) && traj(p - fine * nn));
        return internal;
      });
      internal_face[fi] = internal && tested >= 4;
    };
  });
  std::vector<char> keep(cand.faces.size());
  for (std::size_t fi = 0; fi < keep.size(); ++fi) keep[fi] = !internal_face[fi];
  DroppedFaces dropped;
  cand.keep_only(keep, &dropped);
  return dropped;
}

int restore_near_edges(const std::vector<TopoDS_Edge>& edges, double size, DroppedFaces& dropped, Candidates& cand) {
  std::vector<gp_Pnt> pts;
  for (const auto& e : edges) {
    const BRepAdaptor_Curve c(e);
    const double a = c.FirstParameter(), b = c.LastParameter();
    for (int k = 0; k < 5; ++k) pts.push_back(c.Value(a + (b - a) * (k + 0.5) / 5));
  }
  const double d = Settings::restore_distance * size;
  std::vector<char> near(dropped.faces.size(), 0);
  parallel_for(dropped.faces.size(), [&]() -> std::function<void(std::size_t)> {
    return [&](std::size_t i) {
      const TopoDS_Face& f = dropped.faces[i];
      Bnd_Box box;
      BRepBndLib::Add(f, box);
      box.Enlarge(d);
      double u0, u1, v0, v1;
      BRepTools::UVBounds(f, u0, u1, v0, v1);
      GeomAPI_ProjectPointOnSurf proj;
      proj.Init(BRep_Tool::Surface(f), u0, u1, v0, v1);
      BRepTopAdaptor_FClass2d fc(f, Settings::face_sample_classifier_tolerance);
      for (const gp_Pnt& p : pts) {
        if (box.IsOut(p)) continue;
        proj.Perform(p);
        if (proj.NbPoints() == 0 || proj.LowerDistance() > d) continue;
        double u, v;
        proj.LowerDistanceParameters(u, v);
        if (fc.Perform(gp_Pnt2d(u, v)) != TopAbs_OUT) {
          near[i] = 1;
          return;
        }
      }
    };
  });
  int n = 0;
  DroppedFaces still;
  for (std::size_t i = 0; i < dropped.faces.size(); ++i) {
    if (near[i]) {
      cand.restore(dropped.faces[i], dropped.ids[i]);
      ++n;
    } else {
      still.faces.push_back(dropped.faces[i]);
      still.ids.push_back(dropped.ids[i]);
    }
  }
  dropped = std::move(still);
  return n;
}

}  // namespace sweep::occt
