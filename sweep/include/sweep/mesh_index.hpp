#pragma once
/// @file mesh_index.hpp
/// A closed triangle mesh with a bounding-volume hierarchy: inside tests by ray parity and
/// distances to the surface, for classifying many points against a triangulated solid.
#include <Eigen/Geometry>
#include <array>
#include <vector>

namespace sweep {

struct Triangle {
  Eigen::Vector3d a, b, c;
};

class MeshIndex {
 public:
  /// @param triangles a closed, consistently oriented mesh (orientation is not needed for the
  /// parity test, closedness is).
  explicit MeshIndex(std::vector<Triangle> triangles);
  std::size_t size() const { return tris_.size(); }
  const Eigen::AlignedBox3d& bounds() const { return box_; }

  /// Whether p is inside: the parity of a ray's crossings, cast again in other directions when a
  /// ray passes within rounding of an edge or a vertex; the majority of three clean rays.
  bool inside(const Eigen::Vector3d& p) const;
  /// The same test with rays that miss every box of `avoid` (regions where the triangles may not
  /// follow the surface they stand for: only the triangles elsewhere are crossed, so the answer is
  /// the surface's wherever the triangles outside those regions follow it): 1 inside, 0 outside,
  /// -1 when p lies in one of the boxes or no clean ray misses them all.
  int inside_avoiding(const Eigen::Vector3d& p, const std::vector<Eigen::AlignedBox3d>& avoid) const;
  /// The distance from p to the nearest triangle.
  double distance(const Eigen::Vector3d& p) const;
  /// The distance from p to the nearest triangle when it is below `limit`, else a value >= limit
  /// (cheaper: subtrees farther than the limit are not visited).
  double distance_below(const Eigen::Vector3d& p, double limit) const;

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int left = -1, right = -1;  ///< children, or -1 for a leaf
    int first = 0, count = 0;   ///< a leaf's triangles in order_
  };
  int build(int first, int count, int depth);
  /// The majority of three clean rays among the first `directions` of a fixed set that miss every
  /// box of `avoid`: 1 inside, 0 outside, -1 when no ray is clean.
  int ray_vote(const Eigen::Vector3d& p, const std::vector<Eigen::AlignedBox3d>& avoid, std::size_t directions) const;
  /// Crossings of the ray p + s d (s > 0); false when the ray comes too close to an edge.
  bool crossings(const Eigen::Vector3d& p, const Eigen::Vector3d& d, int* count) const;

  std::vector<Triangle> tris_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
  Eigen::AlignedBox3d box_;
};

/// The distance from p to triangle t.
double point_triangle_distance(const Eigen::Vector3d& p, const Triangle& t);

}  // namespace sweep
