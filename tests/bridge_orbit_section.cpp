// Sections of faces swept along one joint's orbits (turned about an axis, or extruded along a
// direction), found from their profiles, against OCCT's general section of the same faces, and the
// sweeps built either way.
#include <BRepAlgoAPI_Section.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <TopoDS_Compound.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <GProp_GProps.hxx>
#include <Geom_BSplineCurve.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <GeomAPI_PointsToBSpline.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <catch2/catch.hpp>

#include "occt_bridge/sweeper.hpp"
#include "base/internal.hpp"
#include "faces/orbit_section.hpp"
#include "util/random_one_joint.hpp"

using namespace sweep;
using sweep::occt::OrbitPatch;
using sweep::occt::orbit_patch;
using sweep::occt::orbit_section;

namespace {

ScrewJoint z_axis() {
  ScrewJoint j;
  j.type = JointType::Revolute;
  j.point = Eigen::Vector3d(0.3, -0.2, 0);
  j.direction = Eigen::Vector3d::UnitZ();
  return j;
}

/// The face swept by `edge` turned about the joint's axis from `from` through `angle` (radians).
TopoDS_Face turned(const TopoDS_Edge& edge, const ScrewJoint& j, double from, double angle) {
  const gp_Ax1 axis(gp_Pnt(j.point.x(), j.point.y(), j.point.z()), gp_Dir(j.direction.x(), j.direction.y(), j.direction.z()));
  gp_Trsf r;
  r.SetRotation(axis, from);
  BRepPrimAPI_MakeRevol mk(TopoDS::Edge(edge.Moved(TopLoc_Location(r))), axis, angle);
  REQUIRE(mk.IsDone());
  TopExp_Explorer ex(mk.Shape(), TopAbs_FACE);
  REQUIRE(ex.More());
  return TopoDS::Face(ex.Current());
}

/// A B-spline through meridian points (r, z) in the plane through the axis point along +x.
TopoDS_Edge spline_meridian(const ScrewJoint& j, const std::vector<std::pair<double, double>>& rz) {
  TColgp_Array1OfPnt pts(1, int(rz.size()));
  for (std::size_t k = 0; k < rz.size(); ++k)
    pts.SetValue(int(k) + 1, gp_Pnt(j.point.x() + rz[k].first, j.point.y(), rz[k].second));
  GeomAPI_PointsToBSpline fit(pts);
  REQUIRE(fit.IsDone());
  return BRepBuilderAPI_MakeEdge(fit.Curve()).Edge();
}

TopoDS_Edge segment(const ScrewJoint& j, double r0, double z0, double r1, double z1) {
  return BRepBuilderAPI_MakeEdge(gp_Pnt(j.point.x() + r0, j.point.y(), z0), gp_Pnt(j.point.x() + r1, j.point.y(), z1)).Edge();
}

double length(const TopoDS_Shape& s) {
  GProp_GProps g;
  BRepGProp::LinearProperties(s, g);
  return g.Mass();
}

double section_length(const TopoDS_Face& a, const TopoDS_Face& b) {
  BRepAlgoAPI_Section sec(a, b, false);
  sec.Approximation(true);
  sec.Build();
  REQUIRE(sec.IsDone());
  return length(sec.Shape());
}

/// The face swept by `edge` moved along the joint's direction through `length`.
TopoDS_Face extruded(const TopoDS_Edge& edge, const ScrewJoint& j, double length) {
  BRepPrimAPI_MakePrism mk(edge, gp_Vec(j.direction.x(), j.direction.y(), j.direction.z()) * length);
  REQUIRE(mk.IsDone());
  TopExp_Explorer ex(mk.Shape(), TopAbs_FACE);
  REQUIRE(ex.More());
  return TopoDS::Face(ex.Current());
}

/// A cubic through the points.
TopoDS_Edge spline_through(const std::vector<gp_Pnt>& pts) {
  Handle(TColgp_HArray1OfPnt) arr = new TColgp_HArray1OfPnt(1, int(pts.size()));
  for (std::size_t k = 0; k < pts.size(); ++k) arr->SetValue(int(k) + 1, pts[k]);
  GeomAPI_Interpolate interp(arr, false, 1e-12);
  interp.Perform();
  REQUIRE(interp.IsDone());
  return BRepBuilderAPI_MakeEdge(interp.Curve()).Edge();
}

double distance(const TopoDS_Shape& a, const TopoDS_Shape& b) {
  BRepExtrema_DistShapeShape d(a, b);
  REQUIRE(d.IsDone());
  return d.Value();
}

/// The one face that edge `e` sweeps under joint j over [0, T] (fitted to `tol`, its error to *err).
TopoDS_Face one_face_sweep(const TopoDS_Edge& e, const ScrewJoint& j, double T, double tol, double* err) {
  double f, l;
  const Handle(Geom_Curve) c = BRep_Tool::Curve(e, f, l);
  const std::vector<TopoDS_Face> faces = occt::sweep_curve(c, f, l, j, T, tol, err);
  REQUIRE(faces.size() == 1);
  return faces.front();
}

/// Two curves each swept over [0, T] by joint j (one face each, fitted to `tol`), and their orbit
/// patches at the boundary tolerance the fit allows (ten fit errors, at least 100 eps).
struct HelicalPair {
  TopoDS_Face a, b;
  double btol = 0;
  OrbitPatch pa, pb;
};

HelicalPair helical_pair(const TopoDS_Edge& ea, const TopoDS_Edge& eb, const ScrewJoint& j, double T, double tol,
                         double eps) {
  double err = 0;
  HelicalPair h;
  h.a = one_face_sweep(ea, j, T, tol, &err);
  h.b = one_face_sweep(eb, j, T, tol, &err);
  h.btol = std::max(100 * eps, 10 * err);
  const auto pa = orbit_patch(h.a, j, eps, h.btol), pb = orbit_patch(h.b, j, eps, h.btol);
  REQUIRE(pa);
  REQUIRE(pb);
  h.pa = *pa;
  h.pb = *pb;
  return h;
}

}  // namespace

