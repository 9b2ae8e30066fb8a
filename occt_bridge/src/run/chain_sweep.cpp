// The stages of a chain, innermost joint first: the entity's own stage from its sweep boundary
// (or built directly), the later ones from the arrangement of cells (stage_sweep.hpp); points and
// curves sweep curves and surfaces. What they build goes to run_sweep, which judges it, and to
// the segments of keyframe motions, whose union is judged once.
#include <BRepBndLib.hxx>
#include <Bnd_Box.hxx>
#include <TopExp_Explorer.hxx>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>

#include "arrangement/boundary_sweep.hpp"
#include "base/internal.hpp"
#include "base/stop.hpp"
#include "run/run_steps.hpp"
#include "sweep/error.hpp"
#include "sweep/membership.hpp"
#include "sweep/orbit.hpp"
#include "verdict/solid_checks.hpp"

namespace sweep::occt {
namespace {

/// The entity's own stage (a solid) without the arrangement of cells: built directly when it is a
/// ball under a screw, else from its sweep boundary, whose pieces are classified by the entity's
/// orbit intervals (a primitive) or by trajectories against the body's faces. Null when neither
/// builds it (then the cells do). `orbit_entity`: the entity's orbit solid (null when it has none);
/// `start`: the entity's placement at the start of the stage.
TopoDS_Shape entity_stage(const StageInput& in, const OrbitSolidPtr& orbit_entity, const Eigen::Isometry3d& start,
                          const RunOptions& opt, double& fit_err, StageRecord& record, Candidates& stage_cands,
                          const std::function<void(const std::string&)>& step) {
  const ScrewJoint& j = in.j();
  const double T = in.T();
  const TopoDS_Shape direct = opt.direct_builds ? ball_screw_stage(in, fit_err, stage_cands) : TopoDS_Shape();
  if (!direct.IsNull()) {
    record.varieties += int(stage_cands.vars.size());
    record.cells += 1;
    return direct;
  }
  const PointTestMaker stage_member = orbit_entity
                                          ? orbit_membership(orbit_placed(orbit_entity, start), j, T)
                                          : trajectory_membership(in.body, in.motion, Settings::resolution * in.size);
  // A boundary that left a piece out (a sliver whose crossing with an end copy no section found)
  // does not close. Crossings traced where sweeps touch the copies (when there were any: not under
  // a helical joint) are then left to OCCT's general section; when that does not close either,
  // the arrangement of cells is made instead.
  auto boundary = [&](const Settings& settings) {
    BoundarySweep b = boundary_sweep(in.body, j, T, stage_member, in.size, in.tol, settings, in.stage, in.joint_no);
    merge_step_seconds(record.seconds, b.seconds);
    return b;
  };
  BoundarySweep b = boundary(opt.settings);
  if (b.solid.IsNull() && opt.settings.touching_sections && b.touching_sections > 0) {
    Settings general = opt.settings;
    general.touching_sections = false;
    step("stage " + std::to_string(in.stage) + ": " + b.failure + "; again with OCCT's sections where sweeps touch");
    b = boundary(general);
  }
  if (b.solid.IsNull()) {
    step("stage " + std::to_string(in.stage) + ": " + b.failure + "; built from cells instead");
    return {};
  }
  fit_err = std::max(fit_err, b.fit_error);
  for (auto& v : b.varieties) stage_cands.add_variety(std::move(v));
  for (std::size_t k = 0; k < b.candidate_faces.size(); ++k) stage_cands.add(b.candidate_ids[k], {b.candidate_faces[k]});
  record.varieties += int(stage_cands.vars.size());
  record.cells += 1;
  return b.solid;
}

/// A stage whose arrangement lacked faces left out as internal, checked (valid, or valid once
/// healed; closed; its two volumes agreeing): built again by `rebuild` from every candidate when
/// the check fails.
TopoDS_Shape checked_stage(const TopoDS_Shape& shape, double fit_err, double tol, StageRecord& record,
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
      record.healed = true;
    }
  }
  record.add_seconds("stage_checks", since(t_chk));
  if (agree) return checked;
  step("stage " + std::to_string(record.stage) + " failed its checks: again with every candidate");
  return rebuild();
}

