// The randomized differential test: seeded one-joint sweeps of primitives (tests/util/
// random_one_joint.hpp) and of machined parts read from STEP (tests/util/random_parts.hpp) against
// a volume integrated over orbit space, which never looks at the engine's solid. CI runs the cases of tests/data/random_one_joint.tsv, whose references were
// computed once (bench/random_cases --table); the bench label runs more, each reference computed
// in process.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <functional>
#include <sstream>

#include "occt_bridge/sweeper.hpp"
#include "util/random_one_joint.hpp"
#include "util/random_parts.hpp"

using namespace sweep;

namespace {

enum class Outcome { Right, Imprecise, WrongOk, Failed };

/// Counts of a run of random cases.
struct Outcomes {
  int right = 0, imprecise = 0, wrong_ok = 0, failed = 0;
  void add(Outcome o) {
    (o == Outcome::Right ? right : o == Outcome::Imprecise ? imprecise : o == Outcome::WrongOk ? wrong_ok : failed)++;
  }
  int total() const { return right + imprecise + wrong_ok + failed; }
};

/// What a run reports: status, volume, seconds, message.
struct RunOutcome {
  bool ok = false;
  std::string status, message;
  double volume = 0, seconds = 0;
};

/// Case `c` run in this process, without a limit.
RunOutcome run_in_process(const testing::RandomCase& c) {
  const occt::RunResult r = occt::run_sweep(parse_spec(c.spec, "."));
  return {r.report.ok(), r.report.status, r.report.message, r.report.volume_brep, r.report.seconds_total};
}

/// Case `c` run by the command line with `--time-limit` (its worker process ends the run on time
/// also inside OCCT steps that never poll): the report it writes, or failed with the exit code.
RunOutcome run_by_cli(const testing::RandomCase& c, double time_limit) {
  const std::string dir = std::string(SWEEP_BINARY_DIR) + "/random_ci";
  std::filesystem::create_directories(dir);
  const std::string spec = dir + "/" + c.name + ".json", report = dir + "/" + c.name + ".report.json";
  std::ofstream(spec) << c.spec << "\n";
  std::filesystem::remove(report);
  const std::string cmd = std::string(SWEEP_CLI) + " run '" + spec + "' --report '" + report + "' --time-limit " +
                          std::to_string(time_limit) + " > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  std::ifstream in(report);
  if (!in) return {false, "failed", "no report (exit " + std::to_string(rc) + ")", 0, time_limit};
  const nlohmann::json j = nlohmann::json::parse(in);
  RunOutcome o;
  o.status = j.value("status", "");
  o.ok = o.status == "ok";
  o.message = j.value("message", "");
  o.volume = j["volume"].value("brep", 0.0);
  o.seconds = j["seconds"].value("total", 0.0);
  return o;
}

/// Whether `volume` is right against reference `ref` (error estimate `ref_err`): within the
/// requested relative volume (1e-6) and the reference's own error.
bool right_volume(double volume, double ref, double ref_err) {
  return std::abs(volume - ref) <= 1e-6 * ref + 3 * ref_err;
}

/// Runs case `c` (by the command line, stopped after `time_limit` seconds when positive, which
/// makes it failed; else in this process) and judges it against reference `ref` (error estimate
/// `ref_err`): right within the requested relative volume (1e-6) and the reference's own error,
/// imprecise within 1e-4, else wrong; a solid that is not ok is failed. No ok solid may be wrong.
Outcome run_case(const testing::RandomCase& c, double ref, double ref_err, double time_limit) {
  const RunOutcome r = time_limit > 0 ? run_by_cli(c, time_limit) : run_in_process(c);
  const double rel = std::abs(r.volume - ref) / ref;
  std::printf("%-30s %-6s %.10g ref %.10g rel %.2e %.2fs %s\n", c.name.c_str(), r.status.c_str(), r.volume, ref, rel,
              r.seconds, r.message.substr(0, 100).c_str());
  std::fflush(stdout);
  if (!r.ok) return Outcome::Failed;
  INFO(c.name << ": " << c.spec);
  CHECK(rel <= 1e-4);  // a solid off by more is wrong: it must not be ok
  if (right_volume(r.volume, ref, ref_err)) return Outcome::Right;
  return rel <= 1e-4 ? Outcome::Imprecise : Outcome::WrongOk;
}

/// A row of the reference table: the case (seed, index) and its name, volume and error estimate.
struct TableRow {
  std::uint64_t seed = 0;
  int index = 0;
  std::string name;
  double volume = 0, error = 0;
};

std::vector<TableRow> read_table(const std::string& path) {
  std::ifstream in(path);
  REQUIRE(in);
  std::vector<TableRow> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    TableRow r;
    REQUIRE(bool(s >> r.seed >> r.index >> r.name >> r.volume >> r.error));
    rows.push_back(r);
  }
  return rows;
}