TEST_CASE("Orbit sections: crossing meridians give the arcs over the overlap of the angle ranges") {
  const ScrewJoint j = z_axis();
  const double eps = 1e-9, btol = 1e-7;
  // a spline meridian and a segment that cross once, at r = 1.5
  const TopoDS_Edge bent = spline_meridian(j, {{1.0, 0.0}, {1.4, 0.6}, {1.6, 1.2}, {1.7, 2.0}});
  const TopoDS_Edge line = segment(j, 2.2, 0.0, 0.8, 2.0);
  const TopoDS_Face a = turned(bent, j, 0.0, M_PI / 2);
  const TopoDS_Face b = turned(line, j, M_PI / 4, 5 * M_PI / 4);  // 45 to 270 degrees
  const auto pa = orbit_patch(a, j, eps), pb = orbit_patch(b, j, eps);
  REQUIRE(pa);
  REQUIRE(pb);
  const auto arcs = orbit_section(*pa, *pb, j, btol);
  REQUIRE(arcs);
  REQUIRE(arcs->size() == 1);
  // the arc lies on both faces, over 45 to 90 degrees, and is OCCT's section of the two faces
  TopoDS_Compound c;
  BRep_Builder bb;
  bb.MakeCompound(c);
  for (const auto& e : *arcs) bb.Add(c, e);
  const double occt = section_length(a, b);
  CHECK(length(c) == Approx(occt).epsilon(1e-6));
  double f, l;
  const Handle(Geom_Curve) curve = BRep_Tool::Curve(arcs->front(), f, l);
  CHECK(l - f == Approx(M_PI / 4).epsilon(1e-9));
  const gp_Pnt m = curve->Value(0.5 * (f + l));
  const double r = std::hypot(m.X() - j.point.x(), m.Y() - j.point.y());
  // where the spline meets the line r = 2.2 - 0.7 z
  CHECK(std::abs(r - (2.2 - 0.7 * m.Z())) < 1e-9);
  CHECK(std::atan2(m.Y() - j.point.y(), m.X() - j.point.x()) == Approx(3 * M_PI / 8).epsilon(1e-9));
  // turned the other way about the axis, the face gives the same arcs
  ScrewJoint down = j;
  down.direction = -j.direction;
  const auto qa = orbit_patch(a, down, eps), qb = orbit_patch(b, down, eps);
  REQUIRE(qa);
  REQUIRE(qb);
  const auto again = orbit_section(*qa, *qb, down, btol);
  REQUIRE(again);
  REQUIRE(again->size() == 1);
  CHECK(length(again->front()) == Approx(length(arcs->front())).epsilon(1e-9));
  // angle ranges that overlap twice (a 300-degree face and one from 270 through 150 degrees)
  const TopoDS_Face wide = turned(bent, j, 0.0, 300 * M_PI / 180);
  const TopoDS_Face wrap = turned(line, j, 270 * M_PI / 180, 150 * M_PI / 180);
  const auto two = orbit_section(*orbit_patch(wide, j, eps), *orbit_patch(wrap, j, eps), j, btol);
  REQUIRE(two);
  CHECK(two->size() == 2);
}

