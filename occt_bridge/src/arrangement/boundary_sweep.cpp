// One stage built from its sweep boundary (see boundary_sweep.hpp).
#include "arrangement/boundary_sweep.hpp"
#include "arrangement/facing.hpp"
#include "arrangement/hole_fill.hpp"
#include "arrangement/split_tools.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_BuilderAlgo.hxx>
#include <BRepAlgoAPI_Section.hxx>
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeSolid.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Line.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <ShapeFix_Solid.hxx>
#include <Standard_Failure.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <TopExp.hxx>
#include <TopTools_MapOfShape.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shell.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>
#include <gp_Sphere.hxx>

#include <algorithm>
#include <memory>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>
#include <optional>

#include "faces/orbit_section.hpp"
#include "verdict/solid_checks.hpp"
#include "faces/section_refit.hpp"
#include "faces/touching_section.hpp"
#include "base/stop.hpp"
#include "sweep/error.hpp"

namespace sweep::occt {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Points inside a slender face that the grid of face_samples misses: from points along its edges,
/// steps of shrinking length across them in the parameter plane, kept where the step lands inside;
/// up to `count` of them, with outward normals.
std::vector<SurfacePoint> edge_samples(const TopoDS_Face& f, int count) {
  std::vector<SurfacePoint> out;
  BRepTopAdaptor_FClass2d fc(f, Settings::edge_sample_classifier_tolerance);
  BRepAdaptor_Surface S(f);
  for (TopExp_Explorer ex(f, TopAbs_EDGE); ex.More() && int(out.size()) < count; ex.Next()) {
    double a, b;
    const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(TopoDS::Edge(ex.Current()), f, a, b);
    if (pc.IsNull()) continue;
    const double chord = pc->Value(a).Distance(pc->Value(b));
    if (!(chord > 0)) continue;
    for (double at : {0.5, 0.3, 0.7}) {
      gp_Pnt2d uv;
      gp_Vec2d d;
      pc->D1(a + at * (b - a), uv, d);
      if (d.Magnitude() == 0) continue;
      const gp_Vec2d across = gp_Vec2d(-d.Y(), d.X()).Normalized();
      bool found = false;
      for (double h = Settings::edge_sample_first_step; h > Settings::edge_sample_min_step && !found; h /= 3)
        for (int side : {1, -1}) {
          const gp_Pnt2d q = uv.Translated(across * (side * h * chord));
          if (fc.Perform(q) != TopAbs_IN || !add_surface_point(S, f, q, out)) continue;
          found = true;
          break;
        }
    }
  }
  return out;
}

/// The body with its faces split at their grazing curves (shared edges kept); `grazing` receives
/// the number of grazing curves, `fit_error` is raised to their largest measured error. When the
/// pieces come out with edges wider than Settings::reprojected_split_ratio times `tol` (the
/// splitter's own projection of a curve that ends at a cone's apex widened them to 0.015), the
/// curves are given their curves on their faces, fitted to `fit_tol` (accepted within `tol`), when
/// `curves_on_faces`, and the faces split again.
TopoDS_Shape split_at_grazing(const TopoDS_Shape& body, const ScrewJoint& j, double fit_tol, double tol, double size,
                              bool curves_on_faces, int* grazing, double* fit_error) {
  TopTools_ListOfShape tools;
  std::vector<std::pair<TopoDS_Face, TopoDS_Edge>> on_faces;
  *grazing = 0;
  // A face closed on itself (a seam: a cylinder's band, a sphere) is cut in three by exact iso-lines
  // a third of a period apart, so that every edge has two faces (a seam can be a silhouette; two
  // cuts, in case a grazing curve falls on one of them).
  for (TopExp_Explorer ex(body, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& f = TopoDS::Face(ex.Current());
    TopLoc_Location loc;
    const Handle(Geom_Surface) surf = BRep_Tool::Surface(f, loc);
    if (surf.IsNull()) continue;
    double u0, u1, v0, v1;
    BRepTools::UVBounds(f, u0, u1, v0, v1);
    bool useam = false, vseam = false;
    for (TopExp_Explorer ee(f, TopAbs_EDGE); ee.More(); ee.Next()) {
      const TopoDS_Edge& e = TopoDS::Edge(ee.Current());
      if (!BRep_Tool::IsClosed(e, f)) continue;  // (the body's faces are whole: the surface's seam is theirs)
      double a, b;
      const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, f, a, b);
      if (pc.IsNull()) continue;
      const gp_Pnt2d p = pc->Value(a), q = pc->Value(b);
      if (std::abs(p.X() - q.X()) < Settings::seam_end_resolution * (u1 - u0 + 1)) useam = true;
      else if (std::abs(p.Y() - q.Y()) < Settings::seam_end_resolution * (v1 - v0 + 1)) vseam = true;
    }
    for (double frac : {1.0 / 3, 2.0 / 3}) {
      if (useam) {
        Handle(Geom_Curve) iso = surf->UIso(u0 + frac * (u1 - u0));
        if (!iso.IsNull()) tools.Append(BRepBuilderAPI_MakeEdge(iso, v0, v1).Edge().Moved(loc));
      }
      if (vseam) {
        Handle(Geom_Curve) iso = surf->VIso(v0 + frac * (v1 - v0));
        if (!iso.IsNull()) tools.Append(BRepBuilderAPI_MakeEdge(iso, u0, u1).Edge().Moved(loc));
      }
    }
  }
  for (TopExp_Explorer ex(body, TopAbs_FACE); ex.More(); ex.Next()) {
    for (const auto& g : grazing_curves(TopoDS::Face(ex.Current()), VelocityField(j), fit_tol, size)) {
      const TopoDS_Edge e = grazing_edge(g, TopoDS::Face(ex.Current()), fit_tol).edge;
      on_faces.emplace_back(TopoDS::Face(ex.Current()), e);
      tools.Append(e);
      *fit_error = std::max(*fit_error, g.error);
      ++*grazing;
    }
  }
  if (tools.IsEmpty()) return body;
  TopoDS_Shape split = split_by_edges(body, tools, Settings::resolution * size, SplitMode::NonDestructive);
  if (split.IsNull()) throw ComputeError("the body's faces could not be split at their grazing curves");
  if (curves_on_faces && max_tolerance(split) > Settings::reprojected_split_ratio * tol) {
    int added = 0;
    for (const auto& [face, e] : on_faces) added += add_curves_on_face(face, {e}, fit_tol, tol);
    if (added > 0) {
      const TopoDS_Shape again = split_by_edges(body, tools, Settings::resolution * size, SplitMode::NonDestructive);
      if (!again.IsNull()) split = again;
    }
  }
  return split;
}

/// Whether two faces lie on one analytic surface (within eps).
bool same_surface(const TopoDS_Face& a, const TopoDS_Face& b, double eps) {
  const BRepAdaptor_Surface A(a, false), B(b, false);
  if (A.GetType() != B.GetType()) return false;
  auto same_point = [&](const gp_Pnt& p, const gp_Pnt& q) { return p.Distance(q) <= eps; };
  auto same_axis = [&](const gp_Ax1& x, const gp_Ax1& y) {
    return x.Direction().IsParallel(y.Direction(), Settings::parallel_angle) &&
           gp_Lin(x).Distance(y.Location()) <= eps;
  };
  switch (A.GetType()) {
    case GeomAbs_Plane: {
      const gp_Pln p = A.Plane(), q = B.Plane();
      return p.Axis().Direction().IsParallel(q.Axis().Direction(), Settings::parallel_angle) &&
             p.Distance(q.Location()) <= eps;
    }
    case GeomAbs_Cylinder:
      return same_axis(A.Cylinder().Axis(), B.Cylinder().Axis()) &&
             std::abs(A.Cylinder().Radius() - B.Cylinder().Radius()) <= eps;
    case GeomAbs_Sphere:
      return same_point(A.Sphere().Location(), B.Sphere().Location()) &&
             std::abs(A.Sphere().Radius() - B.Sphere().Radius()) <= eps;
    case GeomAbs_Cone: {
      const gp_Cone c = A.Cone(), d = B.Cone();
      return same_axis(c.Axis(), d.Axis()) && same_point(c.Apex(), d.Apex()) &&
             std::abs(c.SemiAngle() - d.SemiAngle()) <= Settings::parallel_angle;
    }
    case GeomAbs_Torus: {
      const gp_Torus t = A.Torus(), u = B.Torus();
      return same_axis(t.Axis(), u.Axis()) && same_point(t.Location(), u.Location()) &&
             std::abs(t.MajorRadius() - u.MajorRadius()) <= eps && std::abs(t.MinorRadius() - u.MinorRadius()) <= eps;
    }
    default:
      return false;
  }
}

Bnd_Box box_of(const TopoDS_Shape& s, double gap) {
  Bnd_Box b;
  BRepBndLib::Add(s, b);
  b.Enlarge(gap);
  return b;
}

/// Whether edge e (a section curve with a pcurve on f, or a curve on it) lies along f's boundary,
/// within tol at five of its points.
bool on_boundary(const TopoDS_Edge& e, const TopoDS_Face& f, double tol) {
  double first, last;
  const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(e, f, first, last);
  if (pc.IsNull()) return false;
  const BRepAdaptor_Surface S(f, false);
  const double tu = S.UResolution(tol), tv = S.VResolution(tol);
  BRepTopAdaptor_FClass2d fc(f, std::max(tu, tv));
  for (int k = 0; k < 5; ++k) {
    const gp_Pnt2d uv = pc->Value(first + (last - first) * (k + 0.5) / 5);
    if (fc.Perform(uv) != TopAbs_ON) return false;
  }
  return true;
}

/// Whether edge e lies on the surface of face f, within tol at five of its points.
bool on_surface_of(const TopoDS_Edge& e, const TopoDS_Face& f, double tol) {
  double first, last;
  const Handle(Geom_Curve) c = BRep_Tool::Curve(e, first, last);
  if (c.IsNull()) return false;
  ShapeAnalysis_Surface S(BRep_Tool::Surface(f));
  for (int k = 0; k < 5; ++k) {
    const gp_Pnt p = c->Value(first + (last - first) * (k + 0.5) / 5);
    S.ValueOfUV(p, Settings::on_surface_projection * tol);
    if (S.Gap() > tol) return false;
  }
  return true;
}

/// A candidate face and what it is.
struct Candidate {
  TopoDS_Face face;
  int variety = -1;
  enum class Kind { Start, End, Swept } kind = Kind::Swept;
  Handle(Geom_Surface) sheet;  ///< a piece of a face through itself: the sheet it lies on
  /// Faces of one arrangement of candidates on one surface share a group (>= 0): they meet only
  /// along their edges, so no section between them is needed.
  int group = -1;
  /// A sweep of a grazing curve: the curve, the joint and the body's surface the curve lies on.
  std::shared_ptr<const TouchingSweep> touching;
  /// A piece of the start or the end copy: the body's surface it lies on (without the copy's
  /// location) and the time of the copy (0 or T; -1 for other candidates).
  Handle(Geom_Surface) body_surface;
  double copy_t = -1;
};

/// When one of two candidates is the sweep of a grazing curve and the other a start or end copy of
/// the body's surface the curve lies on (which the sweep touches along the curve): the sweep, the
/// copy face and the end of the range at which they touch.
std::optional<std::tuple<std::shared_ptr<const TouchingSweep>, TopoDS_Face, double>> touching_pair(const Candidate& a,
                                                                                                    const Candidate& b) {
  for (const auto& [sweep, copy] : {std::pair{&a, &b}, std::pair{&b, &a}})
    if (sweep->touching && copy->copy_t >= 0 && !copy->body_surface.IsNull() &&
        copy->body_surface == sweep->touching->surface)
      return std::tuple{sweep->touching, copy->face, copy->copy_t};
  return std::nullopt;
}

/// The candidates with each face swept along the joint's orbits whose profile crosses itself (an
/// extrusion of a curve whose projection along the direction loops: it passes through itself) cut
/// there into embedded pieces, each with the sheet it lies on.
std::vector<Candidate> cut_where_through_itself(const std::vector<Candidate>& cands, const ScrewJoint& j, double eps,
                                                double boundary_tol) {
  std::vector<Candidate> out;
  for (const Candidate& c : cands) {
    if (c.kind == Candidate::Kind::Swept)
      if (const auto patch = orbit_patch(c.face, j, eps)) {
        const std::vector<double> at = profile_self_crossings(*patch, j, boundary_tol);
        const std::vector<PatchPiece> pieces = at.empty() ? std::vector<PatchPiece>{} : patch_pieces(*patch, at);
        for (const PatchPiece& pp : pieces) out.push_back({pp.face, c.variety, c.kind, pp.sheet, c.group, c.touching, {}, -1});
        if (!pieces.empty()) continue;
      }
    out.push_back(c);
  }
  return out;
}

/// The frame of an elementary face's surface and its size (radius; torus: major + minor; cone:
/// semi-angle, with the frame at the apex), or false for a face of another kind.
bool elementary_frame(const TopoDS_Face& f, GeomAbs_SurfaceType* type, gp_Ax3* frame, double* size) {
  const BRepAdaptor_Surface a(f);
  *type = a.GetType();
  switch (*type) {
    case GeomAbs_Plane: *frame = a.Plane().Position(); *size = 0; return true;
    case GeomAbs_Cylinder: *frame = a.Cylinder().Position(); *size = a.Cylinder().Radius(); return true;
    case GeomAbs_Cone:  // located at its apex, sized by its semi-angle
      *frame = a.Cone().Position();
      frame->SetLocation(a.Cone().Apex());
      *size = a.Cone().SemiAngle();
      return true;
    case GeomAbs_Sphere: *frame = a.Sphere().Position(); *size = a.Sphere().Radius(); return true;
    case GeomAbs_Torus: *frame = a.Torus().Position(); *size = a.Torus().MajorRadius() + a.Torus().MinorRadius(); return true;
    default: return false;
  }
}

/// Whether two elementary surfaces of one type are the same point set: the same size and axis
/// line (a plane: the same plane; a sphere: the same centre).
bool same_domain(GeomAbs_SurfaceType type, const gp_Ax3& a, double sa, const gp_Ax3& b, double sb, double tol) {
  if (std::abs(sa - sb) > tol) return false;
  const gp_Vec d(a.Location(), b.Location());
  if (type == GeomAbs_Sphere) return d.Magnitude() <= tol;
  if (!a.Direction().IsParallel(b.Direction(), Settings::parallel_angle)) return false;
  const gp_Vec z(a.Direction());
  if (type == GeomAbs_Plane) return std::abs(d.Dot(z)) <= tol;
  if (type == GeomAbs_Cone || type == GeomAbs_Torus)  // one apex or centre, one orientation of the axis
    return d.Magnitude() <= tol && a.Direction().IsEqual(b.Direction(), Settings::parallel_angle);
  return d.Crossed(z).Magnitude() <= tol;
}

/// Whether the angle parameters of two frames on one axis line turn the same way about it (u
/// turns counterclockwise about the axis of a right-handed frame, clockwise about a left-handed
/// one's).
bool same_turn(const gp_Ax3& a, const gp_Ax3& b) {
  const gp_Vec ta = a.Direct() ? gp_Vec(a.Direction()) : -gp_Vec(a.Direction());
  const gp_Vec tb = b.Direct() ? gp_Vec(b.Direction()) : -gp_Vec(b.Direction());
  return ta.Dot(tb) > 0;
}

/// The solid with the pieces of one analytic surface (the halves of a closed face, the pieces
/// sections made) merged into one face each, when every face is analytic and the merged solid is
/// valid; else the solid as it is. (Spline-bounded faces are left alone: merging them can stall.)
/// Pieces of one surface of revolution (cylinder, cone, sphere, torus) whose angle parameters turn
/// opposite ways about its axis are not merged: OCCT 7.6's ShapeUpgrade_UnifySameDomain loops on
/// them (the two halves of a ball's capsule, one on a left-handed cylinder of the same axis).
TopoDS_Shape merged_analytic_faces(const TopoDS_Shape& solid) {
  const TopoDS_Shape copy = BRepBuilderAPI_Copy(solid).Shape();
  struct Elementary {
    TopoDS_Face face;
    GeomAbs_SurfaceType type;
    gp_Ax3 frame;
    double size;
  };
  std::vector<Elementary> faces;
  double tol = 0;
  for (TopExp_Explorer ex(copy, TopAbs_FACE); ex.More(); ex.Next()) {
    Elementary e{TopoDS::Face(ex.Current()), GeomAbs_OtherSurface, gp_Ax3(), 0};
    if (!elementary_frame(e.face, &e.type, &e.frame, &e.size)) return solid;
    faces.push_back(e);
    tol = std::max(tol, BRep_Tool::Tolerance(e.face));
  }
  try {
    ShapeUpgrade_UnifySameDomain unify(copy, true, true, true);
    for (std::size_t i = 0; i < faces.size(); ++i)
      for (std::size_t k = i + 1; k < faces.size(); ++k) {
        const Elementary &a = faces[i], &b = faces[k];
        if (a.type != b.type || a.type == GeomAbs_Plane || same_turn(a.frame, b.frame)) continue;
        if (!same_domain(a.type, a.frame, a.size, b.frame, b.size, Settings::same_domain_tolerances * tol)) continue;
        for (const TopoDS_Face& f : {a.face, b.face})
          for (TopExp_Explorer ex(f, TopAbs_EDGE); ex.More(); ex.Next()) unify.KeepShape(ex.Current());
      }
    unify.Build();
    const TopoDS_Shape merged = unify.Shape();
    if (!merged.IsNull() && BRepCheck_Analyzer(merged).IsValid()) return merged;
  } catch (const Standard_Failure&) {
  }
  return solid;
}

/// A step of the sweep boundary that cannot go on, and why.
struct BoundaryFailure {
  std::string why;
};

/// What the steps of the sweep boundary share: the joint and its range, the model size, the
/// tolerances (eps: two points closer are one; boundary_tol: how far a section may lie from a
/// face's boundary and still run along it), the settings, and the result they fill in.
struct BoundaryContext {
  const ScrewJoint& j;
  double T, size, tol, fit_tol, eps;
  const Settings& settings;
  int stage, joint_no;
  BoundarySweep& out;
  double boundary_tol = 0;
  int variety(const std::string& type, const std::string& what, nlohmann::json fixed, nlohmann::json free) {
    out.varieties.push_back({stage, joint_no, type, what, std::move(fixed), std::move(free)});
    return int(out.varieties.size()) - 1;
  }
};

/// A candidate face split where others cross it, with its variety and the sheet it lies on.
struct Piece {
  TopoDS_Face face;
  int variety;
  Handle(Geom_Surface) sheet;
};

/// Steps 1 and 2: the body's faces split at their grazing curves and copied to both ends of the
/// range where they bound the swept region, and the sweeps of the silhouette's edges.
std::vector<Candidate> candidates_of(const TopoDS_Shape& body, BoundaryContext& ctx) {
  const ScrewJoint& j = ctx.j;
  const double T = ctx.T, size = ctx.size, fit_tol = ctx.fit_tol;
  const Settings& settings = ctx.settings;
  BoundarySweep& out = ctx.out;
  const bool full_turn = j.type == JointType::Revolute && T >= 2 * M_PI - Settings::angle_resolution;
  const int joint_no = ctx.joint_no;
  const std::string qn = "q" + std::to_string(joint_no);
  const nlohmann::json qfree = {{qn, {0.0, T}}};
  const int start_id = ctx.variety("limit", "the entity at the start of joint " + std::to_string(joint_no) + "'s range",
                                   {{qn, 0.0}}, nlohmann::json::object());
  const int end_id =
      full_turn ? -1
                : ctx.variety("limit", "the entity at the end of joint " + std::to_string(joint_no) + "'s range",
                              {{qn, T}}, nlohmann::json::object());

  // 1. The body's faces split at their grazing curves, each piece facing one way. Closed faces are
  //    halved first, so that every edge has two faces (a seam can be a silhouette).
  int grazing = 0;
  const TopoDS_Shape split = split_at_grazing(body, j, fit_tol, ctx.tol, size, settings.curves_on_faces, &grazing, &out.fit_error);
  TopTools_IndexedMapOfShape pieces;
  TopExp::MapShapes(split, TopAbs_FACE, pieces);
  std::vector<Facing> face_facing(pieces.Extent() + 1, Facing::Unknown);
  for (int k = 1; k <= pieces.Extent(); ++k) {
    face_facing[k] = facing_of(TopoDS::Face(pieces(k)), VelocityField(j), size);
    if (face_facing[k] == Facing::Mixed) {
      throw BoundaryFailure{"a face of the body could not be split where the motion becomes tangent to it"};
    }
  }

  std::vector<Candidate> cands;
  const Eigen::Isometry3d at_end = j.transform(T);
  for (int k = 1; k <= pieces.Extent(); ++k) {
    const TopoDS_Face& f = TopoDS::Face(pieces(k));
    if (full_turn) continue;
    const Facing fa = face_facing[k];
    // the start and end copies of faces the motion slides within bound the region they sweep
    TopLoc_Location loc;
    const Handle(Geom_Surface) surface = BRep_Tool::Surface(f, loc);
    if (fa == Facing::Back || fa == Facing::Slides || fa == Facing::Unknown)
      cands.push_back({f, start_id, Candidate::Kind::Start, {}, -1, nullptr, surface, 0.0});
    if (fa == Facing::Front || fa == Facing::Slides || fa == Facing::Unknown)
      cands.push_back({TopoDS::Face(moved(f, at_end)), end_id, Candidate::Kind::End, {}, -1, nullptr, surface, T});
  }

  // 2. The sweeps of the silhouette: edges between a face the motion leaves and one it moves into
  //    (grazing curves among them), and the edges of faces it slides within.
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(split, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  int edge_no = 0;
  for (int k = 1; k <= edge_faces.Extent(); ++k) {
    const TopoDS_Edge& e = TopoDS::Edge(edge_faces.FindKey(k));
    if (BRep_Tool::Degenerated(e)) continue;
    const TopTools_ListOfShape& fl = edge_faces(k);
    std::vector<Facing> sides;
    bool seam = false;
    for (TopTools_ListIteratorOfListOfShape it(fl); it.More(); it.Next()) {
      const TopoDS_Face& f = TopoDS::Face(it.Value());
      // a seam of this face: the edge bounds it twice (BRep_Tool::IsClosed asks the surface, which
      // the pieces of one closed face share)
      int uses = 0;
      for (TopExp_Explorer ee(f, TopAbs_EDGE); ee.More(); ee.Next()) uses += ee.Current().IsSame(e);
      if (uses > 1) seam = true;
      sides.push_back(face_facing[pieces.FindIndex(f)]);
    }
    if (std::getenv("SWEEP_DEBUG_EDGES")) {
      double f0, l0;
      Handle(Geom_Curve) c0 = BRep_Tool::Curve(e, f0, l0);
      gp_Pnt m = c0.IsNull() ? gp_Pnt() : c0->Value(0.5 * (f0 + l0));
      std::fprintf(stderr, "edge %d at (%.3f %.3f %.3f) seam %d sides", k, m.X(), m.Y(), m.Z(), int(seam));
      for (Facing x : sides) std::fprintf(stderr, " %d", int(x));
      std::fprintf(stderr, "\n");
    }
    if (seam) continue;
    bool front = false, back = false, slides = false;
    for (Facing s : sides) {
      front = front || s == Facing::Front;
      back = back || s == Facing::Back;
      slides = slides || s == Facing::Slides || s == Facing::Unknown;
    }
    if (!(front && back) && !slides && sides.size() == 2) continue;  // inside the start or the end copy
    double f, l;
    Handle(Geom_Curve) c = BRep_Tool::Curve(e, f, l);
    if (c.IsNull()) continue;
    c = canonical_curve(c, f, l, std::max(fit_tol, Settings::canonical_curve_rounding * size));
    gp_Pln plane;
    const bool planar = !c->IsKind(STANDARD_TYPE(Geom_Line)) && keeps_plane_of(c, f, l, j, size, &plane);
    double err = 0;
    const std::vector<TopoDS_Face> sw =
        planar ? planar_curve_sweep(c, f, l, j, T, plane, size) : sweep_curve(c, f, l, j, T, fit_tol, &err);
    out.fit_error = std::max(out.fit_error, err);
    if (sw.empty()) continue;
    nlohmann::json efree = qfree;
    efree["s"] = {f, l};
    // a grazing curve lies between two pieces of one face of the body
    TopLoc_Location l1, l2;
    const bool is_grazing = sides.size() == 2 && BRep_Tool::Surface(TopoDS::Face(fl.First()), l1) ==
                                                     BRep_Tool::Surface(TopoDS::Face(fl.Last()), l2);
    const int vid = ctx.variety(is_grazing ? "interior" : "boundary",
                                std::string(is_grazing ? "grazing curve (n . v = 0)" : "edge") + " " +
                                    std::to_string(++edge_no) + " swept by joint " + std::to_string(joint_no),
                                nlohmann::json::object(), efree);
    std::shared_ptr<const TouchingSweep> touching;
    // (a helical sweep's faces are fitted: the crossing traced on the exact sweep lies within their
    // fit error of them, which is what OCCT's section of the fitted face could not find at all where
    // the two faces are nearly tangent)
    if (is_grazing && settings.touching_sections) {
      std::vector<double> breaks;
      if (j.type != JointType::Prismatic)
        for (int k = 1; k < sweep_pieces(T); ++k) breaks.push_back(T * k / sweep_pieces(T));
      touching = std::make_shared<const TouchingSweep>(
          TouchingSweep{c, f, l, j, T, BRep_Tool::Surface(TopoDS::Face(fl.First()), l1), breaks});
    }
    for (const auto& face : sw) cands.push_back({face, vid, Candidate::Kind::Swept, {}, -1, touching, {}, -1});
  }
  return cands;
}

/// Step 3: candidates on one analytic surface replaced by their arrangement; sets c.boundary_tol.
void group_by_surface(std::vector<Candidate>& cands, BoundaryContext& c) {
  const ScrewJoint& j = c.j;
  const double eps = c.eps;
  const Settings& settings = c.settings;
  BoundarySweep& out = c.out;
  // 3. Candidates on one analytic surface (regions swept within a surface, sweeps of curves that
  //    revolve into one surface) overlap: each such group is replaced by its arrangement, whose
  //    faces do not overlap.
  const auto t_groups = Clock::now();
  {
    const std::size_t n = cands.size();
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    std::function<int(int)> root = [&](int x) { return parent[x] == x ? x : parent[x] = root(parent[x]); };
    std::vector<Bnd_Box> boxes(n);
    for (std::size_t i = 0; i < n; ++i) boxes[i] = box_of(cands[i].face, Settings::candidate_box_gap * eps);
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = a + 1; b < n; ++b)
        if (!boxes[a].IsOut(boxes[b]) && same_surface(cands[a].face, cands[b].face, eps)) parent[root(int(b))] = root(int(a));
    std::map<int, std::vector<std::size_t>> groups;
    for (std::size_t i = 0; i < n; ++i) groups[root(int(i))].push_back(i);
    std::vector<Candidate> merged;
    for (const auto& [r, members] : groups) {
      if (members.size() == 1) {
        merged.push_back(cands[members[0]]);
        continue;
      }
      // Faces of one copy of the body (a copy split at its grazing curves) meet only along their
      // edges: their arrangement is themselves (OCCT's took minutes to find that on a torus).
      const Candidate::Kind kind0 = cands[members[0]].kind;
      if (kind0 != Candidate::Kind::Swept &&
          std::all_of(members.begin(), members.end(), [&](std::size_t i) { return cands[i].kind == kind0; })) {
        for (std::size_t i : members) {
          merged.push_back(cands[i]);
          merged.back().group = r;
        }
        ++out.copy_groups;
        continue;
      }
      ++out.arranged_groups;
      TopTools_ListOfShape args;
      for (std::size_t i : members) args.Append(cands[i].face);
      BRepAlgoAPI_BuilderAlgo gf;
      gf.SetArguments(args);
      gf.SetNonDestructive(true);
      gf.SetFuzzyValue(eps);
      gf.Build(stop_range());
      check_stop();
      if (!gf.IsDone() || gf.HasErrors()) {
        throw BoundaryFailure{"the arrangement of candidate faces on one surface failed"};
      }
      TopTools_IndexedMapOfShape faces;
      TopExp::MapShapes(gf.Shape(), TopAbs_FACE, faces);
      // Each face of the arrangement keeps what the candidate it comes from lies on (a face of the
      // start or the end copy, a sweep of a grazing curve). The arrangement's faces may cross the
      // start or the end copy: they are swept regions now, unless the group is of one kind.
      std::vector<int> origin(faces.Extent() + 1, -1);
      auto claim = [&](const TopoDS_Shape& face, std::size_t i) {
        if (faces.Contains(face) && origin[faces.FindIndex(face)] < 0) origin[faces.FindIndex(face)] = int(i);
      };
      for (std::size_t i : members) {
        const TopTools_ListOfShape& images = gf.Modified(cands[i].face);
        if (images.IsEmpty()) claim(cands[i].face, i);  // kept as it is (or deleted: then not among the faces)
        for (TopTools_ListIteratorOfListOfShape it(images); it.More(); it.Next()) claim(it.Value(), i);
      }
      const Candidate& first = cands[members[0]];
      bool one_kind = true;
      for (std::size_t i : members) one_kind = one_kind && cands[i].kind == first.kind;
      for (int k = 1; k <= faces.Extent(); ++k) {
        Candidate c{TopoDS::Face(faces(k)), first.variety, one_kind ? first.kind : Candidate::Kind::Swept, {}, r,
                    nullptr, {}, -1};
        if (origin[k] >= 0) {
          const Candidate& o = cands[origin[k]];
          c.touching = o.touching;
          c.body_surface = o.body_surface;
          c.copy_t = o.copy_t;
        }
        merged.push_back(c);
      }
    }
    cands.swap(merged);
  }
  c.boundary_tol = std::max(Settings::section_boundary_margin * eps, Settings::fit_error_margin * out.fit_error);
  if (settings.orbit_sections) cands = cut_where_through_itself(cands, j, eps, c.boundary_tol);
  out.candidates = int(cands.size());
  out.seconds["groups"] = since(t_groups);

}

/// The curves along which candidates cross: per candidate, the edges that split it, and every
/// edge found (for diagnostics).
struct Crossings {
  std::vector<std::vector<TopoDS_Edge>> tools;
  std::vector<std::vector<TopoDS_Edge>> pair_edges;
};

/// Step 4: where candidates cross.
Crossings crossings_of(const std::vector<Candidate>& cands, BoundaryContext& c) {
  const ScrewJoint& j = c.j;
  const double size = c.size, tol = c.tol, fit_tol = c.fit_tol, eps = c.eps;
  const Settings& settings = c.settings;
  BoundarySweep& out = c.out;
  const double boundary_tol = c.boundary_tol;
  // 4. Where candidates cross: the section of every pair whose boxes meet (the start copies among
  //    themselves and the end copies among themselves are faces of one solid and do not cross, nor
  //    do the faces of one group's arrangement).
  const auto t_sec = Clock::now();
  const std::size_t n = cands.size();
  std::vector<Bnd_Box> boxes(n);
  for (std::size_t i = 0; i < n; ++i) boxes[i] = box_of(cands[i].face, Settings::candidate_box_gap * eps);
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 1; b < n; ++b) {
      if (cands[a].kind != Candidate::Kind::Swept && cands[a].kind == cands[b].kind) continue;
      if (cands[a].group >= 0 && cands[a].group == cands[b].group) continue;
      if (boxes[a].IsOut(boxes[b])) continue;
      pairs.push_back({a, b});
    }
  std::vector<std::vector<TopoDS_Edge>> pair_edges(pairs.size());
  // which of the pair's faces each edge splits: 1 the first, 2 the second, 3 both
  std::vector<std::vector<int>> pair_sides(pairs.size());
  std::vector<char> pair_failed(pairs.size(), 0);
  std::vector<double> pair_refit_error(pairs.size(), 0.0);
  // faces swept along a revolute or prismatic joint's orbits cross in circles or segments, found
  // from their profiles
  std::vector<std::optional<OrbitPatch>> carried(n);
  if (settings.orbit_sections)
    for (std::size_t i = 0; i < n; ++i) carried[i] = orbit_patch(cands[i].face, j, eps, boundary_tol);
  // A sweep of a grazing curve and a copy of the surface it touches cross where their distance,
  // divided by the square of the time from the touching copy, vanishes: traced once per sweep and
  // copy face, whichever of the sweep's faces meets it.
  std::vector<int> touch_job(pairs.size(), -1);
  std::vector<std::tuple<std::shared_ptr<const TouchingSweep>, TopoDS_Face, double>> touch_jobs;
  {
    std::map<std::pair<const TouchingSweep*, const TopoDS_TShape*>, int> job_of;
    for (std::size_t k = 0; k < pairs.size(); ++k)
      if (const auto tp = touching_pair(cands[pairs[k].first], cands[pairs[k].second])) {
        const auto key = std::pair{std::get<0>(*tp).get(), std::get<1>(*tp).TShape().get()};
        const auto [it, fresh] = job_of.emplace(key, int(touch_jobs.size()));
        if (fresh) touch_jobs.push_back(*tp);
        touch_job[k] = it->second;
      }
  }
  out.touching_sections = int(touch_jobs.size());
  std::vector<std::optional<std::vector<TopoDS_Edge>>> touch_edges(touch_jobs.size());
  std::vector<double> touch_error(touch_jobs.size(), 0.0);
  parallel_for(touch_jobs.size(), [&]() -> std::function<void(std::size_t)> {
    return [&](std::size_t m) {
      const auto& [sweep, copy, t_touch] = touch_jobs[m];
      touch_edges[m] = touching_section(*sweep, t_touch, copy, fit_tol, size, &touch_error[m]);
    };
  });
  parallel_for(pairs.size(), [&]() -> std::function<void(std::size_t)> {
    return [&](std::size_t k) {
      const TopoDS_Face& fa = cands[pairs[k].first].face;
      const TopoDS_Face& fb = cands[pairs[k].second].face;
      if (touch_job[k] >= 0 && touch_edges[touch_job[k]]) {
        // traced once for every face of the sweep: each splits the faces it lies on (a sweep cut
        // where it passes through itself has faces on other sheets)
        for (const auto& e : *touch_edges[touch_job[k]]) {
          const int sides = (on_surface_of(e, fa, Settings::touching_on_face * tol) ? 1 : 0) |
                            (on_surface_of(e, fb, Settings::touching_on_face * tol) ? 2 : 0);
          if (sides == 0) continue;
          pair_edges[k].push_back(e);
          pair_sides[k].push_back(sides);
        }
        pair_refit_error[k] = touch_error[touch_job[k]];
        return;
      }
      if (carried[pairs[k].first] && carried[pairs[k].second]) {
        if (auto arcs = orbit_section(*carried[pairs[k].first], *carried[pairs[k].second], j, boundary_tol,
                                      &pair_refit_error[k], tol)) {
          pair_edges[k] = std::move(*arcs);
          pair_sides[k].assign(pair_edges[k].size(), 3);
          return;
        }
      }
      // a face on a torus, or a fitted sweep and a face on an elementary surface: the zero set of
      // the one's exact distance over the other face (OCCT's section of two tori walks for seconds,
      // of a helical sweep and a copy of the body for 0.2 s)
      for (const bool b_traced : {true, false}) {
        const TopoDS_Face& on = b_traced ? fa : fb;
        const TopoDS_Face& other = b_traced ? fb : fa;
        double err = 0;
        std::optional<std::vector<TopoDS_Edge>> traced;
        if (settings.torus_sections) traced = torus_section(on, other, fit_tol, size, &err);
        if (!traced && settings.spline_sections) traced = spline_section(on, other, fit_tol, size, &err);
        if (!traced) continue;
        for (const TopoDS_Edge& e : *traced) {
          const int sides = (on_boundary(e, fa, boundary_tol) ? 0 : 1) | (on_boundary(e, fb, boundary_tol) ? 0 : 2);
          if (sides == 0) continue;
          pair_edges[k].push_back(e);
          pair_sides[k].push_back(sides);
        }
        pair_refit_error[k] = err;
        return;
      }
      BRepAlgoAPI_Section sec(fa, fb, false);
      sec.SetNonDestructive(true);
      sec.SetFuzzyValue(eps);
      sec.Approximation(true);
      sec.ComputePCurveOn1(true);
      sec.ComputePCurveOn2(true);
      sec.Build(stop_range());
      check_stop();
      if (!sec.IsDone() || sec.HasErrors()) {
        pair_failed[k] = 1;
        return;
      }
      for (TopExp_Explorer ex(sec.Shape(), TopAbs_EDGE); ex.More(); ex.Next()) {
        const TopoDS_Edge& e = TopoDS::Edge(ex.Current());
        // a section along where the faces meet by construction (a grazing curve, where a swept face
        // touches the face it came from) splits neither; one along the boundary of one face (where
        // that face meets its neighbour) splits the other
        const int sides = (on_boundary(e, fa, boundary_tol) ? 0 : 1) | (on_boundary(e, fb, boundary_tol) ? 0 : 2);
        if (sides == 0) continue;
        // an approximation that strays above the tolerance is refitted onto both surfaces
        double err = 0;
        pair_edges[k].push_back(refitted_section_edge(e, fa, fb, fit_tol, 0.1 * tol, &err));
        pair_sides[k].push_back(sides);
        pair_refit_error[k] = std::max(pair_refit_error[k], err);
      }
    };
  });
  for (std::size_t k = 0; k < pairs.size(); ++k)
    if (pair_failed[k]) {
      throw BoundaryFailure{"the intersection of two candidate faces failed"};
    }
  for (double err : pair_refit_error) out.fit_error = std::max(out.fit_error, err);
  std::vector<std::vector<TopoDS_Edge>> tools(n);
  for (std::size_t k = 0; k < pairs.size(); ++k)
    for (std::size_t m = 0; m < pair_edges[k].size(); ++m) {
      if (pair_sides[k][m] & 1) tools[pairs[k].first].push_back(pair_edges[k][m]);
      if (pair_sides[k][m] & 2) tools[pairs[k].second].push_back(pair_edges[k][m]);
    }
  out.seconds["sections"] = since(t_sec);

