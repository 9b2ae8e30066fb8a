#include "sweep/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "sweep/error.hpp"
#include "sweep/point_text.hpp"

namespace sweep {
namespace {

/// The next token that is not a comment ('#' to the end of the line).
bool next_token(std::istream& in, std::string& token) {
  while (in >> token) {
    if (token[0] != '#') return true;
    std::string rest;
    std::getline(in, rest);
  }
  return false;
}

template <class T>
T number(std::istream& in, const std::string& pointer, const std::string& what) {
  std::string token;
  if (!next_token(in, token)) throw InputError(pointer, "the OFF file ends before " + what);
  std::istringstream ts(token);
  T v{};
  if (!(ts >> v) || !ts.eof())
    throw InputError(pointer, "the OFF file has '" + token + "' where " + what + " should be");
  return v;
}

}  // namespace

TriangleMesh read_off(std::istream& in, const std::string& pointer) {
  std::string head;
  if (!next_token(in, head) || head != "OFF") throw InputError(pointer, "not an OFF file (it must start with 'OFF')");
  const long nv = number<long>(in, pointer, "the vertex count");
  const long nf = number<long>(in, pointer, "the face count");
  number<long>(in, pointer, "the edge count");
  if (nv < 4 || nf < 4) throw InputError(pointer, "an OFF solid needs at least 4 vertices and 4 faces");
  TriangleMesh m;
  for (long k = 0; k < nv; ++k) {
    Eigen::Vector3d p;
    for (int i = 0; i < 3; ++i) p[i] = number<double>(in, pointer, "vertex " + std::to_string(k));
    if (!p.allFinite()) throw InputError(pointer, "vertex " + std::to_string(k) + " of the OFF file is not finite");
    m.vertices.push_back(p);
  }
  for (long k = 0; k < nf; ++k) {
    const std::string what = "face " + std::to_string(k);
    const long n = number<long>(in, pointer, "the corner count of " + what);
    if (n < 3) throw InputError(pointer, what + " of the OFF file has fewer than 3 corners");
    std::vector<int> corners;
    for (long i = 0; i < n; ++i) {
      const long v = number<long>(in, pointer, "a corner of " + what);
      if (v < 0 || v >= nv)
        throw InputError(pointer, what + " of the OFF file names vertex " + std::to_string(v) + ", which does not exist");
      corners.push_back(int(v));
    }
    // a fan, which covers the polygon once only when it is convex: every triangle of the fan must
    // face the way the polygon does (Newell's normal)
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < corners.size(); ++i)
      normal += m.vertices[corners[i]].cross(m.vertices[corners[(i + 1) % corners.size()]]);
    for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
      const Eigen::Vector3d& a = m.vertices[corners[0]];
      const Eigen::Vector3d n = (m.vertices[corners[i]] - a).cross(m.vertices[corners[i + 1]] - a);
      if (corners.size() > 3 && n.dot(normal) <= 0)
        throw InputError(pointer, what + " of the OFF file is not a convex polygon (split it into triangles)");
      m.triangles.push_back({corners[0], corners[i], corners[i + 1]});
    }
    std::string rest;
    std::getline(in, rest);  // (a colour may follow)
  }
  return m;
}

Eigen::AlignedBox3d bounding_box(const TriangleMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const auto& p : mesh.vertices) box.extend(p);
  return box;
}

TriangleMesh merged_vertices(const TriangleMesh& mesh, double merge) {
  const double q = std::max(merge * bounding_box(mesh).sizes().maxCoeff(), 1e-300);
  std::map<std::array<long long, 3>, int> index;
  std::vector<int> to(mesh.vertices.size());
  TriangleMesh out;
  for (std::size_t k = 0; k < mesh.vertices.size(); ++k) {
    const Eigen::Vector3d& p = mesh.vertices[k];
    const std::array<long long, 3> key{std::llround(p.x() / q), std::llround(p.y() / q),
                                       std::llround(p.z() / q)};
    const auto [it, added] = index.emplace(key, int(out.vertices.size()));
    if (added) out.vertices.push_back(p);
    to[k] = it->second;
  }
  for (const auto& t : mesh.triangles) {
    const std::array<int, 3> m{to[t[0]], to[t[1]], to[t[2]]};
    if (m[0] != m[1] && m[1] != m[2] && m[0] != m[2]) out.triangles.push_back(m);
  }
  return out;
}