TEST_CASE("Orbit sections: no arc where faces only meet at their boundaries, OCCT where meridians touch") {
  const ScrewJoint j = z_axis();
  const double eps = 1e-9, btol = 1e-7;
  const TopoDS_Edge bent = spline_meridian(j, {{1.0, 0.0}, {1.4, 0.6}, {1.6, 1.2}, {1.7, 2.0}});
  // two quarter turns of one meridian meet along a meridian edge
  const auto p1 = orbit_patch(turned(bent, j, 0.0, M_PI / 2), j, eps);
  const auto p2 = orbit_patch(turned(bent, j, M_PI / 2, M_PI / 2), j, eps);
  REQUIRE(p1);
  REQUIRE(p2);
  const auto none = orbit_section(*p1, *p2, j, btol);
  REQUIRE(none);
  CHECK(none->empty());
  // overlapping turns of one meridian are left to the general section
  const auto p3 = orbit_patch(turned(bent, j, M_PI / 4, M_PI / 2), j, eps);
  CHECK_FALSE(orbit_section(*p1, *p3, j, btol));
  // a meridian that starts on another's end: they meet on both boundaries
  const auto p4 = orbit_patch(turned(segment(j, 1.7, 2.0, 2.5, 2.5), j, 0.0, M_PI), j, eps);
  REQUIRE(p4);
  const auto shared = orbit_section(*p1, *p4, j, btol);
  REQUIRE(shared);
  CHECK(shared->empty());
  // a segment tangent to the spline is left to the general section
  gp_Pnt p;
  gp_Vec d;
  double f, l;
  BRep_Tool::Curve(bent, f, l)->D1(0.5 * (f + l), p, d);
  const double r0 = p.X() - j.point.x(), z0 = p.Z();
  const auto tangent = orbit_patch(
      turned(segment(j, r0 - 0.3 * d.X(), z0 - 0.3 * d.Z(), r0 + 0.3 * d.X(), z0 + 0.3 * d.Z()), j, 0.0, M_PI), j, eps);
  REQUIRE(tangent);
  CHECK_FALSE(orbit_section(*p1, *tangent, j, btol));
  // faces about another axis, or trimmed to other than their parameter box, are not patches
  ScrewJoint other = j;
  other.point.x() += 0.5;
  CHECK_FALSE(orbit_patch(turned(bent, j, 0.0, M_PI / 2), other, eps));
}