void print_counts(const char* what, const Outcomes& o) {
  std::printf("%-18s right %2d, imprecise %d, wrong but ok %d, failed %2d of %2d\n", what, o.right, o.imprecise,
              o.wrong_ok, o.failed, o.total());
}

}  // namespace

TEST_CASE("Random one-joint sweeps: no wrong solid is reported ok, and ok ones are right", "[random][bench]") {
  // revolute and prismatic cases of seed 17 with references computed here (helical ones take the
  // orbit-space reference minutes each: bench/ runs them from files)
  const int count = 40;
  Outcomes o;
  for (int i = 0, k = 0; k < count; ++i) {
    if (testing::random_case_joint(i) == 2) continue;
    ++k;
    const testing::RandomCase c = testing::random_one_joint_case(17, i);
    double ref_err = 0;
    const double ref = testing::reference_volume(parse_spec(c.spec, "."), 1e-9, &ref_err);
    o.add(run_case(c, ref, ref_err, 0));
  }
  print_counts("all", o);
  CHECK(o.wrong_ok == 0);
}

TEST_CASE("Random one-joint sweeps in CI: every joint and entity kind, no wrong solid reported ok", "[random]") {
  // the cases of the reference table, each run by the command line and stopped after 20 s (a run
  // that meets its stop is failed, never ok)
  const std::vector<TableRow> rows = read_table(std::string(SWEEP_SOURCE_DIR) + "/tests/data/random_one_joint.tsv");
  REQUIRE(rows.size() >= 60);
  Outcomes all, by_joint[3], by_kind[testing::kRandomKindCount];
  for (const TableRow& row : rows) {
    const testing::RandomCase c = testing::random_one_joint_case(row.seed, row.index);
    REQUIRE(c.name == row.name);  // the generator still makes the case the table was made for
    const Outcome o = run_case(c, row.volume, row.error, 20);
    all.add(o);
    by_joint[testing::random_case_joint(row.index)].add(o);
    by_kind[testing::random_case_kind(row.index)].add(o);
  }
  for (int k = 0; k < 3; ++k) print_counts(testing::kRandomJoints[k], by_joint[k]);
  for (int k = 0; k < testing::kRandomKindCount; ++k) print_counts(testing::kRandomKinds[k], by_kind[k]);
  print_counts("all", all);
  // every joint and entity kind is there
  for (const Outcomes& o : by_joint) CHECK(o.total() >= 15);
  for (const Outcomes& o : by_kind) CHECK(o.total() >= 7);
  CHECK(all.wrong_ok == 0);
  // 65 of the 65 are right on an idle machine; the floor leaves room for a few slow ones (up to
  // 15 s) that meet their stop on a loaded one
  CHECK(all.right >= 48);
}