  return {std::move(tools), std::move(pair_edges)};
}

/// Step 5: each candidate split by the curves that cross it.
std::vector<Piece> split_candidates(const std::vector<Candidate>& cands,
                                    const std::vector<std::vector<TopoDS_Edge>>& tools, BoundaryContext& c) {
  const double eps = c.eps;
  BoundarySweep& out = c.out;
  const std::size_t n = cands.size();
  // 5. Each candidate split by its curves; each piece kept when exactly one side is in the set.
  const auto t_split = Clock::now();
  std::vector<std::vector<TopoDS_Face>> split_faces(n);
  std::vector<char> split_failed(n, 0), dangling(n, 0);
  std::vector<double> widest(n, 0.0);  // the largest tolerance of a face's pieces' edges and vertices
  auto split_each = [&](const std::vector<std::size_t>& which) {
    parallel_for(which.size(), [&]() -> std::function<void(std::size_t)> {
      return [&](std::size_t m) {
        const std::size_t i = which[m];
        split_faces[i].clear();
        if (tools[i].empty()) {
          split_faces[i].push_back(cands[i].face);
          return;
        }
        TopTools_ListOfShape tl;
        TopTools_MapOfShape once;  // an edge shared by several pairs splits the face once
        for (const auto& e : tools[i])
          if (once.Add(e)) tl.Append(e);
        const TopoDS_Shape split = split_by_edges(cands[i].face, tl, eps, SplitMode::NonDestructive);
        if (split.IsNull()) {
          split_failed[i] = 1;
          return;
        }
        for (TopExp_Explorer ex(split, TopAbs_FACE); ex.More(); ex.Next()) {
          split_faces[i].push_back(TopoDS::Face(ex.Current()));
          for (TopExp_Explorer ee(ex.Current(), TopAbs_EDGE); ee.More(); ee.Next())
            dangling[i] = dangling[i] || ee.Current().Orientation() == TopAbs_INTERNAL;
        }
        widest[i] = max_tolerance(split);
      };
    });
  };
  std::vector<std::size_t> every(n);
  std::iota(every.begin(), every.end(), std::size_t(0));
  split_each(every);
  // A face split again (one after another: the faces that a section splits share it):
  // - whose pieces came out with tolerances far above the requested one, its curves given their
  //   curves on the face (the splitter's own projection onto a surface of revolution or extrusion
  //   of a spline can go wrong by a tenth of the model; where it is right, it is closer than a
  //   fit, which a tolerance a few times the requested one does not show);
  // - that keeps a section inside a piece (a curve that stops short of the curve it runs into,
  //   within the tolerance), such ends joined to that curve.
  std::vector<std::size_t> again;
  for (std::size_t i = 0; i < n; ++i) {
    if (split_failed[i] || tools[i].empty()) continue;
    const bool projected = c.settings.curves_on_faces && widest[i] > Settings::reprojected_split_ratio * c.tol &&
                           add_curves_on_face(cands[i].face, tools[i], c.fit_tol, c.tol) > 0;
    const bool bridged = dangling[i] && bridge_section_ends(cands[i].face, tools[i], c.tol) > 0;
    if (projected || bridged) again.push_back(i);
  }
  if (!again.empty()) split_each(again);
  for (std::size_t i = 0; i < n; ++i)
    if (split_failed[i]) {
      throw BoundaryFailure{"a candidate face could not be split where others cross it"};
    }
  std::vector<Piece> all;
  for (std::size_t i = 0; i < n; ++i)
    for (const auto& f : split_faces[i]) all.push_back({f, cands[i].variety, cands[i].sheet});
  out.pieces = int(all.size());
  out.seconds["splitting"] = since(t_split);

  return all;
}

