#pragma once
/// @file spec.hpp
/// Sweep spec v1 (SPEC.md): the parsed, validated form of a spec file.
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "sweep/expr.hpp"
#include "sweep/motion.hpp"
#include "sweep/stage_motion.hpp"

namespace sweep {

enum class EntityKind {
  Point, Curve, Surface, Sphere, Box, Cylinder, Cone, Torus,
  EllipticCylinder, Implicit, Brep, Mesh, Tube
};
const char* to_string(EntityKind k);

/// A named parameter with its closed range.
struct ParamRange {
  std::string name;
  double lo = 0.0, hi = 0.0;
};

/// An entity in its own frame; `placement` maps it into the innermost frame of the motion.
/// Only the fields of its kind are meaningful (see SPEC.md).
struct EntitySpec {
  EntityKind kind = EntityKind::Point;
  Eigen::Vector3d at = Eigen::Vector3d::Zero();                  ///< point
  Eigen::Vector3d center = Eigen::Vector3d::Zero();              ///< sphere, torus
  Eigen::Vector3d min = Eigen::Vector3d::Zero(), max = Eigen::Vector3d::Zero();  ///< box; implicit bounds
  Eigen::Vector3d base = Eigen::Vector3d::Zero();                ///< cylinder, cone, elliptic_cylinder
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();               ///< unit; cylinder, cone, torus, elliptic_cylinder
  double radius = 0, radius1 = 0, radius2 = 0, height = 0;       ///< sphere/cylinder; cone
  double major = 0, minor = 0;                                   ///< torus
  double a = 0, b = 0;                                           ///< elliptic_cylinder semi-axes
  std::optional<Expr> twist;                                     ///< elliptic_cylinder, in u
  std::vector<ParamRange> params;                                ///< curve (1), surface (2)
  std::array<Expr, 3> xyz;                                       ///< curve, surface
  std::vector<Expr> inequalities;                                ///< implicit, in x, y, z
  std::string file;                                              ///< brep, mesh: resolved path
  double scale = 1.0;                                            ///< mesh: its coordinates' factor
  std::optional<Expr> tube_radius;                               ///< tube, in the spine parameter
  std::shared_ptr<EntitySpec> spine;                             ///< tube
  Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();

  /// Dimension of the entity: 0 point, 1 curve, 2 surface, 3 solid (brep may be 2 for a shell).
  int dimension() const;
  /// elliptic_cylinder: the frame of its sections, columns X (the `a` semi-axis where the twist is
  /// 0: world x projected normal to the axis, world y when the axis is along x), Y = Z x X, Z the axis.
  Eigen::Matrix3d elliptic_frame() const;
  /// elliptic_cylinder: the angle of the `a` semi-axis from X at height fraction u (0 untwisted).
  double twist_at(double u) const { return twist ? twist->eval(&u) : 0.0; }
};

enum class MotionKind { Dh, Axes, Screw, Path, Keyframes, Toolpath, PolyScrew };
const char* to_string(MotionKind k);

/// One row of a DH table: each of theta, d, a, alpha is an expression in q (constants for the
/// three fixed ones). Angles in radians.
struct DhRow {
  JointType type = JointType::Revolute;
  Expr theta, d, a, alpha;
  double pitch = 0.0;  ///< helical: length per turn as written in the spec
  double lo = 0.0, hi = 0.0;  ///< range of q (radians for revolute/helical)
};

struct MotionSpec {
  MotionKind kind = MotionKind::Axes;
  std::vector<DhRow> dh;  ///< kind dh: the table as written
  /// The motion as a product of exponentials (every kind that reduces to screws: dh, axes, screw).
  Motion motion;
  /// A one-parameter motion that is not a chain of screws (kinds path and keyframes); null otherwise.
  std::shared_ptr<const StageMotion> stage;
};

struct Spec {
  int version = 1;
  std::string name;
  bool degrees = false;
  EntitySpec entity;
  MotionSpec motion;
  double tolerance = 0.0;  ///< requested; 0 means "1e-6 times the model size"
  nlohmann::json json;     ///< the document after --set overrides, comments kept
};

/// Parses and validates spec text. `base_dir` resolves relative file names; `overrides` are
/// "/json/pointer=value" strings applied before validation (value is JSON, or a bare string).
/// @throws InputError naming the JSON pointer (and line:column in `text` when it can be found).
Spec parse_spec(const std::string& text, const std::string& base_dir,
                const std::vector<std::string>& overrides = {});

/// Reads the file and calls parse_spec. @throws InputError (pointer "") when unreadable.
Spec load_spec(const std::string& path, const std::vector<std::string>& overrides = {});

/// 1-based line and column of the value at JSON pointer `pointer` in JSON text, or {0,0}.
std::pair<int, int> locate_pointer(const std::string& text, const std::string& pointer);

}  // namespace sweep
