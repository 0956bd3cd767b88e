#include "loop/incremental_check.hpp"

#include <algorithm>
#include <tuple>

#include "geom/union_find.hpp"
#include "region/region_marks.hpp"

namespace xroute {

namespace {

auto shapeKey(const NetShape& s) { return std::make_tuple(*s.layer, s.rect.xlo, s.rect.ylo, s.rect.xhi, s.rect.yhi); }
bool shapeLess(const NetShape& a, const NetShape& b) { return shapeKey(a) < shapeKey(b); }

// The conductors of one net's rects on one layer, as the checker joins them (sharesSegment):
// a root per rect.
std::vector<int32_t> conductorsOf(const std::vector<Rect>& rects) {
  std::vector<int32_t> order(rects.size());
  for (size_t i = 0; i < rects.size(); ++i) order[i] = static_cast<int32_t>(i);
  UnionFind uf(rects.size());
  std::sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return rects[a].xlo < rects[b].xlo; });
  for (size_t i = 0; i < order.size(); ++i)
    for (size_t j = i + 1; j < order.size() && rects[order[j]].xlo <= rects[order[i]].xhi; ++j)
      if (sharesSegment(rects[order[i]], rects[order[j]])) uf.unite(order[i], order[j]);
  std::vector<int32_t> root(rects.size());
  for (size_t i = 0; i < rects.size(); ++i) root[i] = uf.find(static_cast<int32_t>(i));
  return root;
}

}  // namespace

IncrementalCheck::IncrementalCheck(const RouteContext& ctx, DrcOptions options)
    : ctx_(ctx), options_(std::move(options)), kept_(ctx.design.nets.size(), 0) {
  area_ = ctx_.design.dieArea;
  for (const DrcShape& s : ctx_.fixedShapes) area_.expandToInclude(s.rect);
  const int32_t nets = static_cast<int32_t>(ctx_.design.nets.size());
  netFixedStart_.assign(nets + 1, 0);
  for (const DrcShape& s : ctx_.fixedShapes)
    if (s.net >= 0 && s.net < nets) ++netFixedStart_[s.net + 1];
  for (int32_t n = 0; n < nets; ++n) netFixedStart_[n + 1] += netFixedStart_[n];
  netFixed_.resize(netFixedStart_[nets]);
  std::vector<int32_t> fill(netFixedStart_.begin(), netFixedStart_.end() - 1);
  for (size_t i = 0; i < ctx_.fixedShapes.size(); ++i) {
    const int32_t n = ctx_.fixedShapes[i].net;
    if (n >= 0 && n < nets) netFixed_[fill[n]++] = static_cast<int32_t>(i);
  }
}

void IncrementalCheck::forget() {
  for (int32_t n : keptNets_) kept_[n] = 0;
  keptNets_.clear();
  old_.clear();
}

std::vector<Marker> IncrementalCheck::full() {
  forget();
  std::vector<DrcShape> shapes = collectDesignShapes(ctx_.tech, ctx_.design);
  lastShapes_ = static_cast<int64_t>(shapes.size());
  unmerged_ = checkShapesUnmerged(ctx_.tech, std::move(shapes), options_);
  return finishMarkers(unmerged_, options_);
}

void IncrementalCheck::remember(int32_t net) {
  if (net < 0 || size_t(net) >= kept_.size() || kept_[net]) return;
  kept_[net] = 1;
  keptNets_.push_back(net);
  old_.emplace_back();
  netRoutingShapes(ctx_.tech, ctx_.design, ctx_.design.nets[net].routing, old_.back());
}