/// The stage of one joint that the arrangement of cells builds: candidates pruned, then, for
/// every stage but a judged chain's last, checked and built again from every candidate when the
/// check fails. For the last stage of a judged chain, `redo` receives the rebuild instead.
TopoDS_Shape cells_stage(const StageInput& in, const ChainEntity& entity, std::shared_ptr<const ParametricEntity> spe,
                         bool last_judged, const RunOptions& opt, double& fit_err, StageRecord& record,
                         Candidates& stage_cands, std::function<TopoDS_Shape(Candidates*, StageRecord&)>* redo,
                         const std::function<void(const std::string&)>& step) {
  // the stage's input, copied: the rebuild may run after this function has returned
  const std::optional<Motion> sd_motion = in.sd_motion ? std::optional<Motion>(*in.sd_motion) : std::nullopt;
  auto sweep_stage = [body = in.body, dim = in.dim, motion = in.motion, sd = in.sd, spe, sd_motion, esize = in.esize,
                      size = in.size, tol = in.tol, fit_tol = in.fit_tol, stage = in.stage, joint_no = in.joint_no,
                      &fit_err, direct = opt.direct_builds](bool prune, PruneCount* pruned, Candidates* out,
                                                            StageRecord& rec) {
    StageRecord fresh;  // a rebuild starts the stage's counts again and keeps its seconds
    fresh.stage = rec.stage;
    fresh.from_cells = rec.from_cells;
    fresh.unpruned = !prune;
    fresh.seconds = rec.seconds;
    rec = fresh;
    *out = Candidates();
    StageInput again(body, dim, motion, esize, size, tol, fit_tol, stage, joint_no);
    again.sd = sd;
    again.pe = spe.get();
    again.sd_motion = sd_motion ? &*sd_motion : nullptr;
    return solid_sweep(again, fit_err, rec, out, prune, pruned, direct);
  };
  PruneCount pruned;
  TopoDS_Shape shape = sweep_stage(true, &pruned, &stage_cands, record);
  // Building the arrangement of every candidate again costs time that grows fast with their
  // number; past the settings' limit a stage that fails its checks is not rebuilt.
  const bool may_rebuild = pruned.dropped > 0 && std::size_t(pruned.candidates) <= opt.settings.rebuild_candidate_limit;
  if (!may_rebuild) return shape;
  if (last_judged) {
    *redo = [sweep_stage](Candidates* out, StageRecord& rec) { return sweep_stage(false, nullptr, out, rec); };
    return shape;
  }
  return checked_stage(shape, fit_err, entity.tol, record, step, [&sweep_stage, &stage_cands, &record]() {
    return sweep_stage(false, nullptr, &stage_cands, record);
  });
}

/// The only solid of a shape as itself (classifiers want a solid, not a compound of one).
TopoDS_Shape single_solid(const TopoDS_Shape& shape) {
  TopExp_Explorer sx(shape, TopAbs_SOLID);
  if (!sx.More()) return shape;
  const TopoDS_Shape first = sx.Current();
  sx.Next();
  return sx.More() ? shape : first;
}

}  // namespace

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

