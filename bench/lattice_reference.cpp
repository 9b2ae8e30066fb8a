// The reference volume of a random one-joint case or part by shifted lattices over the space of
// orbits (joint_sweep_volume_lattice), a check of the adaptive orbit integral that random_cases and
// random_parts give, whose scan may step over a narrow gap or strip of a helical sweep; and of a
// one-joint spec whose entity is a solid read from STEP or BREP (faces on planes, quadrics and
// tori), met by orbits at its faces' exact crossings:
//   lattice_reference case|part SEED INDEX [N [SHIFTS]]
//   lattice_reference brep SPEC.json [N [SHIFTS]]
// prints "NAME VOLUME (+- ERROR) SECONDS" (ERROR: the standard error of the shifts' mean).
#include <BRepBndLib.hxx>
#include <Bnd_Box.hxx>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "base/internal.hpp"
#include "util/random_one_joint.hpp"
#include "util/random_parts.hpp"

namespace {

/// The one-joint sweep of a spec's solid read from a file.
sweep::testing::JointSweep brep_sweep(const std::string& path, std::string* name) {
  const sweep::Spec spec = sweep::load_spec(path);
  if (spec.entity.kind != sweep::EntityKind::Brep)
    throw sweep::InputError("/entity/kind", "lattice_reference brep takes a solid read from a file");
  if (spec.motion.motion.joints.size() != 1)
    throw sweep::InputError("/motion", "lattice_reference brep takes one joint");
  const TopoDS_Shape shape = sweep::occt::entity_shape(spec.entity, 0.0, nullptr);
  *name = spec.name.empty() ? path : spec.name;
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  const double size = std::sqrt(box.SquareExtent());
  return sweep::testing::joint_sweep_of(spec, sweep::occt::brep_orbit_solid(shape, 1e-9 * size));
}

}  // namespace

int main(int argc, char** argv) try {
  const std::string kind = argc > 1 ? argv[1] : "";
  if (kind == "brep" && argc >= 3) {
    const int n = argc > 3 ? std::atoi(argv[3]) : 1000, shifts = argc > 4 ? std::atoi(argv[4]) : 8;
    if (n < 1 || shifts < 2) {
      std::fprintf(stderr, "lattice_reference: N must be >= 1 and SHIFTS >= 2\n");
      return 2;
    }
    std::string name;
    const sweep::testing::JointSweep s = brep_sweep(argv[2], &name);
    const auto t0 = std::chrono::steady_clock::now();
    double error = 0;
    const double volume = sweep::joint_sweep_volume_lattice(*s.body, s.j, s.T, n, shifts, 1, &error);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%s %.12g (+- %.2g) %.2f s\n", name.c_str(), volume, error, seconds);
    return 0;
  }
  if (argc < 4 || (kind != "case" && kind != "part")) {
    std::fprintf(stderr, "usage: lattice_reference case|part SEED INDEX [N [SHIFTS]]\n"
                         "       lattice_reference brep SPEC.json [N [SHIFTS]]\n");
    return 2;
  }
  const std::uint64_t seed = std::strtoull(argv[2], nullptr, 10);
  const int index = std::atoi(argv[3]);
  const int n = argc > 4 ? std::atoi(argv[4]) : 1000, shifts = argc > 5 ? std::atoi(argv[5]) : 8;
  if (index < 0 || n < 1 || shifts < 2) {
    std::fprintf(stderr, "lattice_reference: INDEX must be >= 0, N >= 1 and SHIFTS >= 2\n");
    return 2;
  }
  std::string name;
  sweep::testing::JointSweep s;
  if (kind == "case") {
    const sweep::testing::RandomCase c = sweep::testing::random_one_joint_case(seed, index);
    const sweep::Spec spec = sweep::parse_spec(c.spec, ".");
    name = c.name;
    s = sweep::testing::joint_sweep_of(spec, sweep::make_orbit_solid(spec.entity));
  } else {
    const sweep::testing::RandomPart p = sweep::testing::random_part_case(seed, index);
    name = p.name;
    s = sweep::testing::part_joint_sweep(p);
  }
  const auto t0 = std::chrono::steady_clock::now();
  double error = 0;
  const double volume = sweep::joint_sweep_volume_lattice(*s.body, s.j, s.T, n, shifts, seed, &error);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%s %.12g (+- %.2g) %.2f s\n", name.c_str(), volume, error, seconds);
  return 0;
} catch (const sweep::InputError& e) {
  std::fprintf(stderr, "lattice_reference: %s: %s\n", e.pointer().c_str(), e.what());
  return 2;
}
