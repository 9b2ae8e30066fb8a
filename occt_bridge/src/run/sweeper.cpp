// The sweep pipeline: the entity and the model's size and tolerance, the stages of the chain
// (run/chain_sweep.cpp), the checks of the final solid and its verdict (run_steps.hpp), the report.
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Standard_ErrorHandler.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
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
#include "entity/brep_entity.hpp"
#include "sweep/error.hpp"
#include "sweep/membership.hpp"
#include "sweep/swept_box.hpp"
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
  if (has_independent_volume) {
    j["volume"]["orbits"] = volume_independent;
    j["volume"]["orbits_error"] = volume_independent_error;
  }
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
TopoDS_Shape file_shape_of(const EntitySpec& s) {
  const bool file = s.kind == EntityKind::Brep || s.kind == EntityKind::Mesh;
  return file ? entity_shape(s, 0.0, nullptr) : TopoDS_Shape();
}
}  // namespace

RunEntity::RunEntity(const EntitySpec& s)
    : spec(s),
      file_shape(file_shape_of(s)),
      core(file_shape.IsNull() ? make_entity(s) : brep_entity(file_shape, s.kind)),
      pe(ParametricEntity::make(s)) {
  if (core) {
    if (core->tight_distance()) sd = core->distance_bound();
    orbit = core->orbit_solid();
  }
}

std::shared_ptr<const SignedDistance> RunEntity::search_bound() const {
  if (sd || !core || !core->has_distance_bound()) return sd;
  return core->distance_bound();
}

TopoDS_Shape RunEntity::sizing_shape(double* fit_error) const {
  return file_shape.IsNull() ? occt::sizing_shape(spec, fit_error, core.get()) : file_shape;
}

RunTolerance run_tolerance(double spec_tolerance, double size, const Settings& settings) {
  const double tol = spec_tolerance > 0 ? spec_tolerance : settings.default_tolerance * size;
  return {tol, settings.fit_fraction * tol};
}

std::string monte_carlo_disagreement(const Report& rep, double tol, double size, const Settings& settings) {
  if (!rep.has_mc) return {};
  const double band = tol * size * size + settings.volume_relative_band * size * size * size;
  if (std::abs(rep.volume_brep - rep.volume_mc) <= 4.5 * rep.volume_mc_stderr + band) return {};
  return "B-rep and Monte Carlo volumes disagree (" + std::to_string(rep.volume_brep) + " vs " +
         std::to_string(rep.volume_mc) + " +- " + std::to_string(rep.volume_mc_stderr) + ")";
}

bool RunRecord::any_from_cells() const {
  return std::any_of(stages.begin(), stages.end(), [](const StageRecord& s) { return s.from_cells; });
}

void write_run_record(const RunRecord& record, Report& rep) {
  merge_step_seconds(rep.seconds, record.seconds);
  for (const StageRecord& s : record.stages) {
    rep.varieties += s.varieties;
    rep.cells += s.cells;
    if (s.from_cells) rep.cell_stages.push_back(s.stage);
    if (s.unpruned) rep.unpruned_stages.push_back(s.stage);
    if (s.healed) rep.healed_stages.push_back(s.stage);
    for (int faces : s.restored) rep.restored_candidates.push_back({s.stage, faces});
    merge_step_seconds(rep.seconds, s.seconds);
  }
}

RunResult run_sweep(const Spec& spec, const RunOptions& opt) {
  const auto t_start = Clock::now();
  RunResult res;
  Report& rep = res.report;
  rep.dimension = spec.entity.dimension();
  const Motion& motion = spec.motion.motion;
  if (spec.motion.stage) return run_stage_motion_sweep(spec, opt);
  if (motion.dof() == 0) {
    rep.message = "the motion has no joint";
    rep.seconds_total = since(t_start);
    return res;
  }
  install_signal_handlers();
  const StopScope stop_scope(opt.stop);
  // each step of a long run: the stop request is polled, then the step is shown
  std::string last_step = "setting up";  // (named in a failure of OCCT's)
  const auto step = [&](const std::string& what) {
    check_stop();
    last_step = what;
    if (opt.progress) opt.progress(what);
  };
  RunRecord record;
  try {
    OCC_CATCH_SIGNALS
    // Size and tolerance from the entity and the reach of the motion.
    double fit_err = 0;
    const RunEntity entity(spec.entity);
    // Parametric curves and surfaces are fitted once the tolerance is known; their extent comes
    // from a sampled stand-in (a polyline or a point cloud is enough for a bounding box).
    const TopoDS_Shape sizing = entity.sizing_shape(&fit_err);
    const double size = model_size(sizing, motion);
    const auto [tol, fit_tol] = run_tolerance(spec.tolerance, size, opt.settings);
    rep.tol_requested = tol;
    TopoDS_Shape raw = fitted_entity_shape(spec.entity, sizing, fit_tol, &fit_err);
    record.add_seconds("entity", since(t_start));
    ChainSweep chain = sweep_chain({entity, raw, size, tol, fit_tol}, motion, true, opt, fit_err, record, step);
    raw = chain.raw;
    const int n = int(motion.dof());
    const int dim = chain.dim;
    const TopoDS_Shape& shape = chain.shape;
    Candidates& last_cands = chain.last_cands;
    rep.dimension = dim;
    TopoDS_Shape result = shape;
    if (dim < 3) {
      // A point sweeps a curve and a curve a surface: written as edges or faces, with no volume.
      res.shape = std::make_shared<Shape>(finish_curve_or_surface(shape, dim, size, fit_err, opt.verify, rep));
      write_run_record(record, rep);
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
        rep, independent_membership(entity, clipped, raw, size, opt.settings),
        swept_box(entity_box, clipped), tol, size, fit_err, opt.settings, record.any_from_cells(),
        "no membership test independent of the solid exists for a " + std::string(to_string(spec.entity.kind)) +
            " entity under " + std::to_string(n) + " joints: the solid cannot be checked");
    std::string why = check_result.judge(result);
    if (check_result.result_healed()) record.stages.back().healed = true;
    if (!why.empty() && chain.redo_last && check_result.rebuild_may_help()) {
      // Pruning may have left out a face that carries a strip of the boundary: the last stage
      // is built again from every candidate.
      step("the solid failed its checks (" + why + "): last stage again with every candidate");
      result = chain.redo_last(&last_cands, record.stages.back());
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
      monte_carlo_check(entity, clipped, raw, result, size, opt.settings, rep);
    }

    if (why.empty()) why = monte_carlo_disagreement(rep, tol, size, opt.settings);
    rep.status = why.empty() ? "ok" : "failed";
    rep.message = why;
    res.shape = std::make_shared<Shape>(result);
  } catch (const InputError&) {
    throw;
  } catch (const Standard_Failure& f) {
    rep.status = "failed";
    rep.message = std::string("OCCT: ") + (f.GetMessageString() ? f.GetMessageString() : "failure") + " (after: " +
                  last_step + ")";
  } catch (const ComputeError& e) {
    rep.status = "failed";
    rep.message = e.what();
  }
  write_run_record(record, rep);
  rep.seconds_total = since(t_start);
  return res;
}

}  // namespace sweep::occt
