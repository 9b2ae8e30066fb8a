// Writes the random one-joint sweeps of machined parts (tests/util/random_parts.hpp): each part as
// DIR/NAME.step and its spec as DIR/NAME.json with the orbit-space reference volume:
//   random_parts DIR [COUNT [SEED [REL_TOL [FILTER]]]]
// (tests/data/random_parts.tsv holds the references of `random_parts DIR 40 43 1e-7 revolute` and
// `... prismatic`.) FILTER keeps the cases whose name contains it. Each line printed gives the reference's volume,
// its error estimate and the seconds it took.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "util/random_parts.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: random_parts DIR [COUNT [SEED [REL_TOL [FILTER]]]]\n");
    return 2;
  }
  const std::string dir = argv[1];
  const int count = argc > 2 ? std::atoi(argv[2]) : 30;
  const std::uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 17;
  const double rel_tol = argc > 4 ? std::atof(argv[4]) : 1e-7;
  const std::string filter = argc > 5 ? argv[5] : "";
  if (count < 0 || !(rel_tol > 0 && rel_tol < 1)) {
    std::fprintf(stderr, "random_parts: COUNT must be >= 0 and REL_TOL in (0, 1)\n");
    return 2;
  }
  for (int i = 0; i < count; ++i) {
    const sweep::testing::RandomPart p = sweep::testing::random_part_case(seed, i);
    if (p.name.find(filter) == std::string::npos) continue;
    if (!sweep::testing::write_part_step(p, dir + "/" + p.name + ".step")) {
      std::fprintf(stderr, "random_parts: cannot write %s/%s.step\n", dir.c_str(), p.name.c_str());
      return 1;
    }
    const auto t0 = std::chrono::steady_clock::now();
    double error = 0;
    const double volume = sweep::testing::part_reference_volume(p, rel_tol, &error);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::string spec = p.spec(p.name + ".step");
    char tail[160];
    std::snprintf(tail, sizeof tail, ", \"_expected_volume\": %.15g, \"_reference_error\": %.3g}", volume, error);
    std::ofstream(dir + "/" + p.name + ".json") << spec.substr(0, spec.size() - 1) << tail << "\n";
    std::printf("%s %.12g (+- %.2g) %.2f s\n", p.name.c_str(), volume, error, seconds);
    std::fflush(stdout);
  }
  return 0;
}
