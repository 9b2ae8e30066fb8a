// The single-stage sweep pipeline: candidate varieties -> arrangement -> cell classification ->
// solid -> validation and report.
#include <BOPAlgo_Alerts.hxx>
#include <BOPAlgo_MakerVolume.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Curve2d.hxx>
#include <BRepAlgoAPI_BuilderAlgo.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepAlgoAPI_Splitter.hxx>
#include <BRepBndLib.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepLib.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <IntCurvesFace_ShapeIntersector.hxx>
#include <BRepGProp.hxx>
#include <BRepGProp_Domain.hxx>
#include <BRepGProp_Face.hxx>
#include <BRepGProp_Vinert.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomAPI_ProjectPointOnSurf.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Line.hxx>
#include <ShapeAnalysis_Shell.hxx>
#include <ShapeFix_Shape.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <numeric>
#include <memory>
#include <random>
#include <sstream>

#include "internal.hpp"
#include "stop.hpp"
#include "sweep/error.hpp"
#include "sweep/membership.hpp"
#include "sweep/orbit.hpp"
#include "sweep/swept_box.hpp"
#include "boundary_sweep.hpp"
#include "verdict.hpp"

namespace sweep::occt {

nlohmann::json Report::to_json() const {
  nlohmann::json j;
  j["sweep_report"] = 1;
  j["status"] = status;
  j["message"] = message;
  j["volume"] = {{"brep", volume_brep}, {"divergence", volume_divergence}};
  if (has_mc) {
    j["volume"]["monte_carlo"] = volume_mc;
    j["volume"]["monte_carlo_stderr"] = volume_mc_stderr;
    j["volume"]["monte_carlo_samples"] = mc_samples;
    if (mc_compared) j["volume"]["monte_carlo_mismatch"] = volume_mc_mismatch;
  }
  j["area"] = area;
  j["centroid"] = {centroid[0], centroid[1], centroid[2]};
  j["bounding_box"] = {{"min", {bbox_min[0], bbox_min[1], bbox_min[2]}},
                       {"max", {bbox_max[0], bbox_max[1], bbox_max[2]}}};
  j["valid"] = valid;
  j["closed"] = closed;
  j["faces"] = faces;
  j["varieties"] = varieties;
  j["cells"] = cells;
  j["unpruned_stages"] = unpruned_stages;
  j["healed_stages"] = healed_stages;
  j["restored_candidates"] = nlohmann::json::array();
  for (const auto& [stage, faces] : restored_candidates)
    j["restored_candidates"].push_back({{"stage", stage}, {"faces", faces}});
  if (has_verdict)
    j["verify"] = {{"samples", verdict_samples},
                   {"mismatches", verdict_mismatches + verdict_probe_mismatches},
                   {"difference_bound", verdict_difference_bound},
                   {"near_boundary", verdict_near_boundary},
                   {"probes", verdict_probes},
                   {"probe_mismatches", verdict_probe_mismatches},
                   {"undecided", verdict_undecided},
                   {"probe_undecided", verdict_probe_undecided},
                   {"probe_offset", verdict_probe_offset},
                   {"box_volume", verdict_box_volume},
                   {"membership", verdict_membership},
                   {"classifier", verdict_classifier}};
  j["dimension"] = dimension;
  j["tolerance"] = {{"requested", tol_requested}, {"achieved", tol_achieved}};
  nlohmann::json s = seconds;
  s["total"] = seconds_total;
  j["seconds"] = s;
  return j;
}

nlohmann::json Variety::to_json() const {
  nlohmann::json j = {{"stage", stage}, {"joint", joint}, {"type", type}, {"what", what}, {"fixed", fixed},
                      {"free", free}, {"faces", faces}, {"area", area}};
  if (final_stage) {
    j["boundary_area"] = boundary_area;
    j["volume"] = volume;
  }
  return j;
}

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Whether OCCT's cell builder reported shells it could not orient.
bool unable_to_orient(const BOPAlgo_MakerVolume& mv) {
  const Message_ListOfAlert& alerts = mv.GetReport()->GetAlerts(Message_Warning);
  for (Message_ListOfAlert::Iterator it(alerts); it.More(); it.Next())
    if (it.Value()->IsInstance(STANDARD_TYPE(BOPAlgo_AlertUnableToOrientTheShape))) return true;
  return false;
}

/// A point of a face and the unit normal there that points into the solid the face bounds.
struct InwardPoint {
  gp_Pnt p;
  gp_Dir n;
};

/// The points of face f at the fractions a x b of its parameter box that lie inside it and have a
/// normal.
std::vector<InwardPoint> inward_points(const TopoDS_Face& f, std::initializer_list<double> as,
                                       std::initializer_list<double> bs) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  BRepTopAdaptor_FClass2d fc(f, 1e-9);
  const BRepAdaptor_Surface S(f);
  std::vector<InwardPoint> out;
  for (double a : as)
    for (double b : bs) {
      const gp_Pnt2d uv(u0 + a * (u1 - u0), v0 + b * (v1 - v0));
      if (fc.Perform(uv) != TopAbs_IN) continue;
      BRepLProp_SLProps props(S, uv.X(), uv.Y(), 1, 1e-9);
      if (!props.IsNormalDefined()) continue;
      gp_Dir n = props.Normal();
      if (f.Orientation() != TopAbs_REVERSED) n.Reverse();
      out.push_back({props.Value(), n});
    }
  return out;
}

/// A point inside a cell too thin for fixed offsets: from points of its faces a ray goes inward
/// along the normal, and the middle of its way to the next face the ray meets is taken when OCCT's
/// classifier finds it inside.
bool thin_cell_point(const TopoDS_Solid& cell, double size, Eigen::Vector3d* out) {
  IntCurvesFace_ShapeIntersector hits;
  hits.Load(cell, 1e-9 * size);
  for (TopExp_Explorer ex(cell, TopAbs_FACE); ex.More(); ex.Next())
    for (const auto& [p, n] :
         inward_points(TopoDS::Face(ex.Current()), {0.5, 0.29, 0.71, 0.13, 0.87}, {0.5, 0.31, 0.69, 0.17, 0.83})) {
      hits.Perform(gp_Lin(p, n), 1e-7 * size, 2 * size);
      if (!hits.IsDone() || hits.NbPnt() == 0) continue;
      double w = 2 * size;
      for (int k = 1; k <= hits.NbPnt(); ++k) w = std::min(w, hits.WParameter(k));
      const gp_Pnt mid = p.Translated(gp_Vec(n) * (0.5 * w));
      if (BRepClass3d_SolidClassifier(cell, mid, 1e-10 * size).State() == TopAbs_IN) {
        *out = to_eigen(mid);
        return true;
      }
    }
  return false;
}

/// A point inside the solid cell, a small step inward from one of its faces (or, for a thin cell,
/// thin_cell_point's).
bool interior_point(const TopoDS_Solid& cell, double size, Eigen::Vector3d* out) {
  for (double frac : {1e-3, 1e-4, 1e-5})
    for (TopExp_Explorer ex(cell, TopAbs_FACE); ex.More(); ex.Next())
      for (const auto& [p, n] :
           inward_points(TopoDS::Face(ex.Current()), {0.5, 0.37, 0.63, 0.21, 0.79}, {0.5, 0.41, 0.59, 0.27, 0.73})) {
        const gp_Pnt q = p.Translated(gp_Vec(n) * (frac * size));
        if (BRepClass3d_SolidClassifier(cell, q, 1e-9 * size).State() == TopAbs_IN) {
          *out = to_eigen(q);
          return true;
        }
      }
  return thin_cell_point(cell, size, out);
}

/// The number of connected groups among the solids, two solids being connected when they come
/// within `gap` of each other.
int separate_parts(const std::vector<TopoDS_Shape>& parts, double gap) {
  const int n = int(parts.size());
  std::vector<int> group(n);
  std::iota(group.begin(), group.end(), 0);
  std::function<int(int)> root = [&](int x) { return group[x] == x ? x : group[x] = root(group[x]); };
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b) {
      if (root(a) == root(b)) continue;
      BRepExtrema_DistShapeShape dist(parts[a], parts[b]);
      if (dist.IsDone() && dist.Value() <= gap) group[root(b)] = root(a);
    }
  int groups = 0;
  for (int k = 0; k < n; ++k) groups += root(k) == k;
  return groups;
}

double max_tolerance(const TopoDS_Shape& s) {
  double t = 0;
  for (TopExp_Explorer ex(s, TopAbs_VERTEX); ex.More(); ex.Next())
    t = std::max(t, BRep_Tool::Tolerance(TopoDS::Vertex(ex.Current())));
  for (TopExp_Explorer ex(s, TopAbs_EDGE); ex.More(); ex.Next())
    t = std::max(t, BRep_Tool::Tolerance(TopoDS::Edge(ex.Current())));
  return t;
}

void set_centroid_and_box(Report& rep, const gp_Pnt& c, const Bnd_Box& bb) {
  rep.centroid[0] = c.X();
  rep.centroid[1] = c.Y();
  rep.centroid[2] = c.Z();
  bb.Get(rep.bbox_min[0], rep.bbox_min[1], rep.bbox_min[2], rep.bbox_max[0], rep.bbox_max[1], rep.bbox_max[2]);
}

struct Candidates {
  std::vector<TopoDS_Face> faces;
  std::vector<int> ids;         ///< variety of each face (index into vars)
  std::vector<Variety> vars;
  int varieties = 0;
  int add_variety(Variety v) {
    vars.push_back(std::move(v));
    return int(vars.size()) - 1;
  }
  /// Faces of variety `id`; `quadrature`: their areas come from the divergence quadrature
  /// (cheaper than OCCT's integration on high-degree faces).
  void add(int id, const std::vector<TopoDS_Face>& fs, bool quadrature = false) {
    for (const auto& f : fs) {
      faces.push_back(f);
      ids.push_back(id);
      by_quadrature.push_back(quadrature);
      vars[id].faces += 1;
    }
  }
  /// The varieties' candidate areas (only the varieties report needs them).
  void compute_areas() {
    for (auto& v : vars) v.area = 0;
    for (std::size_t k = 0; k < faces.size(); ++k) {
      double a = 0;
      if (by_quadrature[k]) {
        a = face_area(faces[k]);
      } else {
        GProp_GProps g;
        BRepGProp::SurfaceProperties(faces[k], g);
        a = g.Mass();
      }
      vars[ids[k]].area += a;
    }
  }

 private:
  std::vector<bool> by_quadrature;
};

/// Accumulates seconds per step over stages.
struct Seconds {
  nlohmann::json& j;
  double& operator[](const char* key) {
    if (!j.contains(key)) j[key] = 0.0;
    return *j[key].get_ptr<double*>();
  }
};

