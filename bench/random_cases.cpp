// Writes the random one-joint cases (tests/util/random_one_joint.hpp) as spec files with their
// reference volumes, for bench/run_bench.sh, or their references as a table for the tests:
//   random_cases DIR [COUNT [SEED [REL_TOL|none [FILTER]]]]
//   random_cases --table FILE FIRST COUNT SEED REL_TOL
// FILTER keeps the cases whose name contains it (e.g. "helical", "torus_"). Each line printed gives
// the reference's volume, its error estimate and the seconds it took. REL_TOL "none" writes the
// specs alone. --table appends a line "SEED INDEX NAME VOLUME ERROR" for each case FIRST ..
// FIRST + COUNT - 1 to FILE as soon as its reference is done (tests/data/random_one_joint.tsv).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "util/random_one_joint.hpp"

namespace {

/// The case's reference volume and its error estimate, and the seconds they took.
struct Reference {
  double volume = 0, error = 0, seconds = 0;
};

Reference reference_of(const sweep::testing::RandomCase& c, double rel_tol, const std::string& dir) {
  const sweep::Spec spec = sweep::parse_spec(c.spec, dir);
  Reference r;
  const auto t0 = std::chrono::steady_clock::now();
  r.volume = sweep::testing::reference_volume(spec, rel_tol, &r.error);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

int write_table(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr, "usage: random_cases --table FILE FIRST COUNT SEED REL_TOL\n");
    return 2;
  }
  const std::string file = argv[2];
  const int first = std::atoi(argv[3]), count = std::atoi(argv[4]);
  const std::uint64_t seed = std::strtoull(argv[5], nullptr, 10);
  const double rel_tol = std::atof(argv[6]);
  if (first < 0 || count < 0 || !(rel_tol > 0 && rel_tol < 1)) {
    std::fprintf(stderr, "random_cases: FIRST and COUNT must be >= 0 and REL_TOL in (0, 1)\n");
    return 2;
  }
  for (int i = first; i < first + count; ++i) {
    const sweep::testing::RandomCase c = sweep::testing::random_one_joint_case(seed, i);
    const Reference r = reference_of(c, rel_tol, ".");
    std::ofstream out(file, std::ios::app);
    char line[256];
    std::snprintf(line, sizeof line, "%llu %d %s %.15g %.3g\n", static_cast<unsigned long long>(seed), i, c.name.c_str(),
                  r.volume, r.error);
    out << line;
    if (!out.flush()) {
      std::fprintf(stderr, "random_cases: cannot write %s\n", file.c_str());
      return 1;
    }
    std::printf("%s %.12g (+- %.2g) %.2f s\n", c.name.c_str(), r.volume, r.error, r.seconds);
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--table") return write_table(argc, argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: random_cases DIR [COUNT [SEED [REL_TOL|none [FILTER]]]]\n"
                         "       random_cases --table FILE FIRST COUNT SEED REL_TOL\n");
    return 2;
  }
  const std::string dir = argv[1];
  const int count = argc > 2 ? std::atoi(argv[2]) : 200;
  const std::uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 17;
  const bool specs_only = argc > 4 && std::string(argv[4]) == "none";
  const double rel_tol = argc > 4 && !specs_only ? std::atof(argv[4]) : 1e-9;
  const std::string filter = argc > 5 ? argv[5] : "";
  if (count < 0 || !(rel_tol > 0 && rel_tol < 1)) {
    std::fprintf(stderr, "random_cases: COUNT must be >= 0 and REL_TOL in (0, 1)\n");
    return 2;
  }
  for (int i = 0; i < count; ++i) {
    const sweep::testing::RandomCase c = sweep::testing::random_one_joint_case(seed, i);
    if (c.name.find(filter) == std::string::npos) continue;
    if (specs_only) {
      std::ofstream(dir + "/" + c.name + ".json") << c.spec << "\n";
      std::printf("%s\n", c.name.c_str());
      continue;
    }
    const Reference r = reference_of(c, rel_tol, dir);
    char tail[160];
    std::snprintf(tail, sizeof tail, ", \"_expected_volume\": %.15g, \"_reference_error\": %.3g}", r.volume, r.error);
    std::ofstream(dir + "/" + c.name + ".json") << c.spec.substr(0, c.spec.size() - 1) << tail << "\n";
    std::printf("%s %.12g (+- %.2g) %.2f s\n", c.name.c_str(), r.volume, r.error, r.seconds);
    std::fflush(stdout);
  }
  return 0;
}
