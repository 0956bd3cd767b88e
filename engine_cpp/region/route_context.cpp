#include "region/route_context.hpp"

#include <algorithm>

#include "verify/scoring.hpp"

namespace xroute {

void netRoutingShapes(const Tech& tech, const Design& design, const NetRouting& routing, std::vector<NetShape>& out,
                      int ndr) {
  forEachRoutingShape(tech, design, routing, ndr,
                      [&](LayerId layer, const Rect& rect, bool, bool taper) { out.push_back({layer, rect, taper}); });
}

MazeCosts designCosts(const MazeCosts& costs, const RouteContext& ctx) {
  return soleLandingCosts(pitchCosts(guideCosts(costs, ctx.design.guidesBuiltIn), scorerPitch(ctx.tech)),
                          ctx.soleShare);
}

RouteContext::RouteContext(const Tech& t, Design& d, int threads, int accessPointsPerPin) : tech(t), design(d) {
  tracks = buildTracks(tech, design);
  vias = chooseVias(tech, tracks);
  rules = makeFootprintRules(tech, tracks, vias);
  PinAccessSettings pas;
  pas.threads = std::max(1, threads);
  pas.maxPointsPerPin = std::max(1, accessPointsPerPin);
  access = computePinAccess(tech, design, tracks, pas);
  soleShare = soleViaShare(access);
  gcells = makeGCellGrid(design, tracks);

  pinNet.assign(design.pinRefs.size(), -1);
  for (size_t n = 0; n < design.nets.size(); ++n) {
    for (int32_t r = design.netPinStart[n]; r < design.netPinStart[n + 1]; ++r) pinNet[r] = static_cast<int32_t>(n);
  }

  fixedShapes = collectFixedShapes(tech, design);
  std::vector<Rect> rects;
  rects.reserve(fixedShapes.size());
  for (const DrcShape& s : fixedShapes) rects.push_back(s.rect);
  fixedIndex = BoxIndex(std::move(rects));
  fixedCrossEnds.assign(fixedShapes.size(), 0);
  std::vector<Rect> others;
  for (size_t i = 0; i < fixedShapes.size(); ++i) {
    const DrcShape& s = fixedShapes[i];
    const int z = tech.layer(s.layer).routingIndex;
    if (z < 0 || z >= static_cast<int>(tracks.layers.size()) || !narrowAcross(rules, z, s.rect)) continue;
    others.clear();
    fixedIndex.query(s.rect, [&](int32_t j) {
      const DrcShape& o = fixedShapes[j];
      if (j != static_cast<int32_t>(i) && o.layer == s.layer && o.net == s.net && o.rect.overlaps(s.rect))
        others.push_back(o.rect);
    });
    fixedCrossEnds[i] = openCrossEnds(s.rect, rules.horizontal[z] != 0, others);
  }

  netRules = NetRules(tech, design, tracks, vias);
  Dbu maxPitch = 0;
  for (const LayerTracks& lt : tracks.layers) maxPitch = std::max(maxPitch, lt.pitch);
  halo = 2 * maxPitch;
  halo = std::max(halo, netRules.reach());  // a rule's wide wire and spacing reach further
  rebuildRoutedIndex();
}

DrcOptions RouteContext::drcOptions() const {
  DrcOptions o;
  o.skipFixedPairs = true;
  o.ndrSpacing = netRules.drcSpacing();
  return o;
}

int32_t RouteContext::gcellX(Dbu x) const {
  const auto& xs = gcells.xs;
  const int g = static_cast<int>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin()) - 1;
  return std::clamp(g, 0, gcells.nx() - 1);
}

int32_t RouteContext::gcellY(Dbu y) const {
  const auto& ys = gcells.ys;
  const int g = static_cast<int>(std::upper_bound(ys.begin(), ys.end(), y) - ys.begin()) - 1;
  return std::clamp(g, 0, gcells.ny() - 1);
}

namespace {

// The GCell buckets the net's routing touches, ascending.
std::vector<int32_t> routedBuckets(const RouteContext& ctx, int32_t net, std::vector<NetShape>& shapes) {
  std::vector<int32_t> out;
  const NetRouting& routing = ctx.design.nets[net].routing;
  if (routing.empty()) return out;
  const int nx = ctx.gcells.nx();
  shapes.clear();
  netRoutingShapes(ctx.tech, ctx.design, routing, shapes);
  for (const NetShape& s : shapes) {
    const int x0 = ctx.gcellX(s.rect.xlo), x1 = ctx.gcellX(s.rect.xhi);
    const int y0 = ctx.gcellY(s.rect.ylo), y1 = ctx.gcellY(s.rect.yhi);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) out.push_back(y * nx + x);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace

void RouteContext::rebuildRoutedIndex() {
  bucketNets.assign(static_cast<size_t>(gcells.nx()) * gcells.ny(), {});
  netBuckets.assign(design.nets.size(), {});
  std::vector<NetShape> shapes;
  for (size_t n = 0; n < design.nets.size(); ++n) {
    netBuckets[n] = routedBuckets(*this, static_cast<int32_t>(n), shapes);
    for (int32_t b : netBuckets[n]) bucketNets[b].push_back(static_cast<int32_t>(n));
  }
}

void RouteContext::updateRoutedIndex(const std::vector<int32_t>& nets) {
  std::vector<NetShape> shapes;
  for (int32_t n : nets) {
    for (int32_t b : netBuckets[n]) {
      std::vector<int32_t>& v = bucketNets[b];
      const auto it = std::lower_bound(v.begin(), v.end(), n);
      if (it != v.end() && *it == n) v.erase(it);
    }
    netBuckets[n] = routedBuckets(*this, n, shapes);
    for (int32_t b : netBuckets[n]) {
      std::vector<int32_t>& v = bucketNets[b];
      const auto it = std::lower_bound(v.begin(), v.end(), n);
      if (it == v.end() || *it != n) v.insert(it, n);
    }
  }
}

std::vector<int32_t> RouteContext::netsNear(const Rect& w) const {
  std::vector<int32_t> out;
  const int nx = gcells.nx();
  const int x0 = gcellX(w.xlo), x1 = gcellX(w.xhi), y0 = gcellY(w.ylo), y1 = gcellY(w.yhi);
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const auto& b = bucketNets[static_cast<size_t>(y) * nx + x];
      out.insert(out.end(), b.begin(), b.end());
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace xroute
