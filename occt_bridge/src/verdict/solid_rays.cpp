// Whether a point is inside a solid by rays against its exact faces.
#include "verdict/solid_rays.hpp"

#include <BRepBndLib.hxx>
#include <ElSLib.hxx>
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
                          type == GeomAbs_Sphere || type == GeomAbs_Torus;
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
    h.implicit = implicit_surface(*h.surface);
    if (h.implicit) h.fc = std::make_unique<BRepTopAdaptor_FClass2d>(f.second, tol);
    out.push_back(std::move(h));
  }
  return out;
}

namespace {

/// The frame on a surface's axis: origin at its location, local z along its direction.
Eigen::Isometry3d axis_frame(const gp_Ax3& ax) {
  const Eigen::Vector3d z = to_eigen(gp_Vec(ax.Direction())).normalized();
  const Eigen::Vector3d x = z.unitOrthogonal();
  Eigen::Isometry3d F = Eigen::Isometry3d::Identity();
  F.linear().col(0) = x;
  F.linear().col(1) = z.cross(x);
  F.linear().col(2) = z;
  F.translation() = to_eigen(ax.Location());
  return F;
}

}  // namespace

std::optional<OrbitSurface> implicit_surface(const BRepAdaptor_Surface& s) {
  using K = OrbitSurface::Kind;
  OrbitSurface o;
  switch (s.GetType()) {
    case GeomAbs_Plane:
      o.kind = K::Plane;
      o.frame = axis_frame(s.Plane().Position());
      return o;
    case GeomAbs_Cylinder:
      o.kind = K::Cylinder;
      o.frame = axis_frame(s.Cylinder().Position());
      o.radius = s.Cylinder().Radius();
      return o;
    case GeomAbs_Cone:
      // OCCT's cone: radius RefRadius + v sin(a) at height v cos(a) along its axis
      o.kind = K::Cone;
      o.frame = axis_frame(s.Cone().Position());
      o.radius = s.Cone().RefRadius();
      o.slope = std::tan(s.Cone().SemiAngle());
      return o;
    case GeomAbs_Sphere:
      o.kind = K::Sphere;
      o.frame = axis_frame(s.Sphere().Position());
      o.radius = s.Sphere().Radius();
      return o;
    case GeomAbs_Torus:
      o.kind = K::Torus;
      o.frame = axis_frame(s.Torus().Position());
      o.radius = s.Torus().MajorRadius();
      o.minor = s.Torus().MinorRadius();
      return o;
    default:
      return std::nullopt;
  }
}

std::optional<bool> on_face(const FaceHit& h, const Eigen::Vector3d& p, double tol) {
  const gp_Pnt P = to_pnt(p);
  double u = 0, v = 0;
  switch (h.surface->GetType()) {
    case GeomAbs_Plane: ElSLib::Parameters(h.surface->Plane(), P, u, v); break;
    case GeomAbs_Cylinder: ElSLib::Parameters(h.surface->Cylinder(), P, u, v); break;
    case GeomAbs_Cone: ElSLib::Parameters(h.surface->Cone(), P, u, v); break;
    case GeomAbs_Sphere: ElSLib::Parameters(h.surface->Sphere(), P, u, v); break;
    case GeomAbs_Torus: ElSLib::Parameters(h.surface->Torus(), P, u, v); break;
    default: return std::nullopt;
  }
  if (h.surface->Value(u, v).Distance(P) > tol) return std::nullopt;
  const TopAbs_State st = h.fc->Perform(gp_Pnt2d(u, v));
  return st == TopAbs_IN || st == TopAbs_ON;
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
