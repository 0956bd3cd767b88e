#include "region/region_marks.hpp"

#include <algorithm>
#include <limits>

namespace xroute {

Rect grownBox(const Rect& box, Dbu halo) {
  return Rect{box.xlo - halo, box.ylo - halo, box.xhi + halo, box.yhi + halo};
}

void closedRange(const std::vector<Dbu>& v, Dbu lo, Dbu hi, int& first, int& last) {
  first = static_cast<int>(std::lower_bound(v.begin(), v.end(), lo) - v.begin());
  last = static_cast<int>(std::upper_bound(v.begin(), v.end(), hi) - v.begin()) - 1;
}

int cutBelow(const RouteContext& ctx, LayerId cut) {
  for (size_t z = 0; z < ctx.vias.cuts.size(); ++z) {
    if (ctx.tech.vias[*ctx.vias.cuts[z].via].cut == cut) return static_cast<int>(z);
  }
  return -1;
}

void markFixed(const RouteContext& ctx, const Rect& box, RegionGrid& g) {
  ctx.fixedIndex.query(grownBox(box, ctx.halo), [&](int32_t id) {
    const DrcShape& s = ctx.fixedShapes[id];
    const Layer& l = ctx.tech.layer(s.layer);
    if (l.routingIndex >= 0) {
      const int z = l.routingIndex;
      markMetal(g, ctx.rules, z, s.rect, s.net, true, ctx.netRules.spacing(s.net, z), ctx.fixedCrossEnds[id]);
    } else if (l.cutIndex >= 0) {
      const int z = cutBelow(ctx, s.layer);
      if (z >= 0) markCut(g, ctx.rules, z, s.rect, s.net);
    }
  });
}

void markShapes(const RouteContext& ctx, int32_t net, const std::vector<NetShape>& shapes, const Rect& win,
                RegionGrid& g, RoutedMetal& metal) {
  std::vector<Rect> others;
  for (size_t i = 0; i < shapes.size(); ++i) {
    const NetShape& s = shapes[i];
    if (!s.rect.overlaps(win)) continue;
    const Layer& l = ctx.tech.layer(s.layer);
    if (l.routingIndex >= 0) {
      const int z = l.routingIndex;
      // Its cross ends that no other shape of the net on the layer touching it continues.
      uint8_t ends = 0;
      if (narrowAcross(ctx.rules, z, s.rect)) {
        others.clear();
        for (size_t j = 0; j < shapes.size(); ++j)
          if (j != i && shapes[j].layer == s.layer && shapes[j].rect.overlaps(s.rect)) others.push_back(shapes[j].rect);
        ends = openCrossEnds(s.rect, ctx.rules.horizontal[z] != 0, others);
      }
      markMetal(g, ctx.rules, z, s.rect, net, false, ctx.netRules.spacing(net, z), ends);
      metal[l.routingIndex].emplace_back(s.rect, net);
    } else if (l.cutIndex >= 0) {
      const int z = cutBelow(ctx, s.layer);
      if (z >= 0) markCut(g, ctx.rules, z, s.rect, net);
    }
  }
}

void markRoutedNodes(const RouteContext& ctx, int32_t net, const NetRouting& r, RegionGrid& g) {
  for (const RouteWire& w : r.wires) {
    const int z = ctx.tech.layer(w.layer).routingIndex;
    if (z < 0 || z >= g.nz()) continue;
    int x0, x1, y0, y1;
    closedRange(g.xs(), std::min(w.from.x, w.to.x), std::max(w.from.x, w.to.x), x0, x1);
    closedRange(g.ys(), std::min(w.from.y, w.to.y), std::max(w.from.y, w.to.y), y0, y1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) g.routedNet[g.index(x, y, z)] = net;
  }
}

Dbu markerReach(const RouteContext& ctx, const Marker& m) {
  const int z = ctx.tech.layer(m.layer).routingIndex;
  if (z < 0) return 0;
  const Rect& v = ctx.rules.viaLanding[z];
  const Dbu landing = std::max({Dbu(0), -v.xlo, v.xhi, -v.ylo, v.yhi});
  return std::max(landing, m.type == MarkerType::EndOfLine ? ctx.rules.eolSpace[z] : Dbu(0));
}

void markMarker(const RouteContext& ctx, const MarkerCost& m, RegionGrid& g) {
  const Layer& l = ctx.tech.layer(m.layer);
  int zlo = l.routingIndex, zhi = l.routingIndex;
  if (zlo < 0) {
    zlo = cutBelow(ctx, m.layer);
    zhi = zlo + 1;
    if (zlo < 0) return;
  }
  for (int z = zlo; z <= zhi && z < g.nz(); ++z) {
    const Dbu grow = ctx.tracks.layers[z].pitch + m.reach;
    int x0, x1, y0, y1;
    closedRange(g.xs(), m.box.xlo - grow, m.box.xhi + grow, x0, x1);
    closedRange(g.ys(), m.box.ylo - grow, m.box.yhi + grow, y0, y1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        int32_t& c = g.markerCost[g.index(x, y, z)];
        c = static_cast<int32_t>(std::min<int64_t>(int64_t(c) + m.cost, std::numeric_limits<int32_t>::max() / 2));
      }
  }
}

}  // namespace xroute
