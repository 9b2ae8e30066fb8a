// The `mesh` entity: a cube given as OFF and as binary STL, swept and checked against closed forms;
// a mesh that bounds no solid is an input error naming /entity/file.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

#include "occt_bridge/sweeper.hpp"
#include "sweep/error.hpp"
#include "sweep/spec.hpp"

namespace {

const int kCubeQuads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};

Eigen::Vector3d corner(int k, double a) { return a * Eigen::Vector3d(k & 1, (k >> 1) & 1, (k >> 2) & 1); }

/// The cube [0, a]^3 as OFF, each face a quad; `drop` leaves out one face (an open mesh).
void write_cube_off(const std::string& path, double a, bool drop = false) {
  std::ofstream out(path);
  out << "OFF\n8 " << (drop ? 5 : 6) << " 12\n";
  for (int k = 0; k < 8; ++k) out << corner(k, a).transpose() << "\n";
  for (int f = drop ? 1 : 0; f < 6; ++f)
    out << "4 " << kCubeQuads[f][0] << " " << kCubeQuads[f][1] << " " << kCubeQuads[f][2] << " " << kCubeQuads[f][3]
        << "\n";
}

/// The cube [0, a]^3 as binary STL: 12 triangles, each with its own three vertices.
void write_cube_stl(const std::string& path, double a) {
  std::ofstream out(path, std::ios::binary);
  char header[80] = {};
  std::strncpy(header, "cube", sizeof(header));
  out.write(header, 80);
  const std::uint32_t n = 12;
  out.write(reinterpret_cast<const char*>(&n), 4);
  for (const auto& q : kCubeQuads)
    for (const auto& tri : {std::array<int, 3>{q[0], q[1], q[2]}, std::array<int, 3>{q[0], q[2], q[3]}}) {
      const Eigen::Vector3d p0 = corner(tri[0], a), p1 = corner(tri[1], a), p2 = corner(tri[2], a);
      const Eigen::Vector3d nrm = (p1 - p0).cross(p2 - p0).normalized();
      float v[12];
      for (int i = 0; i < 3; ++i) {
        v[i] = float(nrm[i]);
        v[3 + i] = float(p0[i]);
        v[6 + i] = float(p1[i]);
        v[9 + i] = float(p2[i]);
      }
      out.write(reinterpret_cast<const char*>(v), sizeof(v));
      const std::uint16_t attributes = 0;
      out.write(reinterpret_cast<const char*>(&attributes), 2);
    }
}

sweep::occt::RunResult run(const std::string& entity, const std::string& joints) {
  const sweep::Spec spec = sweep::parse_spec(
      R"({"sweep": 1, "angles": "deg", "entity": )" + entity + R"(, "motion": {"kind": "axes", "joints": )" + joints +
          "}}",
      SWEEP_BINARY_DIR);
  return sweep::occt::run_sweep(spec);
}

}  // namespace

TEST_CASE("Mesh entity: an OFF cube scaled, placed and turned a quarter about an outside axis") {
  // [0, 0.5]^3 scaled by 2 and moved to [1, 2] x [0, 1] x [0, 1]: a quarter turn about z sweeps
  // the section of area 1 + pi over a height of 1 (examples/box_revolve_90.json's box)
  write_cube_off(SWEEP_BINARY_DIR "/mesh_cube_turned.off", 0.5);
  const auto r = run(R"({"kind": "mesh", "file": "mesh_cube_turned.off", "scale": 2,
                         "placement": {"translate": [1, 0, 0]}})",
                     R"([{"type": "revolute", "point": [0, 0, 0], "direction": [0, 0, 1], "range": [0, 90]}])");
  CAPTURE(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(r.report.volume_brep == Approx(1 + M_PI).epsilon(1e-9));
}

TEST_CASE("Mesh entity: a binary STL cube slid obliquely") {
  // the unit cube slid L along the unit direction d: 1 + L (|dx| + |dy| + |dz|)
  write_cube_stl(SWEEP_BINARY_DIR "/mesh_cube_slid.stl", 1.0);
  const Eigen::Vector3d d = Eigen::Vector3d(1, 2, 2) / 3;
  const auto r = run(R"({"kind": "mesh", "file": "mesh_cube_slid.stl"})",
                     R"([{"type": "prismatic", "direction": [1, 2, 2], "range": [0, 1.5]}])");
  CAPTURE(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(r.report.volume_brep == Approx(1 + 1.5 * d.cwiseAbs().sum()).epsilon(1e-9));
  CHECK(r.report.faces <= 12);  // the cube's six faces, not its twelve triangles, swept
}

TEST_CASE("Mesh entity: a mesh that bounds no solid is an input error naming /entity/file") {
  write_cube_off(SWEEP_BINARY_DIR "/mesh_cube_open.off", 1.0, true);
  try {
    run(R"({"kind": "mesh", "file": "mesh_cube_open.off"})",
        R"([{"type": "prismatic", "direction": [0, 0, 1], "range": [0, 1]}])");
    FAIL("no error for an open mesh");
  } catch (const sweep::InputError& e) {
    CHECK(e.pointer() == "/entity/file");
    CHECK(std::string(e.what()).find("not closed") != std::string::npos);
  }
}

TEST_CASE("Mesh entity: a cube under a slide and a turn is the box primitive's solid") {
  // the two entities reach the engine by different paths (a polyhedron sewn from triangles, judged
  // with its triangulation's distance bound; the core's box, judged with its exact distance)
  write_cube_off(SWEEP_BINARY_DIR "/mesh_cube_chain.off", 1.0);
  const std::string joints = R"([{"type": "prismatic", "direction": [1, 2, 2], "range": [0, 1.5]},
      {"type": "revolute", "point": [3, 0, 0], "direction": [0, 0.3, 1], "range": [0, 35]}])";
  const auto mesh = run(R"({"kind": "mesh", "file": "mesh_cube_chain.off"})", joints);
  const auto box = run(R"({"kind": "box", "min": [0, 0, 0], "max": [1, 1, 1]})", joints);
  CAPTURE(mesh.report.to_json().dump());
  REQUIRE(mesh.report.ok());
  REQUIRE(box.report.ok());
  CHECK(mesh.report.verdict_membership == "certified search over the joint box (signed distance)");
  CHECK(mesh.report.volume_brep == Approx(box.report.volume_brep).epsilon(1e-9));
}
