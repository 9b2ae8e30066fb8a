#pragma once
/// @file triangle_mesh.hpp
/// A triangle mesh given as a solid (the `mesh` entity): reading OFF, and the checks that make it
/// the boundary of a solid (no degenerate triangle, every edge shared by exactly two triangles
/// that run along it in opposite directions, no two triangles crossing).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <istream>
#include <string>
#include <vector>

namespace sweep {

struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;  ///< vertex indices, counter-clockwise seen from outside
};

/// The box of the mesh's vertices.
Eigen::AlignedBox3d bounding_box(const TriangleMesh& mesh);

/// Reads OFF text ("OFF", the counts, the vertices, then faces as "n i_1 ... i_n"; convex polygons
/// are split into fans, a polygon that is not convex is refused). @throws InputError at `pointer`,
/// saying what is wrong and where.
TriangleMesh read_off(std::istream& in, const std::string& pointer);

/// Vertices closer than `merge` (x the mesh's size) made one, and the triangles that then lose a
/// corner dropped (an STL file repeats each vertex in every triangle).
TriangleMesh merged_vertices(const TriangleMesh& mesh, double merge);

/// @throws InputError at `pointer` when the mesh does not bound a solid: a triangle of no area
/// (index given), an edge used by one triangle or by more than two (its vertices given), or two
/// triangles that run along a shared edge in the same direction (inconsistent orientation).
void check_closed_oriented(const TriangleMesh& mesh, const std::string& pointer);

/// @throws InputError at `pointer` when two triangles that share no vertex cross (a side of one
/// passes through the other's interior): the mesh crosses itself and bounds no solid. Triangles are
/// paired by their boxes along x (sweep and prune).
void check_not_crossing_itself(const TriangleMesh& mesh, const std::string& pointer);

/// The volume the mesh encloses, negative when its triangles face inward.
double signed_volume(const TriangleMesh& mesh);

}  // namespace sweep
