// The zero set of a function of two parameters on a grid (contour.hpp): marching squares whose
// points are roots on the grid lines, with the saddle of the function joining two branches that
// cross inside a cell.
#include "sweep/contour.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace sweep {

using UV = Eigen::Vector2d;

double root_in_unit(const std::function<double(double)>& f, double fa, double fb) {
  double a = 0, b = 1;
  if (fa == 0) return 0;
  if (fb == 0) return 1;
  int side = 0;
  for (int it = 0; it < 100; ++it) {
    double c = (a * fb - b * fa) / (fb - fa);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    double fc = f(c);
    if (fc == 0 || b - a < 1e-15) return c;
    if ((fc > 0) == (fb > 0)) {
      b = c; fb = fc;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      a = c; fa = fc;
      if (side == 1) fb *= 0.5;
      side = 1;
    }
    if (b - a < 1e-15) break;
  }
  return 0.5 * (a + b);
}

UV root_on_segment(const ContourFunction& f, const UV& p, const UV& q, double gp, double gq) {
  const double s = root_in_unit([&](double t) { return f(p + t * (q - p)); }, gp, gq);
  return p + s * (q - p);
}

namespace {

/// The zero set as a graph: roots on grid edges, saddles where branches cross.
struct Graph {
  std::vector<UV> pts;
  std::vector<std::vector<int>> adj;
  int add(const UV& p) {
    pts.push_back(p);
    adj.emplace_back();
    return int(pts.size()) - 1;
  }
  void link(int a, int b) {
    if (a == b) return;
    adj[a].push_back(b);
    adj[b].push_back(a);
  }
};

}  // namespace

