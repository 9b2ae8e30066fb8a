// Sweeps under one-parameter motions that are not chains of screws (SPEC.md `path`, `keyframes`).
// Keyframes with screw interpolation, linear ones whose segments only slide or turn, and any
// motion that is one screw (StageMotion::as_screw: a straight path, a turn about a fixed axis, a
// helix, at any monotone rate) are sequences of screw segments: each segment is the one-joint
// sweep of the entity at its start pose (the stages of run_sweep), and the set is their union,
// judged once. Under a general motion a ball sweeps the tube about its centre's path
// (varieties/ball_path.cpp), judged by a branch and bound over t (sweep/stage_membership.hpp); a
// point sweeps its fitted path and a curve a fitted surface; other solids under general motions
// are built from the arrangement of their candidate patches with --general-motions (decision 0027)
// and fail as not supported yet without it.
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <BRepBndLib.hxx>
#include <BRep_Builder.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS_Compound.hxx>
#include <algorithm>
#include <cmath>
#include <memory>

#include "arrangement/general_candidates.hpp"
#include "arrangement/stage_sweep.hpp"
#include "base/internal.hpp"
#include "base/stop.hpp"
#include "run/run_steps.hpp"
#include "sweep/error.hpp"
#include "sweep/candidate_patches.hpp"
#include "sweep/stage_membership.hpp"
#include "sweep/swept_box.hpp"
#include "varieties/ball_path.hpp"
#include "varieties/tube_fit.hpp"
#include "verdict/solid_checks.hpp"

