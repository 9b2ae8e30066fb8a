// The `mesh` entity: a cube given as OFF and as binary STL and an 80-triangle polyhedron, swept and
// checked against closed forms;
// a mesh that bounds no solid is an input error naming /entity/file.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "occt_bridge/sweeper.hpp"
#include "sweep/error.hpp"
#include "sweep/spec.hpp"
#include "sweep/triangle_mesh.hpp"

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

namespace {

/// An icosahedron on the unit sphere, its triangles split in four `levels` times (vertices pushed
/// out onto the sphere), written as OFF.
void write_icosphere_off(const std::string& path, int levels) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Eigen::Vector3d> v = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                    {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (auto& p : v) p.normalize();
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return middle[key] = int(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& t : f) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      finer.insert(finer.end(), {{t[0], ab, ca}, {t[1], bc, ab}, {t[2], ca, bc}, {ab, bc, ca}});
    }
    f = finer;
  }
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << v.size() << " " << f.size() << " 0\n";
  for (const auto& p : v) out << p.x() << " " << p.y() << " " << p.z() << "\n";
  for (const auto& t : f) out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
}

}  // namespace

TEST_CASE("Mesh entity: a convex polyhedron of 80 triangles slid, against the projected-area formula") {
  // A convex solid K slid L along the unit direction d sweeps vol(K) + L area(K projected along
  // d), and the projection of a convex polyhedron has half the area of its faces' |n . d| sum.
  write_icosphere_off(SWEEP_BINARY_DIR "/mesh_icosphere_80.off", 1);
  std::ifstream in(SWEEP_BINARY_DIR "/mesh_icosphere_80.off");
  const sweep::TriangleMesh m = sweep::read_off(in, "");
  REQUIRE(m.triangles.size() == 80);
  const Eigen::Vector3d d = Eigen::Vector3d(1, 0.3, 0.2).normalized();
  const double L = 2;
  double projected = 0;
  for (const auto& t : m.triangles) {
    const Eigen::Vector3d n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    projected += 0.25 * std::abs(n.dot(d));  // half of each face's area times |cos|
  }
  const auto r = run(R"({"kind": "mesh", "file": "mesh_icosphere_80.off"})",
                     R"([{"type": "prismatic", "direction": [1, 0.3, 0.2], "range": [0, 2]}])");
  CAPTURE(r.report.to_json().dump());
  REQUIRE(r.report.ok());
  CHECK(r.report.volume_brep == Approx(sweep::signed_volume(m) + L * projected).epsilon(1e-9));
}
