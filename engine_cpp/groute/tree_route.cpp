#include "groute/tree_route.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <queue>

namespace xroute {

namespace {

// Edges of the straight run from cell (x0,y0) to (x1,y1) (same row or column).
void straight(const Graph2d& g, int x0, int y0, int x1, int y1, std::vector<int32_t>& out) {
  const int nx = g.nx();
  if (y0 == y1) {
    for (int x = std::min(x0, x1); x < std::max(x0, x1); ++x) out.push_back(Graph2d::edge(y0 * nx + x, 0));
  } else {
    for (int y = std::min(y0, y1); y < std::max(y0, y1); ++y) out.push_back(Graph2d::edge(y * nx + x0, 1));
  }
}

double pathCost(const Graph2d& g, const std::vector<int32_t>& edges, const std::vector<int32_t>& own, double pf) {
  double c = 0;
  for (int32_t e : edges) {
    if (!std::binary_search(own.begin(), own.end(), e)) c += g.cost(e, pf);
  }
  return c;
}

void addSorted(std::vector<int32_t>& set, const std::vector<int32_t>& edges) {
  set.insert(set.end(), edges.begin(), edges.end());
  std::sort(set.begin(), set.end());
  set.erase(std::unique(set.begin(), set.end()), set.end());
}

}  // namespace

std::vector<int32_t> patternRoute(const Graph2d& g, const std::vector<int32_t>& pins, double pf) {
  std::vector<int32_t> route;
  const size_t n = pins.size();
  if (n < 2) return route;
  const int nx = g.nx();
  // Prim's MST over Manhattan distance.
  std::vector<int64_t> best(n, std::numeric_limits<int64_t>::max());
  std::vector<int32_t> parent(n, -1);
  std::vector<uint8_t> done(n, 0);
  std::vector<std::pair<int32_t, int32_t>> treeEdges;
  best[0] = 0;
  for (size_t it = 0; it < n; ++it) {
    size_t u = n;
    for (size_t i = 0; i < n; ++i) {
      if (!done[i] && (u == n || best[i] < best[u])) u = i;
    }
    done[u] = 1;
    if (parent[u] >= 0) treeEdges.push_back({parent[u], static_cast<int32_t>(u)});
    const int ux = pins[u] % nx, uy = pins[u] / nx;
    for (size_t v = 0; v < n; ++v) {
      if (done[v]) continue;
      const int64_t d = std::abs(pins[v] % nx - ux) + std::abs(pins[v] / nx - uy);
      if (d < best[v]) {
        best[v] = d;
        parent[v] = static_cast<int32_t>(u);
      }
    }
  }
  std::vector<int32_t> cand, bestEdges;
  for (const auto& [a, b] : treeEdges) {
    const int x0 = pins[a] % nx, y0 = pins[a] / nx, x1 = pins[b] % nx, y1 = pins[b] / nx;
    double bestCost = std::numeric_limits<double>::max();
    auto consider = [&](std::vector<int32_t>& edges) {
      const double c = pathCost(g, edges, route, pf);
      if (c < bestCost) {
        bestCost = c;
        bestEdges = edges;
      }
    };
    // HVH: horizontal to column xm, vertical, horizontal (xm = x1: L shape, xm = x0: the other L).
    const int xlo = std::min(x0, x1), xhi = std::max(x0, x1), ylo = std::min(y0, y1), yhi = std::max(y0, y1);
    for (int xm = xlo; xm <= xhi; ++xm) {
      cand.clear();
      straight(g, x0, y0, xm, y0, cand);
      straight(g, xm, y0, xm, y1, cand);
      straight(g, xm, y1, x1, y1, cand);
      consider(cand);
    }
    for (int ym = ylo; ym <= yhi; ++ym) {
      cand.clear();
      straight(g, x0, y0, x0, ym, cand);
      straight(g, x0, ym, x1, ym, cand);
      straight(g, x1, ym, x1, y1, cand);
      consider(cand);
    }
    addSorted(route, bestEdges);
  }
  return route;
}

std::vector<int32_t> mazeRoute(const Graph2d& g, const std::vector<int32_t>& pins, double pf, int margin,
                               MazeScratch& s) {
  std::vector<int32_t> route;
  if (pins.size() < 2) return route;
  const int nx = g.nx(), ny = g.ny();
  int bx0 = nx, by0 = ny, bx1 = 0, by1 = 0;
  for (int32_t p : pins) {
    bx0 = std::min(bx0, p % nx);
    bx1 = std::max(bx1, p % nx);
    by0 = std::min(by0, p / nx);
    by1 = std::max(by1, p / nx);
  }
  bx0 = std::max(0, bx0 - margin);
  by0 = std::max(0, by0 - margin);
  bx1 = std::min(nx - 1, bx1 + margin);
  by1 = std::min(ny - 1, by1 + margin);
  const size_t cells = static_cast<size_t>(nx) * ny;
  if (s.dist.size() != cells) {
    s.dist.assign(cells, 0);
    s.from.assign(cells, -1);
    s.stamp.assign(cells, 0);
    s.inTree.assign(cells, 0);
    s.round = 0;
  }
  std::vector<int32_t> tree{pins.front()};
  s.inTree[pins.front()] = 1;
  std::vector<int32_t> left(pins.begin() + 1, pins.end());
  std::sort(left.begin(), left.end());
  using Item = std::pair<double, int32_t>;
  while (!left.empty()) {
    ++s.round;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
    for (int32_t t : tree) {
      s.stamp[t] = s.round;
      s.dist[t] = 0;
      s.from[t] = -1;
      open.push({0.0, t});
    }
    int32_t hit = -1;
    while (!open.empty()) {
      const auto [d, u] = open.top();
      open.pop();
      if (d > s.dist[u]) continue;
      if (!s.inTree[u] && std::binary_search(left.begin(), left.end(), u)) {
        hit = u;
        break;
      }
      const int ux = u % nx, uy = u / nx;
      const int nbx[4] = {ux + 1, ux - 1, ux, ux};
      const int nby[4] = {uy, uy, uy + 1, uy - 1};
      for (int k = 0; k < 4; ++k) {
        if (nbx[k] < bx0 || nbx[k] > bx1 || nby[k] < by0 || nby[k] > by1) continue;
        const int32_t v = nby[k] * nx + nbx[k];
        const double nd = d + g.cost(g.edgeBetween(u, v), pf);
        if (s.stamp[v] != s.round || nd < s.dist[v]) {
          s.stamp[v] = s.round;
          s.dist[v] = nd;
          s.from[v] = u;
          open.push({nd, v});
        }
      }
    }
    if (hit < 0) break;  // cannot happen inside a connected box; keeps the loop finite
    std::vector<int32_t> path;
    for (int32_t v = hit; s.from[v] >= 0 && !s.inTree[v]; v = s.from[v]) {
      route.push_back(g.edgeBetween(v, s.from[v]));
      path.push_back(v);
    }
    for (int32_t v : path) {
      s.inTree[v] = 1;
      tree.push_back(v);
    }
    left.erase(std::lower_bound(left.begin(), left.end(), hit));
    // Pins the new path ran through are joined too.
    std::erase_if(left, [&](int32_t p) { return s.inTree[p] != 0; });
  }
  for (int32_t t : tree) s.inTree[t] = 0;
  std::sort(route.begin(), route.end());
  route.erase(std::unique(route.begin(), route.end()), route.end());
  return route;
}

}  // namespace xroute
