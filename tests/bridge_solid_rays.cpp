// Whether a point is inside a solid by rays against its exact faces, against closed forms.
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <catch2/catch.hpp>

#include <random>

#include "verdict/solid_rays.hpp"

using namespace sweep;

TEST_CASE("Rays against exact faces: a box's inside, outside and boundary") {
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(-0.5, 0.2, 0.1), 1.0, 2.0, 3.0).Shape();
  std::vector<occt::FaceHit> faces = occt::face_hits(box, 1e-9);
  CHECK(faces.size() == 6);
  CHECK(occt::ray_inside(faces, Eigen::Vector3d(0, 1, 1.5), 1e-9) == 1);
  CHECK(occt::ray_inside(faces, Eigen::Vector3d(0.49, 2.19, 3.09), 1e-9) == 1);
  CHECK(occt::ray_inside(faces, Eigen::Vector3d(0.51, 1, 1.5), 1e-9) == 0);
  CHECK(occt::ray_inside(faces, Eigen::Vector3d(-3, -3, -3), 1e-9) == 0);
  CHECK(occt::ray_inside(faces, Eigen::Vector3d(0.5, 1, 1.5), 1e-9) == -1);  // on a face: no clear answer
}

TEST_CASE("Rays against exact faces: a torus against its implicit equation at random points off its surface") {
  const double R = 2.0, r = 0.6;
  const TopoDS_Shape torus = BRepPrimAPI_MakeTorus(gp_Ax2(gp_Pnt(0.3, -0.1, 0.2), gp_Dir(0.2, 0.1, 1)), R, r).Shape();
  const Eigen::Vector3d c(0.3, -0.1, 0.2), w = Eigen::Vector3d(0.2, 0.1, 1).normalized();
  std::vector<occt::FaceHit> faces = occt::face_hits(torus, 1e-9);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(-3, 3);
  int decided = 0, right = 0;
  for (int k = 0; k < 300; ++k) {
    const Eigen::Vector3d x = c + Eigen::Vector3d(coord(rng), coord(rng), 0.4 * coord(rng));
    const Eigen::Vector3d d = x - c;
    const double z = w.dot(d), rho = (d - z * w).norm();
    const double f = std::hypot(rho - R, z) - r;  // signed distance to the torus
    if (std::abs(f) < 1e-3) continue;
    const int inside = occt::ray_inside(faces, x, 1e-9);
    if (inside < 0) continue;
    ++decided;
    right += (inside == 1) == (f < 0);
  }
  CHECK(decided >= 280);
  CHECK(right == decided);
}