TEST_CASE("Orbit sections: helical sweeps of curves through one point cross along the helix through it") {
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = Eigen::Vector3d(0.2, -0.1, 0);
  j.direction = Eigen::Vector3d(0.1, 0.2, 1.0).normalized();
  j.pitch = 0.3;
  const double T = M_PI / 2, tol = 1e-7, eps = 1e-9;
  // a segment and a spline that cross at P, each swept a quarter turn: one face each
  const gp_Pnt P(1.5, 0.15, 0.05);
  const TopoDS_Edge line = BRepBuilderAPI_MakeEdge(gp_Pnt(1, 0, -0.45), gp_Pnt(2, 0.3, 0.55)).Edge();
  const TopoDS_Edge bent = spline_through({gp_Pnt(1.2, -0.4, 0.3), P, gp_Pnt(2.0, 0.5, -0.2)});
  const auto [a, b, btol, pa, pb] = helical_pair(line, bent, j, T, tol, eps);
  CHECK_FALSE(orbit_patch(a, j, eps));  // (only with the fit's tolerance)
  double section_err = 0;
  const auto arcs = orbit_section(pa, pb, j, btol, &section_err);
  REQUIRE(arcs);
  REQUIRE(arcs->size() == 1);
  CHECK(section_err <= 0.1 * btol);
  // the helix through P over the quarter turn: sqrt(r^2 + pitch^2) per radian
  const Eigen::Vector3d d = Eigen::Vector3d(P.X(), P.Y(), P.Z()) - j.point;
  const double r = (d - j.direction * j.direction.dot(d)).norm();
  CHECK(length(arcs->front()) == Approx(std::hypot(r, j.pitch) * T).epsilon(1e-6));
  CHECK(length(arcs->front()) == Approx(section_length(a, b)).epsilon(1e-5));
  double f, l;
  const Handle(Geom_Curve) curve = BRep_Tool::Curve(arcs->front(), f, l);
  for (double t : {0.0, 0.3, 0.5, 1.0}) {
    const gp_Pnt x = curve->Value(f + t * (l - f));
    const TopoDS_Vertex v = BRepBuilderAPI_MakeVertex(x).Vertex();
    CHECK(distance(v, a) < 1e-6);
    CHECK(distance(v, b) < 1e-6);
    // on the helix through P: moved back to P's height it is P turned about the axis
    const Eigen::Vector3d y = Eigen::Vector3d(x.X(), x.Y(), x.Z()) - j.point;
    const double q = j.direction.dot(y - d) / j.pitch;
    const Eigen::Vector3d back = Eigen::AngleAxisd(-q, j.direction) * (y - j.direction * (j.pitch * q));
    CHECK((back - d).norm() < 1e-6);
  }
  // the spline moved a quarter turn on (its face begins where the segment's ends): they meet at a
  // point at most
  const TopoDS_Edge later = TopoDS::Edge(bent.Moved(TopLoc_Location(occt::to_trsf(j.transform(T)))));
  double err = 0;
  const auto pc = orbit_patch(one_face_sweep(later, j, T, tol, &err), j, eps, btol);
  REQUIRE(pc);
  const auto none = orbit_section(pa, *pc, j, btol);
  REQUIRE(none);
  CHECK(none->empty());
  // another pitch: not a patch of this joint
  ScrewJoint other = j;
  other.pitch = 0.5;
  CHECK_FALSE(orbit_patch(a, other, eps, btol));
}

