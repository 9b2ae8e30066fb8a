// Entity -> OCCT shape: exact primitives, fitted parametric curves and surfaces, files.
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <GeomLib_IsPlanarSurface.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Plane.hxx>
#include <Geom_SphericalSurface.hxx>
#include <gp_Ax3.hxx>
#include <Eigen/Dense>
#include <GeomAPI_PointsToBSplineSurface.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeFix_Shape.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>

#include "base/internal.hpp"
#include "entity/elliptic_cylinder.hpp"
#include "entity/mesh_solid.hpp"
#include "faces/patch_face.hpp"
#include "sweep/entity.hpp"
#include "sweep/error.hpp"

namespace sweep::occt {

gp_Trsf to_trsf(const Eigen::Isometry3d& T) {
  gp_Trsf t;
  const auto& M = T.matrix();
  t.SetValues(M(0, 0), M(0, 1), M(0, 2), M(0, 3), M(1, 0), M(1, 1), M(1, 2), M(1, 3), M(2, 0), M(2, 1),
              M(2, 2), M(2, 3));
  return t;
}

TopoDS_Shape moved(const TopoDS_Shape& s, const Eigen::Isometry3d& T) {
  return BRepBuilderAPI_Transform(s, to_trsf(T), true).Shape();
}

namespace {

gp_Pnt eval_xyz(const EntitySpec& e, const double* uv) {
  return gp_Pnt(e.xyz[0].eval(uv), e.xyz[1].eval(uv), e.xyz[2].eval(uv));
}

/// Fits a B-spline curve to the parametric curve, doubling the samples until the error measured
/// between samples is below tol.
Handle(Geom_BSplineCurve) fit_curve(const EntitySpec& e, double tol, double* err) {
  const double lo = e.params[0].lo, hi = e.params[0].hi;
  for (int n = 16; n <= 4096; n *= 2) {
    TColgp_Array1OfPnt pts(1, n + 1);
    TColStd_Array1OfReal par(1, n + 1);
    for (int i = 0; i <= n; ++i) {
      double u = lo + (hi - lo) * i / n;
      pts.SetValue(i + 1, eval_xyz(e, &u));
      par.SetValue(i + 1, u);
    }
    GeomAPI_PointsToBSpline fit(pts, par, 3, 8, GeomAbs_C2, 0.1 * tol);
    if (!fit.IsDone()) continue;
    Handle(Geom_BSplineCurve) c = fit.Curve();
    double e_max = 0;
    for (int i = 0; i < 4 * n; ++i) {
      double u = lo + (hi - lo) * (i + 0.5) / (4 * n);
      e_max = std::max(e_max, c->Value(u).Distance(eval_xyz(e, &u)));
    }
    if (e_max <= tol || n == 4096) {
      *err = std::max(*err, e_max);
      return c;
    }
  }
  throw ComputeError("could not fit the curve entity");
}

Handle(Geom_BSplineSurface) fit_surface(const EntitySpec& e, double tol, double* err) {
  const double u0 = e.params[0].lo, u1 = e.params[0].hi, v0 = e.params[1].lo, v1 = e.params[1].hi;
  auto exact = [&](double fu, double fv) {
    double uv[2] = {u0 + (u1 - u0) * fu, v0 + (v1 - v0) * fv};
    return eval_xyz(e, uv);
  };
  double e_max = 0;
  Handle(Geom_BSplineSurface) s = fit_grid_surface(exact, tol, 0.1 * tol, 16, 256, &e_max);
  if (s.IsNull()) throw ComputeError("could not fit the surface entity");
  *err = std::max(*err, e_max);
  return s;
}

/// A piece of a parametric surface's boundary: a fitted curve, a line or a circle kept exact.
struct BoundaryCurve {
  Handle(Geom_Curve) curve;
  double first = 0, last = 0;
};

/// The images of a parametric surface's domain sides, counter-clockwise in (u, v), less the sides
/// that collapse to a point (poles) and the pairs that coincide (the two sides of a periodic
/// parameter), each fitted within tol with lines and circles recognised. False when a fit fails.
bool boundary_curves(const EntitySpec& e, double tol, std::vector<BoundaryCurve>* out) {
  const double u0 = e.params[0].lo, u1 = e.params[0].hi, v0 = e.params[1].lo, v1 = e.params[1].hi;
  const int n = 64;
  auto side = [&](int k) {
    std::vector<gp_Pnt> pts;
    for (int i = 0; i <= n; ++i) {
      const double t = double(i) / n;
      double uv[2];
      switch (k) {
        case 0: uv[0] = u0 + (u1 - u0) * t; uv[1] = v0; break;
        case 1: uv[0] = u1; uv[1] = v0 + (v1 - v0) * t; break;
        case 2: uv[0] = u1 - (u1 - u0) * t; uv[1] = v1; break;
        default: uv[0] = u0; uv[1] = v1 - (v1 - v0) * t; break;
      }
      pts.push_back(eval_xyz(e, uv));
    }
    return pts;
  };
  std::vector<std::vector<gp_Pnt>> sides;
  for (int k = 0; k < 4; ++k) sides.push_back(side(k));
  auto collapsed = [&](const std::vector<gp_Pnt>& p) {
    for (const auto& q : p)
      if (q.Distance(p[0]) > tol) return false;
    return true;
  };
  auto same_reversed = [&](const std::vector<gp_Pnt>& a, const std::vector<gp_Pnt>& b) {
    for (std::size_t i = 0; i < a.size(); ++i)
      if (a[i].Distance(b[b.size() - 1 - i]) > tol) return false;
    return true;
  };
  std::vector<bool> keep(4, true);
  for (int k = 0; k < 4; ++k)
    if (collapsed(sides[k])) keep[k] = false;
  for (int k = 0; k < 2; ++k)
    if (keep[k] && keep[k + 2] && same_reversed(sides[k], sides[k + 2])) keep[k] = keep[k + 2] = false;
  out->clear();
  for (int k = 0; k < 4; ++k) {
    if (!keep[k]) continue;
    TColgp_Array1OfPnt arr(1, n + 1);
    for (int i = 0; i <= n; ++i) arr.SetValue(i + 1, sides[k][i]);
    GeomAPI_PointsToBSpline fit(arr, 3, 8, GeomAbs_C2, 0.1 * tol);
    if (!fit.IsDone()) return false;
    BoundaryCurve bc;
    bc.curve = fit.Curve();
    bc.first = bc.curve->FirstParameter();
    bc.last = bc.curve->LastParameter();
    bc.curve = canonical_curve(bc.curve, bc.first, bc.last, tol);
    out->push_back(bc);
  }
  return true;
}

/// The area of the face the fitted surface makes over its whole domain.
double fitted_area(const Handle(Geom_BSplineSurface)& fitted, double tol) {
  GProp_GProps g;
  BRepGProp::SurfaceProperties(BRepBuilderAPI_MakeFace(fitted, tol).Face(), g);
  return g.Mass();
}

/// A planar parametric surface as an exact plane face bounded by its boundary curves. Returns a
/// null face when the surface is not planar or the boundary does not close.
TopoDS_Face planar_face(const EntitySpec& e, const Handle(Geom_BSplineSurface)& fitted, double tol) {
  GeomLib_IsPlanarSurface isp(fitted, 10 * tol);
  if (!isp.IsPlanar()) return TopoDS_Face();
  std::vector<BoundaryCurve> curves;
  if (!boundary_curves(e, tol, &curves)) return TopoDS_Face();
  BRepBuilderAPI_MakeWire wire;
  for (const auto& bc : curves) {
    BRepBuilderAPI_MakeEdge me(bc.curve, bc.first, bc.last);
    if (!me.IsDone()) return TopoDS_Face();
    wire.Add(me.Edge());
    if (!wire.IsDone()) return TopoDS_Face();
  }
  if (!wire.IsDone() || !wire.Wire().Closed()) return TopoDS_Face();
  Handle(Geom_Plane) plane = new Geom_Plane(isp.Plan());
  BRepBuilderAPI_MakeFace mf(plane, wire.Wire(), true);
  if (!mf.IsDone()) return TopoDS_Face();
  TopoDS_Face face = mf.Face();
  // the same area as the fitted face, or not used
  GProp_GProps a;
  BRepGProp::SurfaceProperties(face, a);
  const double b = fitted_area(fitted, tol);
  if (std::abs(std::abs(a.Mass()) - b) > 1e-6 * b) return TopoDS_Face();
  if (a.Mass() < 0) face.Reverse();
  return face;
}

/// A parametric surface that is a spherical cap (its points on one sphere within tol, its
/// boundary one whole circle) as the exact cap of a spherical surface whose axis goes through the
/// circle's centre. Returns a null face otherwise, or when the area differs from the fitted face's.
TopoDS_Face spherical_cap_face(const EntitySpec& e, const Handle(Geom_BSplineSurface)& fitted, double tol) {
  // the sphere through sampled points (algebraic least squares), then the largest distance to it
  const int n = 16;
  std::vector<gp_Pnt> pts;
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= n; ++k) {
      const double uv[2] = {e.params[0].lo + (e.params[0].hi - e.params[0].lo) * (i + 0.37 * (i < n)) / n,
                            e.params[1].lo + (e.params[1].hi - e.params[1].lo) * (k + 0.61 * (k < n)) / n};
      pts.push_back(eval_xyz(e, uv));
    }
  Eigen::MatrixXd A(pts.size(), 4);
  Eigen::VectorXd rhs(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const gp_Pnt& p = pts[i];
    A.row(i) << p.X(), p.Y(), p.Z(), 1.0;
    rhs(i) = -(p.X() * p.X() + p.Y() * p.Y() + p.Z() * p.Z());
  }
  const Eigen::Vector4d sol = A.colPivHouseholderQr().solve(rhs);
  Eigen::Vector3d c = -0.5 * sol.head<3>();
  if (!(c.squaredNorm() - sol(3) > 0)) return TopoDS_Face();
  std::vector<BoundaryCurve> curves;
  if (!boundary_curves(e, tol, &curves) || curves.size() != 1) return TopoDS_Face();
  Handle(Geom_Circle) rim = Handle(Geom_Circle)::DownCast(curves[0].curve);
  if (rim.IsNull() || std::abs(curves[0].last - curves[0].first - 2 * M_PI) > 1e-9) return TopoDS_Face();
  // The cap's axis is the rim's normal (the circle through exact points is accurate to rounding;
  // the fitted centre is not quite): the centre goes on the rim's axis, the radius through the rim.
  const Eigen::Vector3d m = to_eigen(rim->Location()), axis = to_eigen(gp_Vec(rim->Axis().Direction()));
  c = m + axis * (c - m).dot(axis);
  const double R = (to_eigen(rim->Value(0.0)) - c).norm();
  for (const auto& p : pts)
    if (std::abs((to_eigen(p) - c).norm() - R) > tol) return TopoDS_Face();
  const Eigen::Vector3d a = (m - c).dot(axis) >= 0 ? axis : Eigen::Vector3d(-axis);
  const double lat0 = std::asin(std::clamp((m - c).dot(a) / R, -1.0, 1.0));
  // which side: the latitude of the surface's middle point
  const double mid[2] = {0.5 * (e.params[0].lo + e.params[0].hi), 0.5 * (e.params[1].lo + e.params[1].hi)};
  const double lat_mid = std::asin(std::clamp((to_eigen(eval_xyz(e, mid)) - c).dot(a) / R, -1.0, 1.0));
  if (std::abs(lat_mid - lat0) <= 1e-6) return TopoDS_Face();
  const gp_Ax3 frame(to_pnt(c), gp_Dir(a.x(), a.y(), a.z()));
  Handle(Geom_SphericalSurface) sphere = new Geom_SphericalSurface(frame, R);
  BRepBuilderAPI_MakeFace mf(sphere, 0, 2 * M_PI, lat_mid > lat0 ? lat0 : -M_PI / 2, lat_mid > lat0 ? M_PI / 2 : lat0,
                             1e-9 * R);
  if (!mf.IsDone()) return TopoDS_Face();
  GProp_GProps g;
  BRepGProp::SurfaceProperties(mf.Face(), g);
  const double b = fitted_area(fitted, tol);
  if (std::abs(g.Mass() - b) > 1e-6 * b) return TopoDS_Face();
  return mf.Face();
}

}  // namespace