namespace {

/// The row named `name` of a reference table in tests/data (the CI table of primitives unless told),
/// of the given seed when one is given (seeds repeat names).
TableRow table_row(const std::string& name, const std::string& table = "random_one_joint.tsv", std::uint64_t seed = 0) {
  const std::vector<TableRow> rows = read_table(std::string(SWEEP_SOURCE_DIR) + "/tests/data/" + table);
  const auto row = std::find_if(rows.begin(), rows.end(),
                                [&](const TableRow& r) { return r.name == name && (seed == 0 || r.seed == seed); });
  REQUIRE(row != rows.end());
  return *row;
}

/// The case of the table's row run in process (stopped after 120 s); `steps` receives its progress.
occt::RunResult run_row(const TableRow& row, std::vector<std::string>* steps = nullptr) {
  const testing::RandomCase c = testing::random_one_joint_case(row.seed, row.index);
  REQUIRE(c.name == row.name);
  occt::RunOptions opt;
  opt.stop = occt::stop_after(120);
  if (steps) opt.progress = [steps](const std::string& s) { steps->push_back(s); };
  return occt::run_sweep(parse_spec(c.spec, "."), opt);
}

/// The first of `steps` that mentions `text` (a failed check prints it); empty when none does.
std::string step_mentioning(const std::vector<std::string>& steps, const std::string& text) {
  for (const std::string& s : steps)
    if (s.find(text) != std::string::npos) return s;
  return {};
}

/// The case of the table's row, run in process, is right from its traced boundary: ok, not made
/// again with OCCT's sections nor from the cells, within its requested tolerance and its reference.
void check_right_from_traced_boundary(const TableRow& row) {
  std::vector<std::string> steps;
  const occt::RunResult r = run_row(row, &steps);
  INFO(row.name << ": " << r.report.message);
  REQUIRE(r.report.ok());
  CHECK(step_mentioning(steps, "again") == "");
  CHECK(step_mentioning(steps, "cells") == "");
  CHECK(r.report.tol_achieved <= r.report.tol_requested);
  CHECK(right_volume(r.report.volume_brep, row.volume, row.error));
}

}  // namespace

TEST_CASE("Random cases: a solid with a sliver face is judged against its triangles, not point by point by OCCT") {
  // a cone screwed 2.5 turns about an oblique axis (case 33 of the CI table): one face of its solid,
  // 1e-4 in area, loses 6 % of it to the chords of its triangulation, far less than the band the
  // samples leave out; OCCT's classifier took 30 s for the verdict's 4,600 points
  const TableRow row = table_row("cone_helical_33");
  const occt::RunResult r = run_row(row);
  INFO(r.report.message << " ; " << r.report.verdict_classifier);
  REQUIRE(r.report.ok());
  CHECK(r.report.verdict_classifier.find("triangulation") != std::string::npos);
  CHECK(r.report.verdict_classifier.find("OCCT's solid classifier") == std::string::npos);
  CHECK(right_volume(r.report.volume_brep, row.volume, row.error));
}

TEST_CASE("Random cases: solids turned about axes through them close their boundary from the traced crossings") {
  // a cylinder and a cone turned about axes that cross them (cases 38 and 21 of the CI table): the
  // crossing of a grazing curve's sweep with the start copy met the copy's rim off the rim by the
  // sagitta of the traced contour's chord (5.5e-4), so it did not split the copy there; the boundary
  // then did not close and the stage was made again with OCCT's sections (19 s instead of 9 s)
  for (const char* name : {"cylinder_revolute_38", "cone_revolute_21"}) {
    const TableRow row = table_row(name);
    std::vector<std::string> steps;
    const occt::RunResult r = run_row(row, &steps);
    INFO(name << ": " << r.report.message);
    REQUIRE(r.report.ok());
    CHECK(step_mentioning(steps, "again") == "");
    CHECK(step_mentioning(steps, "cells") == "");
    CHECK(right_volume(r.report.volume_brep, row.volume, row.error));
  }
}

TEST_CASE("Random cases: a box screwed where a grazing line's sweep crosses the face it lies on is right from the traced crossing") {
  // a box screwed one turn about an oblique axis (case 30 of seed 47): the sweep of a grazing line on
  // the start copy's face leaves the face's plane on one side near one end of the line and on the
  // other side near the other, so it crosses that face along a curve that stays within 3e-4 of the
  // line; OCCT's section of the fitted sweep with the face missed that curve, the boundary was
  // invalid, and the cells ran past 50 s into a failure. The crossing is traced on the exact sweep
  // now, within the sweep's fit error of its fitted face.
  const TableRow row = table_row("box_helical_30", "random_one_joint.tsv", 47);
  check_right_from_traced_boundary(row);
}

