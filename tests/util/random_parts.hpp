#pragma once
// A seeded generator of one-joint sweeps of machined parts, each given to the sweep as a STEP file
// (a `brep` entity), as a user's CAD part is: a plate with a through hole, a block with a boss, an
// L-bracket, a shaft with a collar and a block with a spherical pocket, in a random pose, under a
// revolute, prismatic or helical joint drawn as for the primitives (random_one_joint.hpp). Each part
// is also built as orbit intervals (sweep/orbit.hpp: unions and differences of primitives), which
// give the reference volume without a B-rep. Case i has family i % 5 and joint kind (i / 5) % 3.
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Writer.hxx>
#include <TopoDS_Shape.hxx>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "sweep/orbit.hpp"
#include "sweep/spec.hpp"
#include "util/random_one_joint.hpp"

namespace sweep::testing {

inline const char* const kPartFamilies[] = {"plate_hole", "boss", "l_bracket", "collar", "pocket"};
inline constexpr int kPartFamilyCount = 5;

/// A part, its orbit intervals and the joint that moves it.
struct RandomPart {
  std::string name;    ///< family, joint type and index
  TopoDS_Shape shape;  ///< the part in its pose
  OrbitSolidPtr orbit;  ///< the same solid as orbit intervals
  std::string joint;   ///< the joint's JSON (degrees)
  /// The spec's JSON, the part read from `file`.
  std::string spec(const std::string& file) const {
    return "{\"sweep\": 1, \"name\": \"" + name + "\", \"angles\": \"deg\", \"entity\": {\"kind\": \"brep\", \"file\": \"" +
           file + "\"}, \"motion\": {\"kind\": \"axes\", \"joints\": [" + joint + "]}}";
  }
};

namespace detail {

/// The part in its own frame (OCCT shape and orbit solid) for family k, dimensions drawn by `in`.
template <class In>
void part_in_own_frame(int k, In& in, TopoDS_Shape& shape, OrbitSolidPtr& orbit) {
  const auto box = [](Eigen::Vector3d lo, Eigen::Vector3d hi) {
    return std::make_pair(BRepPrimAPI_MakeBox(gp_Pnt(lo.x(), lo.y(), lo.z()), gp_Pnt(hi.x(), hi.y(), hi.z())).Shape(),
                          orbit_box(lo, hi));
  };
  const auto cylinder_z = [](Eigen::Vector3d base, double r, double h) {
    return std::make_pair(
        BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(base.x(), base.y(), base.z()), gp_Dir(0, 0, 1)), r, h).Shape(),
        orbit_cylinder(base, Eigen::Vector3d::UnitZ(), r, h));
  };
  // (every draw in a statement of its own, so that every compiler draws alike; the order, later
  // arguments first, is the one the tables in tests/data were made in)
  const double a = in(0.6, 1.6), b = in(0.5, 1.4), c = in(0.2, 0.8);
  const auto block = box(Eigen::Vector3d::Zero(), Eigen::Vector3d(a, b, c));
  if (k == 0) {  // a plate with a through hole
    const double r = in(0.1, 0.45) * std::min(a, b) * 0.5;
    const double cy = in(r + 0.05, b - r - 0.05), cx = in(r + 0.05, a - r - 0.05);
    const Eigen::Vector3d ctr(cx, cy, -0.1);
    const auto hole = cylinder_z(ctr, r, c + 0.2);
    shape = BRepAlgoAPI_Cut(block.first, hole.first).Shape();
    orbit = orbit_difference(block.second, hole.second);
  } else if (k == 1) {  // a block with a boss on its top face
    const double r = in(0.15, 0.45) * std::min(a, b) * 0.5;
    const double cy = in(r + 0.05, b - r - 0.05), cx = in(r + 0.05, a - r - 0.05);
    const Eigen::Vector3d ctr(cx, cy, c);
    const auto boss = cylinder_z(ctr, r, in(0.2, 0.8));
    shape = BRepAlgoAPI_Fuse(block.first, boss.first).Shape();
    orbit = orbit_union({block.second, boss.second});
  } else if (k == 2) {  // an L-bracket: a block without a corner strip
    const double nz = in(0.3, 0.7) * c, nx = in(0.25, 0.6) * a;
    const auto notch = box(Eigen::Vector3d(nx, -0.1, nz), Eigen::Vector3d(a + 0.1, b + 0.1, c + 0.1));
    shape = BRepAlgoAPI_Cut(block.first, notch.first).Shape();
    orbit = orbit_difference(block.second, notch.second);
  } else if (k == 3) {  // a shaft with a collar
    const double r1 = in(0.1, 0.35), h1 = in(0.8, 2.0), r2 = r1 + in(0.1, 0.4), h2 = in(0.1, 0.4) * h1;
    const auto shaft = cylinder_z(Eigen::Vector3d::Zero(), r1, h1);
    const auto collar = cylinder_z(Eigen::Vector3d(0, 0, in(0.1, 0.6) * h1), r2, h2);
    shape = BRepAlgoAPI_Fuse(shaft.first, collar.first).Shape();
    orbit = orbit_union({shaft.second, collar.second});
  } else {  // a block with a spherical pocket in its top face
    const double r = in(0.3, 0.9) * std::min({a * 0.5, b * 0.5, c});
    const double cy = in(r + 0.05, b - r - 0.05), cx = in(r + 0.05, a - r - 0.05);
    const Eigen::Vector3d ctr(cx, cy, c);
    const TopoDS_Shape ball = BRepPrimAPI_MakeSphere(gp_Pnt(ctr.x(), ctr.y(), ctr.z()), r).Shape();
    shape = BRepAlgoAPI_Cut(block.first, ball).Shape();
    orbit = orbit_difference(block.second, orbit_sphere(ctr, r));
  }
}

}  // namespace detail

