#include "sweep/mesh_index.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "sweep/error.hpp"

namespace sweep {

using Eigen::Vector3d;

namespace {

Eigen::AlignedBox3d box_of(const Triangle& t) {
  Eigen::AlignedBox3d b(t.a);
  b.extend(t.b);
  b.extend(t.c);
  return b;
}

/// Squared distance from p to box b (0 inside).
double box_distance2(const Eigen::AlignedBox3d& b, const Vector3d& p) {
  const Vector3d d = (b.min() - p).cwiseMax(p - b.max()).cwiseMax(0.0);
  return d.squaredNorm();
}

/// Whether the ray p + s d (s >= 0) meets box b.
bool ray_meets_box(const Eigen::AlignedBox3d& b, const Vector3d& p, const Vector3d& inv) {
  double t0 = 0, t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    double a = (b.min()[k] - p[k]) * inv[k], c = (b.max()[k] - p[k]) * inv[k];
    if (a > c) std::swap(a, c);
    t0 = std::max(t0, a);
    t1 = std::min(t1, c);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

double point_triangle_distance(const Vector3d& p, const Triangle& t) {
  // Ericson, Real-Time Collision Detection, 5.1.5: the closest point by Voronoi regions.
  const Vector3d ab = t.b - t.a, ac = t.c - t.a, ap = p - t.a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Vector3d bp = p - t.b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (t.a + ab * (d1 / (d1 - d3)))).norm();
  const Vector3d cp = p - t.c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (t.a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (t.b + (t.c - t.b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (t.a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

MeshIndex::MeshIndex(std::vector<Triangle> triangles) : tris_(std::move(triangles)) {
  order_.resize(tris_.size());
  for (std::size_t k = 0; k < tris_.size(); ++k) order_[k] = int(k);
  for (const auto& t : tris_) box_.extend(box_of(t));
  if (!tris_.empty()) build(0, int(tris_.size()), 0);
}

namespace {
/// The nodes a traversal has still to visit: at most one more than the tree's depth (each visit
/// replaces a node by its two children), and build() stops at depth 61.
class NodeStack {
 public:
  void push(int node) {
    SWEEP_ASSERT(size_ < int(sizeof(nodes_) / sizeof(nodes_[0])), "mesh index deeper than its stack");
    nodes_[size_++] = node;
  }
  int pop() { return nodes_[--size_]; }
  bool empty() const { return size_ == 0; }

 private:
  int nodes_[64];
  int size_ = 0;
};
}  // namespace

int MeshIndex::build(int first, int count, int depth) {
  Node node;
  for (int k = first; k < first + count; ++k) node.box.extend(box_of(tris_[order_[k]]));
  const int id = int(nodes_.size());
  nodes_.push_back(node);
  if (count <= 4 || depth > 60) {
    nodes_[id].first = first;
    nodes_[id].count = count;
    return id;
  }
  // split at the median of the centroids along the box's longest side
  int axis = 0;
  node.box.sizes().maxCoeff(&axis);
  auto centre = [&](int t) { return (tris_[t].a[axis] + tris_[t].b[axis] + tris_[t].c[axis]) / 3.0; };
  const int half = count / 2;
  std::nth_element(order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
                   [&](int x, int y) { return centre(x) < centre(y); });
  const int left = build(first, half, depth + 1);
  const int right = build(first + half, count - half, depth + 1);
  nodes_[id].left = left;
  nodes_[id].right = right;
  return id;
}

bool MeshIndex::crossings(const Vector3d& p, const Vector3d& d, int* count) const {
  const Vector3d inv(1.0 / d.x(), 1.0 / d.y(), 1.0 / d.z());
  const double scale = std::max(box_.sizes().maxCoeff(), 1e-300);
  int n = 0;
  NodeStack stack;
  if (!nodes_.empty()) stack.push(0);
  while (!stack.empty()) {
    const Node& node = nodes_[stack.pop()];
    if (!ray_meets_box(node.box, p, inv)) continue;
    if (node.left >= 0) {
      stack.push(node.left);
      stack.push(node.right);
      continue;
    }
    for (int k = node.first; k < node.first + node.count; ++k) {
      const Triangle& t = tris_[order_[k]];
      // Moller-Trumbore
      const Vector3d e1 = t.b - t.a, e2 = t.c - t.a, h = d.cross(e2);
      const double det = e1.dot(h);
      const double area = e1.cross(e2).norm();
      if (std::abs(det) <= 1e-12 * area) continue;  // the ray runs along the triangle's plane
      const Vector3d s = p - t.a;
      const double u = s.dot(h) / det;
      const Vector3d q = s.cross(e1);
      const double v = d.dot(q) / det, w = e2.dot(q) / det;
      const double eps = 1e-10;
      if (u < -eps || v < -eps || u + v > 1 + eps || w < -1e-12 * scale) continue;
      // a hit within rounding of an edge, or at the ray's start, is not decided here
      if (u < eps || v < eps || u + v > 1 - eps || w < 1e-12 * scale) return false;
      ++n;
    }
  }
  *count = n;
  return true;
}

namespace {

/// Ray directions away from the axes and from each other: the first seven are the plain test's.
const std::array<Vector3d, 14>& ray_directions() {
  static const std::array<Vector3d, 14> dirs = [] {
    std::array<Vector3d, 14> d = {Vector3d(0.5773, 0.5581, 0.5958),   Vector3d(-0.6312, 0.4137, -0.6561),
                                  Vector3d(0.2113, -0.9417, 0.2619),  Vector3d(-0.3319, -0.2745, 0.9024),
                                  Vector3d(0.8812, 0.1711, -0.4407),  Vector3d(-0.1517, 0.7709, 0.6187),
                                  Vector3d(0.4409, -0.3377, -0.8316), Vector3d(-0.9137, -0.3109, 0.2617),
                                  Vector3d(0.1391, 0.9236, -0.3571),  Vector3d(-0.5127, -0.7384, -0.4381),
                                  Vector3d(0.7262, -0.6129, 0.3113),  Vector3d(-0.2708, 0.2193, -0.9373),
                                  Vector3d(0.3607, 0.3119, 0.8791),   Vector3d(-0.7713, 0.6219, 0.1356)};
    for (auto& v : d) v.normalize();
    return d;
  }();
  return dirs;
}

}  // namespace

int MeshIndex::ray_vote(const Vector3d& p, const std::vector<Eigen::AlignedBox3d>& avoid, std::size_t directions) const {
  int votes_in = 0, votes = 0;
  for (std::size_t k = 0; k < directions; ++k) {
    const Vector3d& d = ray_directions()[k];
    const Vector3d inv(1.0 / d.x(), 1.0 / d.y(), 1.0 / d.z());
    if (std::any_of(avoid.begin(), avoid.end(), [&](const Eigen::AlignedBox3d& b) { return ray_meets_box(b, p, inv); }))
      continue;
    int n = 0;
    if (!crossings(p, d, &n)) continue;
    ++votes;
    votes_in += n % 2;
    if (votes == 3) break;
  }
  if (votes == 0) return -1;
  return 2 * votes_in > votes ? 1 : 0;
}

bool MeshIndex::inside(const Vector3d& p) const {
  if (tris_.empty() || !box_.contains(p)) return false;
  return ray_vote(p, {}, 7) == 1;
}

int MeshIndex::inside_avoiding(const Vector3d& p, const std::vector<Eigen::AlignedBox3d>& avoid) const {
  for (const auto& b : avoid)
    if (b.contains(p)) return -1;
  if (tris_.empty() || !box_.contains(p)) return 0;
  return ray_vote(p, avoid, ray_directions().size());
}

double MeshIndex::distance_below(const Vector3d& p, double limit) const {
  double best2 = limit * limit;
  NodeStack stack;
  if (!nodes_.empty()) stack.push(0);
  while (!stack.empty()) {
    const Node& node = nodes_[stack.pop()];
    if (box_distance2(node.box, p) >= best2) continue;
    if (node.left >= 0) {
      // the nearer child last, so that it is visited first
      const double dl = box_distance2(nodes_[node.left].box, p), dr = box_distance2(nodes_[node.right].box, p);
      if (dl < dr) {
        stack.push(node.right);
        stack.push(node.left);
      } else {
        stack.push(node.left);
        stack.push(node.right);
      }
      continue;
    }
    for (int k = node.first; k < node.first + node.count; ++k) {
      const double d = point_triangle_distance(p, tris_[order_[k]]);
      best2 = std::min(best2, d * d);
    }
  }
  return std::sqrt(best2);
}

double MeshIndex::distance(const Vector3d& p) const {
  return distance_below(p, std::numeric_limits<double>::infinity());
}

}  // namespace sweep
