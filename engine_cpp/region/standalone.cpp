#include "region/standalone.hpp"

#include <algorithm>
#include <map>

#include "region/clip.hpp"

namespace xroute {

namespace {

struct Span {
  Dbu lo = 0, hi = 0;   // DBU along the edge
  uint32_t mask = 0;    // guide layers
};

// Merges overlapping spans (sorted by lo).
std::vector<Span> mergeSpans(std::vector<Span> spans) {
  std::sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) { return a.lo < b.lo; });
  std::vector<Span> out;
  for (const Span& s : spans) {
    if (!out.empty() && s.lo <= out.back().hi) {
      out.back().hi = std::max(out.back().hi, s.hi);
      out.back().mask |= s.mask;
    } else {
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace

RegionTask makeStandaloneTask(const RouteContext& ctx, const Rect& box, int32_t regionId, int32_t iteration,
                              const MazeCosts& costs, CrossingPlan& plan) {
  const Design& d = ctx.design;
  RegionTask task;
  task.region.id = regionId;
  task.region.box = box;
  task.iteration = iteration;
  task.costs = costs;
  plan = CrossingPlan{};
  for (int32_t n = 0; n < static_cast<int32_t>(d.nets.size()); ++n) {
    if (d.pinCount(NetId(n)) < 2) continue;
    RegionNetTask nt;
    nt.net = n;
    for (int32_t pin = d.netPinStart[n]; pin < d.netPinStart[n + 1]; ++pin) {
      for (const AccessPoint* ap = ctx.access.begin(pin); ap != ctx.access.end(pin); ++ap) {
        if (box.contains(ap->at)) {
          nt.pins.push_back(pin);
          break;
        }
      }
    }
    if (!d.nets[n].routing.empty()) {
      if (!routingTouches(d.nets[n].routing, box) && nt.pins.empty()) continue;
      nt.ripup = true;
      std::vector<BoundaryTerminal> terms;
      clipOutside(ctx.tech, d, d.nets[n].routing, box, &terms);
      if (nt.pins.size() + terms.size() >= 2) task.nets.push_back(std::move(nt));
      continue;
    }
    // Unrouted: crossings where guides cut the box edges. Edge k: 0 left, 1 right, 2 bottom, 3 top.
    std::vector<Span> edges[4];
    if (d.hasGuides()) {
      for (int32_t gi = d.guideStart[n]; gi < d.guideStart[n + 1]; ++gi) {
        const Rect& g = d.guideRects[gi];
        const int z = ctx.tech.layer(d.guideLayers[gi]).routingIndex;
        const uint32_t bit = z >= 0 ? 1u << z : 0;
        const Dbu ylo = std::max(g.ylo, box.ylo), yhi = std::min(g.yhi, box.yhi);
        const Dbu xlo = std::max(g.xlo, box.xlo), xhi = std::min(g.xhi, box.xhi);
        if (yhi > ylo) {
          if (g.xlo < box.xlo && g.xhi > box.xlo) edges[0].push_back({ylo, yhi, bit});
          if (g.xlo < box.xhi && g.xhi > box.xhi) edges[1].push_back({ylo, yhi, bit});
        }
        if (xhi > xlo) {
          if (g.ylo < box.ylo && g.yhi > box.ylo) edges[2].push_back({xlo, xhi, bit});
          if (g.ylo < box.yhi && g.yhi > box.yhi) edges[3].push_back({xlo, xhi, bit});
        }
      }
    }
    for (int e = 0; e < 4; ++e) {
      for (const Span& s : mergeSpans(edges[e])) {
        Crossing c;
        c.net = n;
        c.vertical = e < 2;
        c.coord = e == 0 ? box.xlo : e == 1 ? box.xhi : e == 2 ? box.ylo : box.yhi;
        c.lo = s.lo;
        c.hi = s.hi;
        c.layerMask = s.mask;
        const bool thisIsLow = e == 1 || e == 3;  // this region lies left of / below the edge
        c.regionA = thisIsLow ? regionId : -1;
        c.regionB = thisIsLow ? -1 : regionId;
        nt.crossings.push_back(static_cast<int32_t>(plan.crossings.size()));
        plan.crossings.push_back(c);
      }
    }
    if (nt.pins.size() + nt.crossings.size() >= 2) task.nets.push_back(std::move(nt));
  }
  return task;
}

}  // namespace xroute