TEST_CASE("Random cases: a box screwed whose grazing line ends next to a corner closes its boundary from the traced crossings") {
  // a box screwed about an oblique axis (case 48 of the CI table): a face's grazing line ends on an
  // edge 0.0028 from a corner. The profiles of that line's and the edge's sweeps touch where they
  // meet (the line's is the fold of the face's), and the other edge from the corner crosses the
  // edge's sweep at an angle of 4e-4 radians, 0.0043 further on. The strip of the edge's sweep
  // between lies inside the solid, but that other sweep lies closer to it than the classification's
  // offset: both probes landed beyond it, the strip was kept and the boundary did not close, and
  // the cells lost half the solid (failed on its geometric error, 14 s).
  const TableRow row = table_row("box_helical_48");
  check_right_from_traced_boundary(row);
}

TEST_CASE("Random cases: a cone screwed whose grazing curve's profile folds back twice closes its boundary from the traced crossings") {
  // a cone screwed 2.1 turns about an oblique axis (case 15 of the CI table): the profile of its
  // grazing curve across the helices has two cusps (a swallowtail), one where the curve is split in
  // two, so the sweeps of the two parts share an end whose profiles meet there tangentially. A
  // solver found them touching 7e-4 from that end, at a sine of 6e-4, within 1e-6 of each other
  // all the way to it; the pair went to OCCT's general section, which missed the helix where the
  // two outer arms cross, the boundary kept a strip lying 0.0026 inside the solid and the cells ran
  // past the limit
  const TableRow row = table_row("cone_helical_15");
  check_right_from_traced_boundary(row);
}

TEST_CASE("Random cases: a cylinder screwed where two turns of a rim's sweep cross is right from the traced crossings") {
  // a cylinder screwed 2.3 turns (case 14 of seed 47): the profile of an arc of its rim across the
  // helices wraps more than a turn about the axis and crosses itself 0.001 from the arc's end, so
  // the arc's sweep passes through itself there, one turn apart. Its quarter-turn faces have one
  // profile and were taken to meet along an edge at most: the strip next to that end, 9.4e-4
  // inside the solid, was kept, the boundary did not close and the cells ran past the limit
  const TableRow row = table_row("cylinder_helical_14", "random_one_joint.tsv", 47);
  check_right_from_traced_boundary(row);
}

TEST_CASE("Random cases: a torus extruded obliquely is right where a section crosses the fold of its extruded grazing curve") {
  // a torus extruded obliquely (case 28 of the CI table): a section runs on the extrusion of the
  // grazing curve past a fold of it (the outline along the direction has a cusp there); its curve
  // on that face settled on the other sheet and was refused, and the splitter's own projection
  // left its end 1e-3 off: the run failed on its geometric error
  const TableRow row = table_row("torus_prismatic_28");
  const occt::RunResult r = run_row(row);
  INFO(r.report.message);
  REQUIRE(r.report.ok());
  CHECK(r.report.tol_achieved <= r.report.tol_requested);
  CHECK(right_volume(r.report.volume_brep, row.volume, row.error));
}

TEST_CASE("Random cases: a torus turned about a skew axis sews its boundary across a gap within the tolerance") {
  // a torus turned about a skew axis (case 22 of the CI table): two pieces meet along a 1e-3 long
  // edge whose two sides lie 2e-6 apart, wider than the sewing gap (3e-7) but within the requested
  // tolerance (3.4e-6); the boundary did not close, nor again with OCCT's sections, and the cells
  // took 67 s to give a solid 1e-3 off
  const TableRow row = table_row("torus_revolute_22");
  std::vector<std::string> steps;
  const occt::RunResult r = run_row(row, &steps);
  INFO(r.report.message);
  REQUIRE(r.report.ok());
  CHECK(step_mentioning(steps, "do not close") == "");
  CHECK(r.report.tol_achieved <= r.report.tol_requested);
  CHECK(right_volume(r.report.volume_brep, row.volume, row.error));
}

