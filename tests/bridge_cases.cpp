// Every spec with an `_expected_volume` (shared cases and examples) is computed and checked:
// status ok, valid, closed, volume within `_rel_tol` (default 1e-6) of the expected value, and the
// STEP file written reads back to the same volume.
#include <BRepClass3d_SolidClassifier.hxx>
#include <catch2/catch.hpp>

#include <cstdio>
#include <filesystem>

#include "base/internal.hpp"
#include "occt_bridge/sweeper.hpp"
#include "sweep/error.hpp"
#include "sweep/membership.hpp"
#include "sweep/spec.hpp"
#include "util/cases.hpp"
#include "util/random_one_joint.hpp"

namespace {

/// An example run with --verify at `mc_samples` samples (runs of several joints use an eighth).
sweep::occt::RunResult run_verified(const std::string& example, std::size_t mc_samples) {
  sweep::occt::RunOptions opt;
  opt.verify = true;
  opt.settings.mc_samples = mc_samples;
  return sweep::occt::run_sweep(sweep::load_spec(SWEEP_SOURCE_DIR "/examples/" + example), opt);
}

/// Monte Carlo membership in the image of the spec's chain (in_swept_image, a branch and bound
/// over (q, s) that shares nothing with the B-rep) at `samples` points of the solid's box (1 %
/// larger), each also classified against the solid of `r`: the mismatches bound the volume of
/// the symmetric difference between the two, not just the difference of volumes.
sweep::MonteCarloResult against_image(const sweep::Spec& spec, const sweep::occt::RunResult& r, std::size_t samples,
                                      std::uint64_t seed) {
  const auto pe = sweep::ParametricEntity::make(spec.entity);
  REQUIRE(pe);
  Eigen::AlignedBox3d box(Eigen::Vector3d(r.report.bbox_min[0], r.report.bbox_min[1], r.report.bbox_min[2]),
                          Eigen::Vector3d(r.report.bbox_max[0], r.report.bbox_max[1], r.report.bbox_max[2]));
  const double size = box.sizes().maxCoeff();
  box.extend(box.min() - Eigen::Vector3d::Constant(0.01 * size));
  box.extend(box.max() + Eigen::Vector3d::Constant(0.01 * size));
  BRepClass3d_SolidClassifier in_result(r.shape->shape);
  return sweep::monte_carlo_volume(
      [&](const Eigen::Vector3d& x) { return sweep::in_swept_image(*pe, spec.motion.motion, x, 1e-9 * size, size); },
      box, samples, seed,
      [&](const Eigen::Vector3d& x) {
        in_result.Perform(gp_Pnt(x.x(), x.y(), x.z()), 1e-9 * size);
        return in_result.State() == TopAbs_IN;
      });
}

/// Runs an example of a chain and checks it: ok, valid, closed, the two integrals agreeing (to
/// `integrals_rel`), the
/// volume within 3 standard errors of the Monte Carlo volume of its note, and 1200 samples of
/// membership in the chain's image (against_image) that all agree with the solid. A region
/// missing from the solid or added to it of 1 % of its volume (0.4 % of the box or more) would
/// show at some sample with probability 1 - (1 - 0.004)^1200 > 99 %.
sweep::occt::RunResult check_chain_against_image(const std::string& example, double mc_volume, double mc_stderr,
                                                 std::uint64_t seed, double integrals_rel = 1e-6) {
  const sweep::Spec spec = sweep::load_spec(SWEEP_SOURCE_DIR "/examples/" + example);
  auto r = sweep::occt::run_sweep(spec);
  CAPTURE(example, r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(r.report.valid);
  CHECK(r.report.closed);
  CHECK(std::abs(r.report.volume_brep - mc_volume) < 3 * mc_stderr);
  CHECK(r.report.volume_divergence == Approx(r.report.volume_brep).epsilon(integrals_rel));
  const auto mc = against_image(spec, r, 1200, seed);
  CAPTURE(mc.volume, mc.stderr_, mc.mismatches);
  CHECK(mc.mismatches == 0);
  CHECK(std::abs(mc.volume - r.report.volume_brep) < 4.5 * mc.stderr_);
  return r;
}

void check_case(const std::string& path, const sweep::occt::RunOptions& opt = {}) {
  CAPTURE(path, opt.direct_builds);
  sweep::Spec spec = sweep::load_spec(path);
  REQUIRE(spec.json.contains("_expected_volume"));
  const double expected = spec.json["_expected_volume"].get<double>();
  const double rel = spec.json.value("_rel_tol", 1e-6);
  auto r = sweep::occt::run_sweep(spec, opt);
  CAPTURE(r.report.to_json().dump());
  CHECK(r.report.status == "ok");
  CHECK(r.report.valid);
  CHECK(r.report.closed);
  CHECK(r.report.volume_brep == Approx(expected).epsilon(rel));
  CHECK(r.report.volume_divergence == Approx(expected).epsilon(rel));
  if (r.report.ok()) {  // the STEP file written reads back to the same volume
    const std::string out = std::string(SWEEP_BINARY_DIR) + "/case_" +
                            std::filesystem::path(path).stem().string() + ".step";
    sweep::occt::write_shape(*r.shape, out, 1e-3);
    CHECK(sweep::occt::file_volume(out) == Approx(r.report.volume_brep).epsilon(1e-6));
  }
}

}  // namespace

TEST_CASE("Cases: every shared case reproduces its expected volume") {
  // The shared folder beside the checkout when present (it is the contract checked from
  // outside), else the copy kept in examples/cases.
  auto files = sweep_test::json_files(SWEEP_SHARED_DIR "/cases");
  if (files.empty()) files = sweep_test::json_files(SWEEP_SOURCE_DIR "/examples/cases");
  REQUIRE_FALSE(files.empty());
  for (const auto& f : files) SECTION(f) { check_case(f); }
}

TEST_CASE("Examples: every example with an expected volume reproduces it") {
  auto files = sweep_test::json_files(SWEEP_SOURCE_DIR "/examples");
  for (const auto& f : sweep_test::json_files(SWEEP_SOURCE_DIR "/examples/motions")) files.push_back(f);
  for (const auto& f : sweep_test::json_files(SWEEP_SOURCE_DIR "/examples/chains"))
    if (f.find("sphere_four_prismatic") == std::string::npos) files.push_back(f);  // no closed form: see below
  REQUIRE_FALSE(files.empty());
  for (const auto& f : files) {
    if (f.find("brep_box_hole") != std::string::npos) continue;  // needs its STEP file: see below
    SECTION(f) { check_case(f); }
  }
}

TEST_CASE("Cases and examples of one joint: the general pipeline on its own (direct builds off)") {
  auto files = sweep_test::json_files(SWEEP_SHARED_DIR "/cases");
  if (files.empty()) files = sweep_test::json_files(SWEEP_SOURCE_DIR "/examples/cases");
  for (const auto& f : sweep_test::json_files(SWEEP_SOURCE_DIR "/examples")) files.push_back(f);
  sweep::occt::RunOptions general;
  general.direct_builds = false;
  int single = 0;
  for (const auto& f : files) {
    if (f.find("brep_box_hole") != std::string::npos) continue;  // needs its STEP file
    if (sweep::load_spec(f).motion.motion.dof() != 1) continue;
    ++single;
    SECTION(f) { check_case(f, general); }
  }
  CHECK(single >= 10);
}

TEST_CASE("Sweep: STEP written and read back keeps the volume, runs are identical") {
  sweep::Spec spec = sweep::load_spec(SWEEP_SOURCE_DIR "/examples/sphere_extrude.json");
  auto a = sweep::occt::run_sweep(spec);
  auto b = sweep::occt::run_sweep(spec);
  REQUIRE(a.report.ok());
  CHECK(a.report.volume_brep == b.report.volume_brep);  // deterministic, bit for bit
  CHECK(a.report.volume_divergence == b.report.volume_divergence);
  const std::string out = SWEEP_BINARY_DIR "/roundtrip_capsule.step";
  sweep::occt::write_shape(*a.shape, out, 1e-3);
  CHECK(sweep::occt::file_volume(out) == Approx(a.report.volume_brep).epsilon(1e-6));
}

TEST_CASE("Sweep: volume converges as the tolerance tightens (helical sweep)") {
  sweep::Spec spec = sweep::load_spec(SWEEP_SOURCE_DIR "/examples/sphere_spring.json");
  const double exact = spec.json["_expected_volume"].get<double>();
  double prev_err = 1e300;
  for (double tol : {1e-3, 1e-5, 1e-7}) {
    spec.tolerance = tol;
    auto r = sweep::occt::run_sweep(spec);
    CAPTURE(tol, r.report.to_json().dump());
    REQUIRE(r.report.ok());
    const double err = std::abs(r.report.volume_brep - exact) / exact;
    CHECK(err <= prev_err * 1.01 + 1e-9);
    // a surface within tol of the true boundary explains a volume error of at most tol * area
    CHECK(std::abs(r.report.volume_brep - exact) <= tol * r.report.area);
    CHECK(r.report.tol_achieved > 0);
    prev_err = err;
  }
  CHECK(prev_err < 1e-6);
}

TEST_CASE("Sweep: Monte Carlo membership agrees with the B-rep volume (--verify)") {
  auto r = run_verified("box_revolve_90.json", 100000);
  REQUIRE(r.report.ok());
  REQUIRE(r.report.has_mc);
  CHECK(r.report.volume_mc_stderr > 0);
  CHECK(std::abs(r.report.volume_mc - r.report.volume_brep) < 4.5 * r.report.volume_mc_stderr);
}

TEST_CASE("Sweep: overlapping screw turns agree with Monte Carlo membership") {
  auto r = run_verified("sphere_spring_overlap.json", 60000);
  CAPTURE(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(std::abs(r.report.volume_mc - r.report.volume_brep) < 4.5 * r.report.volume_mc_stderr);
  // the tube formula (no overlap) would give pi L + 4/3 pi = 201.93: the overlap is resolved
  CHECK(r.report.volume_brep < 190.0);
}

TEST_CASE("Sweep: overlapping screw turns at other distances, pitches and turns, against slice integrals") {
  // The example's spec with the ball's centre distance, the pitch and the range changed; the
  // references are `scripts/reference_volume_overlap.py 20000 --distance=D --pitch=P --turns=N`
  // (slice integration, estimated relative errors 1.4e-9 and 1.3e-8; its Monte Carlo agreed).
  struct Variant {
    double distance, pitch, turns, reference;
  };
  for (const Variant& c : {Variant{3.5, 1.3, 2.75, 164.93379117526942}, Variant{4, 1.8, 2, 159.34163695729956}}) {
    CAPTURE(c.distance, c.pitch, c.turns);
    const sweep::Spec spec = sweep::load_spec(SWEEP_SOURCE_DIR "/examples/sphere_spring_overlap.json",
                                              {"/entity/center/0=" + std::to_string(c.distance),
                                               "/motion/pitch=" + std::to_string(c.pitch),
                                               "/motion/range/1=" + std::to_string(360 * c.turns)});
    auto r = sweep::occt::run_sweep(spec);
    CAPTURE(r.report.to_json().dump());
    REQUIRE(r.report.ok());
    CHECK(r.report.valid);
    CHECK(r.report.closed);
    CHECK(r.report.faces == 6);  // the trimmed tube and half balls, not the general arrangement
    CHECK(r.report.volume_brep == Approx(c.reference).epsilon(1e-7));
    CHECK(r.report.volume_divergence == Approx(c.reference).epsilon(1e-7));
  }
}

TEST_CASE("Varieties: the last stage's contributions add up to the divergence volume") {
  for (const char* name : {"/examples/box_revolve_90.json", "/examples/sphere_extrude.json",
                           "/examples/chains/box_revolve_extrude.json", "/examples/cylinder_flip.json"}) {
    CAPTURE(name);
    sweep::Spec spec = sweep::load_spec(std::string(SWEEP_SOURCE_DIR) + name);
    sweep::occt::RunOptions opt;
    std::vector<sweep::occt::Variety> vars;
    std::shared_ptr<const sweep::occt::Shape> faces;
    opt.varieties = &vars;
    opt.variety_faces = &faces;
    auto r = sweep::occt::run_sweep(spec, opt);
    REQUIRE(r.report.ok());
    REQUIRE(faces);
    double sum = 0, area = 0;
    int limits = 0;
    for (const auto& v : vars) {
      CHECK((v.type == "limit" || v.type == "boundary" || v.type == "interior"));
      if (v.type == "limit") {
        ++limits;
        CHECK(v.fixed.size() == 1);  // the joint variable, at a range end
      }
      if (v.final_stage) {
        sum += v.volume;
        area += v.boundary_area;
      }
    }
    CHECK(limits >= 1);
    CHECK(sum == Approx(r.report.volume_divergence).epsilon(1e-9));
    CHECK(area == Approx(r.report.area).epsilon(1e-6));
  }
}

TEST_CASE("Design variation: overriding a DH link length and a joint range recomputes the solid") {
  const std::string path = SWEEP_SOURCE_DIR "/examples/chains/dh_point_two_revolutes_extrude.json";
  const std::string text = sweep_test::read_text(path);
  // as written: link 2 of length 2 turned a quarter turn around a unit circle, stroke 2
  auto base = sweep::occt::run_sweep(sweep::parse_spec(text, SWEEP_SOURCE_DIR "/examples/chains"));
  REQUIRE(base.report.ok());
  CHECK(base.report.volume_brep == Approx(2 * 3 * M_PI).epsilon(1e-9));
  // link 2 of length 3 (annulus sector 2..4 over a quarter turn, 3 pi, plus a disk, pi), stroke 3
  auto varied = sweep::occt::run_sweep(sweep::parse_spec(text, SWEEP_SOURCE_DIR "/examples/chains",
                                                         {"/motion/joints/1/a=3", "/motion/joints/0/range=[0,3]"}));
  REQUIRE(varied.report.ok());
  CHECK(varied.report.volume_brep == Approx(3 * 4 * M_PI).epsilon(1e-9));
  // a half turn of link 2 instead: annulus sector 1..3 over a half turn (4 pi) plus a disk (pi), stroke 2
  auto half = sweep::occt::run_sweep(
      sweep::parse_spec(text, SWEEP_SOURCE_DIR "/examples/chains", {"/motion/joints/1/range=[0,180]"}));
  REQUIRE(half.report.ok());
  CHECK(half.report.volume_brep == Approx(2 * 5 * M_PI).epsilon(1e-9));
}

TEST_CASE("Paper 4.4: a point swept by three revolute joints, against an independent integral") {
  const std::string path = SWEEP_SOURCE_DIR "/examples/paper/sec4_4_point_three_revolutes.json";
  sweep::Spec spec = sweep::load_spec(path);
  const double expected = spec.json["_expected_volume"].get<double>();
  auto r = sweep::occt::run_sweep(spec);
  CAPTURE(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(r.report.closed);
  CHECK(r.report.volume_brep == Approx(expected).epsilon(1e-7));
  CHECK(r.report.volume_divergence == Approx(expected).epsilon(1e-7));
  // BREP keeps it; STEP either reads back to the same volume or is refused, never written wrong
  const std::string brep = SWEEP_BINARY_DIR "/sec4_4.brep", step = SWEEP_BINARY_DIR "/sec4_4.step";
  sweep::occt::write_shape(*r.shape, brep, 1e-3);
  CHECK(sweep::occt::file_volume(brep) == Approx(expected).epsilon(1e-7));
  std::remove(step.c_str());
  try {
    sweep::occt::write_shape(*r.shape, step, 1e-3);
    CHECK(sweep::occt::file_volume(step) == Approx(expected).epsilon(1e-6));
  } catch (const sweep::ComputeError& e) {
    CHECK(std::string(e.what()).find("does not read back") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(step));
  }
  // the other ranges of joint 1, against the same integral
  const std::string text = sweep_test::read_text(path);
  const std::pair<const char*, double> ranges[] = {
      {"[0,90]", 3908.899464373913}, {"[0,180]", 7817.798928747826}, {"[0,360]", 11416.467863740885}};
  for (const auto& [range, volume] : ranges) {
    CAPTURE(range);
    auto v = sweep::occt::run_sweep(
        sweep::parse_spec(text, SWEEP_SOURCE_DIR "/examples/paper", {std::string("/motion/joints/0/range=") + range}));
    REQUIRE(v.report.ok());
    CHECK(v.report.volume_brep == Approx(volume).epsilon(1e-7));
  }
}

TEST_CASE("Chains: --verify classifies every sample against the solid as well") {
  // a point swept by two revolutes with parallel axes and extruded: 6 pi; the membership is the
  // search over the chain's image, and the report gives the symmetric difference it sees
  auto r = run_verified("chains/point_two_revolutes_extrude.json", 160000);  // 20000 samples
  CAPTURE(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  const auto j = r.report.to_json();
  REQUIRE(j["volume"].contains("monte_carlo_mismatch"));
  CHECK(j["volume"]["monte_carlo_samples"].get<std::size_t>() == 20000);
  CHECK(r.report.mc_mismatches == 0);
  CHECK(j["volume"]["monte_carlo_mismatch"].get<double>() == 0.0);
  CHECK(std::abs(r.report.volume_mc - 6 * M_PI) < 4.5 * r.report.volume_mc_stderr);
}

TEST_CASE("Chains: a sphere moved by four prismatic joints agrees with Monte Carlo membership") {
  // No closed form at hand: the certified membership test (branch and bound over the four joint
  // values with the sphere's signed distance) is the independent reference.
  auto r = run_verified("chains/sphere_four_prismatic.json", 160000);  // 20000 samples
  CAPTURE(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(r.report.closed);
  CHECK(std::abs(r.report.volume_mc - r.report.volume_brep) < 4.5 * r.report.volume_mc_stderr);
  CHECK(r.report.volume_divergence == Approx(r.report.volume_brep).epsilon(1e-9));
}

namespace {
/// Section 4.3's solid: a 270-degree arc of radius 5 (its missing quarter the one at angles 90-180
/// degrees about the centre) swept by a translation of length L across the axis (along -y) and
/// extruded to height H along the axis. A line x = const meets the swept section in [y - L, y] for
/// each arc point y on it: on the left half one point (length L), on the right half two points
/// 2 s apart (s = sqrt(25 - x^2)), length min(2 L, L + 2 s).
double sec4_3_volume(double L, double H) {
  auto F = [](double x) { return 0.5 * (x * std::sqrt(25 - x * x) + 25 * std::asin(x / 5)); };  // int sqrt(25 - x^2)
  const double xs = L < 10 ? std::sqrt(25 - L * L / 4) : 0.0;  // where 2 s = L
  const double right = 2 * L * xs + L * (5 - xs) + 2 * (F(5) - F(xs));
  return H * (5 * L + right);
}
}  // namespace

TEST_CASE("Paper 4.3: a patch slid along itself by its revolve, extruded, with limits and a DH offset varied") {
  const std::string path = SWEEP_SOURCE_DIR "/examples/paper/sec4_3_surface_revolve_two_extrusions.json";
  auto base = sweep::occt::run_sweep(sweep::load_spec(path));
  INFO(base.report.to_json().dump());
  REQUIRE(base.report.ok());
  CHECK(base.report.valid);
  CHECK(base.report.closed);
  // the example's own reference is the same closed form: 15 (92 + 12.5 pi - 25 asin 0.6)
  CHECK(base.report.volume_brep == Approx(sec4_3_volume(8, 15)).epsilon(1e-8));
  // design variation: the translation across over [0, 3], the one along the axis over [0, 4], and
  // joint 1's DH offset d from q + 10 to q + 4 (which only moves the solid 6 down)
  auto varied = sweep::occt::run_sweep(sweep::load_spec(
      path, {"/motion/joints/1/range=[0, 3]", "/motion/joints/0/range=[0, 4]", "/motion/joints/0/d=\"q+4\""}));
  INFO(varied.report.to_json().dump());
  REQUIRE(varied.report.ok());
  CHECK(varied.report.volume_brep == Approx(sec4_3_volume(3, 9)).epsilon(1e-8));
  // along the axis (z): the offset moves the bottom 6 down, the shorter stroke brings the top 6 more
  CHECK(varied.report.bbox_min[2] == Approx(base.report.bbox_min[2] - 6).margin(1e-6));
  CHECK(varied.report.bbox_max[2] == Approx(base.report.bbox_max[2] - 12).margin(1e-6));
}

TEST_CASE("Paper 4.6: a hemispherical shell extruded and turned about two axes, against an independent integral") {
  // References from scripts/reference_volume_sec4_6.py (a one-dimensional integral over the
  // distance from the point where the two revolute axes meet): the example, joint 2 over [0, 180]
  // degrees (the shell's axis then spans 90 degrees from joint 1's axis instead of 135), and the
  // prismatic stroke 3 instead of 5.
  const std::string path = SWEEP_SOURCE_DIR "/examples/paper/sec4_6_hemisphere_two_revolutes_prismatic.json";
  const std::string text = sweep_test::read_text(path);
  const std::pair<const char*, double> variants[] = {{"", 44980.50839593475},
                                                     {"/motion/joints/1/range=[0,180]", 29662.394592227007},
                                                     {"/motion/joints/2/range=[0,3]", 31709.37977535475}};
  for (const auto& [set, volume] : variants) {
    CAPTURE(set);
    std::vector<std::string> sets;
    if (*set) sets.push_back(set);
    auto r = sweep::occt::run_sweep(sweep::parse_spec(text, SWEEP_SOURCE_DIR "/examples/paper", sets));
    CAPTURE(r.report.to_json().dump());
    REQUIRE(r.report.ok());
    CHECK(r.report.valid);
    CHECK(r.report.closed);
    CHECK(r.report.volume_brep == Approx(volume).epsilon(1e-7));
    CHECK(r.report.volume_divergence == Approx(volume).epsilon(1e-7));
  }
}

TEST_CASE("Paper 4.1: a circular arc revolved about three axes, point by point against independent membership") {
  // The last stage's arrangement leaves shells OCCT cannot orient; the solid is then built from the
  // split faces that separate the swept set from its complement. Checked against the Monte Carlo
  // volume of the example's note (40000 samples), 36734.5 +- 265.7.
  check_chain_against_image("paper/sec4_1_curve_three_revolutes.json", 36734.5, 265.7, 4101);
}

TEST_CASE("Paper 4.2, joints 2 and 3: a stage whose pruned arrangement fails its checks is built again from every candidate") {
  // Sampling finds 25 of the 72 candidate faces inside the swept set, one of them wrongly (a thin
  // strip of it is on the boundary): OCCT's arrangement of the rest builds a wrong cell, whose
  // B-rep and divergence volumes disagree. The stage is then built from all 72. Checked against
  // the Monte Carlo volume of the example's note, 27020 +- 335. The wrong cell differed from the
  // set by about 2300 (8 % of the volume, 1 % of the box): 1200 samples would show it with
  // probability above 99.99 %.
  const auto r = check_chain_against_image("paper/sec4_2_joints_2_3.json", 27020.3, 335.3, 4201);
  CHECK(r.report.unpruned_stages == std::vector<int>{2});
}

TEST_CASE("Paper 4.2: a third stage of 390 candidates is not rebuilt from all of them, and its solid is not called right "
          "beyond what its checks show") {
  // Rebuilding the third stage from all 390 candidates takes about 20 minutes (past the settings'
  // rebuild_candidate_limit): whatever the final checks say, the run ends without it. Its volume
  // stays within 3 standard errors of the Monte Carlo volume of the example's note (207660 +- 1963).
  const sweep::Spec spec = sweep::load_spec(SWEEP_SOURCE_DIR "/examples/paper/sec4_2_curve_three_skew_revolutes.json");
  const auto r = sweep::occt::run_sweep(spec);
  CAPTURE(r.report.to_json().dump());
  CHECK(r.report.unpruned_stages == std::vector<int>{2});
  CHECK(std::abs(r.report.volume_brep - 207660.0) < 3 * 1963.0);
  if (r.report.ok()) {
    CHECK(r.report.volume_divergence == Approx(r.report.volume_brep).epsilon(1e-6));
    CHECK(r.report.verdict_mismatches == 0);
  } else {
    CHECK(!r.report.message.empty());
  }
}

TEST_CASE("Paper 4.2: a curve swept by three skew revolute joints, point by point against independent membership",
          "[bench]") {
  // The third stage's arrangement of the pruned candidates builds no cell, and its boundary pieces
  // leave free edges on candidates that pruning dropped: those are restored, the arrangement then
  // builds 13 cells, and their union, invalid for OCCT (a self-intersecting wire), is healed by
  // ShapeFix and checked like any solid. Checked against the Monte Carlo volume of the example's
  // note, 207660 +- 1963. Not in CI: at the default tolerance (9.8e-5) the healed solid's B-rep
  // and divergence volumes differ by 2.4 (1.2e-5 of the volume), beyond the band the tolerance
  // allows (0.94), so the run reports failed in about 75 s; this test shows when it passes.
  const auto r =
      check_chain_against_image("paper/sec4_2_curve_three_skew_revolutes.json", 207660.0, 1963.0, 4202);
  CHECK(r.report.unpruned_stages == std::vector<int>{2});
  CHECK(r.report.healed_stages == std::vector<int>{3});
  REQUIRE(r.report.restored_candidates.size() == 1);
  CHECK(r.report.restored_candidates[0].first == 3);
}

TEST_CASE("Chains: two revolutes about parallel or shared axes including full turns") {
  // A box [2, 3] x [0, 1] x [0, 1] under two revolutes about z, through (0, 0) and (1, 0) or both
  // through the origin. Parallel, full turns: the inner one sweeps the annulus about (1, 0) with
  // radii 1 and sqrt 5, the outer one the disk of radius 1 + sqrt 5. Shared axis: one revolute
  // over the summed range (6 pi once it reaches a full turn).
  auto spec = [](double inner_x, double range) {
    char text[600];
    std::snprintf(text, sizeof text,
                  R"({"sweep": 1, "angles": "deg", "entity": {"kind": "box", "min": [2, 0, 0], "max": [3, 1, 1]},
                     "motion": {"kind": "axes", "joints": [
                       {"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, %g]},
                       {"type": "revolute", "point": [%g, 0, 0], "direction": [0, 0, 1], "range": [0, %g]}]}})",
                  range, inner_x, range);
    return sweep::parse_spec(text, ".");
  };
  // the box turned 120 degrees about z: the orbit-space integral, independent of the engine
  const sweep::Spec single = sweep::parse_spec(
      R"({"sweep": 1, "angles": "deg", "entity": {"kind": "box", "min": [2, 0, 0], "max": [3, 1, 1]},
          "motion": {"kind": "axes", "joints": [{"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, 120]}]}})",
      ".");
  double ref_err = 0;
  const double turned_120 = sweep::testing::reference_volume(single, 1e-10, &ref_err);
  const struct {
    double inner_x, range, volume;
  } cases[] = {{1, 360, M_PI * (1 + std::sqrt(5.0)) * (1 + std::sqrt(5.0))}, {0, 200, 6 * M_PI}, {0, 60, turned_120}};
  for (const auto& c : cases) {
    CAPTURE(c.inner_x, c.range);
    const auto r = sweep::occt::run_sweep(spec(c.inner_x, c.range));
    CAPTURE(r.report.to_json().dump());
    REQUIRE(r.report.ok());
    CHECK(r.report.volume_brep == Approx(c.volume).epsilon(1e-7));
  }
}