/// The trajectory of a point under one joint as an edge (the sweep of a point).
TopoDS_Shape point_sweep(const TopoDS_Shape& body, const ScrewJoint& j, double T, double tol, double size) {
  TopoDS_Compound comp;
  BRep_Builder bb;
  bb.MakeCompound(comp);
  int n = 0;
  for (TopExp_Explorer ex(body, TopAbs_VERTEX); ex.More(); ex.Next()) {
    Eigen::Vector3d x = to_eigen(BRep_Tool::Pnt(TopoDS::Vertex(ex.Current())));
    if (j.type != JointType::Helical) {
      const TopoDS_Edge e = path_edge(x, j, 0.0, T, 1e-12 * size);
      if (e.IsNull()) continue;
      bb.Add(comp, e);
    } else {
      const int m = std::max(16, int(std::ceil(T / (M_PI / 32))));
      TColgp_Array1OfPnt pts(1, m + 1);
      for (int k = 0; k <= m; ++k) pts.SetValue(k + 1, to_pnt(j.transform(T * k / m) * x));
      GeomAPI_PointsToBSpline fit(pts, 3, 8, GeomAbs_C2, tol);
      Handle(Geom_Curve) c(fit.Curve().get());
      bb.Add(comp, BRepBuilderAPI_MakeEdge(c).Edge());
    }
    ++n;
  }
  if (n == 0) throw ComputeError("the point lies on the joint axis: its sweep is a point");
  return comp;
}

/// The surface swept by the edges of a curve (a compound of faces).
TopoDS_Shape curve_sweep(const TopoDS_Shape& body, const ScrewJoint& j, double T, double tol, double fit_tol,
                         double size, double* fit_err) {
  TopoDS_Compound comp;
  BRep_Builder bb;
  bb.MakeCompound(comp);
  int n = 0;
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(body, TopAbs_EDGE, edges);
  for (int k = 1; k <= edges.Extent(); ++k) {
    TopoDS_Edge e = TopoDS::Edge(edges(k));
    if (BRep_Tool::Degenerated(e)) continue;
    double f, l;
    Handle(Geom_Curve) c = BRep_Tool::Curve(e, f, l);
    if (c.IsNull()) continue;
    c = canonical_curve(c, f, l, fit_tol);
    gp_Pln plane;
    const bool planar = keeps_plane_of(c, f, l, j, size, &plane);
    for (const auto& face : planar ? planar_curve_sweep(c, f, l, j, T, plane, size) : sweep_curve(c, f, l, j, T, tol, fit_err)) {
      bb.Add(comp, face);
      ++n;
    }
  }
  if (n == 0) throw ComputeError("the curve slides along itself: its sweep is a curve");
  return comp;
}

/// A curve piece to be revolved.
struct RevCurve {
  Handle(Geom_Curve) c;
  double f, l;
  int source = -1;  ///< the variety it belongs to
};

/// Sweeps of curves under a rotation by T < 2 pi. Pieces (split where their axial coordinate
/// turns) with the same profile (radius as a function of the axial coordinate) lie on one surface
/// of revolution; when the angular ranges they sweep cover the whole turn at every height, that
/// surface is swept once, as a full turn of one of them, instead of as overlapping pieces.
std::vector<std::pair<int, std::vector<TopoDS_Face>>> revolve_pieces(const std::vector<RevCurve>& curves,
                                                                     const ScrewJoint& j, double T, double tol,
                                                                     double size, double* fit_err) {
  struct Piece {
    RevCurve rc;
    double a0 = 0, a1 = 0;
    std::vector<double> rho, phi;
    bool profiled = false;
  };
  const Eigen::Vector3d w = j.direction;
  Eigen::Vector3d e1 = w.unitOrthogonal(), e2 = w.cross(e1);
  const int K = 9;
  std::vector<Piece> pieces;
  for (const auto& rc : curves) {
    std::vector<double> cuts = axial_breaks(rc.c, rc.f, rc.l, j);
    cuts.push_back(rc.l);
    double a = rc.f;
    for (double b : cuts) {
      Piece p;
      p.rc = {rc.c, a, b, rc.source};
      auto axial = [&](double s) { return w.dot(to_eigen(rc.c->Value(s)) - j.point); };
      double A = axial(a), B = axial(b);
      if (std::abs(B - A) > 1e-9 * size) {
        p.profiled = true;
        p.a0 = std::min(A, B);
        p.a1 = std::max(A, B);
        for (int k = 0; k < K; ++k) {
          const double target = p.a0 + (p.a1 - p.a0) * (k + 0.5) / K;
          double lo = a, hi = b;
          const bool up = B > A;
          for (int it = 0; it < 100; ++it) {
            double m = 0.5 * (lo + hi);
            ((axial(m) < target) == up ? lo : hi) = m;
          }
          Eigen::Vector3d x = to_eigen(rc.c->Value(0.5 * (lo + hi))) - j.point;
          Eigen::Vector3d r = x - w * w.dot(x);
          p.rho.push_back(r.norm());
          p.phi.push_back(std::atan2(e2.dot(r), e1.dot(r)));
        }
      }
      pieces.push_back(p);
      a = b;
    }
  }
  const double eps = 1e-7 * size;
  std::vector<bool> done(pieces.size(), false);
  std::vector<std::pair<int, std::vector<TopoDS_Face>>> out;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (done[i]) continue;
    done[i] = true;
    std::vector<std::size_t> group{i};
    if (pieces[i].profiled)
      for (std::size_t k = i + 1; k < pieces.size(); ++k) {
        if (done[k] || !pieces[k].profiled) continue;
        bool same = std::abs(pieces[k].a0 - pieces[i].a0) < eps && std::abs(pieces[k].a1 - pieces[i].a1) < eps;
        for (int m = 0; same && m < K; ++m) same = std::abs(pieces[k].rho[m] - pieces[i].rho[m]) < eps;
        if (same) group.push_back(k);
      }
    bool covered = group.size() > 1;
    for (int m = 0; covered && m < K; ++m) {
      std::vector<double> starts;
      for (auto g : group) starts.push_back(std::fmod(std::fmod(pieces[g].phi[m], 2 * M_PI) + 2 * M_PI, 2 * M_PI));
      std::sort(starts.begin(), starts.end());
      for (std::size_t q = 0; q < starts.size() && covered; ++q) {
        const double next = q + 1 < starts.size() ? starts[q + 1] : starts[0] + 2 * M_PI;
        covered = next - starts[q] <= T + 1e-9;
      }
    }
    if (covered) {
      for (auto g : group) done[g] = true;
      const auto& rc = pieces[i].rc;
      out.push_back({rc.source, sweep_curve(rc.c, rc.f, rc.l, j, 2 * M_PI, tol, fit_err)});
    } else {
      const auto& rc = pieces[i].rc;
      auto sw = sweep_curve(rc.c, rc.f, rc.l, j, T, tol, fit_err);
      if (!sw.empty()) out.push_back({rc.source, sw});
    }
  }
  return out;
}

/// Valid and closed (the checks a directly built solid must pass to be used).
bool valid_and_closed(const TopoDS_Shape& s) {
  if (s.IsNull() || !BRepCheck_Analyzer(s).IsValid()) return false;
  ShapeAnalysis_Shell sas;
  sas.LoadShells(s);
  return !sas.CheckOrientedShells(s, true) && !sas.HasFreeEdges();
}

/// A ball under a screw motion, built directly as a tube about its centre's helix closed by two
/// half balls (trimmed where neighbouring turns overlap); null when `body` is not one ball or the
/// build is not valid and closed. `faces` and `roles` (0 tube, 1 start, 2 end) describe it.
TopoDS_Shape direct_ball_screw(const TopoDS_Shape& body, const ScrewJoint& j, double T, double fit_tol, double size,
                               double tol, double* fit_err, std::vector<TopoDS_Face>* faces, std::vector<int>* roles) {
  Eigen::Vector3d centre;
  double radius = 0;
  if (j.type != JointType::Helical || j.pitch == 0 || !sphere_of(body, &centre, &radius)) return {};
  *roles = {0, 1, 2};
  const TopoDS_Shape direct = helix_reach_exceeds(j, centre, T, radius, std::max(1e-6 * radius, 100 * tol))
                                  ? ball_screw_sweep(centre, radius, j, T, fit_tol, size, fit_err, faces)
                                  : ball_screw_sweep_overlap(centre, radius, j, T, fit_tol, size, fit_err, faces, roles);
  return valid_and_closed(direct) ? direct : TopoDS_Shape();
}

/// Membership in the sweep of a primitive (at its start pose) by joint j over [0, T], from its
/// orbit intervals: one test per thread.
PointTestMaker orbit_membership(const OrbitSolidPtr& start, const ScrewJoint& j, double T) {
  return [start, j, T]() -> PointTest {
    return [start, j, T](const Eigen::Vector3d& x) { return in_joint_sweep(*start, j, T, x); };
  };
}

/// Membership in the sweep of a solid (at its start pose) by joint j over [0, T], from each
/// point's trajectory against the solid's faces: one test per thread.
PointTestMaker trajectory_membership(const TopoDS_Shape& body, const ScrewJoint& j, double T, double ttol) {
  return [body, j, T, ttol]() -> PointTest {
    auto test = std::make_shared<TrajectoryMembership>(body, true, j, T, ttol);
    return [test](const Eigen::Vector3d& x) { return (*test)(x); };
  };
}

