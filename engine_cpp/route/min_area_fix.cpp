#include "route/min_area_fix.hpp"

#include <algorithm>

#include "geom/union_find.hpp"

namespace xroute {

Area unionArea(const std::vector<Rect>& rects) {
  std::vector<Dbu> xs, ys;
  for (const Rect& r : rects) {
    xs.push_back(r.xlo);
    xs.push_back(r.xhi);
    ys.push_back(r.ylo);
    ys.push_back(r.yhi);
  }
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  Area total = 0;
  for (size_t i = 0; i + 1 < xs.size(); ++i) {
    for (size_t j = 0; j + 1 < ys.size(); ++j) {
      const Dbu cx = xs[i], cy = ys[j];
      for (const Rect& r : rects) {
        if (r.xlo <= cx && xs[i + 1] <= r.xhi && r.ylo <= cy && ys[j + 1] <= r.yhi) {
          total += Area(xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]);
          break;
        }
      }
    }
  }
  return total;
}

namespace {

constexpr int64_t kConflict = 1000;  // a RepairScore at or above this means another net's metal

}  // namespace

int fixMinArea(const Tech& tech, const Design& design, const TrackSet& tracks, const Rect& box,
               const std::vector<MetalAnchor>& anchors, const std::vector<PinMetal>& pins, const RepairScore& score,
               NetRouting& added) {
  int repairs = 0;
  std::vector<RoutePatch> extra;
  for (size_t z = 0; z < tracks.layers.size(); ++z) {
    const LayerTracks& lt = tracks.layers[z];
    const Layer& layer = tech.layer(lt.layer);
    if (layer.minArea <= 0) continue;
    std::vector<Rect> rects;
    for (const RouteWire& w : added.wires) {
      Rect r;
      if (w.layer == lt.layer && routeWireRect(tech, w, r)) rects.push_back(r);
    }
    for (const RouteVia& v : added.vias) {
      for (const ViaShape& s : design.via(tech, v.via).shapes) {
        if (s.layer == lt.layer) rects.push_back(s.rect.translated(v.at));
      }
    }
    if (rects.empty()) continue;
    const size_t routed = rects.size();  // rects[routed..] are pin metal
    for (const PinMetal& p : pins) {
      if (p.z == static_cast<int>(z)) rects.push_back(p.rect);
    }
    UnionFind sets(rects.size());
    for (size_t i = 0; i < rects.size(); ++i)
      for (size_t j = i + 1; j < rects.size(); ++j)
        if (rects[i].overlaps(rects[j])) sets.attach(int32_t(i), int32_t(j));
    std::vector<std::vector<Rect>> comps(rects.size());
    std::vector<int> routedCount(rects.size(), 0);
    std::vector<Rect> firstRouted(rects.size());
    for (size_t i = 0; i < rects.size(); ++i) {
      const int root = sets.find(int32_t(i));
      comps[root].push_back(rects[i]);
      if (i < routed && routedCount[root]++ == 0) firstRouted[root] = rects[i];
    }
    for (size_t ci = 0; ci < comps.size(); ++ci) {
      const std::vector<Rect>& comp = comps[ci];
      if (comp.empty() || routedCount[ci] == 0) continue;
      bool anchored = false;
      for (const MetalAnchor& a : anchors) {
        if (a.z != static_cast<int>(z)) continue;
        for (const Rect& r : comp) anchored = anchored || r.contains(a.at);
      }
      if (anchored) continue;
      const Area area = unionArea(comp);
      if (area >= layer.minArea) continue;
      Rect bb = comp.front();
      for (const Rect& r : comp) bb.expandToInclude(r);
      const Dbu width = std::max<Dbu>(1, lt.wireWidth);
      const Dbu half = width / 2;
      // Length the wire needs (extensions included) to reach the area alone.
      const Dbu need = static_cast<Dbu>((layer.minArea + width - 1) / width);
      const Dbu grid = tech.manufacturingGrid > 0 ? tech.manufacturingGrid : 1;
      const Rect& f = firstRouted[ci];
      RouteWire best;
      int64_t bestScore = -1;
      // Candidates: along the preferred direction first (ties keep it), then across.
      for (int axis = 0; axis < 2; ++axis) {
        const bool horizontal = (axis == 0) == lt.horizontal;
        const Dbu lo = horizontal ? bb.xlo : bb.ylo, hi = horizontal ? bb.xhi : bb.yhi;
        const Dbu across = horizontal ? (f.ylo + f.yhi) / 2 : (f.xlo + f.xhi) / 2;
        Dbu grow = std::max<Dbu>(0, need - (hi - lo));
        grow = (grow + 2 * grid - 1) / (2 * grid) * grid;  // per side, on the manufacturing grid
        const Dbu boxLo = horizontal ? box.xlo : box.ylo, boxHi = horizontal ? box.xhi : box.yhi;
        for (int shift = 0; shift < 3; ++shift) {  // centred, all low, all high
          Dbu a = lo - (shift == 0 ? grow : shift == 1 ? 2 * grow : 0);
          Dbu b = hi + (shift == 0 ? grow : shift == 2 ? 2 * grow : 0);
          if (a < boxLo || b > boxHi) continue;  // keep the repair inside the region
          RouteWire w;
          w.layer = lt.layer;
          w.from = horizontal ? Point{a + half, across} : Point{across, a + half};
          w.to = horizontal ? Point{b - half, across} : Point{across, b - half};
          if (w.from == w.to) continue;
          Rect r;
          routeWireRect(tech, w, r);
          const int64_t sc = score ? score(static_cast<int>(z), r) : 0;
          if (bestScore < 0 || sc < bestScore) {
            bestScore = sc;
            best = w;
          }
        }
      }
      // A patch that would touch another net's metal is worse than the
      // minimum-area violation it mends (a later iteration reroutes instead).
      if (bestScore < 0 || bestScore >= kConflict) continue;
      const RouteWire w = best;
      Rect patch;
      routeWireRect(tech, w, patch);
      extra.push_back({w.layer, patch});
      ++repairs;
    }
  }
  added.patches.insert(added.patches.end(), extra.begin(), extra.end());
  return repairs;
}

}  // namespace xroute