/// Each piece: 1 kept as it is, -1 kept reversed, 0 dropped (exactly one side in the swept set
/// keeps it); a piece that no sample decides fails the boundary. With `closer`, the sample that
/// decides is probed again at offsets down to `finest`, eight times closer each time, and the
/// closest whose answers agree at both offsets decides: another sheet closer to a piece than the
/// offset (crossing it at a small angle over a strip) turns both probes.
std::vector<int> classify_pieces(const std::vector<Piece>& all, const PointTestMaker& member, BoundaryContext& c,
                                 bool closer) {
  const double size = c.size;
  const Settings& settings = c.settings;
  BoundarySweep& out = c.out;
  const auto t_cls = Clock::now();
  const double delta = settings.classify_offset * size;
  const double finest = std::max(settings.classify_finest_offset * size, Settings::fit_error_margin * out.fit_error);
  // 1 keep as is, -1 keep reversed, 0 drop, 2 undecided
  std::vector<int> keep(all.size(), 0);
  parallel_for(all.size(), [&]() -> std::function<void(std::size_t)> {
    const PointTest in_set = member();
    return [&, in_set](std::size_t i) {
      // the first sample whose two sides answer the same at one and at two offsets; a slender
      // piece that the grid misses is sampled on a mesh of it
      auto decide = [&](const std::vector<SurfacePoint>& samples) {
        for (const auto& s : samples) {
          const Eigen::Vector3d p = to_eigen(s.p), nn = to_eigen(s.n);
          // (the answer at offset d, 2 when the offsets d and 2 d disagree)
          auto answer_at = [&](double d) {
            const bool out1 = in_set(p + d * nn), in1 = in_set(p - d * nn);
            const bool out2 = in_set(p + 2 * d * nn), in2 = in_set(p - 2 * d * nn);
            if (out1 != out2 || in1 != in2) return 2;
            return out1 == in1 ? 0 : (in1 ? 1 : -1);
          };
          int answer = answer_at(delta);
          if (answer == 2) continue;
          for (double d = delta / 8; closer && d >= finest; d /= 8)
            if (const int near = answer_at(d); near != 2) answer = near;
          return answer;
        }
        return 2;
      };
      keep[i] = decide(face_samples(all[i].face, Settings::classify_grid));
      if (keep[i] == 2) keep[i] = decide(edge_samples(all[i].face, Settings::classify_edge_samples));
    };
  });
  out.seconds["classification"] = out.seconds.value("classification", 0.0) + since(t_cls);
  for (std::size_t i = 0; i < all.size(); ++i)
    if (keep[i] == 2) {
      throw BoundaryFailure{"a piece of the boundary could not be classified (it is thinner than the classification offset)"};
    }

  return keep;
}

