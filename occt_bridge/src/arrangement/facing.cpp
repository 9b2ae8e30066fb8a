// Points of a face with their outward normals, and how a motion meets the face.
#include "arrangement/facing.hpp"

#include <BRepLProp_SLProps.hxx>
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>

#include "base/internal.hpp"

namespace sweep::occt {

bool add_surface_point(const BRepAdaptor_Surface& S, const TopoDS_Face& f, const gp_Pnt2d& uv,
                       std::vector<SurfacePoint>& out) {
  BRepLProp_SLProps props(S, uv.X(), uv.Y(), 1, Settings::normal_resolution);
  if (!props.IsNormalDefined()) return false;
  gp_Vec nn(props.Normal());
  if (f.Orientation() == TopAbs_REVERSED) nn.Reverse();
  out.push_back({props.Value(), nn});
  return true;
}

std::vector<SurfacePoint> face_samples(const TopoDS_Face& f, int n) {
  std::vector<SurfacePoint> out;
  double u0, u1, v0, v1;
  BRepTools::UVBounds(f, u0, u1, v0, v1);
  BRepTopAdaptor_FClass2d fc(f, Settings::face_sample_classifier_tolerance);
  BRepAdaptor_Surface S(f);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b) {
      const gp_Pnt2d uv(u0 + (u1 - u0) * (a + 0.5 + 0.1180339887 * ((b % 3) - 1)) / n,
                        v0 + (v1 - v0) * (b + 0.5 + 0.0729490168 * ((a % 3) - 1)) / n);
      if (fc.Perform(uv) == TopAbs_IN) add_surface_point(S, f, uv, out);
    }
  return out;
}

Facing facing_of(const TopoDS_Face& f, const VelocityField& field, double size) {
  int pos = 0, neg = 0, zero = 0;
  for (const auto& s : face_samples(f, 7)) {
    const Eigen::Vector3d v = field.at(to_eigen(s.p));
    const double speed = v.norm();
    if (speed < Settings::on_axis_speed * size) continue;  // on the axis
    const double c = to_eigen(s.n).dot(v) / speed;
    if (c > Settings::tangent_motion) ++pos;
    else if (c < -Settings::tangent_motion) ++neg;
    else ++zero;
  }
  if (pos == 0 && neg == 0) return zero > 0 ? Facing::Slides : Facing::Unknown;
  if (pos > 0 && neg > 0) return Facing::Mixed;
  return pos > 0 ? Facing::Front : Facing::Back;
}

}  // namespace sweep::occt
