// A B-rep shape as the engine's Entity: exact faces and edges as patches, a distance bound from a
// triangulation whose deviation is measured.
#include "entity/brep_entity.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom_Curve.hxx>
#include <Geom_Surface.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <limits>
#include <memory>
#include <mutex>

#include "base/internal.hpp"
#include "sweep/mesh_index.hpp"
#include "sweep/settings.hpp"
#include "verdict/verdict.hpp"

namespace sweep::occt {
namespace {

/// The closed form of a face's surface, in PatchForm's frame, when it is elementary.
PatchForm surface_form(const BRepAdaptor_Surface& s) {
  PatchForm f;
  auto frame = [&f](const gp_Ax3& a) {
    f.origin = to_eigen(a.Location());
    f.axis = to_eigen(a.Direction().XYZ());
    f.ref = to_eigen(a.XDirection().XYZ());
  };
  switch (s.GetType()) {
    case GeomAbs_Plane:
      f.kind = PatchForm::Kind::Plane;
      frame(s.Plane().Position());
      // OCCT's (u, v) run along X and Y; PatchForm's along ref and axis x ref, the same when
      // the frame is right-handed
      f.surface_parameters = s.Plane().Position().Direct();
      break;
    case GeomAbs_Cylinder:
      f.kind = PatchForm::Kind::Cylinder;
      frame(s.Cylinder().Position());
      f.radius = s.Cylinder().Radius();
      f.surface_parameters = f.revolved = s.Cylinder().Position().Direct();
      break;
    case GeomAbs_Cone:  // OCCT's v runs along the slant, not the axis
      f.kind = PatchForm::Kind::Cone;
      frame(s.Cone().Position());
      f.radius = s.Cone().RefRadius();
      f.semi_angle = s.Cone().SemiAngle();
      f.revolved = s.Cone().Position().Direct();
      break;
    case GeomAbs_Sphere:
      f.kind = PatchForm::Kind::Sphere;
      frame(s.Sphere().Position());
      f.radius = s.Sphere().Radius();
      f.surface_parameters = f.revolved = s.Sphere().Position().Direct();
      break;
    case GeomAbs_Torus:
      f.kind = PatchForm::Kind::Torus;
      frame(s.Torus().Position());
      f.radius = s.Torus().MajorRadius();
      f.minor = s.Torus().MinorRadius();
      f.surface_parameters = f.revolved = s.Torus().Position().Direct();
      break;
    default:
      break;
  }
  return f;
}

/// The closed form of an edge's curve when it is a line, a circle or an ellipse.
PatchForm curve_form(const BRepAdaptor_Curve& c) {
  PatchForm f;
  switch (c.GetType()) {
    case GeomAbs_Line:
      f.kind = PatchForm::Kind::Line;
      f.origin = to_eigen(c.Line().Location());
      f.axis = to_eigen(c.Line().Direction().XYZ());
      break;
    case GeomAbs_Circle:
      f.kind = PatchForm::Kind::Circle;
      f.origin = to_eigen(c.Circle().Location());
      f.axis = to_eigen(c.Circle().Axis().Direction().XYZ());
      f.ref = to_eigen(c.Circle().XAxis().Direction().XYZ());
      f.radius = c.Circle().Radius();
      break;
    case GeomAbs_Ellipse:
      f.kind = PatchForm::Kind::Ellipse;
      f.origin = to_eigen(c.Ellipse().Location());
      f.axis = to_eigen(c.Ellipse().Axis().Direction().XYZ());
      f.ref = to_eigen(c.Ellipse().XAxis().Direction().XYZ());
      f.radius = c.Ellipse().MajorRadius();
      f.minor = c.Ellipse().MinorRadius();
      break;
    default:
      break;
  }
  return f;
}

PatchPtr face_patch(const TopoDS_Face& face, int index) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);  // located: a moved copy
  auto map = [surface](const double* s) {
    gp_Pnt p;
    gp_Vec du, dv;
    surface->D1(s[0], s[1], p, du, dv);
    return PatchPoint{to_eigen(p), to_eigen(du), to_eigen(dv)};
  };
  auto patch = std::make_shared<Patch>(2, std::vector<double>{u0, v0}, std::vector<double>{u1, v1}, std::move(map),
                                       surface_form(BRepAdaptor_Surface(face)),
                                       "face " + std::to_string(index) + " of the B-rep",
                                       face.Orientation() == TopAbs_REVERSED ? -1 : 1);
  patch->trimmed = true;
  return patch;
}