TEST_CASE("Orbit sections: two turns of one screwed curve cross where its profile crosses itself") {
  // a curve whose profile across the helices (each point moved back along its helix to the plane
  // across the axis) is a nodal cubic, crossing itself at X for sigma = -1 and 1, and whose points
  // sit k * sigma radians along their helices: its sweep over the first quarter turn and over the
  // next one have one profile, and the line of X's place at sigma = 1 on the first meets that of
  // its place at -1 on the second over [pi / 2 - k, pi / 2 + k] of the coordinate along the helix
  // through X. Read as pieces of one sweep (one profile: they meet along an edge at most), they
  // gave no crossing: a cylinder screwed 2.3 turns (seed 47, case 14) kept a strip of a rim's sweep
  // inside the solid and ran out of time.
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = Eigen::Vector3d(0.1, 0.2, -0.3);
  j.direction = Eigen::Vector3d(0.2, -0.1, 1.0).normalized();
  j.pitch = 0.25;
  const double T = M_PI / 2, k = 0.5, tol = 1e-7, eps = 1e-9;
  const Eigen::Vector3d w = j.direction, e1 = w.unitOrthogonal(), e2 = w.cross(e1);
  const Eigen::Vector2d c(1.5, 0.2);
  auto lifted = [&](const Eigen::Vector2d& m, double q) {
    return Eigen::Vector3d(j.point + Eigen::AngleAxisd(q, w) * (e1 * m.x() + e2 * m.y()) + w * (j.pitch * q));
  };
  auto nodal = [&](double s) { return Eigen::Vector2d(c + 0.3 * Eigen::Vector2d(s * s - 1, 0.5 * s * (s * s - 1))); };
  std::vector<gp_Pnt> pts;
  for (int n = 0; n <= 24; ++n) {
    const double s = -1.5 + 3.0 * n / 24;
    pts.push_back(occt::to_pnt(lifted(nodal(s), k * s)));
  }
  const TopoDS_Edge curve = spline_through(pts);
  const TopoDS_Edge next = TopoDS::Edge(curve.Moved(TopLoc_Location(occt::to_trsf(j.transform(T)))));
  const auto [a, b, btol, pa, pb] = helical_pair(curve, next, j, T, tol, eps);
  double section_err = 0;
  const auto arcs = orbit_section(pa, pb, j, btol, &section_err);
  REQUIRE(arcs);
  REQUIRE(arcs->size() == 1);
  CHECK(section_err <= 0.1 * btol);
  const double per_radian = std::hypot(c.norm(), j.pitch);  // X = c
  CHECK(length(arcs->front()) == Approx(per_radian * 2 * k).epsilon(1e-6));
  for (const TopoDS_Edge& e : *arcs) {
    double f, l;
    const Handle(Geom_Curve) g = BRep_Tool::Curve(e, f, l);
    for (double t : {0.0, 0.4, 1.0}) {
      const gp_Pnt x = g->Value(f + t * (l - f));
      const TopoDS_Vertex v = BRepBuilderAPI_MakeVertex(x).Vertex();
      CHECK(distance(v, a) < 1e-6);
      CHECK(distance(v, b) < 1e-6);
      // on the helix through X
      const Eigen::Vector3d y = occt::to_eigen(x) - j.point;
      const double q = w.dot(y) / j.pitch;
      const Eigen::Vector3d back = Eigen::AngleAxisd(-q, w) * (y - w * w.dot(y));
      CHECK((Eigen::Vector2d(back.dot(e1), back.dot(e2)) - c).norm() < 1e-6);
    }
  }
}