/// Why sewn pieces do not make the stage's solid, or "" when they do: they close (as they are or
/// once healed), and the solid is valid as it is. (A boundary that only OCCT's healing makes valid
/// is not taken: kept pieces that overlap or leave a hole come back closed from it, but not as the
/// swept set; an L-bracket turned about a skew axis came back 0.5 % too large.)
std::string not_a_solid(const TopoDS_Shape& solid) {
  if (solid.IsNull() || (!closed_solids(solid) && !closed_solids(healed(solid))))
    return "the pieces of its sweep boundary do not close";
  if (!BRepCheck_Analyzer(solid).IsValid()) return "the pieces of its sweep boundary do not make a valid solid";
  return "";
}

/// Diagnostics (SWEEP_DUMP_BOUNDARY=dir): candidates, pieces, kept pieces and sections as BREP files
/// (dir/general: the attempt with OCCT's sections where sweeps touch).
void dump_boundary(const char* dir, const std::vector<Candidate>& cands, const std::vector<Piece>& all,
                   const std::vector<int>& keep, const std::vector<std::vector<TopoDS_Edge>>& pair_edges) {
  std::filesystem::create_directories(dir);
  auto dump = [&](const std::string& name, const std::function<bool(std::size_t)>& take, std::size_t count,
                  const std::function<TopoDS_Shape(std::size_t)>& get) {
    TopoDS_Compound comp;
    BRep_Builder bb;
    bb.MakeCompound(comp);
    for (std::size_t i = 0; i < count; ++i)
      if (take(i)) bb.Add(comp, get(i));
    BRepTools::Write(comp, (std::string(dir) + "/" + name + ".brep").c_str());
  };
  dump("candidates", [](std::size_t) { return true; }, cands.size(), [&](std::size_t i) { return cands[i].face; });
  dump("pieces", [](std::size_t) { return true; }, all.size(), [&](std::size_t i) { return all[i].face; });
  dump("kept", [&](std::size_t i) { return keep[i] != 0; }, all.size(),
       [&](std::size_t i) { return keep[i] < 0 ? all[i].face.Reversed() : TopoDS_Shape(all[i].face); });
  TopoDS_Compound tl;
  BRep_Builder bb;
  bb.MakeCompound(tl);
  for (const auto& es : pair_edges)
    for (const auto& e : es) bb.Add(tl, e);
  BRepTools::Write(tl, (std::string(dir) + "/sections.brep").c_str());
}

