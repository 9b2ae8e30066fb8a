// The sweep pipeline: the entity and the model's size and tolerance, the stages (innermost joint
// first; the entity's own stage from its sweep boundary, the others from the arrangement of cells:
// stage_sweep.hpp), the checks of the final solid and its verdict (run_steps.hpp), the report.
#include <BRepBndLib.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <memory>

#include "base/internal.hpp"
#include "base/stop.hpp"
#include "sweep/error.hpp"
#include "sweep/membership.hpp"
#include "sweep/orbit.hpp"
#include "sweep/swept_box.hpp"
#include "arrangement/boundary_sweep.hpp"
#include "run/run_steps.hpp"
#include "verdict/solid_checks.hpp"
#include "arrangement/stage_sweep.hpp"
#include "verdict/verdict.hpp"

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

/// The largest side of the shape's box.
double extent(const TopoDS_Shape& s) {
  Bnd_Box b;
  BRepBndLib::Add(s, b);
  double x0, y0, z0, x1, y1, z1;
  b.Get(x0, y0, z0, x1, y1, z1);
  return std::max({x1 - x0, y1 - y0, z1 - z0, 1e-300});
}

/// The model size: the extent of the entity's box corners carried by the motion sampled at the
/// ends and middles of the joint ranges (a point entity has no extent of its own).
double model_size(const TopoDS_Shape& raw, const Motion& motion) {
  double size = extent(raw);
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
    for (int k = 0; k < 8; ++k) reach.extend(M * Eigen::Vector3d(k & 1 ? x1 : x0, k & 2 ? y1 : y0, k & 4 ? z1 : z0));
  }
  return std::max(size, reach.sizes().maxCoeff());
}

/// The entity's own stage (a solid) without the arrangement of cells: built directly when it is a
/// ball under a screw, else from its sweep boundary, whose pieces are classified by the entity's
/// orbit intervals (a primitive) or by trajectories against the body's faces. Null when neither
/// builds it (then the cells do). `G`: the entity's placement before the stage.
TopoDS_Shape entity_stage(const StageInput& in, const EntitySpec& entity, const Eigen::Isometry3d& G,
                          const RunOptions& opt, double& fit_err, Report& rep, Candidates& stage_cands,
                          const std::function<void(const std::string&)>& step) {
  const ScrewJoint& j = in.j;
  const double T = in.T;
  const TopoDS_Shape direct = opt.direct_builds ? ball_screw_stage(in, fit_err, stage_cands) : TopoDS_Shape();
  if (!direct.IsNull()) {
    rep.varieties += int(stage_cands.vars.size());
    rep.cells += 1;
    return direct;
  }
  const OrbitSolidPtr orbit_entity = make_orbit_solid(entity);
  const PointTestMaker stage_member = orbit_entity
                                          ? orbit_membership(orbit_placed(orbit_entity, j.transform(j.lo) * G), j, T)
                                          : trajectory_membership(in.body, j, T, 1e-9 * in.size);
  BoundarySweep b =
      boundary_sweep(in.body, j, T, stage_member, in.size, in.tol, opt.settings, in.stage, in.joint_no);
  for (auto it = b.seconds.begin(); it != b.seconds.end(); ++it)
    rep.seconds[it.key()] = rep.seconds.value(it.key(), 0.0) + it.value().get<double>();
  // a boundary that left a piece out (a sliver whose crossing with an end copy no section found)
  // does not close: the arrangement of cells is made instead
  if (!b.solid.IsNull() && !closed_solids(b.solid) && !closed_solids(healed(b.solid))) {
    b.failure = "the pieces of its sweep boundary do not close";
    b.solid.Nullify();
  }
  if (b.solid.IsNull()) {
    step("stage " + std::to_string(in.stage) + ": " + b.failure + "; built from cells instead");
    return {};
  }
  fit_err = std::max(fit_err, b.fit_error);
  for (auto& v : b.varieties) stage_cands.add_variety(std::move(v));
  for (std::size_t k = 0; k < b.candidate_faces.size(); ++k) stage_cands.add(b.candidate_ids[k], {b.candidate_faces[k]});
  rep.varieties += int(stage_cands.vars.size());
  rep.cells += 1;
  return b.solid;
}

