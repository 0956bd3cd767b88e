#include "groute/layer_assign.hpp"

#include <algorithm>
#include <limits>
#include <queue>

#include "groute/graph2d.hpp"

namespace xroute {

namespace {

enum : uint8_t { kLeft = 1, kRight = 2, kDown = 4, kUp = 8 };

// The nodes of one net's tree with their edge directions, looked up by GCell.
struct TreeNodes {
  std::vector<int32_t> cells;  // sorted unique
  std::vector<uint8_t> bits;   // per cell: kLeft | kRight | kDown | kUp
  int find(int32_t c) const {
    auto it = std::lower_bound(cells.begin(), cells.end(), c);
    return (it != cells.end() && *it == c) ? static_cast<int>(it - cells.begin()) : -1;
  }
};

TreeNodes treeNodes(const std::vector<int32_t>& route, int nx) {
  TreeNodes t;
  for (int32_t e : route) {
    const int32_t c = Graph2d::edgeCell(e);
    t.cells.push_back(c);
    t.cells.push_back(Graph2d::edgeDir(e) == 0 ? c + 1 : c + nx);
  }
  std::sort(t.cells.begin(), t.cells.end());
  t.cells.erase(std::unique(t.cells.begin(), t.cells.end()), t.cells.end());
  t.bits.assign(t.cells.size(), 0);
  for (int32_t e : route) {
    const int32_t c = Graph2d::edgeCell(e);
    if (Graph2d::edgeDir(e) == 0) {
      t.bits[t.find(c)] |= kRight;
      t.bits[t.find(c + 1)] |= kLeft;
    } else {
      t.bits[t.find(c)] |= kUp;
      t.bits[t.find(c + nx)] |= kDown;
    }
  }
  return t;
}

bool isBreak(uint8_t bits) { return bits != (kLeft | kRight) && bits != (kDown | kUp); }

std::vector<GrSegment> cutSegments(const std::vector<int32_t>& route, const TreeNodes& t, int nx) {
  std::vector<GrSegment> segs;
  for (int32_t e : route) {
    const int32_t c = Graph2d::edgeCell(e);
    if (!isBreak(t.bits[t.find(c)])) continue;  // not the start of a run
    const bool h = Graph2d::edgeDir(e) == 0;
    const int32_t step = h ? 1 : nx;
    int32_t cur = c + step;
    while (!isBreak(t.bits[t.find(cur)])) cur += step;
    segs.push_back({c, cur, h, 0});
  }
  return segs;
}

int64_t distToRange(int z, int lo, int hi) {
  if (lo > hi) return 0;  // nothing attached yet
  return z < lo ? lo - z : (z > hi ? z - hi : 0);
}

}  // namespace

LayerAssignment assignLayers(const GrGrid& grid, const std::vector<GrNet>& nets,
                             const std::vector<std::vector<int32_t>>& routes, const std::vector<int32_t>& order,
                             const LayerAssignSettings& st) {
  const int nx = grid.nx(), nz = grid.nz();
  const size_t cells = static_cast<size_t>(nx) * grid.ny();
  std::vector<std::vector<int32_t>> usage(nz, std::vector<int32_t>(cells, 0));
  LayerAssignment out;
  out.segments.resize(nets.size());
  const int minLayer = std::min(st.minLayer, nz - 1);

  for (int32_t n : order) {
    const std::vector<int32_t>& route = routes[n];
    if (route.empty()) continue;
    const TreeNodes t = treeNodes(route, nx);
    std::vector<GrSegment> segs = cutSegments(route, t, nx);

    // Breadth-first distance of every tree node from the first pin.
    std::vector<int32_t> dist(t.cells.size(), std::numeric_limits<int32_t>::max());
    std::queue<int> q;
    const int root = t.find(nets[n].anchors.front());
    dist[root >= 0 ? root : 0] = 0;
    q.push(root >= 0 ? root : 0);
    while (!q.empty()) {
      const int i = q.front();
      q.pop();
      const int32_t c = t.cells[i];
      const int32_t nb[4] = {c - 1, c + 1, c - nx, c + nx};
      const uint8_t need[4] = {kLeft, kRight, kDown, kUp};
      for (int k = 0; k < 4; ++k) {
        if (!(t.bits[i] & need[k])) continue;
        const int j = t.find(nb[k]);
        if (dist[j] > dist[i] + 1) {
          dist[j] = dist[i] + 1;
          q.push(j);
        }
      }
    }
    std::stable_sort(segs.begin(), segs.end(), [&](const GrSegment& x, const GrSegment& y) {
      return std::min(dist[t.find(x.a)], dist[t.find(x.b)]) < std::min(dist[t.find(y.a)], dist[t.find(y.b)]);
    });

    // Layers attached at each node so far (pins first).
    std::vector<int> lo(t.cells.size(), nz), hi(t.cells.size(), -1);
    for (const GrPin& p : nets[n].pins) {
      const int i = t.find(p.anchor);
      if (i < 0) continue;
      lo[i] = std::min(lo[i], p.z);
      hi[i] = std::max(hi[i], p.z);
    }
    for (GrSegment& s : segs) {
      const int ia = t.find(s.a), ib = t.find(s.b);
      const int32_t step = s.horizontal ? 1 : nx;
      int bestZ = -1;
      double bestCost = std::numeric_limits<double>::max();
      for (int z = minLayer; z < nz; ++z) {
        if (grid.layers[z].horizontal != s.horizontal) continue;
        int64_t full = 0;
        double used = 0;  // sum of usage / capacity over the segment's edges
        const GrLayer& gl = grid.layers[z];
        for (int32_t c = s.a; c < s.b; c += step) {
          full += int64_t(usage[z][c]) * 100 >= int64_t(gl.capacity[c]) * st.capacityPercent;
          used += gl.capacity[c] > 0 ? std::min(1.0, double(usage[z][c]) / gl.capacity[c]) : 1.0;
        }
        const double cost = double(st.overflowCost * full) + st.congestionCost * used +
                            double(st.viaCost * (distToRange(z, lo[ia], hi[ia]) + distToRange(z, lo[ib], hi[ib])));
        if (cost < bestCost) {
          bestCost = cost;
          bestZ = z;
        }
      }
      if (bestZ < 0) bestZ = minLayer;  // no layer of that direction: keep the lowest
      s.z = bestZ;
      for (int32_t c = s.a; c < s.b; c += step) ++usage[bestZ][c];
      lo[ia] = std::min(lo[ia], bestZ);
      hi[ia] = std::max(hi[ia], bestZ);
      lo[ib] = std::min(lo[ib], bestZ);
      hi[ib] = std::max(hi[ib], bestZ);
    }
    out.segments[n] = std::move(segs);
  }
  for (int z = 0; z < nz; ++z) {
    for (size_t c = 0; c < cells; ++c) out.overflow += std::max(0, usage[z][c] - grid.layers[z].capacity[c]);
  }
  return out;
}

}  // namespace xroute
