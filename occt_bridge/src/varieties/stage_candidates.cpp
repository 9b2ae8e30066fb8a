// Candidate varieties of one stage: the sweeps of the body's edges and grazing curves, the body
// at both ends of the range, and the direct builds that need no arrangement.
#include <BRepLib.hxx>
#include <Geom_Line.hxx>
#include <ShapeAnalysis_Shell.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
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

#include "arrangement/general_candidates.hpp"
#include "arrangement/stage_sweep.hpp"
#include "base/stop.hpp"
#include "sweep/error.hpp"
#include "sweep/stage_membership.hpp"

namespace sweep::occt {

namespace {

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
      if (std::abs(B - A) > Settings::resolution * size) {
        p.profiled = true;
        p.a0 = std::min(A, B);
        p.a1 = std::max(A, B);
        for (int k = 0; k < K; ++k) {
          const double target = p.a0 + (p.a1 - p.a0) * (k + 0.5) / K;
          double lo = a, hi = b;
          const bool up = B > A;
          for (int it = 0; it < Settings::profile_height_bisections; ++it) {
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
  const double eps = Settings::same_profile_distance * size;
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
        covered = next - starts[q] <= T + Settings::revolve_cover_slack;
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

}  // namespace

bool valid_and_closed(const TopoDS_Shape& s) {
  if (s.IsNull() || !BRepCheck_Analyzer(s).IsValid()) return false;
  ShapeAnalysis_Shell sas;
  sas.LoadShells(s);
  return !sas.CheckOrientedShells(s, true) && !sas.HasFreeEdges();
}

TopoDS_Shape direct_ball_screw(const TopoDS_Shape& body, const ScrewJoint& j, double T, double fit_tol, double size,
                               double tol, double* fit_err, std::vector<TopoDS_Face>* faces, std::vector<int>* roles) {
  Eigen::Vector3d centre;
  double radius = 0;
  if (j.type == JointType::Revolute || !sphere_of(body, &centre, &radius)) return {};
  if (j.type == JointType::Prismatic) {
    const TopoDS_Shape capsule = ball_line_sweep(centre, radius, j.direction, T, faces, roles);
    return valid_and_closed(capsule) ? capsule : TopoDS_Shape();
  }
  if (j.pitch == 0) return {};
  *roles = {0, 1, 2};
  const double margin = std::max(Settings::ball_tube_margin * radius, Settings::ball_tube_margin_tol * tol);
  const TopoDS_Shape direct = helix_reach_exceeds(j, centre, T, radius, margin)
                                  ? ball_screw_sweep(centre, radius, j, T, fit_tol, size, fit_err, faces)
                                  : ball_screw_sweep_overlap(centre, radius, j, T, fit_tol, size, fit_err, faces, roles);
  return valid_and_closed(direct) ? direct : TopoDS_Shape();
}

namespace {

/// The variety of the body at the start or at the end of the joint's range.
int add_limit_variety(const StageInput& in, bool end, Candidates& cand) {
  const std::string qn = "q" + std::to_string(in.joint_no);
  return cand.add_variety({in.stage, in.joint_no, "limit",
                           std::string("the entity at the ") + (end ? "end" : "start") + " of joint " +
                               std::to_string(in.joint_no) + "'s range",
                           {{qn, end ? in.T() : 0.0}}, nlohmann::json::object()});
}

/// The body's parameter-free variety of `type` described by `what`, swept over the joint's range
/// and the curve parameter s in [f, l].
int add_swept_variety(const StageInput& in, const std::string& type, const std::string& what, double f, double l,
                      Candidates& cand) {
  nlohmann::json free = {{"q" + std::to_string(in.joint_no), {0.0, in.T()}}};
  free["s"] = {f, l};
  return cand.add_variety({in.stage, in.joint_no, type, what, nlohmann::json::object(), std::move(free)});
}

/// Whether edge e of the body needs no sweep of its own: smooth (G1) between two faces, whose
/// grazing curves meet across it, unless the motion is tangent to the faces all along it (then it
/// is a grazing curve that the faces' own tracing leaves to it: it lies on their borders).
bool smooth_edge(const TopoDS_Edge& e, const TopTools_IndexedDataMapOfShapeListOfShape& edge_faces,
                 const ScrewJoint& j) {
  if (!edge_faces.Contains(e)) return false;
  const TopTools_ListOfShape& fl = edge_faces.FindFromKey(e);
  if (fl.Extent() != 2) return false;
  const TopoDS_Face& f1 = TopoDS::Face(fl.First());
  const TopoDS_Face& f2 = TopoDS::Face(fl.Last());
  if (f1.IsSame(f2)) return false;
  if (!BRep_Tool::HasContinuity(e, f1, f2) || BRep_Tool::Continuity(e, f1, f2) < GeomAbs_G1) return false;
  BRepAdaptor_Curve2d pc(e, f1);
  BRepAdaptor_Surface S(f1);
  for (int m = 0; m <= 4; ++m) {
    const gp_Pnt2d uv = pc.Value(pc.FirstParameter() + (pc.LastParameter() - pc.FirstParameter()) * m / 4.0);
    BRepLProp_SLProps props(S, uv.X(), uv.Y(), 1, Settings::normal_resolution);
    if (!props.IsNormalDefined()) return true;
    const Eigen::Vector3d v = j.velocity(to_eigen(props.Value()));
    if (std::abs(to_eigen(gp_Vec(props.Normal())).dot(v)) > Settings::tangent_motion * (v.norm() + 1e-300)) return true;
  }
  return false;
}

/// The sweeps of the body's edges (not seams, not smooth, not collapsed) as candidates; with
/// `pending`, curves that do not keep a plane are collected there instead (see revolve_pieces).
void add_edge_sweeps(const StageInput& in, double& fit_err, Candidates& cand, std::vector<RevCurve>* pending) {
  const ScrewJoint& j = in.j();
  TopTools_IndexedMapOfShape edges, faces;
  TopExp::MapShapes(in.body, TopAbs_EDGE, edges);
  TopExp::MapShapes(in.body, TopAbs_FACE, faces);
  auto is_seam = [&](const TopoDS_Edge& e) {
    for (int k = 1; k <= faces.Extent(); ++k)
      if (BRep_Tool::IsClosed(e, TopoDS::Face(faces(k)))) return true;
    return false;
  };
  TopoDS_Shape regular = in.body;
  BRepLib::EncodeRegularity(regular, Settings::smooth_edge_angle);
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(in.body, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  int edge_no = 0;
  for (int k = 1; k <= edges.Extent(); ++k) {
    TopoDS_Edge e = TopoDS::Edge(edges(k));
    if (BRep_Tool::Degenerated(e) || is_seam(e) || smooth_edge(e, edge_faces, j)) continue;
    double f, l;
    Handle(Geom_Curve) c = BRep_Tool::Curve(e, f, l);
    if (c.IsNull()) continue;
    {  // collapsed edges (poles of parametric surfaces) sweep nothing
      double spread = 0;
      gp_Pnt p0 = c->Value(f);
      for (int k = 1; k <= 8; ++k) spread = std::max(spread, p0.Distance(c->Value(f + (l - f) * k / 8.0)));
      if (spread < Settings::resolution * in.esize) continue;
    }
    c = canonical_curve(c, f, l, std::max(in.fit_tol, Settings::canonical_curve_rounding * in.esize));
    gp_Pln plane;
    const bool planar = !c->IsKind(STANDARD_TYPE(Geom_Line)) && keeps_plane_of(c, f, l, j, in.size, &plane);
    const int vid = add_swept_variety(in, "boundary",
                                      "entity edge " + std::to_string(++edge_no) + " swept by joint " +
                                          std::to_string(in.joint_no) + (planar ? " (a planar region)" : ""),
                                      f, l, cand);
    if (!planar && pending) {
      pending->push_back({c, f, l, vid});
      continue;
    }
    auto sw = planar ? planar_curve_sweep(c, f, l, j, in.T(), plane, in.size)
                     : sweep_curve(c, f, l, j, in.T(), in.tol, &fit_err);
    if (!sw.empty()) ++cand.varieties;
    cand.add(vid, sw);
  }
}

/// Face split by the grazing-curve edges `tools`; the face whole when the pieces do not cover it
/// (a grazing curve on the face's border can leave the splitter with nothing).
std::vector<TopoDS_Face> split_at_grazing_curves(const TopoDS_Face& face, const TopTools_ListOfShape& tools,
                                                 double esize) {
  if (tools.IsEmpty()) return {face};
  const TopoDS_Shape split = split_by_edges(face, tools, Settings::resolution * esize, SplitMode::Parallel);
  if (split.IsNull()) return {face};
  std::vector<TopoDS_Face> split_faces;
  double area = 0.0;
  for (TopExp_Explorer ex(split, TopAbs_FACE); ex.More(); ex.Next()) {
    split_faces.push_back(TopoDS::Face(ex.Current()));
    GProp_GProps g;
    BRepGProp::SurfaceProperties(split_faces.back(), g);
    area += g.Mass();
  }
  GProp_GProps g;
  BRepGProp::SurfaceProperties(face, g);
  if (split_faces.empty() || std::abs(area - g.Mass()) > Settings::area_relative_tolerance * g.Mass()) return {face};
  return split_faces;
}

/// The sweeps of the grazing curves as candidates (into `pending` when given), and the body's
/// faces split at them into pieces where n . v keeps one sign (each piece is then wholly inside
/// the swept set or partly on its boundary, which lets pruning decide piece by piece).
std::vector<TopoDS_Face> add_grazing_sweeps(const StageInput& in, double& fit_err, Candidates& cand,
                                            std::vector<RevCurve>* pending) {
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(in.body, TopAbs_FACE, faces);
  std::vector<TopoDS_Face> pieces;
  for (int k = 1; k <= faces.Extent(); ++k) {
    const TopoDS_Face& face = TopoDS::Face(faces(k));
    TopTools_ListOfShape tools;
    for (const auto& g : grazing_curves(face, VelocityField(in.j()), in.fit_tol, in.esize)) {
      fit_err = std::max(fit_err, g.error);
      const GrazingEdge ge = grazing_edge(g, face, in.fit_tol);
      tools.Append(ge.edge);
      const int vid = add_swept_variety(in, "interior",
                                        "grazing curve (n . v = 0) on entity face " + std::to_string(k) +
                                            " swept by joint " + std::to_string(in.joint_no),
                                        ge.first, ge.last, cand);
      if (pending) {
        pending->push_back({ge.curve, ge.first, ge.last, vid});
        continue;
      }
      auto sw = sweep_curve(ge.curve, ge.first, ge.last, in.j(), in.T(), in.tol, &fit_err);
      if (!sw.empty()) ++cand.varieties;
      cand.add(vid, sw);
    }
    for (const auto& p : split_at_grazing_curves(face, tools, in.esize)) pieces.push_back(p);
  }
  return pieces;
}

}  // namespace

LimitIds stage_candidates(const StageInput& in, double& fit_err, Candidates& cand) {
  if (!in.screw) {
    if (!in.core || in.dim != 3) throw ComputeError("only solids that the core describes are swept by a motion that is no screw");
    cand = general_candidates(*in.core, in.motion, stage_swept_box(box_of(in.body), *in.motion), in.size, in.fit_tol,
                              fit_err);
    return {};
  }
  cand.varieties += 2;
  // For a rotation (no pitch) short of a full turn, curve sweeps are collected first: pieces of
  // different curves that revolve into the same surface of revolution would give partly
  // overlapping faces, which the arrangement cannot split.
  const bool full_turn = in.full_turn();
  const bool rotation_only = in.j().type == JointType::Revolute && !full_turn;
  std::vector<RevCurve> pending;
  add_edge_sweeps(in, fit_err, cand, rotation_only ? &pending : nullptr);
  const std::vector<TopoDS_Face> pieces = add_grazing_sweeps(in, fit_err, cand, rotation_only ? &pending : nullptr);
  if (!pending.empty()) {
    for (const auto& [vid, sw] : revolve_pieces(pending, in.j(), in.T(), in.tol, in.size, &fit_err)) {
      ++cand.varieties;
      cand.add(vid, sw);
    }
  }
  LimitIds ids;
  ids.lo = add_limit_variety(in, false, cand);
  ids.hi = full_turn ? -1 : add_limit_variety(in, true, cand);
  for (const auto& f : pieces) {
    cand.add(ids.lo, {f});
    if (!full_turn) cand.add(ids.hi, {TopoDS::Face(moved(f, in.j().transform(in.T())))});
  }
  return ids;
}

TopoDS_Shape ball_screw_stage(const StageInput& in, double& fit_err, Candidates& cand) {
  if (!in.screw) return {};
  const ScrewJoint& j = in.j();
  if (in.dim != 3) return {};  // direct_ball_screw says which joints and bodies it builds
  double err = fit_err;
  std::vector<TopoDS_Face> fs;
  std::vector<int> roles;
  const TopoDS_Shape direct = direct_ball_screw(in.body, j, in.T(), in.fit_tol, in.size, in.tol, &err, &fs, &roles);
  if (direct.IsNull()) return {};
  fit_err = err;
  cand.varieties += 3;
  const std::string qn = "q" + std::to_string(in.joint_no);
  const int tube = cand.add_variety({in.stage, in.joint_no, "interior",
                                     "grazing curve (n . v = 0) on entity face 1 swept by joint " +
                                         std::to_string(in.joint_no) + " (a tube about the centre's " +
                                         (j.type == JointType::Prismatic ? "segment)" : "helix)"),
                                     nlohmann::json::object(), nlohmann::json{{qn, {0.0, in.T()}}}});
  const int lo_id = add_limit_variety(in, false, cand), hi_id = add_limit_variety(in, true, cand);
  for (std::size_t k = 0; k < fs.size(); ++k) cand.add(roles[k] == 0 ? tube : roles[k] == 1 ? lo_id : hi_id, {fs[k]}, true);
  return direct;
}

TopoDS_Shape direct_stage(const StageInput& in, double& fit_err, Candidates& cand) {
  if (!in.screw) return {};
  const ScrewJoint& j = in.j();
  const double T = in.T();
  const std::string qn = "q" + std::to_string(in.joint_no);
  const nlohmann::json qfree = {{qn, {0.0, T}}};
  auto variety = [&](const std::string& type, const std::string& what, nlohmann::json fixed, nlohmann::json free) {
    return cand.add_variety({in.stage, in.joint_no, type, what, std::move(fixed), std::move(free)});
  };
  auto limit_variety = [&](bool end) { return add_limit_variety(in, end, cand); };
  // A ball whose centre's helix has a reach above its radius sweeps a tube closed by two half
  // balls.
  if (const TopoDS_Shape direct = ball_screw_stage(in, fit_err, cand); !direct.IsNull()) return direct;
  // A face translated along a direction in which it is a graph: the face, its translate and the
  // sweep of its boundary, sewn.
  if (in.dim == 2 && j.type == JointType::Prismatic) {
    TopExp_Explorer fx(in.body, TopAbs_FACE);
    const TopoDS_Face face = fx.More() ? TopoDS::Face(fx.Current()) : TopoDS_Face();
    if (fx.More()) fx.Next();
    std::vector<GraphExtrusionFace> gfs;
    double gerr = fit_err;
    TopoDS_Shape direct = !face.IsNull() && !fx.More() ? graph_extrusion(face, j, T, in.size, in.tol, &gerr, &gfs)
                                                       : TopoDS_Shape();
    if (valid_and_closed(direct)) {
      fit_err = gerr;
      cand.varieties += 2;
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
                                                     " swept by joint " + std::to_string(in.joint_no),
                                     nlohmann::json::object(), efree);
          ++cand.varieties;
        }
        cand.add(edge_ids[g.role], {g.face});
      }
      return direct;
    }
  }
  return {};
}

}  // namespace sweep::occt