TEST_CASE("Orbit sections: helical sweeps of a grazing line and an edge from its end touch there and cross nowhere") {
  // a box's face y = 0.0826 screwed about an oblique axis (CI case 48): its grazing line (where
  // the motion is tangent to the face) ends on the face's bottom edge. In the plane across the
  // orbits the line's profile is the fold of the face's, and the edge's leaves it tangentially:
  // the solver stopped 1e-6 short of the shared end, where the profiles meet at no angle, and
  // the pair went to OCCT's section of two faces tangent along the helix of that end.
  ScrewJoint j;
  j.type = JointType::Helical;
  j.point = Eigen::Vector3d(0.606009, 1.763570, 0.786093);
  j.direction = Eigen::Vector3d(0.436393, -0.289719, 0.851836).normalized();
  j.pitch = 1.013665 / (2 * M_PI);
  const double y = 0.082599, z0 = 0.126736, z1 = 0.810331, x1 = 1.483666;
  const double T = M_PI / 2, tol = 1e-7, eps = 1e-9;
  // n . v = 0 on the face, n = -y: linear in x and z
  const Eigen::Vector3d n(0, -1, 0);
  auto g = [&](double x, double z) {
    const Eigen::Vector3d p(x, y, z);
    return n.dot(j.direction.cross(p - j.point) + j.pitch * j.direction);
  };
  auto grazing_x = [&](double z) { return -g(0, z) / (g(1, z) - g(0, z)); };
  const gp_Pnt E(grazing_x(z0), y, z0), F(grazing_x(z1), y, z1);
  REQUIRE(E.X() == Approx(0.32309).margin(1e-5));
  const TopoDS_Edge line = BRepBuilderAPI_MakeEdge(E, F).Edge();
  const TopoDS_Edge edge = BRepBuilderAPI_MakeEdge(E, gp_Pnt(x1, y, z0)).Edge();
  const auto [a, b, btol, pa, pb] = helical_pair(line, edge, j, T, tol, eps);
  for (const bool swap : {false, true}) {
    const auto arcs = swap ? orbit_section(pb, pa, j, btol) : orbit_section(pa, pb, j, btol);
    REQUIRE(arcs);
    CHECK(arcs->empty());
  }
  // they touch along the helix of E
  for (double t : {0.0, 0.3, 0.7, 1.0}) {
    const TopoDS_Vertex v = BRepBuilderAPI_MakeVertex(occt::to_pnt(j.transform(T * t) * occt::to_eigen(E))).Vertex();
    CHECK(distance(v, a) < 1e-6);
    CHECK(distance(v, b) < 1e-6);
  }
  // and cross nowhere: two points lie on one helix when their helical coordinates (r, phi - z /
  // pitch) agree, so the sweeps cross where the polylines of those coordinates cross (within a
  // quarter turn of height), which they do not past the shared end
  const Eigen::Vector3d e0 = occt::to_eigen(E), e1(x1, y, z0), f1 = occt::to_eigen(F);
  const Eigen::Vector3d ax = j.direction, ux = ax.unitOrthogonal(), uy = ax.cross(ux);
  auto profile = [&](const Eigen::Vector3d& x) {
    const Eigen::Vector3d d = x - j.point;
    const double psi = std::atan2(d.dot(uy), d.dot(ux)) - d.dot(ax) / j.pitch;
    const double r = (d - ax * d.dot(ax)).norm();
    return Eigen::Vector2d(r * std::cos(psi), r * std::sin(psi));
  };
  const int N = 2000;
  std::vector<Eigen::Vector2d> pl, pe;
  for (int k = 0; k <= N; ++k) {
    pl.push_back(profile(e0 + (f1 - e0) * double(k) / N));
    pe.push_back(profile(e0 + (e1 - e0) * double(k) / N));
  }
  auto cross2 = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  int crossings = 0;
  for (int k = N / 100; k < N; ++k)
    for (int m = N / 100; m < N; ++m) {
      const Eigen::Vector2d p = pl[k], r = pl[k + 1] - pl[k], q = pe[m], u = pe[m + 1] - pe[m];
      const double den = cross2(r, u);
      if (den == 0) continue;
      const double t = cross2(q - p, u) / den, w = cross2(q - p, r) / den;
      if (t >= 0 && t <= 1 && w >= 0 && w <= 1) ++crossings;
    }
  CHECK(crossings == 0);
}

