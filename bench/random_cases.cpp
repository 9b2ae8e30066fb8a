// Writes the random one-joint cases (tests/util/random_one_joint.hpp) as spec files with their
// reference volumes, for bench/run_bench.sh:
//   random_cases DIR [COUNT [SEED [REL_TOL [FILTER]]]]
// FILTER keeps the cases whose name contains it (e.g. "helical", "torus_"). Each line printed gives
// the reference's volume, its error estimate and the seconds it took. REL_TOL "none" writes the
// specs alone.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "util/random_one_joint.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: random_cases DIR [COUNT [SEED [REL_TOL|none [FILTER]]]]\n");
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
    const sweep::Spec spec = sweep::parse_spec(c.spec, dir);
    double err = 0;
    const auto t0 = std::chrono::steady_clock::now();
    const double v = sweep::testing::reference_volume(spec, rel_tol, &err);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    char tail[160];
    std::snprintf(tail, sizeof tail, ", \"_expected_volume\": %.15g, \"_reference_error\": %.3g}", v, err);
    std::ofstream(dir + "/" + c.name + ".json") << c.spec.substr(0, c.spec.size() - 1) << tail << "\n";
    std::printf("%s %.12g (+- %.2g) %.2f s\n", c.name.c_str(), v, err, s);
    std::fflush(stdout);
  }
  return 0;
}