TopoDS_Shape sampled_points(const EntitySpec& e) {
  TopoDS_Compound comp;
  BRep_Builder b;
  b.MakeCompound(comp);
  const int n = e.params.size() == 1 ? 512 : 48;
  const double u0 = e.params[0].lo, u1 = e.params[0].hi;
  const double v0 = e.params.size() > 1 ? e.params[1].lo : 0, v1 = e.params.size() > 1 ? e.params[1].hi : 0;
  for (int i = 0; i <= n; ++i)
    for (int k = 0; k <= (e.params.size() > 1 ? n : 0); ++k) {
      double uv[2] = {u0 + (u1 - u0) * i / n, v0 + (v1 - v0) * k / n};
      b.Add(comp, BRepBuilderAPI_MakeVertex(eval_xyz(e, uv)).Vertex());
    }
  if (!e.placement.matrix().isIdentity(0.0)) return BRepBuilderAPI_Transform(comp, to_trsf(e.placement), true).Shape();
  return comp;
}

namespace {
bool fitted_once_tolerance_known(const EntitySpec& e) { return e.kind == EntityKind::Curve || e.kind == EntityKind::Surface; }
}  // namespace

TopoDS_Shape sizing_shape(const EntitySpec& e, double* fit_error, const Entity* core) {
  return fitted_once_tolerance_known(e) ? sampled_points(e) : entity_shape(e, 1e-9, fit_error, core);
}

