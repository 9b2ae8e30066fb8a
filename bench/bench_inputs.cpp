// Writes the input files that examples refer to and the repository does not hold, so that the
// benchmark can time those examples too: box_hole.step (examples/brep_box_hole.json), the same
// solid the tests build (tests/util/box_hole.hpp).
// Usage: bench_inputs DIR   (exit 0 when every file was written, 1 otherwise)
#include <iostream>
#include <string>

#include "util/box_hole.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: bench_inputs DIR\n";
    return 2;
  }
  const std::string path = std::string(argv[1]) + "/box_hole.step";
  if (!sweep_test::write_box_with_hole(path)) {
    std::cerr << "bench_inputs: cannot build or write " << path << "\n";
    return 1;
  }
  return 0;
}