namespace {

// Revolute and prismatic sweeps of the random generator's solids but tori
// (seed `seed`), `per_kind` of each joint kind, built with orbit sections and with OCCT's general
// sections, both against the orbit-space reference and against each other.
void compare_orbit_sections(std::uint64_t seed, int per_kind) {
  for (const int kind : {0, 1}) {  // (the generator's joint kinds: revolute, prismatic)
    int compared = 0;
    for (int i = 0; compared < per_kind && i < 200; ++i) {
      if (testing::random_case_joint(i) != kind || testing::random_case_kind(i) == 4) continue;
      const testing::RandomCase c = testing::random_one_joint_case(seed, i);
      const Spec spec = parse_spec(c.spec, ".");
      double ref_err = 0;
      const double ref = testing::reference_volume(spec, 1e-8, &ref_err);
      occt::RunOptions on, off;
      on.stop = occt::stop_after(60);
      off.stop = occt::stop_after(60);
      off.settings.orbit_sections = false;
      const occt::RunResult a = occt::run_sweep(spec, on), b = occt::run_sweep(spec, off);
      INFO(c.name << ": " << c.spec << " ; " << a.report.message << " ; " << b.report.message);
      // a solid within the requested tolerance of the true boundary is within it times the area
      // of the true volume (a ball turned 40 degrees whose grazing circle is recognised to within
      // the tolerance is 5.7e-6 off)
      for (const auto* r : {&a, &b})
        if (r->report.ok())
          CHECK(std::abs(r->report.volume_brep - ref) <= r->report.tol_requested * r->report.area + 3 * ref_err);
      if (a.report.ok() && b.report.ok()) {
        ++compared;
        CHECK(std::abs(a.report.volume_brep - b.report.volume_brep) <= 2e-6 * ref);
      }
    }
    CHECK(compared == per_kind);
  }
}

}  // namespace

TEST_CASE("Orbit sections: revolute and prismatic sweeps built with them and with OCCT's general sections agree", "[random]") {
  compare_orbit_sections(17, 4);  // a box, a sphere, a cylinder and a cone each
}

TEST_CASE("Orbit sections: ten revolute and ten prismatic sweeps of another seed both ways", "[bench]") {
  compare_orbit_sections(29, 10);
}

TEST_CASE("Orbit sections: extrusions whose profiles cross meet in the segment over the overlap of their ranges") {
  ScrewJoint j;
  j.type = JointType::Prismatic;
  j.direction = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  const double eps = 1e-9, btol = 1e-7;
  // two curves in planes z = 0 and z = 0.8 whose projections along the direction cross once
  const TopoDS_Edge c1 = spline_through({gp_Pnt(0, 0, 0), gp_Pnt(1, 0.5, 0), gp_Pnt(2, 0.4, 0), gp_Pnt(3, 1, 0)});
  const TopoDS_Edge c2 = spline_through({gp_Pnt(0, 1, 0.8), gp_Pnt(1, 0.6, 0.8), gp_Pnt(2, 0.2, 0.8), gp_Pnt(3, -0.2, 0.8)});
  const TopoDS_Face a = extruded(c1, j, 2.0), b = extruded(c2, j, 1.5);
  const auto pa = orbit_patch(a, j, eps), pb = orbit_patch(b, j, eps);
  REQUIRE(pa);
  REQUIRE(pb);
  const auto segs = orbit_section(*pa, *pb, j, btol);
  REQUIRE(segs);
  REQUIRE(segs->size() == 1);
  // a segment along the direction, on both faces, of OCCT's section's length
  double f, l;
  const Handle(Geom_Curve) line = BRep_Tool::Curve(segs->front(), f, l);
  gp_Pnt p;
  gp_Vec d;
  line->D1(0.5 * (f + l), p, d);
  CHECK(d.Normalized().Dot(gp_Vec(j.direction.x(), j.direction.y(), j.direction.z())) == Approx(1.0).epsilon(1e-12));
  CHECK(length(segs->front()) == Approx(section_length(a, b)).epsilon(1e-6));
  for (double s : {0.0, 0.5, 1.0}) {
    const TopoDS_Vertex v = BRepBuilderAPI_MakeVertex(line->Value(f + s * (l - f))).Vertex();
    CHECK(distance(v, a) < 1e-9);
    CHECK(distance(v, b) < 1e-9);
  }
  // the second curve moved past the first one's range: the profiles cross, the faces do not
  gp_Trsf up;
  up.SetTranslation(gp_Vec(j.direction.x(), j.direction.y(), j.direction.z()) * 2.5);
  const auto pc = orbit_patch(extruded(TopoDS::Edge(c2.Moved(TopLoc_Location(up))), j, 1.5), j, eps);
  REQUIRE(pc);
  const auto none = orbit_section(*pa, *pc, j, btol);
  REQUIRE(none);
  CHECK(none->empty());
  // a face extruded along another direction is no patch of this joint
  ScrewJoint other = j;
  other.direction = Eigen::Vector3d::UnitZ();
  CHECK_FALSE(orbit_patch(a, other, eps));
}

