// Triangle meshes as solids (sweep/triangle_mesh.hpp): OFF read, merged vertices, the checks that
// make a mesh the boundary of a solid, and its volume.
#include <catch2/catch.hpp>

#include <sstream>

#include "sweep/error.hpp"
#include "sweep/triangle_mesh.hpp"

using namespace sweep;

namespace {

/// The cube [0, a]^3 as OFF with six quads, outward.
std::string cube_off(double a) {
  std::ostringstream os;
  os << "OFF\n# a cube\n8 6 12\n";
  for (int k = 0; k < 8; ++k) os << a * (k & 1) << " " << a * ((k >> 1) & 1) << " " << a * ((k >> 2) & 1) << "\n";
  os << "4 0 2 3 1\n4 4 5 7 6\n4 0 1 5 4\n4 2 6 7 3\n4 0 4 6 2\n4 1 3 7 5\n";
  return os.str();
}

TriangleMesh cube(double a) {
  std::istringstream in(cube_off(a));
  return read_off(in, "/entity/file");
}

std::string error_of(const TriangleMesh& m) {
  try {
    check_closed_oriented(m, "/entity/file");
  } catch (const InputError& e) {
    CHECK(e.pointer() == "/entity/file");
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("Triangle mesh: an OFF cube of quads is a closed, outward solid of its volume") {
  const TriangleMesh m = cube(2);
  CHECK(m.vertices.size() == 8);
  CHECK(m.triangles.size() == 12);
  CHECK(error_of(m).empty());
  CHECK(signed_volume(m) == Approx(8).epsilon(1e-14));
  TriangleMesh in = m;
  for (auto& t : in.triangles) std::swap(t[1], t[2]);
  CHECK(error_of(in).empty());
  CHECK(signed_volume(in) == Approx(-8).epsilon(1e-14));
}

TEST_CASE("Triangle mesh: what keeps a mesh from bounding a solid is said, with where") {
  TriangleMesh open = cube(1);
  open.triangles.pop_back();
  CHECK(error_of(open).find("not closed") != std::string::npos);
  TriangleMesh flipped = cube(1);
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  CHECK(error_of(flipped).find("not consistently oriented") != std::string::npos);
  TriangleMesh fin = cube(1);  // a third triangle on an edge of the cube
  fin.vertices.push_back(Eigen::Vector3d(0.5, -1, 0.5));
  fin.triangles.push_back({0, 1, 8});
  fin.triangles.push_back({1, 0, 8});
  CHECK(error_of(fin).find("not manifold") != std::string::npos);
  TriangleMesh flat = cube(1);
  flat.triangles[0] = {0, 1, 1};
  CHECK(error_of(flat).find("triangle 0") != std::string::npos);
}

TEST_CASE("Triangle mesh: repeated vertices merged, as an STL file gives them") {
  const TriangleMesh m = cube(1);
  TriangleMesh soup;  // every triangle with vertices of its own
  for (const auto& t : m.triangles) {
    const int base = int(soup.vertices.size());
    for (int i = 0; i < 3; ++i) soup.vertices.push_back(m.vertices[t[i]] + Eigen::Vector3d::Constant(1e-15));
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  CHECK_FALSE(error_of(soup).empty());
  const TriangleMesh merged = merged_vertices(soup, 1e-12);
  CHECK(merged.vertices.size() == 8);
  CHECK(error_of(merged).empty());
  CHECK(signed_volume(merged) == Approx(1).epsilon(1e-12));
}

TEST_CASE("Triangle mesh: a mesh that crosses itself is named, one that only touches along shared corners is not") {
  // two closed cubes as one mesh: apart, and overlapping (the second pushed into the first)
  for (const double shift : {1.5, 0.5}) {
    TriangleMesh two = cube(1);
    const TriangleMesh second = cube(1);
    for (const auto& p : second.vertices) two.vertices.push_back(p + Eigen::Vector3d(shift, 0.25, 0.25));
    for (const auto& t : second.triangles) two.triangles.push_back({t[0] + 8, t[1] + 8, t[2] + 8});
    std::string why;
    try {
      check_not_crossing_itself(two, "/entity/file");
    } catch (const InputError& e) {
      why = e.what();
    }
    CAPTURE(shift, why);
    CHECK((shift < 1) == (why.find("crosses itself") != std::string::npos));
  }
  CHECK_NOTHROW(check_not_crossing_itself(cube(1), "/entity/file"));
}

TEST_CASE("Triangle mesh: bad OFF text is an input error") {
  for (const std::string text : {"OFF\n8 6\n", "PLY\n", "OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 1 7\n"}) {
    std::istringstream in(text);
    CHECK_THROWS_AS(read_off(in, "/entity/file"), InputError);
  }
  // a concave quad (an arrowhead), whose fan would cover part of it twice
  std::istringstream arrow("OFF\n5 4 0\n0 0 0\n2 1 0\n0 2 0\n0.5 1 0\n0 0 1\n4 0 1 2 3\n");
  try {
    read_off(arrow, "/entity/file");
    FAIL("a concave polygon read");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("face 0 of the OFF file is not a convex polygon") != std::string::npos);
  }
}
