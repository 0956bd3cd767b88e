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
};

void buildLayer(LayerShapes& ls, std::vector<Entry>& entries, const DrcOptions& options) {
  auto key = [](const Entry& e) { return std::make_tuple(e.rect.xlo, e.rect.ylo, e.rect.xhi, e.rect.yhi, e.net); };
  std::sort(entries.begin(), entries.end(), [&](const Entry& a, const Entry& b) {
    return std::make_tuple(key(a), a.fixed) < std::make_tuple(key(b), b.fixed);
  });
  // Identical duplicates are one shape, fixed only if every copy is.
  for (size_t i = 0; i < entries.size(); ++i) {
    if (!ls.rects.empty() && ls.rects.back() == entries[i].rect && ls.nets.back() == entries[i].net) {
      ls.fixed.back() = ls.fixed.back() && entries[i].fixed;
      continue;
    }
    ls.rects.push_back(entries[i].rect);
    ls.nets.push_back(entries[i].net);
    ls.fixed.push_back(entries[i].fixed);
  }
  const size_t n = ls.rects.size();
  ls.index = ShapeIndex(ls.rects, ls.nets);

  ls.seed.assign(n, 1);
  if (options.window) {
    const Rect roi = expanded(*options.window, 2 * interactionRange(*ls.rules) + 1);
    for (size_t i = 0; i < n; ++i) ls.seed[i] = ls.rects[i].overlaps(roi);
  }

  UnionFind uf(n);
  joinSameNet(ls, uf);
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

std::vector<Marker> checkShapes(const Tech& tech, std::vector<DrcShape> shapes, const DrcOptions& options) {
  using namespace drc;
  std::vector<std::vector<Entry>> byLayer(tech.layers.size());
  for (const DrcShape& s : shapes) {
    if (!s.layer.valid() || size_t(*s.layer) >= tech.layers.size()) continue;
    const LayerType t = tech.layers[*s.layer].type;
    if (t != LayerType::Routing && t != LayerType::Cut) continue;
    if (s.rect.xhi <= s.rect.xlo || s.rect.yhi <= s.rect.ylo) continue;  // no area
    byLayer[*s.layer].push_back({s.rect, s.net < 0 ? -1 : s.net, isFixedOrigin(s.origin)});
  }
  shapes.clear();
  shapes.shrink_to_fit();

  // Layers are independent: each is checked on its own (by up to options.threads workers) into its
  // own sink, and the sinks are joined in layer order, so the markers do not depend on the threads.
  std::vector<MarkerSink> sinks(byLayer.size());
  auto checkLayer = [&](size_t l) {
    if (byLayer[l].empty()) return;
    MarkerSink& raw = sinks[l];
    LayerShapes ls;
    ls.layer = LayerId(int32_t(l));
    ls.rules = &tech.layers[l];
    ls.euclidean = tech.clearanceMeasure != "MAXXY";
    buildLayer(ls, byLayer[l], options);
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
  };
  const int workers = std::clamp(options.threads, 1, static_cast<int>(std::max<size_t>(1, byLayer.size())));
  if (workers == 1) {
    for (size_t l = 0; l < byLayer.size(); ++l) checkLayer(l);
  } else {
    // The layers with the most shapes first, so that no worker is left with a large one at the end.
    std::vector<size_t> order(byLayer.size());
    for (size_t l = 0; l < order.size(); ++l) order[l] = l;
    std::stable_sort(order.begin(), order.end(),
                     [&](size_t a, size_t b) { return byLayer[a].size() > byLayer[b].size(); });
    std::atomic<size_t> next{0};
    std::exception_ptr error;
    std::mutex errorMutex;
    auto work = [&]() {
      for (size_t i = next.fetch_add(1); i < order.size(); i = next.fetch_add(1)) {
        try {
          checkLayer(order[i]);
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
  MarkerSink raw;
  for (MarkerSink& sink : sinks) raw.insert(raw.end(), sink.begin(), sink.end());

  std::vector<Marker> markers;
  markers.reserve(raw.size());
  for (const RawMarker& r : raw) {
    if (options.skipFixedPairs && r.fixed) continue;
    markers.push_back(r.marker);
  }
  if (options.mergeMarkers) markers = mergeTouching(std::move(markers));
  if (options.window) {
    std::erase_if(markers, [&](const Marker& m) { return !m.box.overlaps(*options.window); });
  }
  auto order = [](const Marker& m) {
    return std::make_tuple(m.type, *m.layer, m.box.xlo, m.box.ylo, m.box.xhi, m.box.yhi, m.net1, m.net2);
  };
  std::sort(markers.begin(), markers.end(), [&](const Marker& a, const Marker& b) { return order(a) < order(b); });
  markers.erase(std::unique(markers.begin(), markers.end()), markers.end());
  return markers;
}

}  // namespace xroute