namespace sweep::occt {
namespace {

/// The run's entity, its shape for its extent (sizing_shape) and its fit error, built once per run.
struct Sizing {
  RunEntity entity;
  TopoDS_Shape shape;
  double fit_err = 0;
};

/// The model size: the entity's extent and the box of its corners at sampled poses.
double stage_model_size(const TopoDS_Shape& raw, const StageMotion& m) {
  const Eigen::AlignedBox3d eb = box_of(raw);
  Eigen::AlignedBox3d reach;
  for (int s = 0; s <= 64; ++s) {
    const Eigen::Isometry3d M = m.transform(m.lo() + (m.hi() - m.lo()) * s / 64.0);
    for (int k = 0; k < 8; ++k) reach.extend(M * eb.corner(Eigen::AlignedBox3d::CornerType(k)));
  }
  return std::max({eb.sizes().maxCoeff(), reach.sizes().maxCoeff(), 1e-300});
}

/// In when any part says in; undecided when none does and one is undecided.
IndependentMembership union_of(const std::vector<IndependentMembership>& parts) {
  std::vector<MemberTestMaker> makers;
  for (const auto& p : parts) makers.push_back(p.test);
  return {[makers]() -> MemberTest {
            std::vector<MemberTest> tests;
            for (const auto& m : makers) tests.push_back(m());
            return [tests](const Eigen::Vector3d& x) {
              int result = 0;
              for (const auto& t : tests) {
                const int r = t(x);
                if (r == 1) return 1;
                if (r < 0) result = -1;
              }
              return result;
            };
          },
          "union over the segments of: " + parts.front().name, {}};
}

/// Membership in the sweep of a solid with a signed distance under `m`, by a search over t that
/// never looks at a computed solid.
IndependentMembership search_over_t(const std::shared_ptr<const SignedDistance>& sd, const StageMotion& m, double size,
                                    const Settings& settings) {
  const StageMotion* motion = &m;
  const double resolution = Settings::resolution * size;
  const std::size_t budget = settings.membership_budget;
  const bool certified = std::isfinite(m.speed_bound(1.0));
  return {[sd, motion, resolution, budget]() -> MemberTest {
            auto set = std::make_shared<StageSweptSet>(*sd, *motion, resolution, budget);
            return [set](const Eigen::Vector3d& x) { return (*set)(x); };
          },
          std::string("search over t (signed distance, ") + (certified ? "certified" : "sampled") + " speed bound)", {}};
}

/// The checks of a solid result, the Monte Carlo volume of --verify by `member`, the verdict.
void finish_solid(TopoDS_Shape result, FinalChecks& check, const MemberTestMaker& member, double size, double tol,
                  const RunOptions& opt, RunRecord& record, RunResult& res) {
  Report& rep = res.report;
  std::string why = check.judge(result);
  if (check.result_healed()) record.stages.back().healed = true;
  if (opt.verify) {
    if (opt.progress) opt.progress("Monte Carlo volume");
    const auto t_mc = Clock::now();
    Eigen::AlignedBox3d box(Eigen::Vector3d(rep.bbox_min[0], rep.bbox_min[1], rep.bbox_min[2]),
                            Eigen::Vector3d(rep.bbox_max[0], rep.bbox_max[1], rep.bbox_max[2]));
    box.extend(box.min() - Eigen::Vector3d::Constant(0.01 * size));
    box.extend(box.max() + Eigen::Vector3d::Constant(0.01 * size));
    const MemberTest in = member();
    const MonteCarloResult mc = monte_carlo_volume([&](const Eigen::Vector3d& x) { return in(x) == 1; }, box,
                                                   std::min<std::size_t>(opt.settings.mc_samples, 100000),
                                                   opt.settings.seed);
    rep.has_mc = true;
    rep.volume_mc = mc.volume;
    rep.volume_mc_stderr = mc.stderr_;
    rep.mc_samples = mc.samples;
    record.add_seconds("monte_carlo", since(t_mc));
  }
  if (why.empty()) why = monte_carlo_disagreement(rep, tol, size, opt.settings);
  rep.status = why.empty() ? "ok" : "failed";
  rep.message = why;
  res.shape = std::make_shared<Shape>(result);
}

/// The union of solids (one general fuse), its faces merged where they continue one surface.
TopoDS_Shape fused(const std::vector<TopoDS_Shape>& parts, double size) {
  if (parts.size() == 1) return parts.front();
  TopTools_ListOfShape args, tools;
  args.Append(parts.front());
  for (std::size_t k = 1; k < parts.size(); ++k) tools.Append(parts[k]);
  BRepAlgoAPI_Fuse fuse;
  fuse.SetArguments(args);
  fuse.SetTools(tools);
  fuse.SetRunParallel(true);
  fuse.SetFuzzyValue(Settings::resolution * size);
  fuse.SetNonDestructive(true);
  fuse.Build(stop_range());
  check_stop();
  if (!fuse.IsDone() || fuse.HasErrors()) throw ComputeError("the union of the segments' solids failed (OCCT's fuse)");
  TopoDS_Shape s = fuse.Shape();
  const TopoDS_Shape u = unify_faces(s);
  if (!u.IsNull()) s = u;
  TopExp_Explorer sx(s, TopAbs_SOLID);
  if (sx.More()) {
    const TopoDS_Shape first = sx.Current();
    sx.Next();
    if (!sx.More()) return first;
  }
  return s;
}

/// A motion made of screw segments (keyframes, or a path that is one screw): the union of the
/// segments' screw sweeps, each built by the stages of a one-joint chain, judged once as a whole.
/// Segments that continue one screw are swept as one. The judge is the union of the segments' own
/// independent memberships (exact for each screw; the segments come from the input motion alone).
void screw_segments_sweep(const Spec& spec, const StageMotion& m, const Sizing& sizing,
                          const std::vector<ScrewSegment>& screw_segments, const RunOptions& opt, RunRecord& record,
                          RunResult& res) {
  Report& rep = res.report;
  if (screw_segments.empty()) throw ComputeError("the poses never move the entity: nothing is swept");
  const auto t_fit = Clock::now();
  double fit_err = sizing.fit_err;
  const double size = stage_model_size(sizing.shape, m);
  const auto [tol, fit_tol] = run_tolerance(spec.tolerance, size, opt.settings);
  rep.tol_requested = tol;
  const TopoDS_Shape raw = fitted_entity_shape(spec.entity, sizing.shape, fit_tol, &fit_err);
  const Eigen::AlignedBox3d entity_box = box_of(raw);
  record.add_seconds("entity", since(t_fit));
  const auto segments = KeyframeMotion::merged(screw_segments, size);
  RunOptions chain_opt = opt;  // the segments' candidates are not reported
  chain_opt.varieties = nullptr;
  chain_opt.variety_faces = nullptr;
  chain_opt.variety_face_ids = nullptr;
  std::vector<TopoDS_Shape> parts;
  std::vector<IndependentMembership> members;
  Eigen::AlignedBox3d true_box;
  int dim = 0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const auto& seg = segments[k];
    const std::string name = "segment " + std::to_string(k + 1) + "/" + std::to_string(segments.size()) +
                             " (t in [" + std::to_string(seg.t0) + ", " + std::to_string(seg.t1) + "])";
    const auto step = [&opt, &name](const std::string& what) {
      check_stop();
      if (opt.progress) opt.progress(name + ": " + what);
    };
    Motion motion;
    motion.joints = {seg.joint};
    motion.home = seg.start;
    try {
      const ChainSweep chain = sweep_chain({sizing.entity, raw, size, tol, fit_tol}, motion, false, chain_opt,
                                           fit_err, record, step);
      parts.push_back(chain.shape);
      dim = chain.dim;
    } catch (const ComputeError& e) {
      throw ComputeError(name + ": " + e.what());
    }
    if (dim == 3) {
      Motion clipped = motion;  // a revolute joint beyond a whole turn covers nothing new
      if (seg.joint.type == JointType::Revolute) clipped.joints[0].hi = std::min(seg.joint.hi, seg.joint.lo + 2 * M_PI);
      members.push_back(independent_membership(sizing.entity, clipped, raw, size, opt.settings));
      if (!members.back().test) throw ComputeError(name + ": no membership test independent of the solid exists");
      true_box.extend(swept_box(entity_box, clipped));
    }
  }
  rep.dimension = dim;
  if (dim < 3) {
    TopoDS_Compound comp;
    BRep_Builder bb;
    bb.MakeCompound(comp);
    for (const auto& p : parts) bb.Add(comp, p);
    res.shape = std::make_shared<Shape>(finish_curve_or_surface(comp, dim, size, fit_err, opt.verify, rep));
    return;
  }
  if (parts.size() > 1 && opt.progress) opt.progress("the union of " + std::to_string(parts.size()) + " segments");
  const auto t_union = Clock::now();
  const TopoDS_Shape result = fused(parts, size);
  if (parts.size() > 1) record.add_seconds("union", since(t_union));
  const IndependentMembership member = union_of(members);
  FinalChecks check(rep, member, true_box, tol, size, fit_err, opt.settings, record.any_from_cells(), "");
  finish_solid(result, check, member.test, size, tol, opt, record, res);
}

/// A ball under a general one-parameter motion, given as pieces along which its centre's path is
/// smooth (the whole motion, or the segments of linear keyframes): the union of their tubes.
void ball_stage_sweep(const Spec& spec, const StageMotion& m, const Sizing& sizing,
                      const std::vector<const StageMotion*>& pieces, const RunOptions& opt, RunRecord& record,
                      RunResult& res) {
  Report& rep = res.report;
  double fit_err = sizing.fit_err;
  const TopoDS_Shape& raw = sizing.shape;
  const double size = stage_model_size(raw, m);
  const auto [tol, fit_tol] = run_tolerance(spec.tolerance, size, opt.settings);
  rep.tol_requested = tol;
  const Eigen::Vector3d c0 = spec.entity.placement * spec.entity.center;
  const auto t_build = Clock::now();
  std::vector<TopoDS_Shape> tubes;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    if (opt.progress) opt.progress("the tube about the ball's path, piece " + std::to_string(k + 1));
    std::string why;
    tubes.push_back(ball_path_sweep(c0, spec.entity.radius, *pieces[k], fit_tol, size, &fit_err, nullptr, &why));
    if (tubes.back().IsNull())
      throw ComputeError("a ball under this motion" +
                         (pieces.size() > 1 ? " (segment " + std::to_string(k + 1) + ")" : std::string()) + ": " + why);
  }
  const TopoDS_Shape solid = fused(tubes, size);
  StageRecord tubes_record;  // each piece: its tube and two half balls
  tubes_record.stage = 1;
  tubes_record.varieties = 3 * int(pieces.size());
  tubes_record.cells = int(pieces.size());
  tubes_record.add_seconds("stages", since(t_build));
  record.stages.push_back(tubes_record);
  const IndependentMembership member = search_over_t(sizing.entity.sd, m, size, opt.settings);
  FinalChecks check(rep, member, stage_swept_box(box_of(raw), m), tol, size, fit_err, opt.settings, false, "");
  finish_solid(solid, check, member.test, size, tol, opt, record, res);
}

