#include "flow/region_marks.hpp"

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

namespace {

// The CrossEnd bits of r (routing layer z) that none of the rects `gather` puts in `others` (the
// other shapes of its net on the layer touching it) continues; 0 unless r is narrower across than
// the layer's EOL width.
template <class Gather>
uint8_t crossEnds(const RouteContext& ctx, const Rect& r, int z, std::vector<Rect>& others, Gather&& gather) {
  const bool hz = ctx.rules.horizontal[z] != 0;
  if (ctx.rules.eolSpace[z] <= 0 || (hz ? r.width() : r.height()) >= ctx.rules.eolWidth[z]) return 0;
  others.clear();
  gather();
  return openCrossEnds(r, hz, others);
}

}  // namespace

void markFixed(const RouteContext& ctx, const Rect& box, RegionGrid& g) {
  std::vector<Rect> others;
  ctx.fixedIndex.query(grownBox(box, ctx.halo), [&](int32_t id) {
    const DrcShape& s = ctx.fixedShapes[id];
    const Layer& l = ctx.tech.layer(s.layer);
    if (l.routingIndex >= 0) {
      const int z = l.routingIndex;
      // A pin drawn as several rects: its other rects continue an end.
      const uint8_t ends = crossEnds(ctx, s.rect, z, others, [&] {
        ctx.fixedIndex.query(s.rect, [&](int32_t j) {
          const DrcShape& o = ctx.fixedShapes[j];
          if (j != id && o.layer == s.layer && o.net == s.net && o.rect.overlaps(s.rect)) others.push_back(o.rect);
        });
      });
      markMetal(g, ctx.rules, z, s.rect, s.net, true, ctx.netRules.spacing(s.net, z), ends);
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
      const uint8_t ends = crossEnds(ctx, s.rect, z, others, [&] {
        for (size_t j = 0; j < shapes.size(); ++j)
          if (j != i && shapes[j].layer == s.layer && shapes[j].rect.overlaps(s.rect)) others.push_back(shapes[j].rect);
      });
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
  return m.type == MarkerType::EndOfLine && z >= 0 ? ctx.rules.eolSpace[z] : 0;
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
