#include "route/min_area_fix.hpp"

#include <algorithm>

#include "geom/union_find.hpp"

namespace xroute {

Area unionArea(const std::vector<Rect>& rects) {
  const std::vector<Dbu> xs = edgeCoords(rects, true), ys = edgeCoords(rects, false);
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

struct PatchChoice {
  Rect rect;
  int64_t score = -1;  // -1: none yet
};

void consider(PatchChoice& best, const RepairScore& score, int z, const Rect& r) {
  const int64_t sc = score ? score(z, r) : 0;
  if (best.score < 0 || sc < best.score) best = {r, sc};
}

// Spans [a, b] along one axis that hold the piece's extent [lo, hi] and are at
// least `need` long, on the manufacturing grid and inside [boxLo, boxHi]:
// grown evenly, all towards low, all towards high.
std::vector<std::pair<Dbu, Dbu>> spans(Dbu lo, Dbu hi, Dbu need, Dbu grid, Dbu boxLo, Dbu boxHi) {
  Dbu grow = std::max<Dbu>(0, need - (hi - lo));
  grow = (grow + 2 * grid - 1) / (2 * grid) * grid;  // per side
  std::vector<std::pair<Dbu, Dbu>> out;
  for (int shift = 0; shift < 3; ++shift) {
    const Dbu a = lo - (shift == 0 ? grow : shift == 1 ? 2 * grow : 0);
    const Dbu b = hi + (shift == 0 ? grow : shift == 2 ? 2 * grow : 0);
    if (a >= boxLo && b <= boxHi) out.emplace_back(a, b);  // keep the repair inside the region
  }
  return out;
}

// Where every wire-wide patch meets another net's metal: patches along the
// preferred direction that are thicker (so shorter: a short run beside a
// wide neighbour needs less spacing) or off the wire's centre line (growing
// away from the neighbour), each still holding part of the routed piece `f`.
void thickPatches(PatchChoice& best, const RepairScore& score, int z, const Layer& layer, const LayerTracks& lt,
                  const Rect& f, const Rect& bb, const Rect& box, Dbu grid) {
  const Dbu width = std::max<Dbu>(1, lt.wireWidth);
  const Dbu step = std::max<Dbu>(grid, (width / 4 + grid - 1) / grid * grid);
  const bool h = lt.horizontal;
  const Dbu fLo = h ? f.ylo : f.xlo, fHi = h ? f.yhi : f.xhi;
  const Dbu boxLo = h ? box.ylo : box.xlo, boxHi = h ? box.yhi : box.xhi;
  for (Dbu t = width; t <= 3 * width; t += step) {
    const Dbu need = static_cast<Dbu>((layer.minArea + t - 1) / t);
    const Dbu mid = ((fLo + fHi - t) / 2) / grid * grid;
    for (const Dbu c0 : {mid, fLo, fHi - t, mid + width / 2, mid - width / 2}) {
      const Dbu c1 = c0 + t;
      if (c1 <= fLo || c0 >= fHi || c0 < boxLo || c1 > boxHi) continue;  // must hold part of the piece
      for (const auto& [a, b] : spans(h ? bb.xlo : bb.ylo, h ? bb.xhi : bb.yhi, need, grid,
                                      h ? box.xlo : box.ylo, h ? box.xhi : box.yhi)) {
        consider(best, score, z, h ? Rect{a, c0, b, c1} : Rect{c0, a, c1, b});
      }
    }
  }
}

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
      PatchChoice best;
      // Candidates: along the preferred direction first (ties keep it), then across.
      for (int axis = 0; axis < 2; ++axis) {
        const bool horizontal = (axis == 0) == lt.horizontal;
        const Dbu across = horizontal ? (f.ylo + f.yhi) / 2 : (f.xlo + f.xhi) / 2;
        for (const auto& [a, b] : spans(horizontal ? bb.xlo : bb.ylo, horizontal ? bb.xhi : bb.yhi, need, grid,
                                        horizontal ? box.xlo : box.ylo, horizontal ? box.xhi : box.yhi)) {
          RouteWire w;
          w.layer = lt.layer;
          w.from = horizontal ? Point{a + half, across} : Point{across, a + half};
          w.to = horizontal ? Point{b - half, across} : Point{across, b - half};
          Rect r;
          if (w.from != w.to && routeWireRect(tech, w, r)) consider(best, score, static_cast<int>(z), r);
        }
      }
      if (best.score >= kConflict) thickPatches(best, score, static_cast<int>(z), layer, lt, f, bb, box, grid);
      // A patch that would touch another net's metal is worse than the
      // minimum-area violation it mends (a later iteration reroutes instead).
      if (best.score < 0 || best.score >= kConflict) continue;
      const Rect patch = best.rect;
      extra.push_back({lt.layer, patch});
      ++repairs;
    }
  }
  added.patches.insert(added.patches.end(), extra.begin(), extra.end());
  return repairs;
}

}  // namespace xroute