namespace {

/// The part of the parts table's row `row` as a case: its STEP file written to the build tree and
/// the spec that reads it.
testing::RandomCase part_case(const TableRow& row) {
  const testing::RandomPart p = testing::random_part_case(row.seed, row.index);
  REQUIRE(p.name == row.name);  // the generator still makes the part the table was made for
  const std::string dir = std::string(SWEEP_BINARY_DIR) + "/random_parts";
  std::filesystem::create_directories(dir);
  const std::string step = dir + "/" + p.name + ".step";
  REQUIRE(testing::write_part_step(p, step));
  return {p.name, p.spec(step)};
}

/// Runs the rows of the parts table that `take` selects by the command line, 20 s each.
Outcomes run_parts(const std::function<bool(const TableRow&)>& take) {
  Outcomes all;
  for (const TableRow& row : read_table(std::string(SWEEP_SOURCE_DIR) + "/tests/data/random_parts.tsv"))
    if (take(row)) all.add(run_case(part_case(row), row.volume, row.error, 20));
  print_counts("parts", all);
  return all;
}

}  // namespace

TEST_CASE("Random parts in CI: machined parts from STEP under revolute prismatic and helical joints with no wrong solid ok", "[random]") {
  // each family once per joint kind (the table's first fifteen rows)
  const Outcomes o = run_parts([](const TableRow& r) { return r.index < 15; });
  CHECK(o.total() == 15);
  CHECK(o.wrong_ok == 0);
  // on an idle machine 9 of the 10 under revolute and prismatic joints are right (the L-bracket's
  // cells miss the tolerance by 6 %), and 4 of the 5 helical ones (the boss is 1.9e-6 off its
  // reference; the pocket takes about 15 s)
  CHECK(o.right >= 9);
}

TEST_CASE("Random parts: no wrong solid ok on every part of the table", "[random][bench]") {
  const Outcomes o = run_parts([](const TableRow&) { return true; });
  CHECK(o.total() >= 30);
  CHECK(o.wrong_ok == 0);
}

TEST_CASE("Random parts: an L-bracket whose sweep boundary only healing makes valid goes to the cells") {
  // the boundary's kept pieces of this L-bracket turned 295 degrees about a skew axis overlap; OCCT's
  // healing made a valid solid of them 0.5 % too large, which the verdict caught at 2 of 5,120 points
  const TableRow row = table_row("l_bracket_revolute_2", "random_parts.tsv");
  const testing::RandomCase c = part_case(row);
  occt::RunOptions opt;
  opt.stop = occt::stop_after(120);
  std::vector<std::string> steps;
  opt.progress = [&steps](const std::string& s) { steps.push_back(s); };
  const occt::RunResult r = occt::run_sweep(parse_spec(c.spec, "."), opt);
  CHECK(!step_mentioning(steps, "do not make a valid solid").empty());
  CHECK(!step_mentioning(steps, "built from cells").empty());
  // the cells' volume is right (their solid's geometric error is just over the tolerance)
  CHECK(right_volume(r.report.volume_brep, row.volume, row.error));
}

TEST_CASE("Random cases: a torus whose turned copies cross is right in time") {
  // case 58 of the CI table: the start and end copies of a torus turned 329 degrees cross in 20
  // pairs of their pieces, and OCCT's section of two tori took 1 to 2.4 s a pair (65 s in all, the
  // run stopped at its 20 s); traced as the zero set of one torus's exact distance, 10 s in all
  const TableRow row = table_row("torus_revolute_58");
  const occt::RunResult r = run_row(row);
  INFO(r.report.message);
  REQUIRE(r.report.ok());
  CHECK(right_volume(r.report.volume_brep, row.volume, row.error));
}