/// A point (its trajectory, a curve) or a curve (a surface) under a general motion, one fitted
/// B-spline per smooth piece of the motion.
void low_dimension_stage_sweep(const Spec& spec, const StageMotion& m, const Sizing& sizing,
                               const std::vector<const StageMotion*>& pieces, const RunOptions& opt,
                               RunRecord& record, RunResult& res) {
  Report& rep = res.report;
  const int dim = spec.entity.dimension();
  const std::shared_ptr<const ParametricEntity>& pe = sizing.entity.pe;
  if (!pe) throw InternalError("no parametric map for a point or curve entity");
  double fit_err = sizing.fit_err;
  const double size = stage_model_size(sizing.shape, m);
  const auto [tol, fit_tol] = run_tolerance(spec.tolerance, size, opt.settings);
  rep.tol_requested = tol;
  const auto t_build = Clock::now();
  TopoDS_Compound comp;
  BRep_Builder bb;
  bb.MakeCompound(comp);
  for (const StageMotion* piece : pieces) {
    check_stop();
    const double lo = piece->lo(), L = piece->hi() - lo;
    if (dim == 0) {
      const double at[1] = {0};
      const Eigen::Vector3d x0 = pe->eval(at);
      const auto row = [&](double u) {
        return Eigen::RowVectorXd((piece->transform(std::min(lo + u, piece->hi())) * x0).transpose());
      };
      const int p = 9;
      Fit fit;
      for (int spans = 2; spans <= 4096; spans *= 2) {
        fit = fit_bspline(row, 3, L, p, spans, 1);
        if (fit.error <= fit_tol) break;
      }
      if (!(fit.error <= fit_tol)) throw ComputeError("the point's path could not be fitted within the tolerance");
      fit_err = std::max(fit_err, fit.error);
      TColgp_Array1OfPnt poles(1, int(fit.poles.rows()));
      for (int i = 0; i < int(fit.poles.rows()); ++i) poles.SetValue(i + 1, gp_Pnt(fit.poles(i, 0), fit.poles(i, 1), fit.poles(i, 2)));
      TColStd_Array1OfReal knots(1, int(fit.knots.size()));
      TColStd_Array1OfInteger mults(1, int(fit.knots.size()));
      knots_of(fit, knots, mults);
      bb.Add(comp, BRepBuilderAPI_MakeEdge(new Geom_BSplineCurve(poles, knots, mults, p)).Edge());
    } else {
      const double s0 = pe->lo(0), s1 = pe->hi(0);
      const auto exact = [&](double fu, double fv) {
        const double s[1] = {s0 + (s1 - s0) * fv};
        return to_pnt(piece->transform(std::min(lo + L * fu, piece->hi())) * pe->eval(s));
      };
      double err = 0;
      const Handle(Geom_BSplineSurface) srf = fit_grid_surface(exact, fit_tol, 0.1 * fit_tol, 16, 256, &err);
      if (srf.IsNull()) throw ComputeError("the surface swept by the curve could not be fitted within the tolerance");
      fit_err = std::max(fit_err, err);
      bb.Add(comp, BRepBuilderAPI_MakeFace(srf, Settings::resolution * size).Face());
    }
  }
  record.add_seconds("stages", since(t_build));
  rep.dimension = dim + 1;
  res.shape = std::make_shared<Shape>(finish_curve_or_surface(comp, dim + 1, size, fit_err, opt.verify, rep));
}

