#include "region/patch_score.hpp"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "drc/pair_rules.hpp"

namespace xroute {

namespace {

constexpr int64_t kPatchConflict = 1000;  // a minimum-area patch score meaning "would break a spacing rule"
constexpr int64_t kBlocksAccess = 100;     // per other net's access via whose landing the patch would crowd

// True when another rect of the same net continues the edge of metal[i]
// that faces `r` (the merged edge is longer than the rect's side there), so
// that edge is no line end.
bool edgeContinues(const std::vector<std::pair<Rect, int32_t>>& metal, size_t i, const Rect& r) {
  const auto& [o, net] = metal[i];
  for (size_t j = 0; j < metal.size(); ++j) {
    const Rect& q = metal[j].first;
    if (j == i || metal[j].second != net || !q.overlaps(o)) continue;
    const bool sideways = q.xlo < o.xlo || q.xhi > o.xhi, upways = q.ylo < o.ylo || q.yhi > o.yhi;
    if (r.ylo >= o.yhi && q.yhi == o.yhi && sideways) return true;
    if (r.yhi <= o.ylo && q.ylo == o.ylo && sideways) return true;
    if (r.xlo >= o.xhi && q.xhi == o.xhi && upways) return true;
    if (r.xhi <= o.xlo && q.xlo == o.xlo && upways) return true;
  }
  return false;
}

// Whether `r` (of `net`, on layer z) and another net's metal `o` break the spacing table, the
// end-of-line spacing where a line end of either faces the other (`lineEnd`: o's facing edge may
// be one) or the NONDEFAULTRULE spacing of either net.
bool breaksSpacing(const RouteContext& ctx, int z, const Rect& r, int32_t net, const Rect& o, int32_t other,
                   bool lineEnd) {
  const Layer& layer = *ctx.rules.layers[z];
  const Dbu rule = std::max(ctx.netRules.spacing(net, z), ctx.netRules.spacing(other, z));
  return drc::rectGap(o, r) < std::max(drc::metalNeed(layer, r, o, true, lineEnd), rule);
}

// The least spacing any other metal keeps from `net`'s metal on layer z: the layer's minimum, its
// end-of-line spacing, the net's NONDEFAULTRULE spacing.
Dbu baseSpacing(const RouteContext& ctx, int32_t net, int z) {
  return std::max({ctx.rules.layers[z]->minSpacing(), ctx.rules.eolSpace[z], ctx.netRules.spacing(net, z)});
}

// How far from r another net's metal can still break a rule with it.
Dbu ruleReach(const RouteContext& ctx, int32_t net, int z, const Rect& r) {
  const Layer& layer = *ctx.rules.layers[z];
  return std::max({baseSpacing(ctx, net, z), ctx.netRules.maxSpacing(z),
                   requiredSpacing(layer, std::numeric_limits<Dbu>::max() / 4, r.minSide(),
                                   std::numeric_limits<Dbu>::max() / 4)});
}

}  // namespace

bool breaksRoutedMetal(const RouteContext& ctx, const RoutedMetal& routedMetal, int32_t net, int z, const Rect& r) {
  const Dbu reach = ruleReach(ctx, net, z, r);
  const Rect far{r.xlo - reach, r.ylo - reach, r.xhi + reach, r.yhi + reach};
  const auto& metal = routedMetal[z];
  for (size_t i = 0; i < metal.size(); ++i) {
    if (metal[i].second == net || !metal[i].first.overlaps(far)) continue;
    if (breaksSpacing(ctx, z, r, net, metal[i].first, metal[i].second, !edgeContinues(metal, i, r))) return true;
  }
  return false;
}

// Fixed shapes and routed metal are judged by the spacing table with the run
// length (a patch runs along them, so a wide one, a power rail, may need its
// wide-metal row), by the end-of-line spacing where a line end of either
// faces the other, and by the NONDEFAULTRULE spacing of either net.
int64_t patchScore(const RouteContext& ctx, const RegionGrid& g, const RoutedMetal& routedMetal, int32_t net, int z,
                   const Rect& r) {
  const Layer& layer = *ctx.rules.layers[z];
  const Dbu s = baseSpacing(ctx, net, z);
  const Dbu reach = ruleReach(ctx, net, z, r);
  const Rect grown{r.xlo - s, r.ylo - s, r.xhi + s, r.yhi + s};
  const Rect far{r.xlo - reach, r.ylo - reach, r.xhi + reach, r.yhi + reach};
  int64_t bad = 0;
  // `lineEnd`: whether o's edge facing the patch may be a line end.
  auto judge = [&](const Rect& o, int32_t other, bool lineEnd) {
    if (breaksSpacing(ctx, z, r, net, o, other, lineEnd)) bad += kPatchConflict;
    else if (o.overlaps(grown)) bad += 10;
  };
  ctx.fixedIndex.query(far, [&](int32_t id) {
    const DrcShape& sh = ctx.fixedShapes[id];
    if (sh.net != net && ctx.tech.layer(sh.layer).routingIndex == z) judge(sh.rect, sh.net, true);
  });
  const auto& metal = routedMetal[z];
  for (size_t i = 0; i < metal.size(); ++i) {
    if (metal[i].second != net && metal[i].first.overlaps(far)) {
      judge(metal[i].first, metal[i].second, !edgeContinues(metal, i, r));
    }
  }
  // Another net's pin access via lands above its access point (the grid's
  // reserved nodes): a patch breaking the rules with that landing metal takes
  // the place the pin needs, and that net, routed later, has to break them.
  const Rect& m = ctx.rules.viaLanding[z];
  const Rect landings{r.xlo - s - m.xhi, r.ylo - s - m.yhi, r.xhi + s - m.xlo, r.yhi + s - m.ylo};
  int64_t crowded = 0;
  int x0, x1, y0, y1;
  g.xRangeOpen(landings.xlo, landings.xhi, x0, x1);
  g.yRangeOpen(landings.ylo, landings.yhi, y0, y1);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const int32_t v = g.index(x, y, z);
      const int32_t owner = g.reservedNet(v);
      if (owner == kOwnerNone || owner == net) continue;
      const Rect landing = m.translated(g.point(v));
      if (drc::rectGap(landing, r) < drc::metalNeed(layer, r, landing)) crowded += kBlocksAccess;
    }
  bad += std::min(crowded, kPatchConflict / 2);  // never a conflict: a patch still beats a MinArea marker
  g.xRangeOpen(grown.xlo, grown.xhi, x0, x1);
  g.yRangeOpen(grown.ylo, grown.yhi, y0, y1);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const int32_t v = g.index(x, y, z);
      if (g.accessNet(v) >= 0 && g.accessNet(v) != net) bad += 5;  // keep clear of others' pin access
    }
  return bad;
}

}  // namespace xroute