TopoDS_Shape fitted_entity_shape(const EntitySpec& e, const TopoDS_Shape& sizing, double fit_tol, double* fit_error) {
  return fitted_once_tolerance_known(e) ? entity_shape(e, fit_tol, fit_error) : sizing;
}

TopoDS_Shape read_shape_file(const std::string& path, const std::string& pointer) {
  const std::string ext = file_extension(path);
  TopoDS_Shape s;
  quiet_occt();
  try {
    if (ext == "brep") {
      BRep_Builder b;
      if (!BRepTools::Read(s, path.c_str(), b)) throw InputError(pointer, "cannot read BREP file '" + path + "'");
    } else {
      STEPControl_Reader r;
      if (r.ReadFile(path.c_str()) != IFSelect_RetDone)
        throw InputError(pointer, "cannot read STEP file '" + path + "'");
      if (r.TransferRoots() == 0) throw InputError(pointer, "STEP file '" + path + "' holds no shape");
      s = r.OneShape();
    }
  } catch (const Standard_Failure& f) {
    throw InputError(pointer, "cannot read '" + path + "': " + (f.GetMessageString() ? f.GetMessageString() : "OCCT error"));
  }
  if (s.IsNull()) throw InputError(pointer, "file '" + path + "' holds no shape");
  return s;
}