PatchPtr edge_patch(const TopoDS_Edge& edge, int index) {
  double a, b;
  const Handle(Geom_Curve) curve = BRep_Tool::Curve(edge, a, b);  // located: a moved copy
  if (curve.IsNull()) return nullptr;
  auto map = [curve](const double* s) {
    gp_Pnt p;
    gp_Vec d;
    curve->D1(s[0], p, d);
    return PatchPoint{to_eigen(p), to_eigen(d), Eigen::Vector3d::Zero()};
  };
  return std::make_shared<Patch>(1, std::vector<double>{a}, std::vector<double>{b}, std::move(map),
                                 curve_form(BRepAdaptor_Curve(edge)),
                                 "edge " + std::to_string(index) + " of the B-rep");
}

/// The largest distance measured between the faces and their triangulation: at each triangle's
/// centroid and the midpoints of its sides, taken in the face's parameters, the point of the
/// surface against the triangle's point at the same barycentric place.
double triangulation_deviation(const TopoDS_Shape& meshed) {
  double worst = 0;
  for (TopExp_Explorer ex(meshed, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& face = TopoDS::Face(ex.Current());
    TopLoc_Location loc;
    const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
    if (tri.IsNull() || !tri->HasUVNodes()) continue;
    const gp_Trsf T = loc.Transformation();
    const BRepAdaptor_Surface surface(face, false);
    for (int k = 1; k <= tri->NbTriangles(); ++k) {
      int n[3];
      tri->Triangle(k).Get(n[0], n[1], n[2]);
      gp_Pnt2d uv[3];
      gp_Pnt xyz[3];
      for (int i = 0; i < 3; ++i) {
        uv[i] = tri->UVNode(n[i]);
        xyz[i] = tri->Node(n[i]).Transformed(T);
      }
      static const double weights[4][3] = {{1. / 3, 1. / 3, 1. / 3}, {0.5, 0.5, 0}, {0, 0.5, 0.5}, {0.5, 0, 0.5}};
      for (const auto& w : weights) {
        double u = 0, v = 0;
        gp_XYZ m(0, 0, 0);
        for (int i = 0; i < 3; ++i) {
          u += w[i] * uv[i].X();
          v += w[i] * uv[i].Y();
          m += w[i] * xyz[i].XYZ();
        }
        worst = std::max(worst, surface.Value(u, v).Distance(gp_Pnt(m)));
      }
    }
  }
  return worst;
}

/// The distance bound of a solid: see brep_entity().
class BrepDistance : public SignedDistance {
 public:
  /// `deviation`: how far the faces and the triangles may be apart (measured, with a margin).
  BrepDistance(TopoDS_Shape solid, std::vector<Triangle> triangles, double deviation, double classifier_tol)
      : solid_(std::move(solid)), mesh_(std::move(triangles)), deviation_(deviation), classifier_tol_(classifier_tol) {}
  double operator()(const Eigen::Vector3d& p) const override {
    const double d = mesh_.distance(p);
    if (d < slack()) return std::numeric_limits<double>::min();  // near the faces: either side
    return mesh_.inside(p) ? -(d - deviation_) : d - deviation_;
  }
  /// Within twice the deviation of the triangles, their side is not the faces' side for sure.
  double slack() const override { return 2 * deviation_; }
  double below(const Eigen::Vector3d& p, double limit) const override {
    const double d = mesh_.distance_below(p, std::max(limit, 0.0) + slack());
    if (d < slack()) return std::numeric_limits<double>::min();
    if (mesh_.inside(p)) return -deviation_;  // (the faces are at least that far)
    return d - deviation_;
  }
  /// Exact: by the triangulation away from the faces, by OCCT's classifier near them.
  bool inside(const Eigen::Vector3d& p) const {
    if (mesh_.distance_below(p, slack()) >= slack()) return mesh_.inside(p);
    BRepClass3d_SolidClassifier classifier(solid_, to_pnt(p), classifier_tol_);
    return classifier.State() == TopAbs_IN || classifier.State() == TopAbs_ON;
  }

 private:
  TopoDS_Shape solid_;
  MeshIndex mesh_;
  double deviation_, classifier_tol_;
};

class BrepEntity : public Entity {
 public:
  BrepEntity(const TopoDS_Shape& shape, EntityKind kind) : shape_(shape), kind_(kind), box_(box_of(shape)) {
    if (box_.isEmpty()) throw ComputeError("the B-rep entity has no geometry");
    const TopExp_Explorer solids(shape, TopAbs_SOLID);
    dimension_ = solids.More() ? 3 : 2;
    TopTools_IndexedMapOfShape faces;
    TopExp::MapShapes(shape, TopAbs_FACE, faces);
    for (int k = 1; k <= faces.Extent(); ++k) faces_.push_back(face_patch(TopoDS::Face(faces(k)), k));
    add_edges(shape);
  }
  EntityKind kind() const override { return kind_; }
  int dimension() const override { return dimension_; }
  Eigen::AlignedBox3d box() const override { return box_; }
  bool inside(const Eigen::Vector3d& p) const override { return dimension_ == 3 && bound().inside(p); }
  bool has_distance_bound() const override { return dimension_ == 3; }
  double distance(const Eigen::Vector3d& p) const override { return bound()(p); }
  bool tight_distance() const override { return false; }
  std::unique_ptr<SignedDistance> distance_bound() const override {
    if (dimension_ != 3) return nullptr;
    struct Shared : SignedDistance {
      std::shared_ptr<const BrepDistance> d;
      double operator()(const Eigen::Vector3d& p) const override { return (*d)(p); }
      double slack() const override { return d->slack(); }
      double below(const Eigen::Vector3d& p, double limit) const override { return d->below(p, limit); }
    };
    auto out = std::make_unique<Shared>();
    bound();
    out->d = distance_;
    return out;
  }
  OrbitSolidPtr orbit_solid() const override { return nullptr; }
  const std::vector<PatchPtr>& faces() const override { return faces_; }
  const std::vector<PatchPtr>& edges() const override { return edges_; }

 private:
  /// Edges where two faces meet, or the free edges of a set of faces: not seams (one face on both
  /// sides), not degenerate ones.
  void add_edges(const TopoDS_Shape& shape) {
    TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
    TopExp::MapShapesAndAncestors(shape, TopAbs_EDGE, TopAbs_FACE, edge_faces);
    for (int k = 1; k <= edge_faces.Extent(); ++k) {
      const TopoDS_Edge& e = TopoDS::Edge(edge_faces.FindKey(k));
      if (BRep_Tool::Degenerated(e)) continue;
      const TopTools_ListOfShape& around = edge_faces(k);
      if (!around.IsEmpty() && BRep_Tool::IsClosed(e, TopoDS::Face(around.First()))) continue;
      if (PatchPtr p = edge_patch(e, k)) edges_.push_back(std::move(p));
    }
  }
  /// The distance bound, built at the first call (most runs never ask for it).
  const BrepDistance& bound() const {
    std::call_once(built_, [this] {
      const double size = std::max(box_.sizes().maxCoeff(), 1e-300);
      // a copy of its own: the triangulation stays off the shape the run sweeps, and no step
      // of the run meshes the shape the classifier reads
      const TopoDS_Shape copy = BRepBuilderAPI_Copy(shape_, true, false).Shape();
      std::string problem;
      std::vector<Triangle> tris = triangulate(copy, Settings::brep_distance_deflection * size, &problem);
      if (!problem.empty())
        throw ComputeError("the B-rep entity's triangulation, behind its distance bound, is not usable: " + problem);
      const double deviation = 2 * triangulation_deviation(copy) + Settings::resolution * size;
      distance_ = std::make_shared<const BrepDistance>(copy, std::move(tris), deviation, Settings::resolution * size);
    });
    return *distance_;
  }

  TopoDS_Shape shape_;
  EntityKind kind_;
  Eigen::AlignedBox3d box_;
  int dimension_ = 3;
  std::vector<PatchPtr> faces_, edges_;
  mutable std::once_flag built_;
  mutable std::shared_ptr<const BrepDistance> distance_;
};

}  // namespace

EntityPtr brep_entity(const TopoDS_Shape& shape, EntityKind kind) { return std::make_shared<BrepEntity>(shape, kind); }

}  // namespace sweep::occt
