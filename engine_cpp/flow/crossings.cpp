#include "flow/crossings.hpp"

#include <algorithm>
#include <map>
#include <queue>
#include <set>

namespace xroute {

namespace {

struct Planner {
  const RouteContext& ctx;
  const std::vector<Region>& regions;
  int size, offset;
  int cols = 0, rows = 0;
  CrossingPlan plan;

  int32_t regionOf(Point p) const { return regionAt(regions, ctx.gcells, size, offset, p); }
  int32_t regionAtCell(int rx, int ry) const { return ry * cols + rx; }

  // Edge between two adjacent regions a, b: key a < b.
  struct EdgeInfo {
    Dbu lo = 0, hi = 0;
    uint32_t mask = 0;
    bool any = false;
  };

  void addCrossing(int32_t net, int32_t a, int32_t b, const EdgeInfo& e) {
    const Region& ra = regions[a];
    const Region& rb = regions[b];
    Crossing c;
    c.net = net;
    if (ra.rx != rb.rx) {
      c.vertical = true;
      const Region& left = ra.rx < rb.rx ? ra : rb;
      c.regionA = left.id;
      c.regionB = (left.id == ra.id ? rb : ra).id;
      c.coord = left.box.xhi;
      const Dbu elo = std::max(ra.box.ylo, rb.box.ylo), ehi = std::min(ra.box.yhi, rb.box.yhi);
      c.lo = e.any ? std::max(elo, e.lo) : elo;
      c.hi = e.any ? std::min(ehi, e.hi) : ehi;
    } else {
      c.vertical = false;
      const Region& below = ra.ry < rb.ry ? ra : rb;
      c.regionA = below.id;
      c.regionB = (below.id == ra.id ? rb : ra).id;
      c.coord = below.box.yhi;
      const Dbu elo = std::max(ra.box.xlo, rb.box.xlo), ehi = std::min(ra.box.xhi, rb.box.xhi);
      c.lo = e.any ? std::max(elo, e.lo) : elo;
      c.hi = e.any ? std::min(ehi, e.hi) : ehi;
    }
    if (c.lo > c.hi) std::swap(c.lo, c.hi);
    c.layerMask = e.mask;
    const int32_t id = static_cast<int32_t>(plan.crossings.size());
    plan.crossings.push_back(c);
    plan.regionCrossings[c.regionA].push_back(id);
    plan.regionCrossings[c.regionB].push_back(id);
  }

