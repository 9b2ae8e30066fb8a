// What a FreeCAD user does today instead of a swept volume: N+1 copies of the entity placed at
// evenly spaced values of the joint, fused by one OCCT General Fuse call (parallel), and the
// volume of the result. Prints one markdown row: case | N | seconds | volume | rel. error.
// Usage: fuse_copies SPEC N   (one-joint specs of solid entities; the error is against the spec's
// _expected_volume)
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>

#include "base/internal.hpp"
#include "sweep/spec.hpp"

namespace {

using sweep::occt::moved;

int run(const std::string& path, int n) {
  const sweep::Spec spec = sweep::load_spec(path);
  const sweep::Motion& motion = spec.motion.motion;
  if (motion.dof() != 1) {
    std::cerr << "fuse_copies: " << path << ": one joint only (the motion has " << motion.dof() << ")\n";
    return 2;
  }
  const sweep::ScrewJoint& j = motion.joints[0];
  double fit_error = 0;
  const TopoDS_Shape body = moved(sweep::occt::entity_shape(spec.entity, 1e-7, &fit_error), motion.home);
  if (!TopExp_Explorer(body, TopAbs_SOLID).More()) {
    std::cerr << "fuse_copies: " << path << ": the entity is not a solid\n";
    return 2;
  }

  const auto start = std::chrono::steady_clock::now();
  TopTools_ListOfShape first, others;
  for (int i = 0; i <= n; ++i) {
    const double q = j.lo + (j.hi - j.lo) * i / n;
    (i == 0 ? first : others).Append(moved(body, j.transform(q)));
  }
  BRepAlgoAPI_Fuse fuse;
  fuse.SetArguments(first);
  fuse.SetTools(others);
  fuse.SetRunParallel(true);
  fuse.Build();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::string name = path.substr(path.find_last_of('/') + 1);
  name = name.substr(0, name.rfind(".json"));
  if (!fuse.IsDone()) {
    std::printf("| %s | %d | %.1f | fuse failed | |\n", name.c_str(), n, seconds);
    return 1;
  }
  GProp_GProps props;
  BRepGProp::VolumeProperties(fuse.Shape(), props);
  const double volume = props.Mass();
  const auto expected = spec.json.find("_expected_volume");
  if (expected == spec.json.end()) {
    std::printf("| %s | %d | %.1f | %.6g | |\n", name.c_str(), n, seconds, volume);
  } else {
    const double ref = expected->get<double>();
    std::printf("| %s | %d | %.1f | %.6g | %+.2f %% |\n", name.c_str(), n, seconds, volume,
                100 * (volume - ref) / std::abs(ref));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: fuse_copies SPEC N\n";
    return 2;
  }
  try {
    const int n = std::stoi(argv[2]);
    if (n < 1) throw std::invalid_argument("N must be at least 1");
    return run(argv[1], n);
  } catch (const std::exception& e) {
    std::cerr << "fuse_copies: " << e.what() << "\n";
    return 2;
  }
}