// For each remembered net whose shapes changed, on each layer where they changed: the net on that
// layer, and the bounding box of every conductor with a changed rect (before and after together,
// pins included: no smaller than the conductor before or after) widened by the layer's reach. The
// whole conductor, not only the changed rects: joined or split far from a marker, it can change the
// marker (an end-of-line rule's "other metal" is another conductor).
void IncrementalCheck::changeZone(CheckZone& zone) {
  std::vector<NetShape> now;
  std::vector<Rect> rects;
  std::vector<uint8_t> changed;
  std::vector<std::pair<NetShape, uint8_t>> all;
  for (size_t k = 0; k < keptNets_.size(); ++k) {
    const int32_t n = keptNets_[k];
    std::vector<NetShape>& before = old_[k];
    now.clear();
    netRoutingShapes(ctx_.tech, ctx_.design, ctx_.design.nets[n].routing, now);
    std::sort(before.begin(), before.end(), shapeLess);
    std::sort(now.begin(), now.end(), shapeLess);
    // Both lists in layer order, each shape flagged when it is in one list and not the other.
    all.clear();
    size_t i = 0, j = 0;
    while (i < before.size() || j < now.size()) {
      if (j == now.size() || (i < before.size() && shapeLess(before[i], now[j]))) {
        all.push_back({before[i++], 1});
      } else if (i == before.size() || shapeLess(now[j], before[i])) {
        all.push_back({now[j++], 1});
      } else {
        all.push_back({before[i++], 0});
        ++j;
      }
    }
    for (size_t a = 0; a < all.size();) {
      const LayerId layer = all[a].first.layer;
      size_t b = a;
      rects.clear();
      changed.clear();
      for (; b < all.size() && all[b].first.layer == layer; ++b) {
        rects.push_back(all[b].first.rect);
        changed.push_back(all[b].second);
      }
      a = b;
      if (!layer.valid() || std::none_of(changed.begin(), changed.end(), [](uint8_t c) { return c != 0; })) continue;
      zone.addNet(n, layer);
      for (int32_t p = netFixedStart_[n]; p < netFixedStart_[n + 1]; ++p) {
        const DrcShape& s = ctx_.fixedShapes[netFixed_[p]];
        if (s.layer == layer) rects.push_back(s.rect), changed.push_back(0);
      }
      const std::vector<int32_t> root = conductorsOf(rects);
      std::vector<std::pair<int32_t, Rect>> boxes;  // (root, rect) of each rect of a conductor with a change
      std::vector<int32_t> hit;
      for (size_t r = 0; r < rects.size(); ++r)
        if (changed[r]) hit.push_back(root[r]);
      std::sort(hit.begin(), hit.end());
      for (size_t r = 0; r < rects.size(); ++r)
        if (std::binary_search(hit.begin(), hit.end(), root[r])) boxes.push_back({root[r], rects[r]});
      std::sort(boxes.begin(), boxes.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      for (size_t q = 0; q < boxes.size();) {
        Rect box = boxes[q].second;
        size_t e = q + 1;
        for (; e < boxes.size() && boxes[e].first == boxes[q].first; ++e) box.expandToInclude(boxes[e].second);
        zone.add(layer, grownBox(box, zone.reach(layer)));
        q = e;
      }
    }
  }
}

// The shapes the zone's markers depend on, on each layer with a zone: every shape within twice
// the reach of a zone cell, with the whole conductor it belongs to (routing and pins), and on a
// layer where a net changed, all of that net's metal; the fixed shapes there and under that
// routing, each linked to its conductor of fixed shapes (a special net's rail that leaves the zone
// stays one conductor).
std::vector<DrcShape> IncrementalCheck::zoneShapes(const CheckZone& zone, std::vector<int32_t>& links) const {
  const Tech& tech = ctx_.tech;
  const int32_t nets = static_cast<int32_t>(ctx_.design.nets.size());
  std::vector<uint8_t> fixedIn(ctx_.fixedShapes.size(), 0), layerIn(tech.layers.size(), 0);
  std::vector<int32_t> candidates, fixedList;
  auto near = [&](LayerId layer, const Rect& r) { return zone.near(layer, r, 2 * zone.reach(layer)); };
  auto takeFixed = [&](int32_t j) {
    if (!fixedIn[j]) fixedIn[j] = 1, fixedList.push_back(j);
  };
  // Candidates: the nets listed in the GCells around the zone, those with pins there, the changed ones.
  for (size_t l = 0; l < tech.layers.size(); ++l) {
    const LayerId layer(static_cast<int32_t>(l));
    if (zone.rects(layer).empty()) continue;
    layerIn[l] = 1;
    for (const Rect& z : zone.rects(layer)) {
      const Rect w = grownBox(z, 2 * zone.reach(layer));
      for (int32_t n : ctx_.netsNear(w)) candidates.push_back(n);
      ctx_.fixedIndex.query(w, [&](int32_t j) {
        const DrcShape& s = ctx_.fixedShapes[j];
        if (s.layer != layer) return;
        takeFixed(j);
        if (s.net >= 0 && s.net < nets) candidates.push_back(s.net);
      });
    }
  }
  for (int32_t n : zone.nets()) candidates.push_back(n);
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());

  std::vector<DrcShape> shapes;
  std::vector<NetShape> routing;
  struct Item {
    LayerId layer;
    Rect rect;
    int32_t fixed;  // index into ctx_.fixedShapes (a pin), or -1 (routing)
    bool taper = false;
  };
  std::vector<Item> items;
  std::vector<Rect> rects;
  std::vector<int32_t> keep;
  for (int32_t n : candidates) {
    routing.clear();
    netRoutingShapes(tech, ctx_.design, ctx_.design.nets[n].routing, routing, ctx_.design.nets[n].ndr);
    items.clear();
    for (const NetShape& s : routing)
      if (s.layer.valid() && layerIn[*s.layer]) items.push_back({s.layer, s.rect, -1, s.taper});
    for (int32_t p = netFixedStart_[n]; p < netFixedStart_[n + 1]; ++p) {
      const DrcShape& s = ctx_.fixedShapes[netFixed_[p]];
      if (s.layer.valid() && layerIn[*s.layer]) items.push_back({s.layer, s.rect, netFixed_[p]});
    }
    std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return *a.layer < *b.layer; });
    for (size_t a = 0; a < items.size();) {
      const LayerId layer = items[a].layer;
      size_t b = a;
      while (b < items.size() && items[b].layer == layer) ++b;
      // On a layer where the net changed, all of it; elsewhere the conductors with metal near the zone.
      const bool whole = zone.judgesNet(n, layer);
      keep.assign(b - a, whole ? 1 : 0);
      if (!whole && std::any_of(items.begin() + a, items.begin() + b, [&](const Item& it) { return near(layer, it.rect); })) {
        rects.clear();
        for (size_t k = a; k < b; ++k) rects.push_back(items[k].rect);
        const std::vector<int32_t> root = conductorsOf(rects);
        std::vector<int32_t> nearRoots;
        for (size_t k = a; k < b; ++k)
          if (near(layer, items[k].rect)) nearRoots.push_back(root[k - a]);
        std::sort(nearRoots.begin(), nearRoots.end());
        for (size_t k = a; k < b; ++k) keep[k - a] = std::binary_search(nearRoots.begin(), nearRoots.end(), root[k - a]);
      }
      for (size_t k = a; k < b; ++k) {
        if (!keep[k - a]) continue;
        const Item& it = items[k];
        if (it.fixed >= 0) {
          takeFixed(it.fixed);
          continue;
        }
        shapes.push_back({layer, it.rect, n, ShapeOrigin::Wire, it.taper});
        // A fixed conductor's shapes under the routing, for the rules that ask whether a wire touches it.
        ctx_.fixedIndex.query(it.rect, [&](int32_t j) {
          if (ctx_.fixedShapes[j].layer == layer) takeFixed(j);
        });
      }
      a = b;
    }
  }
  links.assign(shapes.size(), -1);
  std::sort(fixedList.begin(), fixedList.end());
  for (int32_t j : fixedList) {
    shapes.push_back(ctx_.fixedShapes[j]);
    links.push_back(fixedConductor_[j]);
  }
  return shapes;
}

std::vector<Marker> IncrementalCheck::update(double maxShare) {
  CheckZone zone(ctx_.tech, options_, ctx_.design.nets.size(), area_);
  changeZone(zone);
  // When many nets changed, gathering the shapes near them costs more than a whole check.
  if (double(zone.nets().size()) > maxShare * double(ctx_.design.nets.size())) return full();
  forget();
  lastShapes_ = 0;
  if (!zone.empty()) {
    if (fixedConductor_.size() != ctx_.fixedShapes.size()) fixedConductor_ = conductorIds(ctx_.tech, ctx_.fixedShapes);
    std::vector<int32_t> links;
    std::vector<DrcShape> shapes = zoneShapes(zone, links);
    lastShapes_ = static_cast<int64_t>(shapes.size());
    std::vector<Marker> fresh = checkShapesUnmerged(ctx_.tech, std::move(shapes), options_, &zone, links);
    std::erase_if(unmerged_, [&](const Marker& m) { return zone.judges(m); });
    unmerged_.insert(unmerged_.end(), fresh.begin(), fresh.end());
  }
  return finishMarkers(unmerged_, options_);
}

}  // namespace xroute
