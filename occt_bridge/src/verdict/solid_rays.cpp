// Whether a point is inside a solid by rays against its exact faces.
#include "verdict/solid_rays.hpp"

#include <BRepBndLib.hxx>
#include <Precision.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gp_Lin.hxx>

#include <algorithm>
#include <cmath>

namespace sweep::occt {

std::vector<FaceHit> face_hits(const TopoDS_Shape& shape, double tol) {
  std::vector<std::pair<int, TopoDS_Face>> faces;
  for (TopExp_Explorer ex(shape, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& f = TopoDS::Face(ex.Current());
    const GeomAbs_SurfaceType type = BRepAdaptor_Surface(f, false).GetType();
    const bool analytic = type == GeomAbs_Plane || type == GeomAbs_Cylinder || type == GeomAbs_Cone ||
                          type == GeomAbs_Sphere;
    faces.push_back({analytic ? 0 : 1, f});
  }
  std::stable_sort(faces.begin(), faces.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<FaceHit> out;
  for (const auto& f : faces) {
    FaceHit h;
    BRepBndLib::Add(f.second, h.box);
    h.box.SetGap(tol);
    // points met are classified on the face itself, not within its edges' tolerances (which
    // would take points off the face for points on it)
    h.inter = std::make_unique<IntCurvesFace_Intersector>(f.second, tol, true, false);
    h.surface = std::make_unique<BRepAdaptor_Surface>(f.second);
    if (h.surface->GetType() == GeomAbs_Torus) {
      h.torus = std::make_unique<gp_Torus>(h.surface->Torus());
      h.fc = std::make_unique<BRepTopAdaptor_FClass2d>(f.second, tol);
    }
    out.push_back(std::move(h));
  }
  return out;
}

/// The crossings of a half-line from x with the faces, counted, and the first one's transition
/// (leaving means x is inside), along up to three directions.
int ray_inside(std::vector<FaceHit>& faces, const Eigen::Vector3d& x, double tol) {
  static const double dirs[3][3] = {{0.5773, 0.4719, 0.6663}, {-0.3981, 0.8377, -0.3738}, {0.7122, -0.2093, -0.6700}};
  for (const auto& d : dirs) {
    const gp_Lin line(to_pnt(x), gp_Dir(d[0], d[1], d[2]));
    int crossings = 0;
    double first = Precision::Infinite();
    bool first_leaves = false, clear = true;
    for (auto& h : faces) {
      if (h.box.IsOut(line)) continue;
      h.inter->Perform(line, -tol, Precision::Infinite());
      if (!h.inter->IsDone()) continue;  // a face without extent in one direction
      for (int k = 1; k <= h.inter->NbPnt(); ++k) {
        const double w = h.inter->WParameter(k);
        const IntCurveSurface_TransitionOnCurve tr = h.inter->Transition(k);
        // a ray that grazes the face (within about 3 degrees) crosses it twice close together,
        // and OCCT's intersector can find one crossing of the two (a point 2e-5 outside an
        // extruded ellipse was called inside): no clear answer along it
        gp_Pnt at;
        gp_Vec du, dv;
        h.surface->D1(h.inter->UParameter(k), h.inter->VParameter(k), at, du, dv);
        const gp_Vec normal = du.Crossed(dv);
        const bool grazing = normal.Magnitude() > 0 && std::abs(normal.Dot(line.Direction())) < 0.05 * normal.Magnitude();
        if (w < tol || tr == IntCurveSurface_Tangent || grazing || h.inter->State(k) != TopAbs_IN) {
          clear = false;
          break;
        }
        ++crossings;
        if (w < first) {
          first = w;
          first_leaves = tr == IntCurveSurface_Out;
        }
      }
      if (!clear) break;
    }
    if (!clear) continue;
    if (crossings == 0) return 0;
    const bool by_count = crossings % 2 == 1;
    if (by_count == first_leaves) return by_count ? 1 : 0;
  }
  return -1;
}

}  // namespace sweep::occt