  void planNet(int32_t net) {
    const Design& d = ctx.design;
    std::set<int32_t> pinRegions;
    for (int32_t r = d.netPinStart[net]; r < d.netPinStart[net + 1]; ++r) {
      if (ctx.access.count(r) == 0) continue;
      const int32_t reg = regionOf(ctx.access.begin(r)->at);
      if (reg < 0) continue;
      pinRegions.insert(reg);
      plan.regionPins[reg].push_back(r);
    }
    if (d.pinCount(NetId(net)) < 2 || pinRegions.empty()) return;
    for (int32_t reg : pinRegions) plan.regionNets[reg].push_back(net);
    if (pinRegions.size() == 1) return;

    // Region adjacency through the guides.
    std::map<std::pair<int32_t, int32_t>, EdgeInfo> edges;
    if (d.hasGuides()) {
      for (int32_t gi = d.guideStart[net]; gi < d.guideStart[net + 1]; ++gi) {
        const Rect g = d.guideRects[gi];
        const int z = ctx.tech.layer(d.guideLayers[gi]).routingIndex;
        const Rect grown{g.xlo - 1, g.ylo - 1, g.xhi + 1, g.yhi + 1};
        const Region* r0 = &regions[std::max(0, regionOf({grown.xlo, grown.ylo}))];
        const Region* r1 = &regions[std::max(0, regionOf({grown.xhi, grown.yhi}))];
        for (int ry = r0->ry; ry <= r1->ry; ++ry) {
          for (int rx = r0->rx; rx <= r1->rx; ++rx) {
            const int32_t a = regionAtCell(rx, ry);
            const Dbu ylo = std::max(g.ylo, regions[a].box.ylo), yhi = std::min(g.yhi, regions[a].box.yhi);
            const Dbu xlo = std::max(g.xlo, regions[a].box.xlo), xhi = std::min(g.xhi, regions[a].box.xhi);
            // An edge only where the guide runs along it for a positive length
            // (a guide touching a region at a corner links nothing).
            if (rx < r1->rx && yhi > ylo) {  // to the right
              EdgeInfo& e = edges[{a, regionAtCell(rx + 1, ry)}];
              const Dbu lo = ylo, hi = yhi;
              e.lo = e.any ? std::min(e.lo, lo) : lo;
              e.hi = e.any ? std::max(e.hi, hi) : hi;
              e.any = true;
              if (z >= 0) e.mask |= 1u << z;
            }
            if (ry < r1->ry && xhi > xlo) {  // above
              EdgeInfo& e = edges[{a, regionAtCell(rx, ry + 1)}];
              const Dbu lo = xlo, hi = xhi;
              e.lo = e.any ? std::min(e.lo, lo) : lo;
              e.hi = e.any ? std::max(e.hi, hi) : hi;
              e.any = true;
              if (z >= 0) e.mask |= 1u << z;
            }
          }
        }
      }
    }
    std::map<int32_t, std::vector<int32_t>> adj;
    for (const auto& [key, e] : edges) {
      adj[key.first].push_back(key.second);
      adj[key.second].push_back(key.first);
    }
    // A Steiner tree of regions over the guide links: grow from the first
    // pin region, each time joining the pin region nearest to the tree (a
    // breadth-first search from the whole tree) by its shortest path. (A
    // shortest-path tree from one root would star out and waste wire on
    // nets with many pins.)
    std::map<int32_t, int32_t> parent;
    const int32_t root = *pinRegions.begin();
    parent[root] = -1;
    std::set<int32_t> left(pinRegions);
    left.erase(root);
    while (!left.empty()) {
      std::map<int32_t, int32_t> from;
      std::queue<int32_t> q;
      for (const auto& [reg, par] : parent) {
        from[reg] = -1;
        q.push(reg);
      }
      int32_t hit = -1;
      while (!q.empty()) {
        const int32_t u = q.front();
        q.pop();
        if (left.count(u)) {
          hit = u;
          break;
        }
        auto it = adj.find(u);
        if (it == adj.end()) continue;
        std::vector<int32_t> next = it->second;
        std::sort(next.begin(), next.end());
        for (int32_t v : next) {
          if (from.count(v)) continue;
          from[v] = u;
          q.push(v);
        }
      }
      if (hit < 0) break;  // the rest is not linked by guides
      for (int32_t v = hit; !parent.count(v); v = from[v]) {
        parent[v] = from[v];
        left.erase(v);
      }
    }
    // Pin regions the guides do not reach: an L-shaped chain from the nearest reached region.
    for (int32_t pr : pinRegions) {
      if (parent.count(pr)) continue;
      int32_t best = root;
      int bestDist = 1 << 30;
      for (const auto& [reg, par] : parent) {
        const int dist = std::abs(regions[reg].rx - regions[pr].rx) + std::abs(regions[reg].ry - regions[pr].ry);
        if (dist < bestDist) {
          bestDist = dist;
          best = reg;
        }
      }
      int rx = regions[best].rx, ry = regions[best].ry;
      int32_t prev = best;
      while (rx != regions[pr].rx || ry != regions[pr].ry) {
        if (rx != regions[pr].rx) rx += rx < regions[pr].rx ? 1 : -1;
        else ry += ry < regions[pr].ry ? 1 : -1;
        const int32_t cur = regionAtCell(rx, ry);
        if (!parent.count(cur)) parent[cur] = prev;
        prev = cur;
      }
    }
    // Every leaf of this tree is a pin region: each path added ends at one.
    std::map<int32_t, std::vector<int32_t>> tree;
    for (const auto& [reg, par] : parent) {
      if (par < 0) continue;
      tree[reg].push_back(par);
      tree[par].push_back(reg);
    }
    std::map<int32_t, std::vector<Point>> pinsByRegion;
    for (int32_t r = d.netPinStart[net]; r < d.netPinStart[net + 1]; ++r) {
      if (ctx.access.count(r) == 0) continue;
      const Point p = ctx.access.begin(r)->at;
      pinsByRegion[regionOf(p)].push_back(p);
    }
    for (const auto& [reg, par] : parent) {
      if (par < 0) continue;
      const auto key = std::make_pair(std::min(reg, par), std::max(reg, par));
      auto it = edges.find(key);
      addCrossing(net, reg, par, it == edges.end() ? EdgeInfo{} : it->second);
      Crossing& c = plan.crossings.back();
      // For each side, the pins beyond the edge nearest in the tree.
      for (int side = 0; side < 2; ++side) {
        const int32_t here = side == 0 ? c.regionA : c.regionB;
        const int32_t there = here == reg ? par : reg;
        std::map<int32_t, int> depth{{there, 0}};
        std::queue<int32_t> q;
        q.push(there);
        std::vector<Point> near, all;
        while (!q.empty()) {
          const int32_t u = q.front();
          q.pop();
          for (const Point& p : pinsByRegion[u]) {
            all.push_back(p);
            if (depth[u] <= 2) near.push_back(p);
          }
          for (int32_t v : tree[u]) {
            if (v == here || depth.count(v)) continue;
            depth[v] = depth[u] + 1;
            q.push(v);
          }
        }
        const std::vector<Point>& use = near.empty() ? all : near;
        for (const Point& p : use) {
          const Dbu along = c.vertical ? p.y : p.x;
          c.wantLo[side] = c.hasWant[side] ? std::min(c.wantLo[side], along) : along;
          c.wantHi[side] = c.hasWant[side] ? std::max(c.wantHi[side], along) : along;
          c.hasWant[side] = true;
        }
      }
      if (!pinRegions.count(reg)) plan.regionNets[reg].push_back(net);
    }
  }
};

}  // namespace

CrossingPlan planCrossings(const RouteContext& ctx, const std::vector<Region>& regions, int size, int offset) {
  Planner p{ctx, regions, size, offset, 0, 0, {}};
  for (const Region& r : regions) {
    p.cols = std::max(p.cols, r.rx + 1);
    p.rows = std::max(p.rows, r.ry + 1);
  }
  p.plan.regionCrossings.assign(regions.size(), {});
  p.plan.regionPins.assign(regions.size(), {});
  p.plan.regionNets.assign(regions.size(), {});
  for (size_t n = 0; n < ctx.design.nets.size(); ++n) p.planNet(static_cast<int32_t>(n));
  for (auto& nets : p.plan.regionNets) {
    std::sort(nets.begin(), nets.end());
    nets.erase(std::unique(nets.begin(), nets.end()), nets.end());
  }
  return std::move(p.plan);
}

}  // namespace xroute