/// A solid under a general one-parameter motion (the engine of seed 001), as one stage of the
/// joints' engine (solid_sweep): the core's candidate patches made faces, their arrangement, its
/// cells kept by the search over t (which never looks at the solid), judged by the verdict
/// against the same search.
void general_solid_sweep(const Spec& spec, const StageMotion& m, const Sizing& sizing, const RunOptions& opt,
                         RunRecord& record, RunResult& res) {
  Report& rep = res.report;
  double fit_err = sizing.fit_err;
  const TopoDS_Shape& raw = sizing.shape;
  const double size = stage_model_size(raw, m);
  const auto [tol, fit_tol] = run_tolerance(spec.tolerance, size, opt.settings);
  rep.tol_requested = tol;
  const IndependentMembership member = search_over_t(sizing.entity.sd, m, size, opt.settings);
  StageInput in(raw, 3, spec.motion.stage, extent(raw), size, tol, fit_tol, 1, 1);
  in.core = sizing.entity.core.get();
  in.member = decided_or_failed(member.test, "the search over t could not decide whether a cell is in the swept set");
  if (opt.progress) opt.progress("candidate varieties and the arrangement of their faces");
  record.stages.emplace_back();  // first, so that a failure keeps what the stage did
  StageRecord& stage = record.stages.back();
  stage.stage = 1;
  stage.from_cells = true;
  Candidates cand;
  const TopoDS_Shape solid = solid_sweep(in, fit_err, stage, &cand, false, nullptr, false);
  if (opt.varieties) {
    cand.compute_areas();
    for (const auto& v : cand.vars) opt.varieties->push_back(v);
  }
  const Eigen::AlignedBox3d reach = stage_swept_box(box_of(raw), m);
  FinalChecks check(rep, member, reach, tol, size, fit_err, opt.settings, false, "");
  finish_solid(solid, check, member.test, size, tol, opt, record, res);
}