/// A stage whose arrangement lacked faces left out as internal, checked (valid, or valid once
/// healed; closed; its two volumes agreeing): built again by `rebuild` from every candidate when
/// the check fails.
TopoDS_Shape checked_stage(const TopoDS_Shape& shape, int stage, double fit_err, double tol, Report& rep,
                           const std::function<void(const std::string&)>& step,
                           const std::function<TopoDS_Shape()>& rebuild) {
  const auto t_chk = Clock::now();
  const SolidChecks sc = check_solid(shape);
  TopoDS_Shape checked = shape;
  bool agree = sc.agree(std::max({fit_err, max_tolerance(shape), tol}));
  if (!agree && !sc.valid) {
    const TopoDS_Shape h = healed(shape);
    if (!h.IsNull() && check_solid(h).agree(std::max({fit_err, max_tolerance(h), tol}))) {
      checked = h;
      agree = true;
      rep.healed_stages.push_back(stage);
    }
  }
  rep.seconds["stage_checks"] = rep.seconds.value("stage_checks", 0.0) + since(t_chk);
  if (agree) return checked;
  step("stage " + std::to_string(stage) + " failed its checks: again with every candidate");
  const TopoDS_Shape rebuilt = rebuild();
  rep.unpruned_stages.push_back(stage);
  return rebuilt;
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
  if (spec.motion.stage) return run_stage_motion_sweep(spec, opt);
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
    const double size = model_size(raw, motion);
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
        const auto t_stage = Clock::now();
        const StageInput in{body, dim, j, T, nullptr, nullptr, motion, extent(body), size, tol, fit_tol, n - i, i + 1};
        const TopoDS_Shape solid = entity_stage(in, spec.entity, G, opt, fit_err, rep, stage_cands, step);
        if (!solid.IsNull()) {
          shape = solid;
          built = true;
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
          const StageInput in{body, dim, j, T, use_sd ? sd.get() : nullptr, spe, sd_motion, esize, size, tol,
                              fit_tol, n - i, i + 1};
          return solid_sweep(in, fit_err, rep, out, prune, pruned, opt.direct_builds);
        };
        PruneCount pruned;
        shape = sweep_stage(true, &pruned, &stage_cands);
        // Building the arrangement of every candidate again costs time that grows fast with their
        // number; past the settings' limit a stage that fails its checks is not rebuilt.
        const bool may_rebuild =
            pruned.dropped > 0 && std::size_t(pruned.candidates) <= opt.settings.rebuild_candidate_limit;
        if (i > 0 && may_rebuild)
          shape = checked_stage(shape, n - i, fit_err, tol, rep, step,
                                [&sweep_stage, &stage_cands]() { return sweep_stage(false, nullptr, &stage_cands); });
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
      res.shape = std::make_shared<Shape>(finish_curve_or_surface(shape, dim, size, fit_err, opt.verify, rep));
      rep.seconds_total = since(t_start);
      return res;
    }

    Motion clipped = motion;  // a revolute joint beyond a whole turn covers nothing new
    for (auto& jj : clipped.joints)
      if (jj.type == JointType::Revolute && jj.hi - jj.lo > 2 * M_PI) jj.hi = jj.lo + 2 * M_PI;
    // The box that holds the true swept set: from the entity's box and the motion.
    const Eigen::AlignedBox3d entity_box = [&] {
      const Bnd_Box b = shape_box(raw);
      double x0, y0, z0, x1, y1, z1;
      b.Get(x0, y0, z0, x1, y1, z1);
      return Eigen::AlignedBox3d(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1));
    }();
    FinalChecks check_result(
        rep, independent_membership(spec.entity, clipped, raw, sd.get(), pe.get(), size, opt.settings),
        swept_box(entity_box, clipped), tol, size, fit_err, opt.settings,
        "no membership test independent of the solid exists for a " + std::string(to_string(spec.entity.kind)) +
            " entity under " + std::to_string(n) + " joints: the solid cannot be checked");
    std::string why = check_result.judge(result, n);
    if (!why.empty() && redo_last && check_result.rebuild_may_help()) {
      // Pruning may have left out a face that carries a strip of the boundary: the last stage
      // is built again from every candidate.
      step("the solid failed its checks (" + why + "): last stage again with every candidate");
      result = redo_last();
      rep.unpruned_stages.push_back(n);
      why = check_result(result);
    }

    if (opt.varieties || opt.variety_faces) {
      attribute_result_faces(last_cands, result, size);
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
      monte_carlo_check(spec.entity, clipped, raw, result, sd.get(), pe.get(), size, opt.settings, rep);
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
