// checkShapes: groups the shapes by layer, builds each layer's index and
// connectivity, runs the rule families, then filters, merges and sorts.
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <tuple>

#include "drc/layer_shapes.hpp"
#include "geom/union_find.hpp"

namespace xroute {

namespace drc {

void addPairMarker(MarkerSink& out, const LayerShapes& ls, MarkerType type, const Rect& box, int32_t a, int32_t b) {
  int32_t n1 = ls.nets[a] < 0 ? -1 : ls.nets[a];
  int32_t n2 = ls.nets[b] < 0 ? -1 : ls.nets[b];
  if (n1 < 0 || (n2 >= 0 && n2 < n1)) std::swap(n1, n2);
  out.push_back({Marker{type, ls.layer, box, n1, n2}, ls.fixed[a] && ls.fixed[b]});
}

Dbu interactionRange(const Layer& l) {
  Dbu r = 0;
  for (Dbu s : l.prlTable.spacing) r = std::max(r, s);
  for (const SpacingRule& s : l.spacings) r = std::max(r, s.space);
  for (const EolRule& e : l.eolRules) r = std::max({r, e.space + e.within, e.parSpace + e.within, e.parWithin});
  for (const CutSpacingRule& c : l.cutSpacings) r = std::max({r, c.space, c.cutWithin});
  for (const CornerSpacingRule& c : l.cornerSpacings)
    for (Dbu s : c.spacings) r = std::max(r, s);
  return r;
}

namespace {

struct Entry {
  Rect rect;
  int32_t net;
  bool fixed;
  int32_t link = -1;  // CheckZone links: same value >= 0, one conductor
  bool taper = false;  // DrcShape::taper
};

// Builds one layer: the shapes (duplicates as one), index, seeds, components.
void buildLayer(LayerShapes& ls, std::vector<Entry>& entries, const DrcOptions& options, const CheckZone* zone) {
  auto key = [](const Entry& e) { return std::make_tuple(e.rect.xlo, e.rect.ylo, e.rect.xhi, e.rect.yhi, e.net); };
  std::sort(entries.begin(), entries.end(), [&](const Entry& a, const Entry& b) {
    return std::make_tuple(key(a), a.fixed) < std::make_tuple(key(b), b.fixed);
  });
  // Identical duplicates are one shape, fixed (or tapered) only if every copy is.
  std::vector<std::pair<int32_t, int32_t>> links;  // (link, shape)
  for (size_t i = 0; i < entries.size(); ++i) {
    if (!ls.rects.empty() && ls.rects.back() == entries[i].rect && ls.nets.back() == entries[i].net) {
      ls.fixed.back() = ls.fixed.back() && entries[i].fixed;
      ls.taper.back() = ls.taper.back() && entries[i].taper;
    } else {
      ls.rects.push_back(entries[i].rect);
      ls.nets.push_back(entries[i].net);
      ls.fixed.push_back(entries[i].fixed);
      ls.taper.push_back(entries[i].taper);
    }
    const int32_t shape = int32_t(ls.rects.size()) - 1;
    if (entries[i].link >= 0) links.push_back({entries[i].link, shape});
  }
  const size_t n = ls.rects.size();
  ls.index = ShapeIndex(ls.rects, ls.nets);

  ls.seed.assign(n, 1);
  if (options.window) {
    const Rect roi = expanded(*options.window, 2 * interactionRange(*ls.rules) + 1);
    for (size_t i = 0; i < n; ++i) ls.seed[i] = ls.rects[i].overlaps(roi);
  }
  if (zone != nullptr) {
    const Dbu reach = zone->reach(ls.layer);
    for (size_t i = 0; i < n; ++i)
      ls.seed[i] = ls.seed[i] && (zone->judgesNet(ls.nets[i], ls.layer) || zone->near(ls.layer, ls.rects[i], reach));
  }

  UnionFind uf(n);
  joinSameNet(ls, uf);
  std::sort(links.begin(), links.end());
  for (size_t k = 1; k < links.size(); ++k)
    if (links[k].first == links[k - 1].first) uf.unite(links[k - 1].second, links[k].second);
  // Components numbered by their smallest member.
  ls.comp.assign(n, -1);
  int32_t count = 0;
  std::vector<int32_t> rootComp(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const int32_t r = uf.find(int32_t(i));
    if (rootComp[r] < 0) rootComp[r] = count++;
    ls.comp[i] = rootComp[r];
  }
  ls.compStart.assign(count + 1, 0);
  for (size_t i = 0; i < n; ++i) ++ls.compStart[ls.comp[i] + 1];
  for (int32_t c = 0; c < count; ++c) ls.compStart[c + 1] += ls.compStart[c];
  ls.compMembers.resize(n);
  std::vector<int32_t> fill(ls.compStart.begin(), ls.compStart.end() - 1);
  for (size_t i = 0; i < n; ++i) ls.compMembers[fill[ls.comp[i]]++] = int32_t(i);
  ls.compFixed.assign(count, 1);
  ls.compSeed.assign(count, 0);
  for (size_t i = 0; i < n; ++i) {
    if (!ls.fixed[i]) ls.compFixed[ls.comp[i]] = 0;
    if (ls.seed[i]) ls.compSeed[ls.comp[i]] = 1;
  }
}

// Types whose markers come from pairs of rects, so that one contiguous
// violation between two conductors can be cut into several pieces. Cut
// spacing markers (one per pair of cuts) and min-area markers (one per
// conductor) are never merged.
bool mergeable(MarkerType t) {
  return t == MarkerType::Short || t == MarkerType::MetalSpacing || t == MarkerType::EndOfLine ||
         t == MarkerType::CutShort || t == MarkerType::CornerSpacing;
}

// Merges markers of a mergeable type with the same (type, layer, nets) whose
// boxes intersect (touching counts) into one marker with their bounding box.
std::vector<Marker> mergeTouching(std::vector<Marker> ms) {
  auto group = [](const Marker& m) { return std::make_tuple(m.type, *m.layer, m.net1, m.net2); };
  std::sort(ms.begin(), ms.end(), [&](const Marker& a, const Marker& b) {
    return std::make_tuple(group(a), a.box.xlo, a.box.ylo, a.box.xhi, a.box.yhi) <
           std::make_tuple(group(b), b.box.xlo, b.box.ylo, b.box.xhi, b.box.yhi);
  });
  UnionFind uf(ms.size());
  for (size_t i = 0; i < ms.size(); ++i) {
    for (size_t j = i + 1; j < ms.size() && group(ms[j]) == group(ms[i]) && ms[j].box.xlo <= ms[i].box.xhi; ++j) {
      if (mergeable(ms[i].type) && ms[i].box.overlaps(ms[j].box)) uf.unite(int32_t(i), int32_t(j));
    }
  }
  std::vector<Marker> out;
  std::vector<int32_t> slot(ms.size(), -1);
  for (size_t i = 0; i < ms.size(); ++i) {
    const int32_t r = uf.find(int32_t(i));
    if (slot[r] < 0) {
      slot[r] = int32_t(out.size());
      out.push_back(ms[i]);
    } else {
      out[slot[r]].box.expandToInclude(ms[i].box);
    }
  }
  return out;
}

}  // namespace
}  // namespace drc

namespace drc {
namespace {

// The input shapes by layer (routing and cut layers, positive area), with their links and indices.
std::vector<std::vector<Entry>> entriesByLayer(const Tech& tech, const std::vector<DrcShape>& shapes,
                                               const std::vector<int32_t>& links) {
  std::vector<std::vector<Entry>> byLayer(tech.layers.size());
  for (size_t i = 0; i < shapes.size(); ++i) {
    const DrcShape& s = shapes[i];
    if (!s.layer.valid() || size_t(*s.layer) >= tech.layers.size()) continue;
    const LayerType t = tech.layers[*s.layer].type;
    if (t != LayerType::Routing && t != LayerType::Cut) continue;
    if (s.rect.xhi <= s.rect.xlo || s.rect.yhi <= s.rect.ylo) continue;  // no area
    byLayer[*s.layer].push_back({s.rect, s.net < 0 ? -1 : s.net, isFixedOrigin(s.origin),
                                 links.empty() ? -1 : links[i], s.taper});
  }
  return byLayer;
}

// Runs job(l) for every layer l, by up to `threads` workers, the layers with the most entries first
// (so that no worker is left with a large one at the end). Rethrows the first error.
template <class Job>
void forEachLayer(const std::vector<std::vector<Entry>>& byLayer, int threads, Job&& job) {
  const int workers = std::clamp(threads, 1, static_cast<int>(std::max<size_t>(1, byLayer.size())));
  if (workers == 1) {
    for (size_t l = 0; l < byLayer.size(); ++l) job(l);
    return;
  }
  std::vector<size_t> order(byLayer.size());
  for (size_t l = 0; l < order.size(); ++l) order[l] = l;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return byLayer[a].size() > byLayer[b].size(); });
  std::atomic<size_t> next{0};
  std::exception_ptr error;
  std::mutex errorMutex;
  auto work = [&]() {
    for (size_t i = next.fetch_add(1); i < order.size(); i = next.fetch_add(1)) {
      try {
        job(order[i]);
      } catch (...) {
        std::lock_guard<std::mutex> lock(errorMutex);
        if (!error) error = std::current_exception();
        next = order.size();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int w = 0; w < workers; ++w) pool.emplace_back(work);
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace
}  // namespace drc

std::vector<Marker> checkShapesUnmerged(const Tech& tech, std::vector<DrcShape> shapes, const DrcOptions& options,
                                        const CheckZone* zone, const std::vector<int32_t>& links) {
  using namespace drc;
  std::vector<std::vector<Entry>> byLayer = entriesByLayer(tech, shapes, links);
  shapes.clear();
  shapes.shrink_to_fit();

  // Layers are independent: each is checked on its own (by up to options.threads workers) into its
  // own sink, and the sinks are joined in layer order, so the markers do not depend on the threads.
  std::vector<MarkerSink> sinks(byLayer.size());
  forEachLayer(byLayer, options.threads, [&](size_t l) {
    if (byLayer[l].empty()) return;
    if (zone != nullptr && zone->rects(LayerId(int32_t(l))).empty()) return;
    MarkerSink& raw = sinks[l];
    LayerShapes ls;
    ls.layer = LayerId(int32_t(l));
    ls.rules = &tech.layers[l];
    ls.euclidean = tech.clearanceMeasure != "MAXXY";
    buildLayer(ls, byLayer[l], options, zone);
    byLayer[l].clear();
    byLayer[l].shrink_to_fit();
    if (ls.rules->type == LayerType::Routing) {
      checkShorts(ls, MarkerType::Short, raw);
      checkPrlSpacing(ls, options, raw);
      checkEndOfLine(ls, raw);
      checkMinArea(ls, raw);
      checkCornerSpacing(ls, raw);
    } else {
      checkShorts(ls, MarkerType::CutShort, raw);
      checkCutSpacing(ls, raw);
    }
  });
  std::vector<Marker> markers;
  for (const MarkerSink& sink : sinks) {
    for (const RawMarker& r : sink) {
      if (options.skipFixedPairs && r.fixed) continue;
      if (zone != nullptr && !zone->judges(r.marker)) continue;
      markers.push_back(r.marker);
    }
  }
  return markers;
}

std::vector<Marker> finishMarkers(std::vector<Marker> markers, const DrcOptions& options) {
  using namespace drc;
  if (options.mergeMarkers) markers = mergeTouching(std::move(markers));
  if (options.window) {
    std::erase_if(markers, [&](const Marker& m) { return !m.box.overlaps(*options.window); });
  }
  sortMarkers(markers);
  return markers;
}

void sortMarkers(std::vector<Marker>& markers) {
  auto order = [](const Marker& m) {
    return std::make_tuple(m.type, *m.layer, m.box.xlo, m.box.ylo, m.box.xhi, m.box.yhi, m.net1, m.net2);
  };
  std::sort(markers.begin(), markers.end(), [&](const Marker& a, const Marker& b) { return order(a) < order(b); });
  markers.erase(std::unique(markers.begin(), markers.end()), markers.end());
}

std::vector<Marker> checkShapes(const Tech& tech, std::vector<DrcShape> shapes, const DrcOptions& options) {
  return finishMarkers(checkShapesUnmerged(tech, std::move(shapes), options), options);
}

CheckZone::CheckZone(const Tech& tech, const DrcOptions& options, size_t nets, const Rect& area)
    : area_(area), side_(tech.layers.size(), 1), nx_(tech.layers.size(), 0), ny_(tech.layers.size(), 0),
      cells_(tech.layers.size()), rects_(tech.layers.size()),
      reach_(tech.layers.size(), 0), netCount_(nets), netFlag_(tech.layers.size()) {
  // Cells of the layer's reach, at most 1024 along a side.
  const int64_t span = std::max<int64_t>({1, int64_t(area.xhi) - area.xlo, int64_t(area.yhi) - area.ylo});
  for (size_t l = 0; l < tech.layers.size(); ++l) {
    const Layer& layer = tech.layers[l];
    Dbu range = drc::interactionRange(layer);
    if (l < options.ndrSpacing.size())
      for (Dbu s : options.ndrSpacing[l]) range = std::max(range, s);
    Dbu eolWidth = 0;
    for (const EolRule& e : layer.eolRules) eolWidth = std::max(eolWidth, e.eolWidth);
    reach_[l] = 2 * range + eolWidth + 1;
    side_[l] = static_cast<Dbu>(std::max<int64_t>(reach_[l], (span + 1023) / 1024));
    nx_[l] = static_cast<int>((int64_t(area.xhi) - area.xlo) / side_[l] + 1);
    ny_[l] = static_cast<int>((int64_t(area.yhi) - area.ylo) / side_[l] + 1);
  }
}

// The cells [x0, x1] x [y0, y1] of the layer's grid that r touches (clipped to it); false when none.
bool CheckZone::cellRange(size_t l, const Rect& r, int& x0, int& x1, int& y0, int& y1) const {
  const int64_t side = side_[l];
  const int nx = nx_[l], ny = ny_[l];
  auto cell = [&](int64_t v, int64_t lo) {
    const int64_t d = v - lo;
    return d >= 0 ? d / side : -((-d + side - 1) / side);  // floor
  };
  const int64_t cx0 = cell(r.xlo, area_.xlo), cx1 = cell(r.xhi, area_.xlo);
  const int64_t cy0 = cell(r.ylo, area_.ylo), cy1 = cell(r.yhi, area_.ylo);
  if (cx1 < 0 || cy1 < 0 || cx0 >= nx || cy0 >= ny) return false;
  x0 = int(std::max<int64_t>(cx0, 0)), x1 = int(std::min<int64_t>(cx1, nx - 1));
  y0 = int(std::max<int64_t>(cy0, 0)), y1 = int(std::min<int64_t>(cy1, ny - 1));
  return true;
}

void CheckZone::add(LayerId layer, const Rect& rect) {
  const size_t l = size_t(*layer);
  int x0, x1, y0, y1;
  if (!cellRange(l, rect, x0, x1, y0, y1)) {  // outside the grid: no cell, but the layer is checked
    rects_[l].push_back(rect);
    return;
  }
  std::vector<uint8_t>& cells = cells_[l];
  if (cells.empty()) cells.assign(size_t(nx_[l]) * ny_[l], 0);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) cells[size_t(y) * nx_[l] + x] = 1;
  const int64_t side = side_[l];
  rects_[l].push_back({Dbu(area_.xlo + x0 * side), Dbu(area_.ylo + y0 * side), Dbu(area_.xlo + (x1 + 1) * side),
                       Dbu(area_.ylo + (y1 + 1) * side)});
}

CheckZone CheckZone::rows(Dbu ylo, Dbu yhi) const {
  CheckZone part;
  part.area_ = area_;
  part.side_ = side_;
  part.nx_ = nx_;
  part.ny_ = ny_;
  part.cells_.resize(cells_.size());
  part.rects_.resize(rects_.size());
  part.reach_ = reach_;
  part.netCount_ = netCount_;
  part.netFlag_.resize(netFlag_.size());
  part.minAreaByBox_ = minAreaByBox_;
  for (size_t l = 0; l < rects_.size(); ++l) {
    for (const Rect& r : rects_[l]) {
      int x0, x1, y0, y1;
      if (!cellRange(l, r, x0, x1, y0, y1)) {  // off the grid: no cell, the layer checked in every part
        part.rects_[l].push_back(r);
        continue;
      }
      // A cell-aligned rect of add(): its upper edges are the next cells' lower ones.
      const Rect clipped{r.xlo, std::max(r.ylo, ylo), r.xhi - 1, std::min(r.yhi - 1, yhi)};
      if (clipped.ylo <= clipped.yhi) part.add(LayerId(static_cast<int32_t>(l)), clipped);
    }
  }
  return part;
}

void CheckZone::addNet(int32_t net, LayerId layer) {
  if (net < 0 || size_t(net) >= netCount_) return;
  if (anyNet_.empty()) anyNet_.assign(netCount_, 0);
  if (!anyNet_[net]) nets_.push_back(net);
  anyNet_[net] = 1;
  std::vector<uint8_t>& f = netFlag_[*layer];
  if (f.empty()) f.assign(netCount_, 0);
  f[net] = 1;
}

bool CheckZone::near(LayerId layer, const Rect& rect, Dbu margin) const {
  const size_t l = size_t(*layer);
  const std::vector<uint8_t>& cells = cells_[l];
  int x0, x1, y0, y1;
  if (cells.empty() || !cellRange(l, drc::expanded(rect, margin), x0, x1, y0, y1)) return false;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x)
      if (cells[size_t(y) * nx_[l] + x]) return true;
  return false;
}

bool CheckZone::judges(const Marker& m) const {
  if (m.type == MarkerType::MinArea && !minAreaByBox_) return judgesNet(m.net1, m.layer);
  return near(m.layer, m.box, 0);
}

}  // namespace xroute