inline RandomPart random_part_case(std::uint64_t seed, int index) {
  std::mt19937_64 rng(seed * 7000003ULL + std::uint64_t(index));
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  auto in = [&](double lo, double hi) { return lo + (hi - lo) * uni(rng); };
  auto u = [&]() { return uni(rng); };
  const auto num = fixed6;
  auto unit = [&]() {
    for (;;) {
      const double z = in(-1, 1), y = in(-1, 1), x = in(-1, 1);
      const Eigen::Vector3d v(x, y, z);
      if (v.norm() > 0.2 && v.norm() <= 1) return Eigen::Vector3d(v.normalized());
    }
  };
  auto vec_json = [&](const Eigen::Vector3d& v) { return "[" + num(v.x()) + ", " + num(v.y()) + ", " + num(v.z()) + "]"; };
  RandomPart p;
  const int family = index % kPartFamilyCount;
  TopoDS_Shape local;
  OrbitSolidPtr local_orbit;
  detail::part_in_own_frame(family, in, local, local_orbit);
  // a random pose, the part's origin within the unit cube about the origin
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d turn_axis = unit();
  const double turn = in(0, M_PI);
  pose.linear() = Eigen::AngleAxisd(turn, turn_axis).toRotationMatrix();
  const double tz = in(-1, 0.5), ty = in(-1, 0.5), tx = in(-1, 0.5);
  pose.translation() = Eigen::Vector3d(tx, ty, tz);
  gp_Trsf trsf;
  const Eigen::Matrix3d& R = pose.linear();
  const Eigen::Vector3d& t = pose.translation();
  trsf.SetValues(R(0, 0), R(0, 1), R(0, 2), t.x(), R(1, 0), R(1, 1), R(1, 2), t.y(), R(2, 0), R(2, 1), R(2, 2), t.z());
  p.shape = BRepBuilderAPI_Transform(local, trsf, true).Shape();
  p.orbit = orbit_placed(local_orbit, pose);
  // the joint: as for the primitives
  const double reach = random_axis_reach(u);
  const double pz = in(-reach, reach), py = in(-reach, reach), px = in(-reach, reach);
  const Eigen::Vector3d point(px, py, pz);
  const std::string direction = uni(rng) < 0.3 ? "[0, 0, 1]" : vec_json(unit());
  const std::string type = kRandomJoints[(index / kPartFamilyCount) % 3];
  p.joint = "{\"type\": \"" + type + "\", \"point\": " + vec_json(point) + ", \"direction\": " + direction +
            random_joint_range(type, in, u);
  p.name = std::string(kPartFamilies[family]) + "_" + type + "_" + std::to_string(index);
  return p;
}

/// Writes the part as STEP, without the writer's statistics on the output; false when that fails.
inline bool write_part_step(const RandomPart& p, const std::string& path) {
  const Handle(Message_Messenger) messenger = Message::DefaultMessenger();
  const Message_SequenceOfPrinters printers = messenger->Printers();
  messenger->ChangePrinters().Clear();
  STEPControl_Writer w;
  const bool ok = w.Transfer(p.shape, STEPControl_AsIs) == IFSelect_RetDone && w.Write(path.c_str()) == IFSelect_RetDone;
  messenger->ChangePrinters() = printers;
  return ok;
}

/// The part's sweep as orbit intervals (never a B-rep).
inline JointSweep part_joint_sweep(const RandomPart& p) {
  // the joint as the parser reads it (a ball stands in for the part)
  const Spec spec = parse_spec("{\"sweep\": 1, \"angles\": \"deg\", \"entity\": {\"kind\": \"sphere\", \"center\": [0, 0, 0], "
                               "\"radius\": 1}, \"motion\": {\"kind\": \"axes\", \"joints\": [" + p.joint + "]}}",
                               ".");
  return joint_sweep_of(spec, p.orbit);
}

/// The part's swept volume from its orbit intervals; *err its error estimate.
inline double part_reference_volume(const RandomPart& p, double rel_tol, double* err) {
  const JointSweep s = part_joint_sweep(p);
  return joint_sweep_volume(*s.body, s.j, s.T, rel_tol, err);
}

}  // namespace sweep::testing
