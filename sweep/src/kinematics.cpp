/// @file kinematics.cpp
/// Screws, basic and geometry constraints as wrenches, Algorithm 1 and joint classification.
#include "sweep/kinematics.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>

#include "kinematics_internal.hpp"
#include "sweep/error.hpp"
#include "sweep/settings.hpp"

namespace sweep {
namespace kinematics {

namespace {

Vec3 unit(const Vec3& v, const char* what) {
  const double n = v.norm();
  SWEEP_ASSERT(n > 0.0 && std::isfinite(n), std::string(what) + " must be a non-zero finite vector");
  return v / n;
}

Screw make_screw(const Vec3& a, const Vec3& b) {
  Screw s;
  s.head<3>() = a;
  s.tail<3>() = b;
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Screws

Twist revolute_twist(const Vec3& point, const Vec3& direction) {
  const Vec3 s = unit(direction, "revolute direction");
  return make_screw(s, point.cross(s));
}

Twist prismatic_twist(const Vec3& direction) {
  return make_screw(Vec3::Zero(), unit(direction, "prismatic direction"));
}

Twist helical_twist(const Vec3& point, const Vec3& direction, double pitch) {
  const Vec3 s = unit(direction, "helical direction");
  return make_screw(s, point.cross(s) + pitch * s);
}

Wrench force_wrench(const Vec3& point, const Vec3& direction) {
  const Vec3 s = unit(direction, "force direction");
  return make_screw(s, point.cross(s));
}

Wrench couple_wrench(const Vec3& direction) {
  return make_screw(Vec3::Zero(), unit(direction, "couple direction"));
}

double reciprocal_product(const Twist& t, const Wrench& w) {
  return t.head<3>().dot(w.tail<3>()) + t.tail<3>().dot(w.head<3>());
}

Screw swap_triplets(const Screw& s) { return make_screw(s.tail<3>(), s.head<3>()); }

Twist transform_twist(const Eigen::Isometry3d& T, const Twist& t) {
  const Eigen::Matrix3d R = T.linear();
  const Vec3 w = R * t.head<3>();
  return make_screw(w, R * t.tail<3>() + T.translation().cross(w));
}

Wrench transform_wrench(const Eigen::Isometry3d& T, const Wrench& w) {
  const Eigen::Matrix3d R = T.linear();
  const Vec3 f = R * w.head<3>();
  return make_screw(f, R * w.tail<3>() + T.translation().cross(f));
}

double twist_pitch(const Twist& t) {
  const double w2 = t.head<3>().squaredNorm();
  if (w2 == 0.0) return std::numeric_limits<double>::infinity();
  return t.head<3>().dot(t.tail<3>()) / w2;
}

// ---------------------------------------------------------------------------------------------
// Basic constraints

Wrench dot1_wrench(const Vec3& a_i, const Vec3& a_j) {
  const Vec3 c = unit(a_i, "dot-1 a_i").cross(unit(a_j, "dot-1 a_j"));
  SWEEP_ASSERT(c.norm() > sweep::Settings::kinematics_rounding, "dot-1 needs non-parallel vectors");
  return couple_wrench(c);
}

Wrench dot2_wrench(const Vec3& a_i, const Vec3& p_j) { return force_wrench(p_j, a_i); }

std::vector<Wrench> distance_wrenches(const Vec3& p_i, const Vec3& p_j, double coincidence) {
  const Vec3 d = p_j - p_i;
  if (d.norm() > coincidence && d.norm() > 0.0) return {force_wrench(p_j, d)};
  return {force_wrench(p_j, Vec3::UnitX()), force_wrench(p_j, Vec3::UnitY()),
          force_wrench(p_j, Vec3::UnitZ())};
}

// ---------------------------------------------------------------------------------------------
// Geometry constraints

const char* to_string(ConstraintType t) {
  switch (t) {
    case ConstraintType::Coaxial:
      return "coaxial";
    case ConstraintType::Coplanar:
      return "coplanar";
    case ConstraintType::Spherical:
      return "spherical";
    case ConstraintType::Align:
      return "align";
    case ConstraintType::LineSurfaceDistance:
      return "line_surface_distance";
    case ConstraintType::PointOnLine:
      return "point_on_line";
  }
  return "?";
}

int degree_of_constraint(ConstraintType t) {
  switch (t) {
    case ConstraintType::Coaxial:
      return 4;
    case ConstraintType::Coplanar:
      return 3;
    case ConstraintType::Spherical:
      return 3;
    case ConstraintType::Align:
      return 2;
    case ConstraintType::LineSurfaceDistance:
      return 2;
    case ConstraintType::PointOnLine:
      return 2;
  }
  return 0;
}

std::pair<Vec3, Vec3> perpendicular_pair(const Vec3& d) {
  const Vec3 s = unit(d, "direction");
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(s[i]) < std::abs(s[k])) k = i;
  const Vec3 u = s.cross(Vec3::Unit(k)).normalized();
  return {u, s.cross(u)};
}

std::vector<Wrench> coaxial_wrenches(const Axis& axis1, const Axis& axis2) {
  const auto [u2, w2] = perpendicular_pair(axis2.direction);
  const auto [u1, w1] = perpendicular_pair(axis1.direction);
  return {dot1_wrench(axis1.direction, u2), dot1_wrench(axis1.direction, w2), dot2_wrench(u1, axis2.point),
          dot2_wrench(w1, axis2.point)};
}

std::vector<Wrench> coplanar_wrenches(const Plane& plane1, const Plane& plane2) {
  const auto [u2, w2] = perpendicular_pair(plane2.normal);
  return {dot1_wrench(plane1.normal, u2), dot1_wrench(plane1.normal, w2),
          dot2_wrench(plane1.normal, plane2.point)};
}

std::vector<Wrench> spherical_wrenches(const Vec3& point1, const Vec3& point2) {
  // The distance constraint with c = 0: the points coincide at the assembled position.
  return distance_wrenches(point1, point2, std::numeric_limits<double>::infinity());
}

std::vector<Wrench> align_wrenches(const Plane& plane1, const Plane& plane2) {
  const auto [u2, w2] = perpendicular_pair(plane2.normal);
  return {dot1_wrench(plane1.normal, u2), dot1_wrench(plane1.normal, w2)};
}

std::vector<Wrench> line_surface_distance_wrenches(const Axis& axis1, const Plane& plane2) {
  return {dot1_wrench(plane2.normal, axis1.direction), dot2_wrench(plane2.normal, axis1.point)};
}

std::vector<Wrench> point_on_line_wrenches(const Vec3& point1, const Axis& axis2) {
  const auto [u2, w2] = perpendicular_pair(axis2.direction);
  return {dot2_wrench(u2, point1), dot2_wrench(w2, point1)};
}

std::vector<Wrench> constraint_wrenches(const GeometryConstraint& c) {
  switch (c.type) {
    case ConstraintType::Coaxial:
      return coaxial_wrenches(c.axis1, c.axis2);
    case ConstraintType::Coplanar:
      return coplanar_wrenches(c.plane1, c.plane2);
    case ConstraintType::Spherical:
      return spherical_wrenches(c.point1, c.point2);
    case ConstraintType::Align:
      return align_wrenches(c.plane1, c.plane2);
    case ConstraintType::LineSurfaceDistance:
      return line_surface_distance_wrenches(c.axis1, c.plane2);
    case ConstraintType::PointOnLine:
      return point_on_line_wrenches(c.point1, c.axis2);
  }
  assert_fail("known constraint type", __FILE__, __LINE__, "unknown constraint type");
}

// ---------------------------------------------------------------------------------------------
// Numerics

Wrench NumericFrame::wrench_to_local(const Wrench& w) const {
  const Vec3 f = w.head<3>();
  return make_screw(f, (w.tail<3>() - center.cross(f)) / scale);
}

Twist NumericFrame::twist_to_local(const Twist& t) const {
  const Vec3 om = t.head<3>();
  return make_screw(om, (t.tail<3>() + om.cross(center)) / scale);
}

Twist NumericFrame::twist_to_world(const Twist& local) const {
  const Vec3 om = local.head<3>();
  return make_screw(om, local.tail<3>() * scale + center.cross(om));
}

namespace detail {

int numeric_rank(const Eigen::VectorXd& singular_values, const NumericFrame& frame) {
  if (singular_values.size() == 0) return 0;
  const double thr = frame.rank_tolerance() * std::max(1.0, singular_values[0]);
  int r = 0;
  for (Eigen::Index i = 0; i < singular_values.size(); ++i)
    if (singular_values[i] > thr) ++r;
  return r;
}

Eigen::MatrixXd span_basis(const Eigen::MatrixXd& cols, const NumericFrame& frame, bool normalize) {
  const Eigen::Index n = cols.rows();
  if (cols.cols() == 0) return Eigen::MatrixXd(n, 0);
  Eigen::MatrixXd m = cols;
  for (Eigen::Index j = 0; normalize && j < m.cols(); ++j) {
    const double nn = m.col(j).norm();
    if (nn > 0.0) m.col(j) /= nn;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeFullU);
  const int r = numeric_rank(svd.singularValues(), frame);
  return svd.matrixU().leftCols(r);
}

Eigen::MatrixXd complement_basis(const Eigen::MatrixXd& cols, const NumericFrame& frame) {
  const Eigen::Index n = cols.rows();
  if (cols.cols() == 0) return Eigen::MatrixXd::Identity(n, n);
  Eigen::MatrixXd m = cols;
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    const double nn = m.col(j).norm();
    if (nn > 0.0) m.col(j) /= nn;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeFullU);
  const int r = numeric_rank(svd.singularValues(), frame);
  return svd.matrixU().rightCols(n - r);
}

Eigen::MatrixXd null_space(const Eigen::MatrixXd& a, const NumericFrame& frame, int* rank) {
  const Eigen::Index n = a.cols();
  if (a.rows() == 0) {
    if (rank) *rank = 0;
    return Eigen::MatrixXd::Identity(n, n);
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
  const int r = numeric_rank(svd.singularValues(), frame);
  if (rank) *rank = r;
  return svd.matrixV().rightCols(n - r);
}

ScrewBasis to_local(const ScrewBasis& world, const NumericFrame& frame) {
  ScrewBasis out(6, world.cols());
  for (Eigen::Index j = 0; j < world.cols(); ++j) out.col(j) = frame.twist_to_local(world.col(j));
  return out;
}

ScrewBasis to_world(const ScrewBasis& local, const NumericFrame& frame) {
  ScrewBasis out(6, local.cols());
  for (Eigen::Index j = 0; j < local.cols(); ++j) out.col(j) = frame.twist_to_world(local.col(j));
  return out;
}

}  // namespace detail

ScrewBasis orthonormal_span(const ScrewBasis& screws, const NumericFrame& frame) {
  return detail::span_basis(screws, frame);
}

ScrewBasis reciprocal_twists_local(const std::vector<Wrench>& wrenches, const NumericFrame& frame,
                                   int* rank) {
  Eigen::MatrixXd w(6, static_cast<Eigen::Index>(wrenches.size()));
  for (std::size_t j = 0; j < wrenches.size(); ++j)
    w.col(static_cast<Eigen::Index>(j)) = frame.wrench_to_local(wrenches[j]);
  const Eigen::MatrixXd span = detail::span_basis(w, frame);
  if (rank) *rank = static_cast<int>(span.cols());
  const Eigen::MatrixXd comp = detail::complement_basis(span, frame);
  ScrewBasis twists(6, comp.cols());
  for (Eigen::Index j = 0; j < comp.cols(); ++j) twists.col(j) = swap_triplets(comp.col(j));
  return twists;
}

// ---------------------------------------------------------------------------------------------
// Classification

const char* to_string(JointKind k) {
  switch (k) {
    case JointKind::Fixed:
      return "fixed";
    case JointKind::Revolute:
      return "revolute";
    case JointKind::Prismatic:
      return "prismatic";
    case JointKind::Helical:
      return "helical";
    case JointKind::Cylindrical:
      return "cylindrical";
    case JointKind::Spherical:
      return "spherical";
    case JointKind::Planar:
      return "planar";
    case JointKind::Unrecognized:
      return "unrecognized";
  }
  return "?";
}

namespace {

/// Unit vector with its largest component (the first of equal ones) positive.
Vec3 canonical_direction(const Vec3& v) {
  Vec3 s = v.normalized();
  int k = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(s[i]) > std::abs(s[k]) + sweep::Settings::kinematics_rounding) k = i;
  if (s[k] < 0) s = -s;
  return s;
}

/// Foot of the perpendicular from the origin onto the line through p along unit s.
Vec3 nearest_to_origin(const Vec3& p, const Vec3& s) { return p - p.dot(s) * s; }

/// Reduced row echelon form of the span of `cols` (columns in, columns out).
ScrewBasis echelon_basis(const ScrewBasis& cols) {
  Eigen::MatrixXd m = cols.transpose();  // one screw per row
  const double big = std::max(1.0, m.cwiseAbs().maxCoeff());
  const double eps = sweep::Settings::screw_rank_rounding * big;
  Eigen::Index row = 0;
  for (Eigen::Index c = 0; c < 6 && row < m.rows(); ++c) {
    Eigen::Index piv = row;
    for (Eigen::Index r = row + 1; r < m.rows(); ++r)
      if (std::abs(m(r, c)) > std::abs(m(piv, c))) piv = r;
    if (std::abs(m(piv, c)) <= eps) continue;
    m.row(row).swap(m.row(piv));
    m.row(row) /= m(row, c);
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      if (r != row) m.row(r) -= m(r, c) * m.row(row);
    ++row;
  }
  return m.topRows(row).transpose();
}

}  // namespace

namespace detail {

void clean(ScrewBasis& b, double scale) {
  const double eps = sweep::Settings::kinematics_rounding * std::max(1.0, scale);
  for (Eigen::Index j = 0; j < b.cols(); ++j)
    for (int i = 0; i < 6; ++i) {
      double& x = b(i, j);
      const double e = i < 3 ? sweep::Settings::kinematics_rounding : eps;
      if (std::abs(x) < e) x = 0.0;
    }
}

/// Classifies an orthonormal local-frame basis of a twist space.
Joint classify_local(const ScrewBasis& local, const NumericFrame& frame) {
  Joint j;
  const Eigen::Index k = local.cols();
  j.dof = static_cast<int>(k);
  const double tol = frame.rank_tolerance();
  const double L = frame.scale;
  if (k == 0) {
    j.kind = JointKind::Fixed;
    j.twists = ScrewBasis(6, 0);
    return j;
  }
  const Eigen::MatrixXd om = local.topRows(3);
  const Eigen::MatrixXd vel = local.bottomRows(3);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(om, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const int rw = numeric_rank(svd.singularValues(), frame);
  // Coefficient vectors of the pure translations and of the rotational part.
  const Eigen::MatrixXd trans_coef = svd.matrixV().rightCols(k - rw);
  const Eigen::MatrixXd trans = vel * trans_coef;  // 3 x (k - rw), orthonormal up to tolerance

  auto screw_axis = [&](const Screw& t, Vec3* s, Vec3* p, double* h) {
    const Vec3 w = t.head<3>();
    const Vec3 v = t.tail<3>();
    const double w2 = w.squaredNorm();
    *s = w / std::sqrt(w2);
    *p = w.cross(v) / w2;
    *h = w.dot(v) / w2;
  };

  j.kind = JointKind::Unrecognized;
  if (k == 1) {
    const Screw t = local.col(0);
    if (rw == 0) {
      j.kind = JointKind::Prismatic;
      j.direction = canonical_direction(t.tail<3>());
    } else {
      Vec3 s, p;
      double h;
      screw_axis(t, &s, &p, &h);
      j.direction = canonical_direction(s);
      j.point = nearest_to_origin(frame.center + L * p, j.direction);
      if (std::abs(h) <= tol) {
        j.kind = JointKind::Revolute;
      } else {
        j.kind = JointKind::Helical;
        j.pitch = h * L;
      }
    }
  } else if (k == 2 && rw == 1) {
    const Vec3 s = svd.matrixU().col(0);
    const Vec3 tr = trans.col(0);
    if (tr.norm() > 0.5 && tr.normalized().cross(s).norm() <= tol) {
      const Screw t = local * svd.matrixV().col(0);
      Vec3 ss, p;
      double h;
      screw_axis(t, &ss, &p, &h);
      j.kind = JointKind::Cylindrical;
      j.direction = canonical_direction(s);
      j.point = nearest_to_origin(frame.center + L * p, j.direction);
    }
  } else if (k == 3 && rw == 3) {
    // Every twist a pure rotation about one centre c: v = c x omega, i.e. -[omega]x c = v.
    Eigen::MatrixXd A(9, 3);
    Eigen::VectorXd b(9);
    for (int c = 0; c < 3; ++c) {
      const Vec3 w = local.col(c).head<3>();
      Eigen::Matrix3d skew;
      skew << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
      A.block<3, 3>(3 * c, 0) = -skew;
      b.segment<3>(3 * c) = local.col(c).tail<3>();
    }
    const Vec3 c = A.colPivHouseholderQr().solve(b);
    if ((A * c - b).norm() <= tol) {
      j.kind = JointKind::Spherical;
      j.point = frame.center + L * c;
    }
  } else if (k == 3 && rw == 1) {
    const Vec3 n = svd.matrixU().col(0);
    const Screw t = local * svd.matrixV().col(0);
    const Vec3 nn = t.head<3>().normalized();
    bool planar = std::abs(t.tail<3>().dot(nn)) <= tol * t.head<3>().norm();
    for (Eigen::Index c = 0; c < trans.cols(); ++c) planar = planar && std::abs(trans.col(c).dot(n)) <= tol;
    if (planar) {
      j.kind = JointKind::Planar;
      j.direction = canonical_direction(n);
    }
  }

  // Rounding noise off the geometry, then the canonical world basis.
  const double eps_len = sweep::Settings::kinematics_rounding * (frame.center.norm() + L);
  for (int i = 0; i < 3; ++i) {
    if (std::abs(j.direction[i]) < sweep::Settings::kinematics_rounding) j.direction[i] = 0.0;
    if (std::abs(j.point[i]) < eps_len) j.point[i] = 0.0;
  }
  if (j.direction.norm() > 0.0) j.direction.normalize();
  if (std::abs(j.pitch) < eps_len) j.pitch = 0.0;
  const Vec3& s = j.direction;
  switch (j.kind) {
    case JointKind::Revolute:
      j.twists = revolute_twist(j.point, s);
      break;
    case JointKind::Helical:
      j.twists = helical_twist(j.point, s, j.pitch);
      break;
    case JointKind::Prismatic:
      j.twists = prismatic_twist(s);
      break;
    case JointKind::Cylindrical:
      j.twists.resize(6, 2);
      j.twists << revolute_twist(j.point, s), prismatic_twist(s);
      break;
    case JointKind::Spherical:
      j.twists.resize(6, 3);
      j.twists << revolute_twist(j.point, Vec3::UnitX()), revolute_twist(j.point, Vec3::UnitY()),
          revolute_twist(j.point, Vec3::UnitZ());
      break;
    case JointKind::Planar: {
      int m = 0;
      for (int i = 1; i < 3; ++i)
        if (std::abs(s[i]) < std::abs(s[m]) - sweep::Settings::kinematics_rounding) m = i;
      const Vec3 u = (Vec3::Unit(m) - s[m] * s).normalized();
      j.twists.resize(6, 3);
      j.twists << revolute_twist(Vec3::Zero(), s), prismatic_twist(u), prismatic_twist(s.cross(u));
      break;
    }
    default:
      j.twists = echelon_basis(to_world(local, frame));
      break;
  }
  clean(j.twists, frame.center.norm() + L);
  return j;
}

}  // namespace detail

Joint recognize_joint(const std::vector<Wrench>& wrenches, const NumericFrame& frame) {
  int rank = 0;
  const ScrewBasis local = reciprocal_twists_local(wrenches, frame, &rank);
  Joint j = detail::classify_local(local, frame);
  j.components = static_cast<int>(wrenches.size());
  j.rank = rank;
  j.redundant = j.components - rank;
  return j;
}

Joint classify_twists(const ScrewBasis& twists, const NumericFrame& frame) {
  return detail::classify_local(detail::span_basis(detail::to_local(twists, frame), frame), frame);
}

ScrewBasis twist_sum(const ScrewBasis& a, const ScrewBasis& b, const NumericFrame& frame) {
  Eigen::MatrixXd both(6, a.cols() + b.cols());
  both << detail::to_local(a, frame), detail::to_local(b, frame);
  return detail::to_world(detail::span_basis(both, frame), frame);
}

ScrewBasis twist_intersection(const ScrewBasis& a, const ScrewBasis& b, const NumericFrame& frame) {
  const Eigen::MatrixXd ca = detail::complement_basis(detail::to_local(a, frame), frame);
  const Eigen::MatrixXd cb = detail::complement_basis(detail::to_local(b, frame), frame);
  Eigen::MatrixXd both(6, ca.cols() + cb.cols());
  both << ca, cb;
  return detail::to_world(detail::complement_basis(detail::span_basis(both, frame), frame), frame);
}

int twist_dimension(const ScrewBasis& twists, const NumericFrame& frame) {
  return static_cast<int>(detail::span_basis(detail::to_local(twists, frame), frame).cols());
}

bool same_twist_space(const ScrewBasis& a, const ScrewBasis& b, const NumericFrame& frame) {
  const int da = twist_dimension(a, frame), db = twist_dimension(b, frame);
  return da == db && twist_dimension(twist_sum(a, b, frame), frame) == da;
}

}  // namespace kinematics
}  // namespace sweep
