#include "loop/incremental_check.hpp"

#include <algorithm>
#include <tuple>

#include "region/region_marks.hpp"

namespace xroute {

namespace {

auto shapeKey(const NetShape& s) { return std::make_tuple(*s.layer, s.rect.xlo, s.rect.ylo, s.rect.xhi, s.rect.yhi); }
bool shapeLess(const NetShape& a, const NetShape& b) { return shapeKey(a) < shapeKey(b); }

}  // namespace

IncrementalCheck::IncrementalCheck(const RouteContext& ctx, DrcOptions options)
    : ctx_(ctx), options_(std::move(options)), kept_(ctx.design.nets.size(), 0) {
  area_ = ctx_.design.dieArea;
  for (const DrcShape& s : ctx_.fixedShapes) area_.expandToInclude(s.rect);
  shapesByNet(ctx_.fixedShapes, ctx_.design.nets.size(), netFixedStart_, netFixed_);
}

FixedShapeView IncrementalCheck::fixedView() {
  return FixedShapeView{&ctx_.fixedShapes, &ctx_.fixedIndex, &netFixedStart_, &netFixed_, &fixedConductor_};
}

void IncrementalCheck::forget() {
  for (int32_t n : keptNets_) kept_[n] = 0;
  keptNets_.clear();
  old_.clear();
}

std::vector<Marker> IncrementalCheck::full() {
  forget();
  const FixedShapeView fixed = fixedView();
  DesignCheckStats stats;
  unmerged_ = checkDesignUnmerged(ctx_.tech, ctx_.design, options_, &fixed, nullptr, &stats);
  lastShapes_ = stats.shapes;
  bandCuts_ = stats.cuts;
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
      const std::vector<int32_t> root = sameNetConductors(rects);
      std::vector<std::pair<int32_t, Rect>> boxes;  // (root, rect) of each rect of a conductor with a change
      std::vector<int32_t> hit;
      for (size_t r = 0; r < rects.size(); ++r)
        if (changed[r]) hit.push_back(root[r]);
      std::sort(hit.begin(), hit.end());
      for (size_t r = 0; r < rects.size(); ++r)
        if (std::binary_search(hit.begin(), hit.end(), root[r])) boxes.push_back({root[r], rects[r]});
      std::sort(boxes.begin(), boxes.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      if (!boxes.empty()) {
        const Rect& first = boxes.front().second;
        changed_.push_back({n, layer, static_cast<Dbu>((int64_t(first.ylo) + first.yhi) / 2)});
      }
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

std::vector<Marker> IncrementalCheck::checkZone(const CheckZone& zone) {
  // Candidates: the nets listed in the GCells around the zone (zoneShapes adds those with pins there).
  std::vector<int32_t> near;
  for (size_t l = 0; l < ctx_.tech.layers.size(); ++l) {
    const LayerId layer(static_cast<int32_t>(l));
    for (const Rect& z : zone.rects(layer))
      for (int32_t n : ctx_.netsNear(grownBox(z, 2 * zone.reach(layer)))) near.push_back(n);
  }
  std::vector<int32_t> links;
  std::vector<DrcShape> shapes = zoneShapes(ctx_.tech, ctx_.design, fixedView(), zone, std::move(near), links);
  lastShapes_ += static_cast<int64_t>(shapes.size());
  return checkShapesUnmerged(ctx_.tech, std::move(shapes), options_, &zone, links);
}

std::vector<Marker> IncrementalCheck::update(double maxShare) {
  CheckZone zone(ctx_.tech, options_, ctx_.design.nets.size(), area_);
  changed_.clear();
  changeZone(zone);
  // When many nets changed, gathering the shapes near them costs more than a whole check.
  if (double(zone.nets().size()) > maxShare * double(ctx_.design.nets.size())) return full();
  forget();
  lastShapes_ = 0;
  if (!zone.empty()) {
    std::vector<Marker> fresh;
    const size_t bands = bandCuts_.size() > 2 ? bandCuts_.size() - 1 : 1;
    if (bands > 1) {
      // The whole check ran in bands: so does the zone's, each changed net's MinArea markers judged
      // in one band, where a rect of one of its changed conductors lies. A band without a zone
      // cell is left out.
      for (size_t b = 0; b < bands; ++b) {
        CheckZone part = zone.rows(bandCuts_[b], bandCuts_[b + 1]);
        bool any = false;
        for (const ChangedNet& c : changed_) {
          const size_t at = std::upper_bound(bandCuts_.begin() + 1, bandCuts_.end() - 1, c.y) - (bandCuts_.begin() + 1);
          if (at == b) part.addNet(c.net, c.layer), any = true;
        }
        for (size_t l = 0; l < ctx_.tech.layers.size() && !any; ++l) any = !part.rects(LayerId(static_cast<int32_t>(l))).empty();
        if (!any) continue;
        std::vector<Marker> found = checkZone(part);
        fresh.insert(fresh.end(), found.begin(), found.end());
      }
      sortMarkers(fresh);  // a marker that touches two bands was found by both
    } else {
      fresh = checkZone(zone);
    }
    std::erase_if(unmerged_, [&](const Marker& m) { return zone.judges(m); });
    unmerged_.insert(unmerged_.end(), fresh.begin(), fresh.end());
  }
  return finishMarkers(unmerged_, options_);
}

}  // namespace xroute
