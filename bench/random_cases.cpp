// Writes the random one-joint cases (tests/util/random_one_joint.hpp) as spec files with their
// reference volumes, for bench/run_bench.sh:  random_cases DIR [COUNT [SEED]]
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "util/random_one_joint.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: random_cases DIR [COUNT [SEED]]\n");
    return 2;
  }
  const std::string dir = argv[1];
  const int count = argc > 2 ? std::atoi(argv[2]) : 200;
  const std::uint64_t seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 17;
  for (int i = 0; i < count; ++i) {
    const sweep::testing::RandomCase c = sweep::testing::random_one_joint_case(seed, i);
    const sweep::Spec spec = sweep::parse_spec(c.spec, dir);
    double err = 0;
    const double v = sweep::testing::reference_volume(spec, 1e-9, &err);
    char tail[160];
    std::snprintf(tail, sizeof tail, ", \"_expected_volume\": %.15g, \"_reference_error\": %.3g}", v, err);
    std::ofstream(dir + "/" + c.name + ".json") << c.spec.substr(0, c.spec.size() - 1) << tail << "\n";
    std::printf("%s %.12g (+- %.2g)\n", c.name.c_str(), v, err);
    std::fflush(stdout);
  }
  return 0;
}