void check_closed_oriented(const TriangleMesh& mesh, const std::string& pointer) {
  if (mesh.triangles.size() < 4) throw InputError(pointer, "the mesh has fewer than 4 triangles: it bounds no solid");
  const double size = bounding_box(mesh).sizes().maxCoeff();
  // each directed edge (a, b) and how many triangles run along it
  std::map<std::pair<int, int>, int> directed;
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const auto& t = mesh.triangles[k];
    const Eigen::Vector3d& a = mesh.vertices[t[0]];
    const double area = 0.5 * (mesh.vertices[t[1]] - a).cross(mesh.vertices[t[2]] - a).norm();
    if (!(area > 1e-14 * size * size))
      throw InputError(pointer, "triangle " + std::to_string(k) + " of the mesh has no area (at " + point_text(a) + ")");
    for (int i = 0; i < 3; ++i) ++directed[{t[i], t[(i + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    const auto back = directed.find({edge.second, edge.first});
    const int opposite = back == directed.end() ? 0 : back->second;
    const std::string where = "the edge from " + point_text(mesh.vertices[edge.first]) + " to " +
                              point_text(mesh.vertices[edge.second]) + " (vertices " + std::to_string(edge.first) +
                              " and " + std::to_string(edge.second) + ")";
    if (count + opposite == 1) throw InputError(pointer, "the mesh is not closed: " + where + " borders one triangle");
    if (count + opposite > 2)
      throw InputError(pointer, "the mesh is not manifold: " + where + " borders " + std::to_string(count + opposite) +
                                    " triangles");
    if (count != 1 || opposite != 1)
      throw InputError(pointer, "the mesh is not consistently oriented: two triangles run along " + where +
                                    " in the same direction");
  }
}

namespace {

/// Whether the segment [p, q] passes through the triangle (a, b, c) away from its sides and from
/// the segment's ends (by `eps` in the barycentric and segment parameters).
bool segment_crosses(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                     const Eigen::Vector3d& b, const Eigen::Vector3d& c, double eps) {
  const Eigen::Vector3d d = q - p, e1 = b - a, e2 = c - a, h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) <= 1e-14 * e1.cross(e2).norm() * d.norm()) return false;  // parallel
  const Eigen::Vector3d s = p - a;
  const double u = s.dot(h) / det;
  const Eigen::Vector3d r = s.cross(e1);
  const double v = d.dot(r) / det, t = e2.dot(r) / det;
  return u > eps && v > eps && u + v < 1 - eps && t > eps && t < 1 - eps;
}

}  // namespace

void check_not_crossing_itself(const TriangleMesh& mesh, const std::string& pointer) {
  const std::size_t n = mesh.triangles.size();
  std::vector<Eigen::AlignedBox3d> boxes(n);
  std::vector<std::size_t> order(n);
  for (std::size_t k = 0; k < n; ++k) {
    for (int i = 0; i < 3; ++i) boxes[k].extend(mesh.vertices[mesh.triangles[k][i]]);
    order[k] = k;
  }
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return boxes[a].min().x() < boxes[b].min().x(); });
  const double eps = 1e-9;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = order[i];
    const auto& ta = mesh.triangles[a];
    for (std::size_t j = i + 1; j < n && boxes[order[j]].min().x() <= boxes[a].max().x(); ++j) {
      const std::size_t b = order[j];
      if (!boxes[a].intersects(boxes[b])) continue;
      const auto& tb = mesh.triangles[b];
      bool shared = false;
      for (int x = 0; x < 3; ++x)
        for (int y = 0; y < 3; ++y) shared = shared || ta[x] == tb[y];
      if (shared) continue;
      bool cross = false;
      for (int s = 0; s < 3 && !cross; ++s) {
        const auto& V = mesh.vertices;
        cross = segment_crosses(V[ta[s]], V[ta[(s + 1) % 3]], V[tb[0]], V[tb[1]], V[tb[2]], eps) ||
                segment_crosses(V[tb[s]], V[tb[(s + 1) % 3]], V[ta[0]], V[ta[1]], V[ta[2]], eps);
      }
      if (cross)
        throw InputError(pointer, "the mesh crosses itself: triangles " + std::to_string(std::min(a, b)) + " and " +
                                      std::to_string(std::max(a, b)) + " cross (near " +
                                      point_text(mesh.vertices[ta[0]]) + ")");
    }
  }
}

double signed_volume(const TriangleMesh& mesh) {
  double v = 0;
  for (const auto& t : mesh.triangles)
    v += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]]));
  return v / 6;
}

}  // namespace sweep