/// One stage: the solid swept by `body` (a solid, or faces when dim == 2) under joint j for
/// q in [0, T]. `sd`, when given, is the entity's signed distance, or `pe` its parametric map, and
/// `sd_motion` the motion that carries the entity to this stage's swept set (for the membership
/// test independent of the B-rep). With `prune`, candidate faces found inside the swept set at
/// sampled points are left out of the arrangement; `pruned` receives how many of how many. With
/// `direct_builds`, the shapes that have a direct construction (balls under screws, graph
/// extrusions) are built so first.
struct PruneCount {
  int candidates = 0;  ///< candidate faces before pruning
  int dropped = 0;     ///< left out as internal (some may be restored later)
};
TopoDS_Shape solid_sweep(const TopoDS_Shape& body, int dim, const ScrewJoint& j, double T, const SignedDistance* sd,
                         const ParametricEntity* pe, const Motion& sd_motion, double esize, double size, double tol, double fit_tol,
                         double& fit_err, Report& rep, int stage, int joint_no, Candidates* cand_out, bool prune,
                         PruneCount* pruned, bool direct_builds) {
  Seconds sec{rep.seconds};
  auto stage_fail = [](const std::string& m) -> TopoDS_Shape { throw ComputeError(m); };
  const bool full_turn = j.type == JointType::Revolute && T >= 2 * M_PI - 1e-12;
  // Candidate varieties.
  const auto t_cand = Clock::now();
  Candidates cand;
  cand.varieties += 2;
  const std::string qn = "q" + std::to_string(joint_no);
  auto variety = [&](const std::string& type, const std::string& what, nlohmann::json fixed, nlohmann::json free) {
    return cand.add_variety({stage, joint_no, type, what, std::move(fixed), std::move(free)});
  };
  const nlohmann::json qfree = {{qn, {0.0, T}}};
  // the entity at the start or at the end of the joint's range
  auto limit_variety = [&](bool end) {
    return variety("limit",
                   std::string("the entity at the ") + (end ? "end" : "start") + " of joint " + std::to_string(joint_no) +
                       "'s range",
                   {{qn, end ? T : 0.0}}, nlohmann::json::object());
  };
  // A ball whose centre's helix has a reach above its radius sweeps a tube closed by two half
  // balls: built directly, without an arrangement, when the build is valid and closed.
  if (direct_builds && dim == 3 && j.type == JointType::Helical && j.pitch != 0) {
    double err = fit_err;
    std::vector<TopoDS_Face> fs;
    std::vector<int> roles;
    const TopoDS_Shape direct = direct_ball_screw(body, j, T, fit_tol, size, tol, &err, &fs, &roles);
    if (!direct.IsNull()) {
      fit_err = err;
      const int tube = variety("interior", "grazing curve (n . v = 0) on entity face 1 swept by joint " +
                                               std::to_string(joint_no) + " (a tube about the centre's helix)",
                               nlohmann::json::object(), qfree);
      const int lo_id = limit_variety(false), hi_id = limit_variety(true);
      cand.varieties += 1;
      for (std::size_t k = 0; k < fs.size(); ++k)
        cand.add(roles[k] == 0 ? tube : roles[k] == 1 ? lo_id : hi_id, {fs[k]}, true);
      rep.varieties += cand.varieties;
      rep.cells += 1;
      sec["varieties"] += since(t_cand);
      if (cand_out) *cand_out = std::move(cand);
      return direct;
    }
  }
  // A face translated along a direction in which it is a graph: the face, its translate and the
  // sweep of its boundary, sewn without an arrangement, when the result is valid and closed.
  if (direct_builds && dim == 2 && j.type == JointType::Prismatic) {
    TopExp_Explorer fx(body, TopAbs_FACE);
    const TopoDS_Face face = fx.More() ? TopoDS::Face(fx.Current()) : TopoDS_Face();
    if (fx.More()) fx.Next();
    std::vector<GraphExtrusionFace> gfs;
    double gerr = fit_err;
    TopoDS_Shape direct = !face.IsNull() && !fx.More() ? graph_extrusion(face, j, T, size, tol, &gerr, &gfs)
                                                       : TopoDS_Shape();
    if (valid_and_closed(direct)) {
      fit_err = gerr;
      const int lo_id = limit_variety(false), hi_id = limit_variety(true);
      std::map<int, int> edge_ids;
      for (const auto& g : gfs) {
        if (g.role < 0) {
          cand.add(g.role == -1 ? lo_id : hi_id, {g.face});
          continue;
        }
        if (!edge_ids.count(g.role)) {
          nlohmann::json efree = qfree;
          efree["s"] = {g.first, g.last};
          edge_ids[g.role] = variety("boundary", "entity edge " + std::to_string(edge_ids.size() + 1) +
                                                     " swept by joint " + std::to_string(joint_no),
                                     nlohmann::json::object(), efree);
          ++cand.varieties;
        }
        cand.add(edge_ids[g.role], {g.face});
      }
      rep.varieties += cand.varieties;
      rep.cells += 1;
      sec["varieties"] += since(t_cand);
      if (cand_out) *cand_out = std::move(cand);
      return direct;
    }
  }
  int edge_no = 0;
  // For a rotation (no pitch) short of a full turn, curve sweeps are collected first: pieces of
  // different curves that revolve into the same surface of revolution would give partly
  // overlapping faces, which the arrangement cannot split.
  const bool rotation_only = j.type == JointType::Revolute && !full_turn;
  struct Pending {
    Handle(Geom_Curve) c;
    double f, l;
    int source;
  };
  std::vector<Pending> pending;
  auto pending_curves = [](const std::vector<Pending>& p) {
    std::vector<RevCurve> out;
    for (const auto& x : p) out.push_back({x.c, x.f, x.l, x.source});
    return out;
  };
  TopTools_IndexedMapOfShape edges, faces;
  TopExp::MapShapes(body, TopAbs_EDGE, edges);
  TopExp::MapShapes(body, TopAbs_FACE, faces);
  auto is_seam = [&](const TopoDS_Edge& e) {
    for (int k = 1; k <= faces.Extent(); ++k)
      if (BRep_Tool::IsClosed(e, TopoDS::Face(faces(k)))) return true;
    return false;
  };
  // Smooth (G1) edges between two faces need no sweep of their own: the grazing curves of the two
  // faces meet across them.
  TopoDS_Shape regular = body;
  BRepLib::EncodeRegularity(regular, 1e-9);
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(body, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  auto is_smooth = [&](const TopoDS_Edge& e) {
    if (!edge_faces.Contains(e)) return false;
    const TopTools_ListOfShape& fl = edge_faces.FindFromKey(e);
    if (fl.Extent() != 2) return false;
    const TopoDS_Face& f1 = TopoDS::Face(fl.First());
    const TopoDS_Face& f2 = TopoDS::Face(fl.Last());
    if (f1.IsSame(f2)) return false;
    if (!BRep_Tool::HasContinuity(e, f1, f2) || BRep_Tool::Continuity(e, f1, f2) < GeomAbs_G1) return false;
    // ... unless the motion is tangent to the faces all along it: then it is a grazing curve that
    // the faces' own tracing leaves to it (it lies on their borders).
    BRepAdaptor_Curve2d pc(e, f1);
    BRepAdaptor_Surface S(f1);
    for (int m = 0; m <= 4; ++m) {
      const gp_Pnt2d uv = pc.Value(pc.FirstParameter() + (pc.LastParameter() - pc.FirstParameter()) * m / 4.0);
      BRepLProp_SLProps props(S, uv.X(), uv.Y(), 1, 1e-9);
      if (!props.IsNormalDefined()) return true;
      const Eigen::Vector3d v = j.velocity(to_eigen(props.Value()));
      if (std::abs(to_eigen(gp_Vec(props.Normal())).dot(v)) > 1e-9 * (v.norm() + 1e-300)) return true;
    }
    return false;
  };
  for (int k = 1; k <= edges.Extent(); ++k) {
    TopoDS_Edge e = TopoDS::Edge(edges(k));
    if (BRep_Tool::Degenerated(e) || is_seam(e) || is_smooth(e)) continue;
    double f, l;
    Handle(Geom_Curve) c = BRep_Tool::Curve(e, f, l);
    if (c.IsNull()) continue;
    {  // collapsed edges (poles of parametric surfaces) sweep nothing
      double spread = 0;
      gp_Pnt p0 = c->Value(f);
      for (int k = 1; k <= 8; ++k) spread = std::max(spread, p0.Distance(c->Value(f + (l - f) * k / 8.0)));
      if (spread < 1e-9 * esize) continue;
    }
    c = canonical_curve(c, f, l, std::max(fit_tol, 1e-10 * esize));
    gp_Pln plane;
    const bool planar = !c->IsKind(STANDARD_TYPE(Geom_Line)) && keeps_plane_of(c, f, l, j, size, &plane);
    nlohmann::json efree = qfree;
    efree["s"] = {f, l};
    const int vid = variety("boundary", "entity edge " + std::to_string(++edge_no) + " swept by joint " +
                                            std::to_string(joint_no) + (planar ? " (a planar region)" : ""),
                            nlohmann::json::object(), efree);
    if (!planar && rotation_only) {
      pending.push_back({c, f, l, vid});
      continue;
    }
    auto sw = planar ? planar_curve_sweep(c, f, l, j, T, plane, size) : sweep_curve(c, f, l, j, T, tol, &fit_err);
    if (!sw.empty()) ++cand.varieties;
    cand.add(vid, sw);
  }
  // Grazing curves: their sweeps are candidates, and they split the entity's faces into pieces
  // where n . v keeps one sign (each piece is then wholly inside the swept set or partly on its
  // boundary, which lets the pruning below decide piece by piece).
  std::vector<TopoDS_Face> pieces;
  for (int k = 1; k <= faces.Extent(); ++k) {
    const TopoDS_Face& face = TopoDS::Face(faces(k));
    TopTools_ListOfShape tools;
    for (const auto& g : grazing_curves(face, j, fit_tol, esize)) {
      fit_err = std::max(fit_err, g.error);
      const GrazingEdge ge = grazing_edge(g, face, fit_tol);
      const Handle(Geom_Curve)& cc = ge.curve;
      const double f = ge.first, l = ge.last;
      tools.Append(ge.edge);
      nlohmann::json gfree = qfree;
      gfree["s"] = {f, l};
      const int vid = variety("interior", "grazing curve (n . v = 0) on entity face " + std::to_string(k) +
                                              " swept by joint " + std::to_string(joint_no),
                              nlohmann::json::object(), gfree);
      if (rotation_only) {
        pending.push_back({cc, f, l, vid});
        continue;
      }
      auto sw = sweep_curve(cc, f, l, j, T, tol, &fit_err);
      if (!sw.empty()) ++cand.varieties;
      cand.add(vid, sw);
    }
    bool split = false;
    if (!tools.IsEmpty()) {
      BRepAlgoAPI_Splitter splitter;
      TopTools_ListOfShape args;
      args.Append(face);
      splitter.SetArguments(args);
      splitter.SetTools(tools);
      splitter.SetRunParallel(true);
      splitter.SetFuzzyValue(1e-9 * esize);
      splitter.Build(stop_range());
      check_stop();
      if (splitter.IsDone() && !splitter.HasErrors()) {
        // The pieces must cover the face (a grazing curve on the face's border can leave the
        // splitter with nothing); otherwise the face goes on whole.
        std::vector<TopoDS_Face> split_faces;
        double area = 0.0;
        for (TopExp_Explorer ex(splitter.Shape(), TopAbs_FACE); ex.More(); ex.Next()) {
          split_faces.push_back(TopoDS::Face(ex.Current()));
          GProp_GProps g;
          BRepGProp::SurfaceProperties(split_faces.back(), g);
          area += g.Mass();
        }
        GProp_GProps g;
        BRepGProp::SurfaceProperties(face, g);
        if (!split_faces.empty() && std::abs(area - g.Mass()) <= 1e-6 * g.Mass()) {
          pieces.insert(pieces.end(), split_faces.begin(), split_faces.end());
          split = true;
        }
      }
    }
    if (!split) pieces.push_back(face);
  }
  if (!pending.empty()) {
    for (const auto& [vid, sw] : revolve_pieces(pending_curves(pending), j, T, tol, size, &fit_err)) {
      ++cand.varieties;
      cand.add(vid, sw);
    }
  }
  const int lo_id = limit_variety(false), hi_id = full_turn ? -1 : limit_variety(true);
  {
    for (const auto& f : pieces) {
      cand.add(lo_id, {f});
      if (!full_turn) cand.add(hi_id, {TopoDS::Face(moved(f, j.transform(T)))});
    }
  }
  rep.varieties += cand.varieties;
  sec["varieties"] += since(t_cand);

  // Point membership: the certified analytic test for primitive solids, else the trajectory test
  // (which keeps OCCT state: one per thread, each made by trajectory_test or member_test).
  const bool solid_entity = dim == 3;
  auto trajectory_test = [&](double tol_factor) -> PointTest {
    auto by_trajectory = std::make_shared<std::unique_ptr<TrajectoryMembership>>();
    return [&, by_trajectory, tol_factor](const Eigen::Vector3d& x) {
      if (!*by_trajectory)
        *by_trajectory = std::make_unique<TrajectoryMembership>(body, solid_entity, j, T, tol_factor * size);
      return (**by_trajectory)(x);
    };
  };
  auto member_test = [&]() -> PointTest {
    if (sd) return [&](const Eigen::Vector3d& x) { return in_swept_set(*sd, sd_motion, x, 1e-9 * size); };
    if (pe) return [&](const Eigen::Vector3d& x) { return in_swept_image(*pe, sd_motion, x, 1e-9 * size, size); };
    return trajectory_test(1e-9);
  };

  // Drop duplicate candidates (the same face reached twice, e.g. by symmetric edges): the
  // general fuse handles coincident analytic faces, but not coincident general ones. Done before
  // pruning, so that a candidate restored after it cannot duplicate one kept.
  {
    std::vector<TopoDS_Face> uniq;
    std::vector<std::pair<double, Bnd_Box>> props;
    auto lies_on = [&](const TopoDS_Face& a, const TopoDS_Face& b) {
      double u0, u1, v0, v1;
      BRepTools::UVBounds(a, u0, u1, v0, v1);
      BRepAdaptor_Surface SA(a);
      BRepTopAdaptor_FClass2d fa(a, 1e-9);
      Handle(Geom_Surface) gb = BRep_Tool::Surface(b);
      BRepTopAdaptor_FClass2d fb(b, 1e-9);
      int n = 0;
      for (int i = 0; i < 5; ++i)
        for (int k = 0; k < 5; ++k) {
          gp_Pnt2d uv(u0 + (u1 - u0) * (i + 0.5) / 5, v0 + (v1 - v0) * (k + 0.5) / 5);
          if (fa.Perform(uv) != TopAbs_IN) continue;
          gp_Pnt p = SA.Value(uv.X(), uv.Y());
          GeomAPI_ProjectPointOnSurf proj(p, gb);
          if (proj.NbPoints() == 0 || proj.LowerDistance() > 1e-7 * size) return false;
          double pu, pv;
          proj.LowerDistanceParameters(pu, pv);
          if (fb.Perform(gp_Pnt2d(pu, pv)) == TopAbs_OUT) return false;
          ++n;
        }
      return n >= 3;
    };
    std::vector<int> uniq_ids;
    for (std::size_t fi = 0; fi < cand.faces.size(); ++fi) {
      const TopoDS_Face& f = cand.faces[fi];
      GProp_GProps g;
      BRepGProp::SurfaceProperties(f, g);
      Bnd_Box b;
      BRepBndLib::Add(f, b);
      bool dup = false;
      for (std::size_t k = 0; k < uniq.size() && !dup; ++k) {
        if (std::abs(props[k].first - g.Mass()) > 1e-6 * std::max(g.Mass(), 1e-300)) continue;
        {
          double a[6], c[6];
          props[k].second.Get(a[0], a[1], a[2], a[3], a[4], a[5]);
          b.Get(c[0], c[1], c[2], c[3], c[4], c[5]);
          bool same_box = true;
          for (int m = 0; m < 6; ++m) same_box = same_box && std::abs(a[m] - c[m]) <= 1e-6 * size;
          if (!same_box) continue;
        }
        dup = lies_on(f, uniq[k]) && lies_on(uniq[k], f);
      }
      if (!dup) {
        uniq.push_back(f);
        uniq_ids.push_back(cand.ids[fi]);
        props.push_back({g.Mass(), b});
      }
    }
    cand.faces.swap(uniq);
    cand.ids.swap(uniq_ids);
  }

  // Drop candidates that lie inside the swept set: sample points of the face's interior with
  // both sides in the set. Keeping a face is always safe; dropping internal ones spares the
  // arrangement needless (often tangential) intersections. Faces are tested in parallel.
  // Sampling can miss a strip of boundary on a face that is internal almost everywhere (next to
  // where the envelope touches it tangentially): the caller checks the stage's solid and builds it
  // again without pruning when a check fails.
  if (pruned) *pruned = PruneCount{int(cand.faces.size()), 0};
  std::vector<TopoDS_Face> dropped_faces;
  std::vector<int> dropped_ids;
  if (prune) {
    const auto t_prune = Clock::now();
    // A quick test with a comfortable offset; a sample that fails it (near the boundary, or at a
    // point where an internal face touches the boundary) is tested again with the trajectory
    // test at an offset just above the geometric error.
    const double delta = 1e-4 * size, fine = std::max(1e-7 * size, 20 * fit_err);
    std::vector<char> internal_face(cand.faces.size(), 0);
    parallel_for(cand.faces.size(), [&]() -> std::function<void(std::size_t)> {
      const auto quick = member_test(), traj = trajectory_test(1e-10);
      return [&, quick, traj](std::size_t fi) {
        const TopoDS_Face& f = cand.faces[fi];
        double u0, u1, v0, v1;
        BRepTools::UVBounds(f, u0, u1, v0, v1);
        BRepTopAdaptor_FClass2d fc(f, 1e-9);
        BRepAdaptor_Surface S(f);
        // visit(point, outward normal) at the points of a 7 x 7 grid inside the face, while it
        // returns true; the number of points visited
        auto samples = [&](const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&)>& visit) {
          const int n = 7;
          int visited = 0;
          for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) {
              gp_Pnt2d uv(u0 + (u1 - u0) * (a + 0.5) / n, v0 + (v1 - v0) * (b + 0.5) / n);
              if (fc.Perform(uv) != TopAbs_IN) continue;
              BRepLProp_SLProps props(S, uv.X(), uv.Y(), 1, 1e-9);
              if (!props.IsNormalDefined()) continue;
              Eigen::Vector3d nn = to_eigen(gp_Vec(props.Normal()));
              if (f.Orientation() == TopAbs_REVERSED) nn = -nn;
              ++visited;
              check_stop();
              if (!visit(to_eigen(props.Value()), nn)) return visited;
            }
          return visited;
        };
        // A solid at the start of the range is inside the swept set wherever the motion carries
        // it forward (n . v > 0: the space in front is swept next, the space behind is the solid),
        // and at the end wherever it came from behind (n . v < 0); over a whole turn both. Its
        // pieces (split at the grazing curves) with one strict sign need no membership test.
        const int id = cand.ids[fi];
        if (solid_entity && (id == lo_id || id == hi_id)) {
          bool all_pos = true, all_neg = true;
          const int sampled = samples([&](const Eigen::Vector3d& p, const Eigen::Vector3d& nn) {
            // how far the range moves the point along the normal, at least ten times the offset
            // of the membership tests below (a face the motion barely leaves is tested)
            const double c = nn.dot(j.velocity(p)) * T;
            all_pos = all_pos && c > 10 * delta;
            all_neg = all_neg && c < -10 * delta;
            return true;
          });
          if (sampled >= 4 && ((full_turn && (all_pos || all_neg)) || (!full_turn && id == lo_id && all_pos) ||
                               (!full_turn && id == hi_id && all_neg))) {
            internal_face[fi] = 1;
            return;
          }
        }
        bool internal = true;
        const int tested = samples([&](const Eigen::Vector3d& p, const Eigen::Vector3d& nn) {
          internal = (quick(p + delta * nn) && quick(p - delta * nn)) || (traj(p + fine * nn) && traj(p - fine * nn));
          return internal;
        });
        internal_face[fi] = internal && tested >= 4;
      };
    });
    std::vector<TopoDS_Face> keep;
    std::vector<int> keep_ids;
    for (std::size_t fi = 0; fi < cand.faces.size(); ++fi) {
      if (!internal_face[fi]) {
        keep.push_back(cand.faces[fi]);
        keep_ids.push_back(cand.ids[fi]);
      } else {
        dropped_faces.push_back(cand.faces[fi]);
        dropped_ids.push_back(cand.ids[fi]);
      }
    }
    sec["pruning"] += since(t_prune);
    if (pruned) pruned->dropped = int(cand.faces.size() - keep.size());
    cand.faces.swap(keep);
    cand.ids.swap(keep_ids);
  }

  // Dropped candidates that contain a point of one of the edges (within 1e-5 of the model size),
  // moved back among the candidates; how many.
  auto restore_near = [&](const std::vector<TopoDS_Edge>& edges) {
    std::vector<gp_Pnt> pts;
    for (const auto& e : edges) {
      const BRepAdaptor_Curve c(e);
      const double a = c.FirstParameter(), b = c.LastParameter();
      for (int k = 0; k < 5; ++k) pts.push_back(c.Value(a + (b - a) * (k + 0.5) / 5));
    }
    const double d = 1e-5 * size;
    std::vector<char> near(dropped_faces.size(), 0);
    parallel_for(dropped_faces.size(), [&]() -> std::function<void(std::size_t)> {
      return [&](std::size_t i) {
        const TopoDS_Face& f = dropped_faces[i];
        Bnd_Box box;
        BRepBndLib::Add(f, box);
        box.Enlarge(d);
        double u0, u1, v0, v1;
        BRepTools::UVBounds(f, u0, u1, v0, v1);
        GeomAPI_ProjectPointOnSurf proj;
        proj.Init(BRep_Tool::Surface(f), u0, u1, v0, v1);
        BRepTopAdaptor_FClass2d fc(f, 1e-9);
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
    std::vector<TopoDS_Face> still;
    std::vector<int> still_ids;
    for (std::size_t i = 0; i < dropped_faces.size(); ++i) {
      if (near[i]) {
        cand.faces.push_back(dropped_faces[i]);
        cand.ids.push_back(dropped_ids[i]);
        ++n;
      } else {
        still.push_back(dropped_faces[i]);
        still_ids.push_back(dropped_ids[i]);
      }
    }
    dropped_faces.swap(still);
    dropped_ids.swap(still_ids);
    return n;
  };

  // Arrangement of the candidate faces. OCCT's cell builder can leave shells it cannot orient and
  // lose the cells they bound, or build no cell at all: then the solid is built from the split
  // faces that separate the swept set from its complement, each classified by the membership of
  // points just off both of its sides. When those leave free edges where candidates that pruning
  // dropped lie (a thin strip of boundary on a face that is internal almost everywhere), such
  // candidates are restored and the arrangement is made again, at most three times.
  // OCCT's arrangement can build no cell at one fuzzy value and every cell at a neighbouring one
  // (a ball extruded along (1, 0, 1): none at 1e-6, all at 1e-7 and 1e-5): other values are tried
  // when it builds none.
  const double fuzzy = std::max(1e-7 * size, 10 * fit_err);
  BOPAlgo_MakerVolume mv;
  TopoDS_Shape result;
  std::string arrangement_error;
  for (int round = 0;; ++round) {
    const auto t_arr = Clock::now();
    TopTools_ListOfShape args;
    for (const auto& f : cand.faces) args.Append(f);
    for (double factor : {1.0, 0.1, 10.0}) {
      mv.Clear();
      mv.SetArguments(args);
      mv.SetRunParallel(true);
      mv.SetFuzzyValue(fuzzy * factor);
      mv.SetNonDestructive(true);
      mv.Perform(stop_range());
      check_stop();
      if (!mv.HasErrors() && TopExp_Explorer(mv.Shape(), TopAbs_SOLID).More()) break;
    }
    if (const char* dump = std::getenv("SWEEP_DUMP_CANDIDATES")) {  // diagnostics: the arrangement's input
      TopoDS_Compound comp;
      BRep_Builder bb;
      bb.MakeCompound(comp);
      for (const auto& f : cand.faces) bb.Add(comp, f);
      BRepTools::Write(comp, dump);
    }
    // Failing to build the cells after splitting the faces (OCCT's solid builder) leaves the split
    // faces, from which the solid is built as when it cannot orient shells.
    arrangement_error.clear();
    if (mv.HasErrors()) {
      std::ostringstream why;
      mv.DumpErrors(why);
      arrangement_error = "the arrangement of the candidate faces failed: " + why.str();
      if (mv.Images().IsEmpty()) return stage_fail(arrangement_error);
    }
    sec["arrangement"] += since(t_arr);

    const auto t_bnd = Clock::now();
    std::vector<TopoDS_Edge> free_edges;
    if (mv.HasErrors() || unable_to_orient(mv) || !TopExp_Explorer(mv.Shape(), TopAbs_SOLID).More()) {
      TopTools_IndexedMapOfShape split;
      for (const auto& f : cand.faces) {
        if (mv.Images().IsBound(f))
          for (TopTools_ListIteratorOfListOfShape it(mv.Images().Find(f)); it.More(); it.Next()) split.Add(it.Value());
        else
          split.Add(f);
      }
      std::vector<TopoDS_Face> split_faces;
      for (int k = 1; k <= split.Extent(); ++k) split_faces.push_back(TopoDS::Face(split(k)));
      const TopoDS_Shape bounded = solid_from_boundary_faces(split_faces, member_test, size, nullptr, &free_edges);
      if (valid_and_closed(bounded)) {
        for (TopExp_Explorer ex(bounded, TopAbs_SOLID); ex.More(); ex.Next()) ++rep.cells;
        result = bounded;
      }
    }
    // (not after a failed arrangement: OCCT's solid builder can then run for many minutes without
    // polling the stop request)
    const int restored =
        result.IsNull() && round < 3 && !free_edges.empty() && arrangement_error.empty() ? restore_near(free_edges) : 0;
    sec["classification"] += since(t_bnd);
    if (restored == 0) break;
    rep.restored_candidates.push_back({stage, restored});
  }
  if (result.IsNull() && !arrangement_error.empty()) return stage_fail(arrangement_error);
  const auto t_cls = Clock::now();

  // Otherwise: classify the cells.
  std::vector<TopoDS_Solid> kept;
  if (result.IsNull()) {
    const auto member = member_test();
    int ncells = 0;
    for (TopExp_Explorer ex(mv.Shape(), TopAbs_SOLID); ex.More(); ex.Next()) {
      check_stop();
      ++ncells;
      TopoDS_Solid cell = TopoDS::Solid(ex.Current());
      Eigen::Vector3d p;
      if (!interior_point(cell, size, &p)) {
        GProp_GProps g;
        BRepGProp::VolumeProperties(cell, g);
        if (std::abs(g.Mass()) < 1e-9 * size * size * size) continue;  // a sliver of nothing
        return stage_fail("no interior point found for a cell of volume " + std::to_string(g.Mass()));
      }
      if (member(p)) kept.push_back(cell);
    }
    rep.cells += ncells;
    if (kept.empty()) return stage_fail("no cell of the arrangement is in the swept set");
  }
  sec["classification"] += since(t_cls);

  // Union of the kept cells (they share faces exactly), then merge same-domain faces.
  const auto t_build = Clock::now();
  if (result.IsNull()) {
    if (kept.size() == 1) {
      result = kept[0];
    } else {
      BRepAlgoAPI_Fuse fuse;
      TopTools_ListOfShape a, t;
      a.Append(kept[0]);
      for (std::size_t k = 1; k < kept.size(); ++k) t.Append(kept[k]);
      fuse.SetArguments(a);
      fuse.SetTools(t);
      fuse.SetRunParallel(true);
      fuse.SetGlue(BOPAlgo_GlueShift);
      fuse.Build(stop_range());
      check_stop();
      if (!fuse.IsDone() || fuse.HasErrors()) return stage_fail("the union of the swept cells failed");
      result = fuse.Shape();
    }
  }
  // Merging the pieces of a surface is cosmetic: its result is used only when it is a valid solid.
  const TopoDS_Shape merged = unify_faces(result);
  if (!merged.IsNull()) result = merged;
  sec["build"] += since(t_build);
  if (cand_out) *cand_out = std::move(cand);
  return result;
}

/// OCCT's shape healing of a solid that fails OCCT's validity check (as a self-intersecting wire
/// of one face left by the union of a stage's cells); null when the healed shape is not valid
/// either. The caller checks the healed solid like any other.
TopoDS_Shape healed(const TopoDS_Shape& s) {
  ShapeFix_Shape fix(s);
  fix.Perform();
  const TopoDS_Shape h = fix.Shape();
  if (h.IsNull() || !BRepCheck_Analyzer(h).IsValid()) return {};
  return h;
}

/// How far two volumes of a solid may differ: a band `tol` wide over its whole boundary (`area`),
/// plus rounding.
double volume_band(double tol, double area, double volume) { return tol * area + 1e-9 * std::abs(volume); }

/// What the validation measures on a solid: OCCT's validity, closedness, OCCT's adaptive volume
/// and the divergence volume computed independently in the faces' parameter domains with the area
/// at the same quadrature points, and the box (check_solid: tasks on the machine's cores that only
/// read the shape).
struct SolidChecks {
  bool valid = false, closed = false;
  double volume_brep = 0, volume_divergence = 0, area = 0;
  gp_Pnt centroid;
  Bnd_Box box;
  /// Valid, closed, with a positive volume on which both integrals agree within volume_band.
  bool agree(double tol) const {
    return valid && closed && volume_brep > 0 &&
           std::abs(volume_brep - volume_divergence) <= volume_band(tol, area, volume_brep);
  }
};

/// OCCT's volume integral of oriented faces, each about P (BRepGProp's adaptive Gauss integration,
/// face by face as BRepGProp::VolumeProperties does): the volume and the first moment about the
/// origin add to those of the other faces taken about the same P.
void occt_volume_of_faces(const std::vector<TopoDS_Face>& faces, const gp_Pnt& P, double eps, double* volume,
                          gp_XYZ* moment) {
  BRepGProp_Face BF;
  BRepGProp_Domain BD;
  BRepGProp_Vinert G;
  G.SetLocation(P);
  for (const TopoDS_Face& f : faces) {
    if (f.Orientation() != TopAbs_FORWARD && f.Orientation() != TopAbs_REVERSED) continue;
    TopLoc_Location loc;
    if (BRep_Tool::Surface(f, loc).IsNull()) continue;
    BF.Load(f);
    if (f.NbChildren() == 0) {
      G.Perform(BF, eps);
    } else {
      BD.Init(f);
      G.Perform(BF, BD, eps);
    }
    *volume += G.Mass();
    *moment += G.CentreOfMass().XYZ() * G.Mass();
  }
}

/// Closed: every shell of every solid has each edge used twice, with opposite orientations.
/// Checked solid by solid, so solids that touch along an edge do not count as open.
bool closed_solids(const TopoDS_Shape& shape) {
  int nsolids = 0;
  for (TopExp_Explorer ex(shape, TopAbs_SOLID); ex.More(); ex.Next()) {
    ++nsolids;
    ShapeAnalysis_Shell sas;
    sas.LoadShells(ex.Current());
    if (sas.CheckOrientedShells(ex.Current(), true) || sas.HasFreeEdges()) return false;
  }
  return nsolids > 0;
}

SolidChecks check_solid(const TopoDS_Shape& result) {
  SolidChecks c;
  // OCCT's volume integral is a sum over the faces: they are shared out between two parts of
  // about equal cost (large B-spline faces dominate), integrated on two threads about one point.
  std::vector<std::pair<double, TopoDS_Face>> faces;
  for (TopExp_Explorer ex(result, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& f = TopoDS::Face(ex.Current());
    const BRepAdaptor_Surface S(f, false);
    double cost = 1;
    if (S.GetType() == GeomAbs_BSplineSurface)
      cost = double(S.NbUKnots() * S.NbVKnots()) * (S.UDegree() + 1) * (S.VDegree() + 1);
    faces.push_back({cost, f});
  }
  std::stable_sort(faces.begin(), faces.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<TopoDS_Face> part[2];
  double load[2] = {0, 0};
  for (const auto& [cost, f] : faces) {
    const int k = load[0] <= load[1] ? 0 : 1;
    part[k].push_back(f);
    load[k] += cost;
  }
  gp_XYZ P(0, 0, 0);  // the mean of the vertices, near the solid
  int nv = 0;
  for (TopExp_Explorer ex(result, TopAbs_VERTEX); ex.More(); ex.Next(), ++nv)
    P += BRep_Tool::Pnt(TopoDS::Vertex(ex.Current())).XYZ();
  if (nv > 0) P /= nv;
  double volume[2] = {0, 0};
  gp_XYZ moment[2] = {gp_XYZ(0, 0, 0), gp_XYZ(0, 0, 0)};
  // Tasks, the long ones first so that the short ones fill in behind them: OCCT's integral of the
  // two parts, the box, validity and closedness, then the divergence integral face by face (the
  // costliest faces first).
  const std::size_t nf = faces.size();
  std::vector<std::pair<double, double>> div_area(nf);
  parallel_for(nf + 4, [&]() -> std::function<void(std::size_t)> {
    return [&](std::size_t task) {
      if (task < 2) {
        occt_volume_of_faces(part[task], gp_Pnt(P), 1e-10, &volume[task], &moment[task]);
      } else if (task >= 4) {
        div_area[task - 4] = face_divergence_and_area(faces[task - 4].second);
      } else if (task == 2) {
        c.box = shape_box(result);
      } else {
        c.valid = BRepCheck_Analyzer(result).IsValid();
        c.closed = closed_solids(result);
      }
    };
  });
  for (const auto& [v, a] : div_area) {
    c.volume_divergence += v;
    c.area += a;
  }
  c.volume_brep = volume[0] + volume[1];
  // (no volume, no centroid: the point integrated about stands in, a finite number for the report)
  c.centroid = c.volume_brep != 0 ? gp_Pnt((moment[0] + moment[1]) / c.volume_brep) : gp_Pnt(P);
  return c;
}

}  // namespace

RunResult run_sweep(const Spec& spec, const RunOptions& opt) {
  const auto t_start = Clock::now();
  RunResult res;
  Report& rep = res.report;
  rep.dimension = spec.entity.dimension();
  const Motion& motion = spec.motion.motion;
  auto fail = [&](const std::string& msg) {
    rep.status = "failed";
    rep.message = msg;
    rep.seconds_total = since(t_start);
    return res;
  };
  if (motion.dof() == 0) return fail("the motion has no joint");
  install_signal_handlers();
  const StopScope stop_scope(opt.stop);
  // each step of a long run: the stop request is polled, then the step is shown
  std::string last_step = "setting up";  // (named in a failure of OCCT's)
  const auto step = [&](const std::string& what) {
    check_stop();
    last_step = what;
    if (opt.progress) opt.progress(what);
  };
  try {
    OCC_CATCH_SIGNALS
    // Size and tolerance from the entity and the reach of the motion.
    double fit_err = 0;
    // Parametric curves and surfaces are fitted once the tolerance is known; their extent comes
    // from a sampled stand-in (a polyline or a point cloud is enough for a bounding box).
    const bool parametric = spec.entity.kind == EntityKind::Curve || spec.entity.kind == EntityKind::Surface;
    TopoDS_Shape raw = parametric ? sampled_points(spec.entity) : entity_shape(spec.entity, 1e-9, &fit_err);
    auto extent = [](const TopoDS_Shape& s) {
      Bnd_Box b;
      BRepBndLib::Add(s, b);
      double x0, y0, z0, x1, y1, z1;
      b.Get(x0, y0, z0, x1, y1, z1);
      return std::max({x1 - x0, y1 - y0, z1 - z0, 1e-300});
    };
    // The model size: the extent of the entity's box corners carried by the motion sampled at
    // the ends and middles of the joint ranges (a point entity has no extent of its own).
    double size = extent(raw);
    {
      Bnd_Box eb;
      BRepBndLib::Add(raw, eb);
      double x0, y0, z0, x1, y1, z1;
      eb.Get(x0, y0, z0, x1, y1, z1);
      Eigen::AlignedBox3d reach;
      const int n = int(motion.dof());
      std::vector<double> q(n);
      int combos = 1;
      for (int i = 0; i < n && combos < 100000; ++i) combos *= 5;
      for (int c = 0; c < combos; ++c) {
        int code = c;
        for (int i = 0; i < n; ++i) {
          const auto& jj = motion.joints[i];
          const double hi = std::min(jj.hi, jj.lo + (jj.type == JointType::Revolute ? 2 * M_PI : 1e300));
          q[i] = jj.lo + (hi - jj.lo) * (code % 5) / 4.0;
          code /= 5;
        }
        const Eigen::Isometry3d M = motion.transform(q);
        for (int k = 0; k < 8; ++k)
          reach.extend(M * Eigen::Vector3d(k & 1 ? x1 : x0, k & 2 ? y1 : y0, k & 4 ? z1 : z0));
      }
      size = std::max(size, reach.sizes().maxCoeff());
    }
    rep.tol_requested = spec.tolerance > 0 ? spec.tolerance : 1e-6 * size;
    const double tol = rep.tol_requested;
    const double fit_tol = 0.01 * tol;
    if (parametric) raw = entity_shape(spec.entity, fit_tol, &fit_err);
    TopoDS_Shape shape = moved(raw, motion.home);
    rep.seconds["entity"] = since(t_start);
    std::unique_ptr<SignedDistance> sd = make_signed_distance(spec.entity);
    const std::unique_ptr<ParametricEntity> pe = ParametricEntity::make(spec.entity);
    // the entity's map as the stages see it (its ranges extended where a joint slides it along itself)
    std::unique_ptr<ParametricEntity> stage_pe = ParametricEntity::make(spec.entity);

    // Stages, innermost joint first: each sweeps the previous stage's set. While that set is still
    // the parametric entity (placed by G), a joint that slides it along itself only extends one of
    // its parameter ranges: the set keeps its dimension and the next joint sweeps it.
    int dim = rep.dimension;
    Candidates last_cands;
    // the last stage built again from every candidate, when pruning left some out
    std::function<TopoDS_Shape()> redo_last;
    const int n = int(motion.dof());
    EntitySpec entity = spec.entity;
    Eigen::Isometry3d G = motion.home;
    bool entity_intact = parametric;
    for (int i = n - 1; i >= 0; --i) {
      step("stage " + std::to_string(n - i) + "/" + std::to_string(n) + ": joint " + std::to_string(i + 1) + " (" +
           to_string(motion.joints[i].type) + ")");
      ScrewJoint j = motion.joints[i];
      double T = j.hi - j.lo;
      if (j.type == JointType::Revolute && T >= 2 * M_PI) T = 2 * M_PI;  // a full turn covers everything
      EntitySpec extended;
      if (entity_intact && (dim == 1 || dim == 2) && slides_along_itself(entity, G, j, T, size, &extended)) {
        step("joint " + std::to_string(i + 1) + " slides the entity along itself");
        entity = extended;
        G = j.transform(j.lo) * G;
        raw = entity_shape(entity, fit_tol, &fit_err);
        shape = moved(raw, G);
        stage_pe = ParametricEntity::make(entity);
        rep.seconds["entity"] = since(t_start);
        continue;
      }
      TopoDS_Shape body = moved(shape, j.transform(j.lo));
      if (dim == 0) {
        shape = point_sweep(body, j, T, fit_tol, size);
      } else if (dim == 1) {
        shape = curve_sweep(body, j, T, tol, fit_tol, size, &fit_err);
      }
      // The sweep-boundary engine builds the entity's own stage (a solid); later stages of chains,
      // and a stage it cannot build, go through the arrangement of cells.
      bool built = dim <= 1;
      Candidates stage_cands;
      if (!built && dim == 3 && i == n - 1 && !std::getenv("SWEEP_CELLS_ENGINE")) {
        // A solid: built directly when it is a ball under a screw, else from its sweep boundary,
        // whose pieces are classified by the entity's orbit intervals (a primitive) or by
        // trajectories against the body's faces.
        const auto t_stage = Clock::now();
        std::vector<TopoDS_Face> direct_faces;
        std::vector<int> roles;
        double err = fit_err;
        TopoDS_Shape direct = opt.direct_builds ? direct_ball_screw(body, j, T, fit_tol, size, tol, &err, &direct_faces, &roles)
                                                : TopoDS_Shape();
        if (!direct.IsNull()) {
          fit_err = err;
          const int tube = stage_cands.add_variety(
              {n - i, i + 1, "interior", "grazing curve (n . v = 0) swept by joint " + std::to_string(i + 1) +
                                             " (a tube about the centre's helix)"});
          const int lo_id = stage_cands.add_variety({n - i, i + 1, "limit", "the entity at the start of the range"});
          const int hi_id = stage_cands.add_variety({n - i, i + 1, "limit", "the entity at the end of the range"});
          for (std::size_t k = 0; k < direct_faces.size(); ++k)
            stage_cands.add(roles[k] == 0 ? tube : roles[k] == 1 ? lo_id : hi_id, {direct_faces[k]}, true);
          rep.varieties += 3;
          rep.cells += 1;
          shape = direct;
          built = true;
        } else {
          const OrbitSolidPtr orbit_entity = make_orbit_solid(spec.entity);
          const PointTestMaker stage_member =
              orbit_entity ? orbit_membership(orbit_placed(orbit_entity, j.transform(j.lo) * G), j, T)
                           : trajectory_membership(body, j, T, 1e-9 * size);
          BoundarySweep b = boundary_sweep(body, j, T, stage_member, size, tol, opt.settings, n - i, i + 1);
          for (auto it = b.seconds.begin(); it != b.seconds.end(); ++it)
            rep.seconds[it.key()] = rep.seconds.value(it.key(), 0.0) + it.value().get<double>();
          // a boundary that left a piece out (a sliver whose crossing with an end copy no
          // section found) does not close: the arrangement of cells is made instead
          if (!b.solid.IsNull() && !closed_solids(b.solid) && !closed_solids(healed(b.solid))) {
            b.failure = "the pieces of its sweep boundary do not close";
            b.solid.Nullify();
          }
          if (b.solid.IsNull()) {
            step("stage " + std::to_string(n - i) + ": " + b.failure + "; built from cells instead");
          } else {
            fit_err = std::max(fit_err, b.fit_error);
            for (auto& v : b.varieties) stage_cands.add_variety(std::move(v));
            for (std::size_t k = 0; k < b.candidate_faces.size(); ++k)
              stage_cands.add(b.candidate_ids[k], {b.candidate_faces[k]});
            rep.varieties += int(stage_cands.vars.size());
            rep.cells += 1;
            shape = b.solid;
            built = true;
          }
        }
        rep.seconds["stages"] = rep.seconds.value("stages", 0.0) + since(t_stage);
      }
      if (!built) {
        Motion sd_motion;
        sd_motion.home = G;
        sd_motion.joints = {j};
        sd_motion.joints[0].hi = j.lo + T;
        const bool use_sd = sd && i == n - 1 && dim == 3;
        // A surface entity's first stage: points are classified against its parametric map.
        const bool use_pe = stage_pe && entity_intact && dim == 2;
        const ParametricEntity* spe = use_pe ? stage_pe.get() : nullptr;
        const int varieties_before = rep.varieties, cells_before = rep.cells;
        auto sweep_stage = [&, body, dim, j, T, spe, sd_motion, esize = extent(body), i, use_sd, varieties_before,
                            cells_before](bool prune, PruneCount* pruned, Candidates* out) {
          rep.varieties = varieties_before;
          rep.cells = cells_before;
          auto& rc = rep.restored_candidates;
          rc.erase(std::remove_if(rc.begin(), rc.end(), [&](const auto& r) { return r.first == n - i; }), rc.end());
          *out = Candidates();
          return solid_sweep(body, dim, j, T, use_sd ? sd.get() : nullptr, spe, sd_motion, esize, size, tol, fit_tol,
                             fit_err, rep, n - i, i + 1, out, prune, pruned, opt.direct_builds);
        };
        PruneCount pruned;
        shape = sweep_stage(true, &pruned, &stage_cands);
        // Building the arrangement of every candidate again costs time that grows fast with their
        // number; past the settings' limit a stage that fails its checks is not rebuilt.
        const bool may_rebuild =
            pruned.dropped > 0 && std::size_t(pruned.candidates) <= opt.settings.rebuild_candidate_limit;
        if (i > 0 && may_rebuild) {
          // A stage whose arrangement lacked faces left out as internal is checked here (the last
          // one with the result): built again from every candidate when the check fails.
          const auto t_chk = Clock::now();
          const SolidChecks sc = check_solid(shape);
          bool agree = sc.agree(std::max({fit_err, max_tolerance(shape), tol}));
          if (!agree && !sc.valid) {
            const TopoDS_Shape h = healed(shape);
            if (!h.IsNull() && check_solid(h).agree(std::max({fit_err, max_tolerance(h), tol}))) {
              shape = h;
              agree = true;
              rep.healed_stages.push_back(n - i);
            }
          }
          rep.seconds["stage_checks"] = rep.seconds.value("stage_checks", 0.0) + since(t_chk);
          if (!agree) {
            step("stage " + std::to_string(n - i) + " failed its checks: again with every candidate");
            shape = sweep_stage(false, nullptr, &stage_cands);
            rep.unpruned_stages.push_back(n - i);
          }
        }
        if (i == 0 && may_rebuild) redo_last = [sweep_stage, &last_cands]() { return sweep_stage(false, nullptr, &last_cands); };
      }
      if (dim >= 2) {
        // a solid stage, from either engine: its candidates go to the report
        if (i == 0) {
          last_cands = std::move(stage_cands);
        } else if (opt.varieties) {
          stage_cands.compute_areas();
          opt.varieties->insert(opt.varieties->end(), stage_cands.vars.begin(), stage_cands.vars.end());
        }
        // a single solid travels on as itself (classifiers want a solid, not a compound of one)
        TopExp_Explorer sx(shape, TopAbs_SOLID);
        if (sx.More()) {
          TopoDS_Shape first = sx.Current();
          sx.Next();
          if (!sx.More()) shape = first;
        }
      }
      dim = std::min(3, dim + 1);
      entity_intact = false;
    }
    rep.dimension = dim;
    TopoDS_Shape result = shape;
    if (dim < 3) {
      // A point sweeps a curve and a curve a surface: written as edges or faces, with no volume.
      // The sweeps of a curve's pieces can overlap (two halves of a circle turned about an axis
      // through its plane's normal): their general fuse keeps each part once, for the area too.
      if (dim == 2) {
        TopTools_ListOfShape faces;
        for (TopExp_Explorer ex(result, TopAbs_FACE); ex.More(); ex.Next()) faces.Append(ex.Current());
        if (faces.Extent() > 1) {
          BRepAlgoAPI_BuilderAlgo gf;
          gf.SetArguments(faces);
          gf.SetRunParallel(true);
          gf.SetFuzzyValue(1e-9 * size);
          gf.SetNonDestructive(true);
          gf.Build(stop_range());
          check_stop();
          if (gf.IsDone() && !gf.HasErrors()) {
            TopTools_IndexedMapOfShape unique;
            TopExp::MapShapes(gf.Shape(), TopAbs_FACE, unique);
            TopoDS_Compound comp;
            BRep_Builder bb;
            bb.MakeCompound(comp);
            for (int k = 1; k <= unique.Extent(); ++k) bb.Add(comp, unique(k));
            result = comp;
          }
        }
      }
      BRepCheck_Analyzer check(result);
      rep.valid = check.IsValid();
      rep.closed = false;
      for (TopExp_Explorer ex(result, TopAbs_FACE); ex.More(); ex.Next()) ++rep.faces;
      GProp_GProps g;
      if (dim == 2) BRepGProp::SurfaceProperties(result, g, 1e-10);
      else BRepGProp::LinearProperties(result, g);
      rep.area = dim == 2 ? g.Mass() : 0.0;
      set_centroid_and_box(rep, g.CentreOfMass(), shape_box(result));
      rep.tol_achieved = std::max(fit_err, max_tolerance(result));
      rep.status = rep.valid ? "ok" : "failed";
      rep.message = std::string(rep.valid ? "" : "the result is not valid (BRepCheck); ") + "the swept set is a " +
                    (dim == 2 ? "surface" : "curve") + ": it has no volume";
      if (opt.verify) rep.message += "; --verify applies to solids only";
      res.shape = std::make_shared<Shape>(result);
      rep.seconds_total = since(t_start);
      return res;
    }

    // A membership test that never looks at the computed solid, for the verdict: the entity's
    // orbit intervals for a primitive under one joint, the trajectory's intersections with the
    // entity's own faces for other solids under one joint, the certified search over the joint box
    // for primitives under chains and for points, curves and surfaces.
    Motion clipped = motion;  // a revolute joint beyond a whole turn covers nothing new
    for (auto& jj : clipped.joints)
      if (jj.type == JointType::Revolute && jj.hi - jj.lo > 2 * M_PI) jj.hi = jj.lo + 2 * M_PI;
    MemberTestMaker independent;
    const OrbitSolidPtr orbit_entity = make_orbit_solid(spec.entity);
    if (n == 1 && orbit_entity) {
      const ScrewJoint j = clipped.joints[0];
      independent =
          always_decided(orbit_membership(orbit_placed(orbit_entity, j.transform(j.lo) * motion.home), j, j.hi - j.lo));
      rep.verdict_membership = "orbit intervals of the entity";
    } else if (n == 1 && spec.entity.dimension() == 3) {
      const ScrewJoint j = clipped.joints[0];
      const TopoDS_Shape body = moved(moved(raw, motion.home), j.transform(j.lo));
      independent = always_decided(trajectory_membership(body, j, j.hi - j.lo, 1e-9 * size));
      rep.verdict_membership = "trajectories against the entity's faces";
    } else if (sd) {
      const SignedDistance* sdp = sd.get();
      const std::size_t budget = opt.settings.membership_budget;
      independent = [sdp, clipped, size, budget]() -> MemberTest {
        return [sdp, clipped, size, budget](const Eigen::Vector3d& x) {
          return swept_set_membership(*sdp, clipped, x, 1e-9 * size, budget);
        };
      };
      rep.verdict_membership = "certified search over the joint box (signed distance)";
    } else if (pe) {
      const ParametricEntity* pep = pe.get();
      const std::size_t budget = opt.settings.membership_budget;
      independent = [pep, clipped, size, budget]() -> MemberTest {
        return [pep, clipped, size, budget](const Eigen::Vector3d& x) {
          return swept_image_membership(*pep, clipped, x, 1e-9 * size, size, budget);
        };
      };
      rep.verdict_membership = "certified search over the joint and entity parameters";
    }
    // The box that holds the true swept set: from the entity's box and the motion.
    const Eigen::AlignedBox3d entity_box = [&] {
      const Bnd_Box b = shape_box(raw);
      double x0, y0, z0, x1, y1, z1;
      b.Get(x0, y0, z0, x1, y1, z1);
      return Eigen::AlignedBox3d(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
    }();
    const Eigen::AlignedBox3d true_box = swept_box(entity_box, clipped);

    // The checks on the final solid: the reason it fails, if any. Bands come from the requested
    // tolerance and the model size, never from what the computation achieved.
    const std::string invalid = "the solid is not valid (BRepCheck)";
    // whether the last failure is one that a face left out by pruning can cause (a missing or
    // wrong piece of boundary); a geometric error or an undecided verdict is not
    bool rebuild_may_help = false, geometric_error = false;
    auto check_result = [&](const TopoDS_Shape& solid) -> std::string {
      rebuild_may_help = true;
      geometric_error = false;
      const auto t_val = Clock::now();
      const SolidChecks checks = check_solid(solid);
      rep.valid = checks.valid;
      rep.closed = checks.closed;
      rep.volume_brep = checks.volume_brep;
      rep.volume_divergence = checks.volume_divergence;
      rep.area = checks.area;
      rep.faces = 0;
      for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next()) ++rep.faces;
      std::vector<TopoDS_Shape> parts;
      for (TopExp_Explorer ex(solid, TopAbs_SOLID); ex.More(); ex.Next()) parts.push_back(ex.Current());
      // solids that touch (along the axis of a revolve, say) make one connected set
      const int solids = separate_parts(parts, tol);
      set_centroid_and_box(rep, checks.centroid, checks.box);
      rep.tol_achieved = std::max(fit_err, measured_geometric_error(solid));
      if (const char* dir = std::getenv("SWEEP_DUMP_BOUNDARY"))  // diagnostics: the solid checked last
        BRepTools::Write(solid, (std::string(dir) + "/checked.brep").c_str());
      rep.seconds["validation"] = rep.seconds.value("validation", 0.0) + since(t_val);

      std::string why;
      if (!rep.valid) why = invalid;
      else if (!rep.closed) why = "the solid is not closed";
      else if (rep.volume_brep <= 0) why = "the solid has no volume";
      else if (solids > 1)
        why = "the result has " + std::to_string(solids) +
              " separate solids (that do not touch), where a connected entity under a continuous motion sweeps one connected set";
      else if (rep.tol_achieved > tol) {
        rebuild_may_help = false;
        geometric_error = true;
        why = "the geometric error of the solid (" + std::to_string(rep.tol_achieved) +
              ", its largest fitting error or gap between its curves, surfaces and vertices) exceeds the requested tolerance (" + std::to_string(tol) + ")";
      } else if (std::abs(rep.volume_brep - rep.volume_divergence) >
               tol * size * size + opt.settings.volume_relative_band * size * size * size)
        why = "B-rep and divergence volumes disagree (" + std::to_string(rep.volume_brep) + " vs " +
              std::to_string(rep.volume_divergence) + ")";

      // The verdict, for a solid that passed every check above (one that failed is not judged
      // again: healing and rebuilding may call this more than once).
      if (!why.empty()) return why;
      const auto t_verdict = Clock::now();
      if (!independent) {
        rep.has_verdict = false;
        rebuild_may_help = false;
        return why.empty() ? "no membership test independent of the solid exists for a " +
                                 std::string(to_string(spec.entity.kind)) + " entity under " + std::to_string(n) +
                                 " joints: the solid cannot be checked"
                           : why;
      }
      const VerdictResult v = judge_solid(solid, true_box, independent, tol, size, opt.settings);
      rep.has_verdict = true;
      rep.verdict_samples = v.samples;
      rep.verdict_near_boundary = v.near_boundary;
      rep.verdict_mismatches = v.mismatches;
      rep.verdict_probes = v.probes;
      rep.verdict_probe_mismatches = v.probe_mismatches;
      rep.verdict_undecided = v.undecided;
      rep.verdict_probe_undecided = v.probe_undecided;
      rep.verdict_probe_offset = v.probe_offset_max;
      rep.verdict_difference_bound = v.difference_bound;
      rep.verdict_box_volume = v.box_volume;
      rep.verdict_classifier = v.classifier;
      rep.seconds["verdict"] = rep.seconds.value("verdict", 0.0) + since(t_verdict);
      if (why.empty() && !v.decided()) {
        rebuild_may_help = false;
        why = "the independent membership test could not decide " + std::to_string(v.undecided) + " of " +
              std::to_string(v.samples) + " samples within its budget: the solid cannot be checked";
      } else if (why.empty() && !v.ok())
        why = "the solid disagrees with the independent membership test at " +
              std::to_string(v.mismatches + v.probe_mismatches) + " of " + std::to_string(v.samples + 2 * v.probes) +
              " points; " + v.first_mismatch;
      return why;
    };
    std::string why = check_result(result);
    if (why == invalid) {
      const TopoDS_Shape h = healed(result);
      if (!h.IsNull()) {
        // the report now describes the healed solid, and so does the reason when it still fails
        const std::string why_healed = check_result(h);
        if (why_healed.empty() || geometric_error) {
          result = h;
          rep.healed_stages.push_back(n);
          why = why_healed;
        } else {
          why = why_healed + " (after OCCT's shape healing of a solid that was not valid)";
        }
      }
    }
    if (geometric_error) {
      // A pcurve that strays from its edge (a fuse's or the healing's approximation) is
      // projected again from the edge's 3-D curve; the solid is then checked again in full.
      for (TopExp_Explorer fx(result, TopAbs_FACE); fx.More(); fx.Next()) tighten_pcurves(TopoDS::Face(fx.Current()), 0.5 * tol);
      why = check_result(result);
    }
    if (!why.empty() && redo_last && rebuild_may_help) {
      // Pruning may have left out a face that carries a strip of the boundary: the last stage
      // is built again from every candidate.
      step("the solid failed its checks (" + why + "): last stage again with every candidate");
      result = redo_last();
      rep.unpruned_stages.push_back(n);
      why = check_result(result);
    }

    if (opt.varieties || opt.variety_faces) {
      last_cands.compute_areas();
      // Each face of the result lies on the surface of the candidate it was cut from.
      std::map<const Geom_Surface*, int> by_surface;
      TopLoc_Location loc;
      for (std::size_t k = 0; k < last_cands.faces.size(); ++k)
        by_surface[BRep_Tool::Surface(last_cands.faces[k], loc).get()] = last_cands.ids[k];
      for (auto& v : last_cands.vars) v.final_stage = true;
      for (TopExp_Explorer ex(result, TopAbs_FACE); ex.More(); ex.Next()) {
        const TopoDS_Face& f = TopoDS::Face(ex.Current());
        GProp_GProps g;
        BRepGProp::SurfaceProperties(f, g);
        const double area = g.Mass(), vol = face_divergence(f);
        auto it = by_surface.find(BRep_Tool::Surface(f, loc).get());
        if (it != by_surface.end()) {
          last_cands.vars[it->second].boundary_area += area;
          last_cands.vars[it->second].volume += vol;
          continue;
        }
        // A face merged from several candidates gets a surface of its own: share it out by the
        // candidates its sample points lie on.
        double u0, u1, v0, v1;
        BRepTools::UVBounds(f, u0, u1, v0, v1);
        BRepTopAdaptor_FClass2d fc(f, 1e-9);
        BRepAdaptor_Surface S(f);
        std::map<int, int> hits;
        int total = 0;
        for (int a = 0; a < 8; ++a)
          for (int b = 0; b < 8; ++b) {
            gp_Pnt2d uv(u0 + (u1 - u0) * (a + 0.5) / 8, v0 + (v1 - v0) * (b + 0.5) / 8);
            if (fc.Perform(uv) != TopAbs_IN) continue;
            const gp_Pnt p = S.Value(uv.X(), uv.Y());
            for (std::size_t k = 0; k < last_cands.faces.size(); ++k) {
              const TopoDS_Face& cf = last_cands.faces[k];
              GeomAPI_ProjectPointOnSurf proj(p, BRep_Tool::Surface(cf));
              if (proj.NbPoints() == 0 || proj.LowerDistance() > 1e-6 * size) continue;
              double pu, pv;
              proj.LowerDistanceParameters(pu, pv);
              if (BRepTopAdaptor_FClass2d(cf, 1e-9).Perform(gp_Pnt2d(pu, pv)) == TopAbs_OUT) continue;
              ++hits[last_cands.ids[k]];
              ++total;
              break;
            }
          }
        for (const auto& [id, count] : hits) {
          last_cands.vars[id].boundary_area += area * count / total;
          last_cands.vars[id].volume += vol * count / total;
        }
      }
      const int offset = opt.varieties ? int(opt.varieties->size()) : 0;
      if (opt.varieties) opt.varieties->insert(opt.varieties->end(), last_cands.vars.begin(), last_cands.vars.end());
      if (opt.variety_faces) {
        TopoDS_Compound comp;
        BRep_Builder bb;
        bb.MakeCompound(comp);
        for (const auto& f : last_cands.faces) bb.Add(comp, f);
        *opt.variety_faces = std::make_shared<Shape>(comp);
        if (opt.variety_face_ids) {
          opt.variety_face_ids->clear();
          for (int id : last_cands.ids) opt.variety_face_ids->push_back(id >= 0 ? offset + id : -1);
        }
      }
    }

    if (opt.verify) {
      step("Monte Carlo volume");
      const auto t_mc = Clock::now();
      Eigen::AlignedBox3d box(Eigen::Vector3d(rep.bbox_min[0], rep.bbox_min[1], rep.bbox_min[2]),
                              Eigen::Vector3d(rep.bbox_max[0], rep.bbox_max[1], rep.bbox_max[2]));
      box.extend(box.min() - Eigen::Vector3d::Constant(0.01 * size));
      box.extend(box.max() + Eigen::Vector3d::Constant(0.01 * size));
      MonteCarloResult mc;
      // the membership searches run over the clipped motion of the verdict
      const Motion& m = clipped;
      const std::size_t chain_samples = std::max<std::size_t>(opt.settings.mc_samples / 8, 20000);
      if (sd) {
        mc = monte_carlo_volume([&](const Eigen::Vector3d& x) { return in_swept_set(*sd, m, x, 1e-9 * size); }, box,
                                n == 1 ? opt.settings.mc_samples : chain_samples, opt.settings.seed);
      } else if (n == 1) {
        const ScrewJoint& j = clipped.joints[0];
        const double T = j.hi - j.lo;
        TopoDS_Shape body = moved(moved(raw, motion.home), j.transform(j.lo));
        TrajectoryMembership by_trajectory(body, rep.dimension == 3 && spec.entity.dimension() == 3, j, T, 1e-9 * size);
        mc = monte_carlo_volume(
            [&](const Eigen::Vector3d& x) { return by_trajectory(x); },
            box, std::min<std::size_t>(opt.settings.mc_samples, 20000), opt.settings.seed);
      } else if (pe) {
        // Here the independent membership is a search over the joint and entity parameters, far
        // slower than classifying a point against the solid: each sample is classified against
        // the solid too, and where the two disagree one of them is wrong.
        BRepClass3d_SolidClassifier in_result(result);
        const auto in_solid = [&](const Eigen::Vector3d& x) {
          in_result.Perform(to_pnt(x), 1e-9 * size);
          return in_result.State() == TopAbs_IN;
        };
        mc = monte_carlo_volume([&](const Eigen::Vector3d& x) { return in_swept_image(*pe, m, x, 1e-9 * size, size); },
                                box, chain_samples, opt.settings.seed, in_solid);
        rep.mc_compared = true;
      } else {
        throw ComputeError("--verify needs a primitive solid, a point, a curve or a surface entity for motions of "
                           "several joints");
      }
      rep.has_mc = true;
      rep.volume_mc = mc.volume;
      rep.volume_mc_stderr = mc.stderr_;
      rep.mc_samples = mc.samples;
      rep.mc_mismatches = mc.mismatches;
      rep.volume_mc_mismatch = mc.mismatch_volume;
      rep.seconds["monte_carlo"] = since(t_mc);
    }

    // Verdict.
    const double vtol = tol * size * size + opt.settings.volume_relative_band * size * size * size;
    if (why.empty() && rep.has_mc && std::abs(rep.volume_brep - rep.volume_mc) > 4.5 * rep.volume_mc_stderr + vtol)
      why = "B-rep and Monte Carlo volumes disagree (" + std::to_string(rep.volume_brep) + " vs " +
            std::to_string(rep.volume_mc) + " +- " + std::to_string(rep.volume_mc_stderr) + ")";
    rep.status = why.empty() ? "ok" : "failed";
    rep.message = why;
    res.shape = std::make_shared<Shape>(result);
  } catch (const InputError&) {
    throw;
  } catch (const Standard_Failure& f) {
    return fail(std::string("OCCT: ") + (f.GetMessageString() ? f.GetMessageString() : "failure") + " (after: " +
                last_step + ")");
  } catch (const ComputeError& e) {
    return fail(e.what());
  }
  rep.seconds_total = since(t_start);
  return res;
}

}  // namespace sweep::occt
