// A net of a NONDEFAULTRULE in a region: the grid's marks are made for default-width wires and
// default vias at the layer's spacing, so before the maze runs for such a net, every other net's
// metal near the box (fixed shapes and routed metal) is judged again for the net's own wire
// width, its vias' landing metal and the larger of the two nets' rule spacings, as extra node
// costs (MazeNet::ruleWire / ruleVia). Only the layers where the rule differs from the defaults
// are judged again; elsewhere the grid's marks hold. (The cut of a rule's via is judged as the
// default via's.)
#include <algorithm>
#include <limits>

#include "region/region_impl.hpp"

namespace xroute {

namespace {

void addCost(int32_t& c, int64_t cost) {
  c = static_cast<int32_t>(std::min<int64_t>(int64_t(c) + cost, std::numeric_limits<int32_t>::max() / 2));
}

}  // namespace

bool RegionRouter::Impl::ruleCosts(int32_t net, RuleCosts& out) const {
  if (!ctx.netRules.any(net)) return false;
  const RegionGrid& g = *grid;
  out.wire.assign(g.size(), 0);
  out.via.assign(g.size(), 0);
  const Rect win = grownBox(box(), ctx.halo);
  for (int z = 0; z < g.nz(); ++z) {
    const Dbu width = ctx.netRules.width(net, z), space = ctx.netRules.spacing(net, z);
    const Rect* landing = ctx.netRules.landing(net, z);
    if (width == 0 && space == 0 && *landing == ctx.rules.viaLanding[z]) continue;
    const Dbu half = (width > 0 ? width : ctx.tracks.layers[z].wireWidth) / 2;
    // `fixed`: a pin, obstruction or special net, which pin access already judged at the net's
    // own access points and the landings above them.
    auto judge = [&](const Rect& r, int32_t other, int64_t cost, bool fixed) {
      const Dbu minSpace = std::max(space, ctx.netRules.spacing(other, z));
      const MetalReach reach = metalReach(ctx.rules, z, r, half, minSpace, landing);
      forMetalReach(g, reach, z, [&](int32_t n, bool via) {
        if (fixed && (g.accessNet(n) == net || g.reservedNet(n) == net)) return;
        addCost((via ? out.via : out.wire)[n], cost);
      });
    };
    ctx.fixedIndex.query(win, [&](int32_t id) {
      const DrcShape& s = ctx.fixedShapes[id];
      if (s.net != net && routingIndex(s.layer) == z) judge(s.rect, s.net, task.costs.fixedPenalty, true);
    });
    for (const auto& [rect, other] : routedMetal[z]) {
      if (other != net && rect.overlaps(win)) judge(rect, other, task.costs.usePenalty, false);
    }
  }
  return true;
}

}  // namespace xroute
