// Minimum area (LEF "AREA a"): every connected same-net set of metal on a
// routing layer (a component: pins and wires together) needs a union area
// >= a, each point counted once. Obstructions are not checked. Marker box:
// the bounding box of the component; net2 = -1.
#include <algorithm>

#include "drc/layer_shapes.hpp"

namespace xroute::drc {

namespace {

// Area of the union of rects (DBU^2): a sweep over x slabs.
Area unionArea(const std::vector<Rect>& rects) {
  std::vector<Dbu> xs;
  for (const Rect& r : rects) {
    xs.push_back(r.xlo);
    xs.push_back(r.xhi);
  }
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  Area total = 0;
  std::vector<std::pair<Dbu, Dbu>> spans;
  for (size_t k = 0; k + 1 < xs.size(); ++k) {
    spans.clear();
    for (const Rect& r : rects)
      if (r.xlo <= xs[k] && r.xhi >= xs[k + 1]) spans.push_back({r.ylo, r.yhi});
    std::sort(spans.begin(), spans.end());
    Dbu covered = 0, top = 0;
    bool open = false;
    for (const auto& [lo, hi] : spans) {
      if (!open || lo > top) {
        covered += hi - lo;
        top = hi;
        open = true;
      } else if (hi > top) {
        covered += hi - top;
        top = hi;
      }
    }
    total += Area(covered) * Area(xs[k + 1] - xs[k]);
  }
  return total;
}

}  // namespace

void checkMinArea(const LayerShapes& ls, MarkerSink& out) {
  const Area minArea = ls.rules->minArea;
  if (minArea <= 0) return;
  const int32_t comps = int32_t(ls.compStart.size()) - 1;
  std::vector<Rect> rects;
  for (int32_t c = 0; c < comps; ++c) {
    const int32_t first = ls.compMembers[ls.compStart[c]];
    if (!ls.compSeed[c] || ls.isObs(first)) continue;
    rects.clear();
    bool bigEnough = false;
    Rect box = ls.rects[first];
    for (int32_t k = ls.compStart[c]; k < ls.compStart[c + 1]; ++k) {
      const Rect& r = ls.rects[ls.compMembers[k]];
      bigEnough = bigEnough || r.area() >= minArea;
      box.expandToInclude(r);
      rects.push_back(r);
    }
    if (bigEnough) continue;
    // The union is no larger than the bounding box.
    if (box.area() >= minArea && unionArea(rects) >= minArea) continue;
    out.push_back({Marker{MarkerType::MinArea, ls.layer, box, ls.nets[first], -1}, bool(ls.compFixed[c])});
  }
}

}  // namespace xroute::drc
