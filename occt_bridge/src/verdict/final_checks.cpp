// The membership that judges the final solid, the solid's checks and verdict, and the Monte Carlo
// volume of --verify.
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepTools.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <cmath>
#include <cstdlib>

#include "run/run_steps.hpp"
#include "verdict/solid_checks.hpp"
#include "sweep/error.hpp"
#include "sweep/orbit.hpp"
#include "verdict/verdict.hpp"

namespace sweep::occt {

IndependentMembership independent_membership(const RunEntity& run_entity, const Motion& clipped, const TopoDS_Shape& raw,
                                             double size, const Settings& settings) {
  const std::size_t n = clipped.dof();
  const EntitySpec& entity = run_entity.spec;
  const OrbitSolidPtr& orbit_entity = run_entity.orbit;
  const std::shared_ptr<const SignedDistance> sd = run_entity.sd;
  const std::shared_ptr<const ParametricEntity> pe = run_entity.pe;
  const std::size_t budget = settings.membership_budget;
  if (n == 1 && orbit_entity) {
    const ScrewJoint j = clipped.joints[0];
    const OrbitSolidPtr start = orbit_placed(orbit_entity, j.transform(j.lo) * clipped.home);
    return {always_decided(orbit_membership(start, j, j.hi - j.lo)), "orbit intervals of the entity",
            [start, j](double rel_tol, double* error) { return joint_sweep_volume(*start, j, j.hi - j.lo, rel_tol, error); }};
  }
  if (n == 1 && entity.dimension() == 3 && !sd) {
    const ScrewJoint j = clipped.joints[0];
    const TopoDS_Shape body = moved(moved(raw, clipped.home), j.transform(j.lo));
    return {always_decided(trajectory_membership(body, screw_stage_motion(j, j.hi - j.lo), Settings::resolution * size)),
            "trajectories against the entity's faces", {}};
  }
  if (n == 1 && entity.dimension() == 2 && pe) {
    // A surface under one joint: a point whose trajectory meets the surface is swept; one whose
    // trajectory misses it is asked of the search over joint and surface parameters, and is
    // swept when that finds it so (a trajectory can miss the surface where it crosses it at a
    // grazing angle), outside otherwise (the search alone leaves most points near the boundary
    // undecided).
    const ScrewJoint j = clipped.joints[0];
    const TopoDS_Shape body = moved(moved(raw, clipped.home), j.transform(j.lo));
    const PointTestMaker by_trajectory =
        trajectory_membership(body, screw_stage_motion(j, j.hi - j.lo), Settings::resolution * size, false);
    return {[by_trajectory, pe, clipped, size, budget]() -> MemberTest {
              const PointTest meets = by_trajectory();
              return [meets, pe, clipped, size, budget](const Eigen::Vector3d& x) {
                if (meets(x)) return 1;
                return swept_image_membership(*pe, clipped, x, Settings::resolution * size, size, budget, true, false) == 1
                           ? 1
                           : 0;
              };
            },
            "trajectories against the surface, the search over joint and surface parameters where they miss it", {}};
  }
  if (const std::shared_ptr<const SignedDistance> bound = run_entity.search_bound()) {
    // (a B-rep solid's bound is loose within its triangulation's deviation: points that near the
    // swept set's boundary are left undecided)
    return {[sd = bound, clipped, size, budget]() -> MemberTest {
              return [sd, clipped, size, budget](const Eigen::Vector3d& x) {
                return swept_set_membership(*sd, clipped, x, Settings::resolution * size, budget);
              };
            },
            "certified search over the joint box (signed distance)", {}};
  }
  if (pe) {
    // The second-order exclusion decides the probes of points and curves in far fewer boxes
    // (paper 4.4: 12 s to 2 s). For surfaces it decides more probes of maps that drop rank
    // everywhere (paper 4.3), each at the cost of the whole budget (7 s to 100 s): first order there.
    const bool second_order = pe->num_params() <= 1;
    return {[pe, clipped, size, budget, second_order]() -> MemberTest {
              return [pe, clipped, size, budget, second_order](const Eigen::Vector3d& x) {
                return swept_image_membership(*pe, clipped, x, Settings::resolution * size, size, budget, true, second_order);
              };
            },
            std::string("certified search over the joint and entity parameters") +
                (second_order ? " (second-order exclusion)" : ""), {}};
  }
  return {};
}

const std::string FinalChecks::invalid = "the solid is not valid (BRepCheck)";

std::string FinalChecks::judge(TopoDS_Shape& result) {
  healed_ = false;
  std::string why = (*this)(result);
  if (why == invalid) {
    const TopoDS_Shape h = healed(result);
    if (!h.IsNull()) {
      // the report now describes the healed solid, and so does the reason when it still fails
      const std::string why_healed = (*this)(h);
      if (why_healed.empty() || geometric_error()) {
        result = h;
        healed_ = true;
        why = why_healed;
      } else {
        why = why_healed + " (after OCCT's shape healing of a solid that was not valid)";
      }
    }
  }
  if (geometric_error()) {
    // A pcurve that strays from its edge (a fuse's or the healing's approximation) is projected
    // again from the edge's 3-D curve; the solid is then checked again in full.
    for (TopExp_Explorer fx(result, TopAbs_FACE); fx.More(); fx.Next())
      tighten_pcurves(TopoDS::Face(fx.Current()), 0.5 * tol_);
    why = (*this)(result);
  }
  return why;
}

FinalChecks::FinalChecks(Report& rep, IndependentMembership independent, const Eigen::AlignedBox3d& true_box,
                         double tol, double size, const double& fit_err, const Settings& settings, bool cells_built,
                         std::string no_test)
    : rep_(rep),
      independent_(std::move(independent)),
      true_box_(true_box),
      tol_(tol),
      size_(size),
      fit_err_(fit_err),
      settings_(settings),
      cells_built_(cells_built),
      no_test_(std::move(no_test)) {
  rep_.verdict_membership = independent_.name;
}

std::string FinalChecks::operator()(const TopoDS_Shape& solid) {
  rebuild_may_help_ = true;
  geometric_error_ = false;
  const auto t_val = Clock::now();
  const SolidChecks checks = check_solid(solid);
  Report& rep = rep_;
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
  const int solids = separate_parts(parts, tol_);
  set_centroid_and_box(rep, checks.centroid, checks.box);
  rep.tol_achieved = std::max(fit_err_, measured_geometric_error(solid));
  if (const char* dir = std::getenv("SWEEP_DUMP_BOUNDARY"))  // diagnostics: the solid checked last
    BRepTools::Write(solid, (std::string(dir) + "/checked.brep").c_str());
  rep.seconds["validation"] = rep.seconds.value("validation", 0.0) + since(t_val);

  const double size = size_;
  if (!rep.valid) return invalid;
  if (!rep.closed) return "the solid is not closed";
  if (rep.volume_brep <= 0) return "the solid has no volume";
  if (solids > 1)
    return "the result has " + std::to_string(solids) +
           " separate solids (that do not touch), where a connected entity under a continuous motion sweeps one "
           "connected set";
  if (rep.tol_achieved > tol_) {
    rebuild_may_help_ = false;
    geometric_error_ = true;
    return "the geometric error of the solid (" + std::to_string(rep.tol_achieved) +
           ", its largest fitting error or gap between its curves, surfaces and vertices) exceeds the requested "
           "tolerance (" +
           std::to_string(tol_) + ")";
  }
  if (std::abs(rep.volume_brep - rep.volume_divergence) >
      tol_ * size * size + settings_.volume_relative_band * size * size * size)
    return "B-rep and divergence volumes disagree (" + std::to_string(rep.volume_brep) + " vs " +
           std::to_string(rep.volume_divergence) + ")";
  // The verdict, for a solid that passed every check above (one that failed is not judged again:
  // healing and rebuilding may check more than once).
  return verdict(solid);
}

std::string FinalChecks::verdict(const TopoDS_Shape& solid) {
  Report& rep = rep_;
  const auto t_verdict = Clock::now();
  if (!independent_.test) {
    rep.has_verdict = false;
    rebuild_may_help_ = false;
    return no_test_;
  }
  const VerdictResult v = judge_solid(solid, true_box_, independent_.test, tol_, size_, settings_);
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
  if (!v.decided()) {
    rebuild_may_help_ = false;
    return "the independent membership test could not decide " + std::to_string(v.undecided) + " of " +
           std::to_string(v.samples) + " samples within its budget: the solid cannot be checked";
  }
  if (!v.ok())
    return "the solid disagrees with the independent membership test at " +
           std::to_string(v.mismatches + v.probe_mismatches) + " of " + std::to_string(v.samples + 2 * v.probes) +
           " points; " + v.first_mismatch;
  return independent_volume_check();
}

std::string FinalChecks::independent_volume_check() {
  // Sampling bounds the volume of a wrong region only coarsely (to the box's volume times the share
  // of samples near the boundary). A stage built from the arrangement of cells (after its sweep
  // boundary did not close) is held to the independent volume as well: a solid whose faces all lie
  // within the tolerance of the true boundary has a volume within the tolerance times its area.
  Report& rep = rep_;
  if (!independent_.volume || !cells_built_ || settings_.independent_volume_rel_tol <= 0) return "";
  const auto t_vol = Clock::now();
  double error = 0;
  const double v = independent_.volume(settings_.independent_volume_rel_tol, &error);
  rep.seconds["independent_volume"] = rep.seconds.value("independent_volume", 0.0) + since(t_vol);
  rep.has_independent_volume = true;
  rep.volume_independent = v;
  rep.volume_independent_error = error;
  const double band = 3 * error + tol_ * rep.area + settings_.volume_relative_band * size_ * size_ * size_;
  if (std::abs(rep.volume_brep - v) > band) {
    rebuild_may_help_ = false;
    return "the solid's volume (" + std::to_string(rep.volume_brep) +
           ") disagrees with the volume integrated over the orbits without it (" + std::to_string(v) + " +- " +
           std::to_string(error) + ") by more than the tolerance times the area";
  }
  return "";
}

void monte_carlo_check(const RunEntity& run_entity, const Motion& clipped, const TopoDS_Shape& raw,
                       const TopoDS_Shape& result, double size, const Settings& settings, Report& rep) {
  const EntitySpec& entity = run_entity.spec;
  const SignedDistance* sd = run_entity.sd.get();
  const ParametricEntity* pe = run_entity.pe.get();
  const auto t_mc = Clock::now();
  Eigen::AlignedBox3d box(Eigen::Vector3d(rep.bbox_min[0], rep.bbox_min[1], rep.bbox_min[2]),
                          Eigen::Vector3d(rep.bbox_max[0], rep.bbox_max[1], rep.bbox_max[2]));
  box.extend(box.min() - Eigen::Vector3d::Constant(0.01 * size));
  box.extend(box.max() + Eigen::Vector3d::Constant(0.01 * size));
  MonteCarloResult mc;
  // the membership searches run over the clipped motion of the verdict
  const Motion& m = clipped;
  const std::size_t n = clipped.dof();
  const std::size_t chain_samples = std::max<std::size_t>(settings.mc_samples / 8, 20000);
  if (sd) {
    mc = monte_carlo_volume([&](const Eigen::Vector3d& x) { return in_swept_set(*sd, m, x, Settings::resolution * size); }, box,
                            n == 1 ? settings.mc_samples : chain_samples, settings.seed);
  } else if (n == 1) {
    const ScrewJoint& j = clipped.joints[0];
    const double T = j.hi - j.lo;
    TopoDS_Shape body = moved(moved(raw, clipped.home), j.transform(j.lo));
    TrajectoryMembership by_trajectory(body, rep.dimension == 3 && entity.dimension() == 3, *screw_stage_motion(j, T),
                                       Settings::resolution * size);
    mc = monte_carlo_volume([&](const Eigen::Vector3d& x) { return by_trajectory(x); }, box,
                            std::min<std::size_t>(settings.mc_samples, 20000), settings.seed);
  } else if (const auto bound = n > 1 && !pe ? run_entity.search_bound() : nullptr) {
    // a B-rep solid's bound: the points it leaves undecided (within its slack of the boundary)
    // count as out, far below the estimate's own error
    const auto in_set = [&](const Eigen::Vector3d& x) {
      return in_swept_set(*bound, m, x, Settings::resolution * size);
    };
    mc = monte_carlo_volume(in_set, box, chain_samples, settings.seed);
  } else if (pe) {
    // Here the independent membership is a search over the joint and entity parameters, far
    // slower than classifying a point against the solid: each sample is classified against the
    // solid too, and where the two disagree one of them is wrong.
    BRepClass3d_SolidClassifier in_result(result);
    const auto in_solid = [&](const Eigen::Vector3d& x) {
      in_result.Perform(to_pnt(x), Settings::resolution * size);
      return in_result.State() == TopAbs_IN;
    };
    mc = monte_carlo_volume([&](const Eigen::Vector3d& x) { return in_swept_image(*pe, m, x, Settings::resolution * size, size); },
                            box, chain_samples, settings.seed, in_solid);
    rep.mc_compared = true;
  } else {
    throw ComputeError("--verify needs a solid, a point, a curve or a surface entity for motions of several joints");
  }
  rep.has_mc = true;
  rep.volume_mc = mc.volume;
  rep.volume_mc_stderr = mc.stderr_;
  rep.mc_samples = mc.samples;
  rep.mc_mismatches = mc.mismatches;
  rep.volume_mc_mismatch = mc.mismatch_volume;
  rep.seconds["monte_carlo"] = since(t_mc);
}

}  // namespace sweep::occt
