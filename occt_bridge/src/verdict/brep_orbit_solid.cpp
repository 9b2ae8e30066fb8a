// A B-rep solid whose faces lie on planes, quadrics and tori as an orbit solid: the reference of
// one-joint sweeps of parts read from STEP.
#include <BRepAdaptor_Surface.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepBndLib.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include "base/internal.hpp"
#include "verdict/solid_rays.hpp"

namespace sweep::occt {

namespace {

/// The faces, their rays' intersectors and a classifier, shared by the faces' and the inside test.
struct BrepState {
  std::vector<FaceHit> faces;
  BRepClass3d_SolidClassifier classifier;
  double tol = 0;

  bool inside(const Eigen::Vector3d& p) {
    const int by_ray = ray_inside(faces, p, tol);
    if (by_ray >= 0) return by_ray == 1;
    classifier.Perform(to_pnt(p), tol);
    return classifier.State() == TopAbs_IN;
  }
};

const char* surface_kind_name(GeomAbs_SurfaceType t) {
  switch (t) {
    case GeomAbs_BezierSurface: return "Bezier surface";
    case GeomAbs_BSplineSurface: return "B-spline surface";
    case GeomAbs_SurfaceOfRevolution: return "surface of revolution";
    case GeomAbs_SurfaceOfExtrusion: return "surface of extrusion";
    case GeomAbs_OffsetSurface: return "offset surface";
    default: return "surface of another kind";
  }
}

Eigen::AlignedBox3d eigen_box(const Bnd_Box& b) {
  double x0, y0, z0, x1, y1, z1;
  b.Get(x0, y0, z0, x1, y1, z1);
  return {Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1)};
}

}  // namespace

OrbitSolidPtr brep_orbit_solid(const TopoDS_Shape& body, double tol) {
  int index = 0;  // (faces in the order the shape holds them)
  for (TopExp_Explorer ex(body, TopAbs_FACE); ex.More(); ex.Next(), ++index) {
    const BRepAdaptor_Surface s(TopoDS::Face(ex.Current()), false);
    if (!implicit_surface(s))
      throw InputError("/entity/file", "face " + std::to_string(index) + " of the solid lies on a " +
                                           surface_kind_name(s.GetType()) +
                                           ": its orbits' crossings have no exact form (planes, cylinders, cones, "
                                           "spheres and tori do)");
  }
  auto state = std::make_shared<BrepState>();
  state->tol = tol;
  state->faces = face_hits(body, tol);
  state->classifier.Load(body);
  std::vector<OrbitFace> faces;
  for (std::size_t k = 0; k < state->faces.size(); ++k) {
    const FaceHit& h = state->faces[k];
    // (a root whose point has no clear parameters on the surface is a cut: one too many changes
    // nothing, the pieces are classified)
    faces.push_back({*h.implicit, eigen_box(h.box),
                     [state, k](const Eigen::Vector3d& p) { return on_face(state->faces[k], p, state->tol).value_or(true); }});
  }
  Bnd_Box box;
  BRepBndLib::Add(body, box);
  box.SetGap(tol);
  return orbit_faces(std::move(faces), [state](const Eigen::Vector3d& p) { return state->inside(p); }, eigen_box(box));
}

}  // namespace sweep::occt
