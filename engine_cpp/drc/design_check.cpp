// checkDesign: the whole design at once, or band by band; zoneShapes: what one zone depends on.
#include "drc/design_check.hpp"

#include <algorithm>
#include <optional>
#include <utility>

#include "drc/layer_shapes.hpp"
#include "geom/union_find.hpp"

namespace xroute {

void shapesByNet(const std::vector<DrcShape>& shapes, size_t nets, std::vector<int32_t>& start,
                 std::vector<int32_t>& byNet) {
  const int32_t n = static_cast<int32_t>(nets);
  start.assign(nets + 1, 0);
  for (const DrcShape& s : shapes)
    if (s.net >= 0 && s.net < n) ++start[s.net + 1];
  for (int32_t i = 0; i < n; ++i) start[i + 1] += start[i];
  byNet.resize(start[nets]);
  std::vector<int32_t> fill(start.begin(), start.end() - 1);
  for (size_t i = 0; i < shapes.size(); ++i) {
    const int32_t net = shapes[i].net;
    if (net >= 0 && net < n) byNet[fill[net]++] = static_cast<int32_t>(i);
  }
}

FixedShapeSet::FixedShapeSet(std::vector<DrcShape> shapes, std::vector<int32_t> conductor, size_t nets)
    : shapes_(std::move(shapes)), conductor_(std::move(conductor)) {
  std::vector<Rect> rects;
  rects.reserve(shapes_.size());
  for (const DrcShape& s : shapes_) rects.push_back(s.rect);
  index_ = BoxIndex(std::move(rects));
  shapesByNet(shapes_, nets, netStart_, byNet_);
}

std::vector<int32_t> sameNetConductors(const std::vector<Rect>& rects) {
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

std::vector<int32_t> fixedConductorIds(const Tech& tech, const std::vector<DrcShape>& shapes) {
  std::vector<int32_t> ids(shapes.size(), -1);
  // The shapes that may join others (a net, positive area, a checked layer), by layer and net.
  std::vector<int32_t> order;
  for (size_t i = 0; i < shapes.size(); ++i) {
    const DrcShape& s = shapes[i];
    if (!s.layer.valid() || size_t(*s.layer) >= tech.layers.size()) continue;
    const LayerType t = tech.layers[*s.layer].type;
    if (t != LayerType::Routing && t != LayerType::Cut) continue;
    if (s.rect.xhi <= s.rect.xlo || s.rect.yhi <= s.rect.ylo) continue;
    ids[i] = static_cast<int32_t>(i);  // an obstruction stays alone
    if (s.net >= 0) order.push_back(static_cast<int32_t>(i));
  }
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {
    return std::make_pair(*shapes[a].layer, shapes[a].net) < std::make_pair(*shapes[b].layer, shapes[b].net);
  });
  drc::LayerShapes group;
  UnionFind uf;
  for (size_t a = 0; a < order.size();) {
    size_t b = a + 1;
    while (b < order.size() && shapes[order[b]].layer == shapes[order[a]].layer && shapes[order[b]].net == shapes[order[a]].net) ++b;
    uf.reset(b - a);
    if (b - a <= 16) {  // a pin's few rects: every pair
      for (size_t i = a; i < b; ++i)
        for (size_t j = i + 1; j < b; ++j)
          if (sharesSegment(shapes[order[i]].rect, shapes[order[j]].rect))
            uf.unite(static_cast<int32_t>(i - a), static_cast<int32_t>(j - a));
    } else {
      group.rects.clear();
      group.nets.assign(b - a, shapes[order[a]].net);
      for (size_t k = a; k < b; ++k) group.rects.push_back(shapes[order[k]].rect);
      group.index = drc::ShapeIndex(group.rects, group.nets);
      drc::joinSameNet(group, uf);
    }
    // The root of a set is its smallest member: the conductor's first shape in `order`.
    for (size_t k = a; k < b; ++k) ids[order[k]] = order[a + uf.find(static_cast<int32_t>(k - a))];
    a = b;
  }
  return ids;
}

std::vector<DrcShape> zoneShapes(const Tech& tech, const Design& design, const FixedShapeView& fixed,
                                 const CheckZone& zone, std::vector<int32_t> candidates, std::vector<int32_t>& links) {
  const std::vector<DrcShape>& fixedShapes = *fixed.shapes;
  const std::vector<int32_t>& netStart = *fixed.netStart;
  const std::vector<int32_t>& byNet = *fixed.byNet;
  const int32_t nets = static_cast<int32_t>(design.nets.size());
  std::vector<uint8_t> fixedIn(fixedShapes.size(), 0), layerIn(tech.layers.size(), 0), fixedOn(tech.layers.size(), 0);
  for (const DrcShape& s : fixedShapes)
    if (s.layer.valid() && size_t(*s.layer) < fixedOn.size()) fixedOn[*s.layer] = 1;
  std::vector<int32_t> fixedList;
  auto near = [&](LayerId layer, const Rect& r) { return zone.near(layer, r, 2 * zone.reach(layer)); };
  auto takeFixed = [&](int32_t j) {
    if (!fixedIn[j]) fixedIn[j] = 1, fixedList.push_back(j);
  };
  // Candidates besides the caller's: the nets with pins around the zone, the changed ones.
  for (size_t l = 0; l < tech.layers.size(); ++l) {
    const LayerId layer(static_cast<int32_t>(l));
    if (zone.rects(layer).empty()) continue;
    layerIn[l] = 1;
    if (!fixedOn[l]) continue;
    for (const Rect& z : zone.rects(layer)) {
      fixed.index->query(drc::expanded(z, 2 * zone.reach(layer)), [&](int32_t j) {
        const DrcShape& s = fixedShapes[j];
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
  struct Item {
    LayerId layer;
    Rect rect;
    int32_t fixed;  // index into the fixed shapes (a pin), or -1 (routing)
    bool taper = false;
  };
  std::vector<Item> items;
  std::vector<Rect> rects;
  std::vector<uint8_t> keep, isNear;
  for (int32_t n : candidates) {
    if (n < 0 || n >= nets) continue;
    items.clear();
    forEachRoutingShape(tech, design, design.nets[n].routing, design.nets[n].ndr,
                        [&](LayerId layer, const Rect& rect, bool, bool taper) {
                          if (layer.valid() && layerIn[*layer]) items.push_back({layer, rect, -1, taper});
                        });
    for (int32_t p = netStart[n]; p < netStart[n + 1]; ++p) {
      const DrcShape& s = fixedShapes[byNet[p]];
      if (s.layer.valid() && layerIn[*s.layer]) items.push_back({s.layer, s.rect, byNet[p]});
    }
    std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return *a.layer < *b.layer; });
    for (size_t a = 0; a < items.size();) {
      const LayerId layer = items[a].layer;
      size_t b = a;
      while (b < items.size() && items[b].layer == layer) ++b;
      // On a layer where the net changed, all of it; elsewhere the conductors with metal near the zone.
      const bool whole = zone.judgesNet(n, layer);
      keep.assign(b - a, whole ? 1 : 0);
      if (!whole) {
        isNear.resize(b - a);
        size_t nearCount = 0;
        for (size_t k = a; k < b; ++k) nearCount += isNear[k - a] = near(layer, items[k].rect);
        if (nearCount == b - a) {
          keep.assign(b - a, 1);
        } else if (nearCount > 0) {
          rects.clear();
          for (size_t k = a; k < b; ++k) rects.push_back(items[k].rect);
          const std::vector<int32_t> root = sameNetConductors(rects);
          std::vector<int32_t> nearRoots;
          for (size_t k = a; k < b; ++k)
            if (isNear[k - a]) nearRoots.push_back(root[k - a]);
          std::sort(nearRoots.begin(), nearRoots.end());
          for (size_t k = a; k < b; ++k) keep[k - a] = std::binary_search(nearRoots.begin(), nearRoots.end(), root[k - a]);
        }
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
        if (fixedOn[*layer])
          fixed.index->query(it.rect, [&](int32_t j) {
            if (fixedShapes[j].layer == layer) takeFixed(j);
          });
      }
      a = b;
    }
  }
  if (fixed.conductor->size() != fixedShapes.size()) *fixed.conductor = fixedConductorIds(tech, fixedShapes);
  links.assign(shapes.size(), -1);
  std::sort(fixedList.begin(), fixedList.end());
  for (int32_t j : fixedList) {
    shapes.push_back(fixedShapes[j]);
    links.push_back((*fixed.conductor)[j]);
  }
  return shapes;
}

namespace {

// The routing of every regular net, summed up for the band plan: its bounding box over every
// layer and its shape count.
struct NetExtent {
  Rect box;
  int64_t shapes = 0;
};

std::vector<NetExtent> netExtents(const Tech& tech, const Design& design) {
  std::vector<NetExtent> out(design.nets.size());
  for (size_t n = 0; n < design.nets.size(); ++n) {
    NetExtent& e = out[n];
    forEachRoutingShape(tech, design, design.nets[n].routing, design.nets[n].ndr,
                        [&](LayerId layer, const Rect& rect, bool, bool) {
                          if (!layer.valid()) return;
                          if (e.shapes++ == 0) e.box = rect;
                          else e.box.expandToInclude(rect);
                        });
  }
  return out;
}

// The y coordinates that cut `area` into `bands` bands of about equal shape counts (a net's shapes
// counted at its box's centre, a fixed shape at its own): bands + 1 values from area.ylo to
// area.yhi, ascending, without repeats (fewer bands where the shapes crowd one place).
std::vector<Dbu> bandCuts(const Rect& area, int64_t bands, const std::vector<NetExtent>& extents,
                          const std::vector<DrcShape>& fixedShapes, int64_t total) {
  constexpr int kBins = 4096;
  const int64_t height = std::max<int64_t>(1, int64_t(area.yhi) - area.ylo);
  std::vector<int64_t> bins(kBins, 0);
  auto bin = [&](const Rect& r) {
    const int64_t mid = (int64_t(r.ylo) + r.yhi) / 2 - area.ylo;
    return static_cast<size_t>(std::clamp<int64_t>(mid * kBins / (height + 1), 0, kBins - 1));
  };
  for (const NetExtent& e : extents)
    if (e.shapes > 0) bins[bin(e.box)] += e.shapes;
  for (const DrcShape& s : fixedShapes) ++bins[bin(s.rect)];
  std::vector<Dbu> cuts{area.ylo};
  int64_t sum = 0;
  int64_t next = 1;
  for (int b = 0; b < kBins && next < bands; ++b) {
    sum += bins[b];
    if (sum * bands < next * total) continue;
    // The band ends with bin b: the next starts at the bin's upper edge.
    const Dbu y = static_cast<Dbu>(area.ylo + (int64_t(b) + 1) * (height + 1) / kBins);
    if (y > cuts.back() && y < area.yhi) cuts.push_back(y);
    while (next < bands && sum * bands >= next * total) ++next;
  }
  cuts.push_back(area.yhi);
  return cuts;
}

}  // namespace

std::vector<Marker> checkDesignUnmerged(const Tech& tech, const Design& design, const DrcOptions& options,
                                        const FixedShapeView* fixed, std::vector<std::string>* netNames,
                                        DesignCheckStats* stats) {
  DesignCheckStats local;
  DesignCheckStats& st = stats != nullptr ? *stats : local;
  st = DesignCheckStats{};
  auto whole = [&]() {
    std::vector<DrcShape> shapes = collectDesignShapes(tech, design, netNames);
    st.shapes = static_cast<int64_t>(shapes.size());
    return checkShapesUnmerged(tech, std::move(shapes), options);
  };
  // Bands judge markers whose shapes are fixed only partly (a rail's MinArea), so not when fixed
  // pairs are reported; a window's check starts from the shapes near it already.
  if (options.bandShapes <= 0 || !options.skipFixedPairs || options.window) return whole();
  const std::vector<NetExtent> extents = netExtents(tech, design);
  int64_t routing = 0;
  for (const NetExtent& e : extents) routing += e.shapes;
  // The fixed shapes: the caller's, indexed, or the design's, each band's indexed in turn.
  std::vector<DrcShape> allFixed;
  std::vector<int32_t> allConductors;
  if (fixed != nullptr) {
    if (netNames != nullptr) collectFixedShapes(tech, design, netNames);  // for the names
  } else {
    if (routing + int64_t(design.nets.size()) <= options.bandShapes) return whole();  // not worth the fixed set
    allFixed = collectFixedShapes(tech, design, netNames);
  }
  const std::vector<DrcShape>& fixedShapes = fixed != nullptr ? *fixed->shapes : allFixed;
  const int64_t total = routing + static_cast<int64_t>(fixedShapes.size());
  const int64_t bands = (total + options.bandShapes - 1) / options.bandShapes;
  if (bands <= 1) return whole();

  // The area holds every shape, so that each marker's box touches a cell of some band.
  Rect area = design.dieArea;
  for (const DrcShape& s : fixedShapes) area.expandToInclude(s.rect);
  for (const NetExtent& e : extents)
    if (e.shapes > 0) area.expandToInclude(e.box);
  const std::vector<Dbu> cuts = bandCuts(area, bands, extents, fixedShapes, total);
  if (cuts.size() <= 2) return whole();  // the shapes crowd one row of bins
  st.cuts = cuts;
  std::vector<int32_t> pinStart, pins;  // the regular nets' fixed shapes in allFixed
  if (fixed == nullptr) {
    allConductors = fixedConductorIds(tech, allFixed);
    shapesByNet(allFixed, design.nets.size(), pinStart, pins);
  }

  std::vector<Marker> markers;
  std::vector<int32_t> links, candidates;
  for (size_t b = 0; b + 1 < cuts.size(); ++b) {
    CheckZone zone(tech, options, design.nets.size(), area);
    zone.judgeMinAreaByBox();
    const Rect band{area.xlo, cuts[b], area.xhi, cuts[b + 1]};
    Dbu ylo = band.ylo, yhi = band.yhi;
    for (size_t l = 0; l < tech.layers.size(); ++l) {
      const LayerType t = tech.layers[l].type;
      if (t != LayerType::Routing && t != LayerType::Cut) continue;
      const LayerId layer(static_cast<int32_t>(l));
      zone.add(layer, band);
      for (const Rect& z : zone.rects(layer)) {
        ylo = std::min<Dbu>(ylo, z.ylo - 2 * zone.reach(layer));
        yhi = std::max<Dbu>(yhi, z.yhi + 2 * zone.reach(layer));
      }
    }
    candidates.clear();
    Dbu wylo = ylo, wyhi = yhi;  // the rows of every shape the band may ask for
    for (size_t n = 0; n < extents.size(); ++n) {
      if (extents[n].shapes > 0 && extents[n].box.yhi >= ylo && extents[n].box.ylo <= yhi) {
        candidates.push_back(static_cast<int32_t>(n));
        wylo = std::min(wylo, extents[n].box.ylo);
        wyhi = std::max(wyhi, extents[n].box.yhi);
        if (fixed != nullptr) continue;
        for (int32_t p = pinStart[n]; p < pinStart[n + 1]; ++p) {
          wylo = std::min(wylo, allFixed[pins[p]].rect.ylo);
          wyhi = std::max(wyhi, allFixed[pins[p]].rect.yhi);
        }
      }
    }
    // The design's fixed shapes in those rows (the zone's, those under its nets' routing, those
    // nets' pins), indexed for this band only: one band's index at a time.
    std::optional<FixedShapeSet> local;
    FixedShapeView view;
    if (fixed != nullptr) {
      view = *fixed;
    } else {
      std::vector<DrcShape> in;
      std::vector<int32_t> conductor;
      for (size_t j = 0; j < allFixed.size(); ++j) {
        if (allFixed[j].rect.yhi >= wylo && allFixed[j].rect.ylo <= wyhi) {
          in.push_back(allFixed[j]);
          conductor.push_back(allConductors[j]);
        }
      }
      local.emplace(std::move(in), std::move(conductor), design.nets.size());
      view = local->view();
    }
    std::vector<DrcShape> shapes = zoneShapes(tech, design, view, zone, candidates, links);
    local.reset();
    st.shapes += static_cast<int64_t>(shapes.size());
    std::vector<Marker> found = checkShapesUnmerged(tech, std::move(shapes), options, &zone, links);
    markers.insert(markers.end(), found.begin(), found.end());
  }
  sortMarkers(markers);  // a marker that touches two bands was found by both
  return markers;
}

std::vector<Marker> checkDesign(const Tech& tech, const Design& design, const DrcOptions& options,
                                std::vector<std::string>* netNames, DesignCheckStats* stats) {
  return finishMarkers(checkDesignUnmerged(tech, design, options, nullptr, netNames, stats), options);
}

}  // namespace xroute