TEST_CASE("Orbit sections: an extrusion whose profile loops is cut where it passes through itself") {
  ScrewJoint j;
  j.type = JointType::Prismatic;
  j.direction = Eigen::Vector3d::UnitZ();
  const double eps = 1e-9, btol = 1e-7;
  // a prolate cycloid x = t - 1.5 sin t, y = 1 - 1.5 cos t rising as z = 0.1 t: its projection crosses
  // itself at t = +-s with s = 1.5 sin s, at (0, 1 - 1.5 cos s)
  std::vector<gp_Pnt> pts;
  for (int k = 0; k <= 60; ++k) {
    const double t = -2.5 + 5.0 * k / 60;
    pts.emplace_back(t - 1.5 * std::sin(t), 1 - 1.5 * std::cos(t), 0.1 * t);
  }
  double s = 1.5;
  for (int it = 0; it < 60; ++it) s -= (s - 1.5 * std::sin(s)) / (1 - 1.5 * std::cos(s));
  const TopoDS_Face loop = extruded(spline_through(pts), j, 1.0);
  const auto p = orbit_patch(loop, j, eps);
  REQUIRE(p);
  const std::vector<double> cuts = sweep::occt::profile_self_crossings(*p, j, btol);
  REQUIRE(cuts.size() == 3);  // both places of the crossing, and halfway between
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(loop);
  for (double c : {cuts[0], cuts[2]}) {
    const gp_Pnt q = p->orbit_is_u ? surface->Value(p->a0, c) : surface->Value(c, p->a0);
    CHECK(std::abs(q.X()) < 1e-4);
    CHECK(std::abs(q.Y() - (1 - 1.5 * std::cos(s))) < 1e-4);
  }
  const auto pieces = sweep::occt::patch_pieces(*p, cuts);
  REQUIRE(pieces.size() == 4);
  // the pieces cover the profile's range one after another, each on its own sheet with the same
  // parameters
  double next = std::min(p->b0, p->b1);
  for (const auto& piece : pieces) {
    double u0, u1, v0, v1;
    BRepTools::UVBounds(piece.face, u0, u1, v0, v1);
    const double lo = p->orbit_is_u ? v0 : u0, hi = p->orbit_is_u ? v1 : u1;
    CHECK(lo == Approx(next).margin(1e-12));
    next = hi;
    GProp_GProps g, h;
    BRepGProp::SurfaceProperties(piece.face, g);
    BRepGProp::SurfaceProperties(sweep::occt::on_own_sheet(piece.face, piece.sheet), h);
    CHECK(h.Mass() == Approx(g.Mass()).epsilon(1e-9));
  }
  CHECK(next == Approx(std::max(p->b0, p->b1)).margin(1e-12));
  // a profile that does not loop is not cut
  const auto pa = orbit_patch(extruded(spline_through({gp_Pnt(0, 0, 0), gp_Pnt(1, 0.5, 0), gp_Pnt(2, 0.4, 0)}), j, 1.0), j, eps);
  REQUIRE(pa);
  CHECK(sweep::occt::profile_self_crossings(*pa, j, btol).empty());
}