/// Step 6: the kept pieces, oriented outward, sewn into the solid (c.out.solid); a hole of the
/// sewn pieces that one dropped piece fills exactly is filled with it, and one that a kept sliver
/// lies across is closed without the sliver.
void sew_kept(const std::vector<Piece>& all, std::vector<int> keep, BoundaryContext& c) {
  const double size = c.size;
  BoundarySweep& out = c.out;
  // 6. The kept pieces, oriented outward, sewn into a solid.
  const auto t_sew = Clock::now();
  double gap = std::max(Settings::sewing_gap * size, Settings::fit_error_margin * out.fit_error);
  auto sew = [&](std::unique_ptr<BRepBuilderAPI_Sewing>& sewing) {
    sewing = std::make_unique<BRepBuilderAPI_Sewing>(gap);
    out.candidate_faces.clear();
    out.candidate_ids.clear();
    int kept = 0;
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (keep[i] == 0) continue;
      TopoDS_Face f = all[i].sheet.IsNull() ? all[i].face : on_own_sheet(all[i].face, all[i].sheet);
      if (keep[i] < 0) f = TopoDS::Face(f.Reversed());
      sewing->Add(f);
      out.candidate_faces.push_back(f);
      out.candidate_ids.push_back(all[i].variety);
      ++kept;
    }
    out.kept = kept;
    if (kept == 0) {
      throw BoundaryFailure{"no piece of the candidate boundary separates the swept set from its complement"};
    }
    sewing->Perform(stop_range());
    check_stop();
  };
  std::unique_ptr<BRepBuilderAPI_Sewing> sewing;
  sew(sewing);
  auto widest_edge = [](const TopoDS_Shape& shape) {
    double widest = 0;
    for (TopExp_Explorer ex(shape, TopAbs_EDGE); ex.More(); ex.Next())
      widest = std::max(widest, BRep_Tool::Tolerance(TopoDS::Edge(ex.Current())));
    return widest;
  };
  // keep changed to `changed` and the pieces sewn again, taken only when the shell closes and its
  // widest edge is within the gap or narrower than before (an open shell whose sewing bridged a
  // gap elsewhere keeps that gap when closed so: the hole was not what kept it open), else undone
  auto sew_if_it_closes = [&](const std::vector<int>& changed) {
    const double widest_open = widest_edge(sewing->SewedShape());
    const std::vector<int> before = keep;
    keep = changed;
    sew(sewing);
    const double widest = widest_edge(sewing->SewedShape());
    if (sewing->NbFreeEdges() == 0 && (widest <= gap || widest < widest_open)) return;
    keep = before;
    sew(sewing);
  };
  // (a sliver between two candidates that touch along a curve can be classified by samples on
  // either side of their contact and dropped: the shell without it is open, with it closed; the
  // verdict still judges the solid against the membership test)
  std::vector<std::size_t> dropped;
  std::vector<TopoDS_Face> dropped_faces;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (keep[i] == 0) dropped.push_back(i), dropped_faces.push_back(all[i].face);
  const std::vector<std::size_t> fill = faces_filling_holes(dropped_faces, *sewing, gap);
  if (!fill.empty()) {
    std::vector<int> with = keep;
    for (std::size_t k : fill) with[dropped[k]] = 1;
    sew_if_it_closes(with);
  }
  // (a sliver of one candidate kept beside the two pieces that meet at its edges, which it crosses
  // as a third sheet: the shell without it closes)
  if (sewing->NbFreeEdges() > 0) {
    std::vector<std::size_t> kept_index;
    std::vector<TopoDS_Face> kept_faces;
    for (std::size_t i = 0; i < all.size(); ++i)
      if (keep[i] != 0) kept_index.push_back(i), kept_faces.push_back(all[i].face);
    const std::vector<std::size_t> extra = faces_left_over(kept_faces, *sewing, gap);
    if (!extra.empty()) {
      std::vector<int> without = keep;
      for (std::size_t k : extra) without[kept_index[k]] = 0;
      sew_if_it_closes(without);
    }
  }
  // Pieces left apart by more than the sewing gap but less than the requested tolerance (the ends
  // of two sections of one crossing, near where the sweeps touch) are sewn across it: the solid's
  // measured geometric error is still held to that tolerance.
  if (sewing->NbFreeEdges() > 0 && gap < c.tol) {
    gap = c.tol;
    sew(sewing);
  }
  const TopoDS_Shape sewn = sewing->SewedShape();
  BRepBuilderAPI_MakeSolid ms;
  int shells = 0;
  for (TopExp_Explorer ex(sewn, TopAbs_SHELL); ex.More(); ex.Next()) {
    ms.Add(TopoDS::Shell(ex.Current()));
    ++shells;
  }
  if (shells == 0) {
    throw BoundaryFailure{"the kept pieces do not sew into a shell"};
  }
  ShapeFix_Solid fix;
  fix.Init(ms.Solid());
  fix.Perform();
  out.solid = merged_analytic_faces(fix.Solid());
  out.seconds["sewing"] = out.seconds.value("sewing", 0.0) + since(t_sew);
}

}  // namespace