TopoDS_Shape primitive_from_patches(const Entity& entity) {
  if (entity.dimension() != 3) return {};
  for (const PatchPtr& p : entity.faces())
    if (p->form().kind == PatchForm::Kind::General) return {};
  const double scale = entity.box().sizes().maxCoeff();
  std::vector<TopoDS_Face> faces;
  for (const PatchPtr& p : entity.faces()) {
    const PatchFace f = patch_face(*p, Settings::resolution * scale);
    if (!f.exact || f.error > 1e-12 * scale) return {};
    faces.push_back(f.face);
  }
  if (faces.size() == 1) {  // one closed face (a ball, a torus): its shell is the solid's
    BRep_Builder b;
    TopoDS_Shell shell;
    b.MakeShell(shell);
    b.Add(shell, faces.front());
    shell.Closed(true);
    TopoDS_Solid solid;
    b.MakeSolid(solid);
    b.Add(solid, shell);
    return solid;
  }
  return sew_solid(faces, Settings::resolution * scale);
}

TopoDS_Shape entity_shape(const EntitySpec& e, double tol, double* fit_error, const Entity* core) {
  TopoDS_Shape s;
  switch (e.kind) {
    case EntityKind::Sphere:
    case EntityKind::Box:
    case EntityKind::Cylinder:
    case EntityKind::Cone:
    case EntityKind::Torus: {
      // placed already, on the exact surfaces of their core patches
      const EntityPtr built = core ? nullptr : make_entity(e);
      if (!core && !built) throw InternalError(std::string("no core entity for a ") + to_string(e.kind));
      s = primitive_from_patches(core ? *core : *built);
      if (s.IsNull())
        throw ComputeError(std::string("the faces of the ") + to_string(e.kind) + " entity do not make a valid solid");
      return s;
    }
    case EntityKind::Point:
      s = BRepBuilderAPI_MakeVertex(to_pnt(e.at)).Vertex();
      break;
    case EntityKind::EllipticCylinder:
      s = elliptic_cylinder_shape(e, tol, fit_error);
      break;
    case EntityKind::Curve: {
      auto c = fit_curve(e, tol, fit_error);
      s = BRepBuilderAPI_MakeEdge(c).Edge();
      break;
    }
    case EntityKind::Surface: {
      auto f = fit_surface(e, tol, fit_error);
      BRepBuilderAPI_MakeFace mf(f, tol);
      if (!mf.IsDone()) throw ComputeError("could not build a face from the surface entity");
      s = mf.Face();
      TopoDS_Face exact = planar_face(e, f, tol);
      if (exact.IsNull()) exact = spherical_cap_face(e, f, tol);
      if (!exact.IsNull()) s = exact;
      break;
    }
    case EntityKind::Mesh:
      s = mesh_solid(e);
      break;
    case EntityKind::Brep: {
      s = read_shape_file(e.file, "/entity/file");
      ShapeFix_Shape fix(s);
      fix.Perform();
      s = fix.Shape();
      TopExp_Explorer ex(s, TopAbs_SOLID);
      if (!ex.More()) {
        TopExp_Explorer fx(s, TopAbs_FACE);
        if (!fx.More()) throw InputError("/entity/file", "file '" + e.file + "' holds no solid and no face");
      }
      break;
    }
    default:
      throw InputError("/entity/kind", std::string("entity kind '") + to_string(e.kind) +
                                           "' is not supported by the sweep yet");
  }
  if (!e.placement.matrix().isIdentity(0.0))
    s = BRepBuilderAPI_Transform(s, to_trsf(e.placement), true).Shape();
  return s;
}

}  // namespace sweep::occt