std::vector<std::vector<UV>> contour_chains(const ContourFunction& g, double ua, double ub, double va, double vb,
                                            int nu, int nv, double flat) {
  std::vector<double> G((nu + 1) * (nv + 1));
  auto node = [&](int i, int j) { return UV(ua + (ub - ua) * i / nu, va + (vb - va) * j / nv); };
  double gmax = 0;
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      G[i * (nv + 1) + j] = g(node(i, j));
      gmax = std::max(gmax, std::abs(G[i * (nv + 1) + j]));
    }
  if (gmax <= flat) return {};
  auto val = [&](int i, int j) { return G[i * (nv + 1) + j]; };
  auto pos = [&](double g) { return g > 0; };
  Graph gr;
  std::map<long, int> edge_pt;  // grid edge -> graph node
  auto edge_node = [&](int i0, int j0, int i1, int j1) -> int {
    long key = (long(i0) * (nv + 1) + j0) * 2 + (i1 != i0 ? 0 : 1);
    auto it = edge_pt.find(key);
    if (it != edge_pt.end()) return it->second;
    UV p = root_on_segment(g, node(i0, j0), node(i1, j1), val(i0, j0), val(i1, j1));
    int id = gr.add(p);
    edge_pt[key] = id;
    return id;
  };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      // corners in order: (i,j) (i+1,j) (i+1,j+1) (i,j+1); edges e0..e3 between them
      int ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
      int crossing[4], nc = 0;
      for (int e = 0; e < 4; ++e) {
        int a = e, b = (e + 1) % 4;
        if (pos(val(ci[a], cj[a])) != pos(val(ci[b], cj[b]))) {
          int i0 = std::min(ci[a], ci[b]), j0 = std::min(cj[a], cj[b]);
          int i1 = std::max(ci[a], ci[b]), j1 = std::max(cj[a], cj[b]);
          crossing[nc++] = edge_node(i0, j0, i1, j1);
        }
      }
      if (nc == 2) {
        gr.link(crossing[0], crossing[1]);
      } else if (nc == 4) {
        // Two branches cross (or pass close): locate the saddle of g in the cell by Newton on
        // grad g = 0 (central differences); if g vanishes there, all four meet at it.
        UV c = 0.5 * (node(i, j) + node(i + 1, j + 1));
        const double hu = (ub - ua) / nu * 1e-3, hv = (vb - va) / nv * 1e-3;
        bool ok = false;
        for (int it = 0; it < 30; ++it) {
          double g0 = g(c);
          double gpu = g(c + UV(hu, 0)), gmu = g(c - UV(hu, 0));
          double gpv = g(c + UV(0, hv)), gmv = g(c - UV(0, hv));
          double gu = (gpu - gmu) / (2 * hu), gv = (gpv - gmv) / (2 * hv);
          double guu = (gpu - 2 * g0 + gmu) / (hu * hu), gvv = (gpv - 2 * g0 + gmv) / (hv * hv);
          double guv = (g(c + UV(hu, hv)) - g(c + UV(hu, -hv)) - g(c + UV(-hu, hv)) + g(c - UV(hu, hv))) /
                       (4 * hu * hv);
          double det = guu * gvv - guv * guv;
          if (std::abs(det) < 1e-300) break;
          UV d((gvv * gu - guv * gv) / det, (guu * gv - guv * gu) / det);
          c -= d;
          if (d.norm() < 1e-13 * (1 + c.norm())) { ok = true; break; }
        }
        bool inside = c.x() >= node(i, j).x() && c.x() <= node(i + 1, j).x() && c.y() >= node(i, j).y() &&
                      c.y() <= node(i, j + 1).y();
        if (ok && inside && std::abs(g(c)) < 100 * flat) {
          int s = gr.add(c);
          for (int k = 0; k < 4; ++k) gr.link(crossing[k], s);
        } else {
          double gc = g(0.5 * (node(i, j) + node(i + 1, j + 1)));
          // resolve the ambiguous cell by the sign at its centre
          if (pos(gc) == pos(val(i, j))) {
            gr.link(crossing[0], crossing[1]);
            gr.link(crossing[2], crossing[3]);
          } else {
            gr.link(crossing[1], crossing[2]);
            gr.link(crossing[3], crossing[0]);
          }
        }
      }
    }
  // Chains between nodes of degree != 2, and closed loops.
  std::vector<std::vector<UV>> chains;
  std::vector<std::vector<bool>> used(gr.pts.size());
  for (std::size_t k = 0; k < gr.pts.size(); ++k) used[k].assign(gr.adj[k].size(), false);
  auto mark = [&](int a, int b) {
    for (std::size_t m = 0; m < gr.adj[a].size(); ++m)
      if (gr.adj[a][m] == b && !used[a][m]) { used[a][m] = true; break; }
    for (std::size_t m = 0; m < gr.adj[b].size(); ++m)
      if (gr.adj[b][m] == a && !used[b][m]) { used[b][m] = true; break; }
  };
  auto walk = [&](int start, std::size_t slot) {
    std::vector<UV> chain{gr.pts[start]};
    int cur = gr.adj[start][slot];
    mark(start, cur);
    chain.push_back(gr.pts[cur]);
    while (gr.adj[cur].size() == 2 && cur != start) {
      int nxt = -1;
      for (std::size_t m = 0; m < 2; ++m)
        if (!used[cur][m]) { nxt = gr.adj[cur][m]; break; }
      if (nxt < 0) break;
      mark(cur, nxt);
      cur = nxt;
      chain.push_back(gr.pts[cur]);
    }
    chains.push_back(chain);
  };
  for (std::size_t k = 0; k < gr.pts.size(); ++k)
    if (gr.adj[k].size() != 2)
      for (std::size_t m = 0; m < gr.adj[k].size(); ++m)
        if (!used[k][m]) walk(int(k), m);
  for (std::size_t k = 0; k < gr.pts.size(); ++k)
    for (std::size_t m = 0; m < gr.adj[k].size(); ++m)
      if (!used[k][m]) walk(int(k), m);
  return chains;
}

std::vector<UV> densified(const ContourFunction& g, const std::vector<UV>& c) {
  std::vector<UV> out{c.front()};
  for (std::size_t k = 0; k + 1 < c.size(); ++k) {
    UV a = c[k], b = c[k + 1], m = 0.5 * (a + b), d = b - a;
    UV n(-d.y(), d.x());
    UV p = m - n, q = m + n;
    double gp = g(p), gq = g(q);
    if ((gp > 0) != (gq > 0)) out.push_back(root_on_segment(g, p, q, gp, gq));
    out.push_back(b);
  }
  return out;
}

}  // namespace sweep