BoundarySweep boundary_sweep(const TopoDS_Shape& body, const ScrewJoint& j, double T, const PointTestMaker& member,
                             double size, double tol, const Settings& settings, int stage, int joint_no) {
  BoundarySweep out;
  BoundaryContext c{j, T, size, tol, settings.fit_fraction * tol, Settings::resolution * size, settings, stage, joint_no,
                    out};
  try {
    const auto t0 = Clock::now();
    std::vector<Candidate> cands = candidates_of(body, c);
    out.seconds["candidates"] = since(t0);
    group_by_surface(cands, c);
    const Crossings crossings = crossings_of(cands, c);
    const std::vector<Piece> pieces = split_candidates(cands, crossings.tools, c);
    const std::vector<int> keep = classify_pieces(pieces, member, c, false);
    if (const char* dir = std::getenv("SWEEP_DUMP_BOUNDARY"))
      dump_boundary((std::string(dir) + (settings.touching_sections ? "" : "/general")).c_str(), cands, pieces, keep,
                    crossings.pair_edges);
    // Pieces that do not close into a valid solid are classified again closer to each sample (a
    // sheet within the offset of a piece turns both its probes), and taken when those close into
    // one. (Not at first: a piece that lies within the tolerance of its sheet but farther than a
    // closer offset would be dropped.)
    std::optional<BoundaryFailure> failed;
    try {
      sew_kept(pieces, keep, c);
    } catch (const BoundaryFailure& f) {
      failed = f;
      out.solid.Nullify();
    }
    std::string why = not_a_solid(out.solid);
    if (!why.empty()) {
      const std::vector<int> keep_closer = classify_pieces(pieces, member, c, true);
      if (keep_closer != keep) {
        const BoundarySweep first = out;
        try {
          sew_kept(pieces, keep_closer, c);
        } catch (const BoundaryFailure&) {
          out.solid.Nullify();
        }
        if (not_a_solid(out.solid).empty()) {
          failed.reset();
          why.clear();
        } else {
          out = first;
        }
      }
    }
    if (failed) throw *failed;
    if (!why.empty()) throw BoundaryFailure{why};
  } catch (const BoundaryFailure& f) {
    out.failure = f.why;
    out.solid.Nullify();
  }
  return out;
}

}  // namespace sweep::occt
