// Minimum area (LEF "AREA a"): every connected same-net set of metal on a
// routing layer (a component: pins and wires together) needs a union area
// >= a, each point counted once. Obstructions are not checked. A component
// with fixed metal (a pin, a special net) that its routing does not cover has
// part of its outline from the input, and routing only adds area to it: its
// marker counts as fixed, like an all-fixed component's (skipFixedPairs drops
// both; drt's gc skips a polygon with a fixed edge, TritonRoute and Dr. CU
// take a pin as giving enough area; drc/README.md).
// Marker box: the bounding box of the component; net2 = -1.
#include <algorithm>

#include "drc/layer_shapes.hpp"

namespace xroute::drc {

namespace {

// Area of the union of rects (DBU^2): a sweep over x slabs.
Area unionArea(const std::vector<Rect>& rects) {
  const std::vector<Dbu> xs = edgeCoords(rects, true);
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
  std::vector<Rect> rects, routed;
  for (int32_t c = 0; c < comps; ++c) {
    const int32_t first = ls.compMembers[ls.compStart[c]];
    if (!ls.compSeed[c] || ls.isObs(first)) continue;
    rects.clear();
    routed.clear();
    bool bigEnough = false, hasFixed = false;
    Rect box = ls.rects[first];
    for (int32_t k = ls.compStart[c]; k < ls.compStart[c + 1]; ++k) {
      const int32_t i = ls.compMembers[k];
      const Rect& r = ls.rects[i];
      bigEnough = bigEnough || r.area() >= minArea;
      box.expandToInclude(r);
      rects.push_back(r);
      if (ls.fixed[i]) hasFixed = true;
      else routed.push_back(r);
    }
    if (bigEnough) continue;
    // The union is no larger than the bounding box.
    if (box.area() >= minArea && unionArea(rects) >= minArea) continue;
    // Some fixed metal lies outside the routing (part of the outline is
    // fixed): the input's violation, like an all-fixed conductor.
    const bool fixed = ls.compFixed[c] || (hasFixed && unionArea(routed) < unionArea(rects));
    out.push_back({Marker{MarkerType::MinArea, ls.layer, box, ls.nets[first], -1}, fixed});
  }
}

}  // namespace xroute::drc