/// The candidate varieties of an entity under a general motion, for `sweepvol varieties`, when
/// they are asked for and the core has the entity: the core's candidate patches with their areas
/// (no faces are made of them yet); whether they were listed.
bool list_general_candidates(const Spec& spec, const Sizing& sizing, const RunOptions& opt, RunRecord& record) {
  if (!opt.varieties || !sizing.entity.core || spec.entity.dimension() != 3) return false;
  if (has_trimmed_faces(*sizing.entity.core)) return false;
  const auto t0 = Clock::now();
  for (const CandidatePatch& c : candidate_patches(*sizing.entity.core, spec.motion.stage, [] { check_stop(); })) {
    Variety v = candidate_variety(c);
    v.area = patch_area(*c.patch);
    check_stop();
    opt.varieties->push_back(std::move(v));
  }
  record.add_seconds("varieties", since(t0));
  return true;
}

}  // namespace

RunResult run_stage_motion_sweep(const Spec& spec, const RunOptions& opt) {
  const auto t_start = Clock::now();
  RunResult res;
  Report& rep = res.report;
  rep.dimension = spec.entity.dimension();
  install_signal_handlers();
  const StopScope stop_scope(opt.stop);
  const StageMotion& m = *spec.motion.stage;
  RunRecord record;
  try {
    OCC_CATCH_SIGNALS
    Sizing sizing{RunEntity(spec.entity), {}, 0.0};
    sizing.shape = sizing.entity.sizing_shape(&sizing.fit_err);
    record.add_seconds("entity", since(t_start));
    const auto* km = dynamic_cast<const KeyframeMotion*>(&m);
    auto segments = km ? km->screw_segments() : std::nullopt;
    // any other motion that is one screw goes to the screw engine
    const std::optional<ScrewSegment> screw = km ? std::nullopt : m.as_screw(radius_of(sizing.shape));
    if (screw) segments = std::vector<ScrewSegment>{*screw};
    // a ball slid along a line is a tube about its centre's path too (and the one-joint engine
    // stalls on a ball slid along the normal of its surface's seam plane)
    if (segments && spec.entity.kind == EntityKind::Sphere)
      for (const auto& seg : *segments)
        if (seg.joint.type == JointType::Prismatic) segments.reset();
    if (segments) {
      screw_segments_sweep(spec, m, sizing, *segments, opt, record, res);
    } else if (spec.entity.kind == EntityKind::Sphere || spec.entity.dimension() <= 1) {
      // linear keyframes that are not screws turn at the poses: one smooth piece per segment
      std::vector<std::unique_ptr<KeyframeMotion>> segments;
      std::vector<const StageMotion*> pieces{&m};
      if (km) {
        pieces.clear();
        for (std::size_t k = 0; k + 1 < km->times().size(); ++k) {
          segments.push_back(std::make_unique<KeyframeMotion>(
              std::vector<double>{km->times()[k], km->times()[k + 1]},
              std::vector<Eigen::Isometry3d>{km->poses()[k], km->poses()[k + 1]}, km->interpolation()));
          pieces.push_back(segments.back().get());
        }
      }
      if (spec.entity.dimension() <= 1) {
        low_dimension_stage_sweep(spec, m, sizing, pieces, opt, record, res);
      } else {
        ball_stage_sweep(spec, m, sizing, pieces, opt, record, res);
      }
    } else if (opt.settings.general_motions && sizing.entity.core && sizing.entity.sd &&
               spec.entity.dimension() == 3) {
      general_solid_sweep(spec, m, sizing, opt, record, res);
    } else {
      const bool listed = list_general_candidates(spec, sizing, opt, record);
      throw ComputeError(std::string("a ") + to_string(spec.entity.kind) + " entity under a " +
                         to_string(spec.motion.kind) +
                         " motion that is not a sequence of screws is not supported yet (points, curves and balls are; "
                         "keyframes whose segments are screws and paths that are one screw take every entity)" +
                         (listed ? "; its candidate varieties are listed, with the areas of their patches" : ""));
    }
  } catch (const InputError&) {
    throw;
  } catch (const Standard_Failure& f) {
    rep.status = "failed";
    rep.message = std::string("OCCT: ") + (f.GetMessageString() ? f.GetMessageString() : "failure");
  } catch (const ComputeError& e) {
    rep.status = "failed";
    rep.message = e.what();
  }
  write_run_record(record, rep);
  rep.seconds_total = since(t_start);
  return res;
}

}  // namespace sweep::occt