ChainSweep sweep_chain(const ChainEntity& entity, const Motion& motion, bool judged, const RunOptions& opt,
                       double& fit_err, RunRecord& record, const std::function<void(const std::string&)>& step) {
  ChainSweep out;
  out.raw = entity.raw;
  const bool parametric = entity.run.spec.kind == EntityKind::Curve || entity.run.spec.kind == EntityKind::Surface;
  // the entity's map as the stages see it (its ranges extended where a joint slides it along itself)
  std::shared_ptr<const ParametricEntity> stage_pe = entity.run.pe;
  TopoDS_Shape shape = moved(out.raw, motion.home);

  // Stages, innermost joint first: each sweeps the previous stage's set. While that set is still
  // the parametric entity (placed by G), a joint that slides it along itself only extends one of
  // its parameter ranges: the set keeps its dimension and the next joint sweeps it.
  int dim = entity.run.spec.dimension();
  const int n = int(motion.dof());
  EntitySpec current = entity.run.spec;
  Eigen::Isometry3d G = motion.home;
  bool entity_intact = parametric;
  for (int i = n - 1; i >= 0; --i) {
    step("stage " + std::to_string(n - i) + "/" + std::to_string(n) + ": joint " + std::to_string(i + 1) + " (" +
         to_string(motion.joints[i].type) + ")");
    const ScrewJoint j = motion.joints[i];
    double T = j.hi - j.lo;
    if (j.type == JointType::Revolute && T >= 2 * M_PI) T = 2 * M_PI;  // a full turn covers everything
    EntitySpec extended;
    if (entity_intact && (dim == 1 || dim == 2) && slides_along_itself(current, G, j, T, entity.size, &extended)) {
      step("joint " + std::to_string(i + 1) + " slides the entity along itself");
      const auto t_fit = Clock::now();
      current = extended;
      G = j.transform(j.lo) * G;
      out.raw = entity_shape(current, entity.fit_tol, &fit_err);
      shape = moved(out.raw, G);
      stage_pe = ParametricEntity::make(current);
      record.add_seconds("entity", since(t_fit));
      continue;
    }
    const TopoDS_Shape body = moved(shape, j.transform(j.lo));
    if (dim == 0) shape = point_sweep(body, j, T, entity.fit_tol, entity.size);
    if (dim == 1) shape = curve_sweep(body, j, T, entity.tol, entity.fit_tol, entity.size, &fit_err);
    // The sweep-boundary engine builds the entity's own stage (a solid); later stages of chains,
    // and a stage it cannot build, go through the arrangement of cells.
    bool built = dim <= 1;
    Candidates stage_cands;
    // a solid stage's record goes in first, so that a failure keeps what the stage did
    StageRecord point_or_curve_stage;
    if (dim >= 2) {
      record.stages.emplace_back();
      record.stages.back().stage = n - i;
    }
    StageRecord& stage_record = dim >= 2 ? record.stages.back() : point_or_curve_stage;
    if (!built && dim == 3 && i == n - 1 && !std::getenv("SWEEP_CELLS_ENGINE")) {
      const auto t_stage = Clock::now();
      const StageInput in(body, dim, screw_stage_motion(j, T), extent(body), entity.size, entity.tol, entity.fit_tol,
                          n - i, i + 1);
      const TopoDS_Shape solid =
          entity_stage(in, entity.run.orbit, j.transform(j.lo) * G, opt, fit_err, stage_record, stage_cands, step);
      if (!solid.IsNull()) {
        shape = solid;
        built = true;
      }
      stage_record.add_seconds("stages", since(t_stage));
    }
    if (!built) {
      Motion sd_motion;
      sd_motion.home = G;
      sd_motion.joints = {j};
      sd_motion.joints[0].hi = j.lo + T;
      const bool use_sd = entity.run.sd && i == n - 1 && dim == 3;
      // A surface entity's first stage: points are classified against its parametric map.
      const bool use_pe = stage_pe && entity_intact && dim == 2;
      StageInput in(body, dim, screw_stage_motion(j, T), extent(body), entity.size, entity.tol, entity.fit_tol, n - i,
                    i + 1);
      in.sd = use_sd ? entity.run.sd.get() : nullptr;
      in.sd_motion = &sd_motion;
      stage_record.from_cells = dim == 3;
      shape = cells_stage(in, entity, use_pe ? stage_pe : nullptr, judged && i == 0, opt, fit_err, stage_record,
                          stage_cands, &out.redo_last, step);
    }
    if (dim >= 2) {
      // a solid stage, from either engine: its candidates go to the report
      if (i == 0) {
        out.last_cands = std::move(stage_cands);
      } else if (opt.varieties) {
        stage_cands.compute_areas();
        opt.varieties->insert(opt.varieties->end(), stage_cands.vars.begin(), stage_cands.vars.end());
      }
      shape = single_solid(shape);
    }
    dim = std::min(3, dim + 1);
    entity_intact = false;
  }
  out.shape = shape;
  out.dim = dim;
  return out;
}

}  // namespace sweep::occt
