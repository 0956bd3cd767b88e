// checkConnectivity: per net, union-find over its conductors. Same-layer
// contacts come from a sweep over the net's shapes sorted by xlo (a box index
// for layers where a net has many shapes), so the work is local to each net.
#include "verify/connectivity.hpp"

#include <algorithm>

#include "geom/box_index.hpp"
#include "geom/union_find.hpp"

namespace xroute {

namespace {

// Above this many shapes of one net on one layer, contacts come from a box
// index instead of the x sweep (whose cost grows with overlapping x spans).
constexpr size_t kSweepLimit = 256;

struct NetShape {
  LayerId layer;
  Rect rect;     // DBU
  int32_t node;  // union-find node: pins first (local pin index), then routing pieces
};

class NetChecker {
 public:
  NetChecker(const Tech& tech, const Design& design) : tech_(tech), design_(design) {}

  NetConnectivity check(NetId net);

 private:
  void collect(NetId net, int32_t pins);
  size_t mergeStrips(size_t begin, size_t end, bool alongX);
  void connectLayer(size_t begin, size_t end);

  const Tech& tech_;
  const Design& design_;
  std::vector<NetShape> shapes_;
  UnionFind sets_;              // over the nodes (index)
  std::vector<int32_t> label_;  // per root node: group id, or -1
};

// Fills shapes_ and sizes sets_: node p < pins is pin p of the net; every
// wire, via and patch is one node after those.
void NetChecker::collect(NetId net, int32_t pins) {
  shapes_.clear();
  const int32_t first = design_.netPinStart[*net];
  for (const PlacedShape& s : netPinShapes(tech_, design_, net)) shapes_.push_back({s.layer, s.rect, s.pinRef - first});
  int32_t node = pins;
  const NetRouting& routing = design_.nets[*net].routing;
  for (const RouteWire& w : routing.wires) {
    Rect r;
    if (routeWireRect(tech_, w, r)) shapes_.push_back({w.layer, r, node++});
  }
  for (const RouteVia& v : routing.vias) {
    if (!v.via.valid()) continue;
    for (const ViaShape& s : design_.via(tech_, v.via).shapes) shapes_.push_back({s.layer, s.rect.translated(v.at), node});
    ++node;
  }
  for (const RoutePatch& p : routing.patches) shapes_.push_back({p.layer, p.rect, node++});
  shapes_.erase(std::remove_if(shapes_.begin(), shapes_.end(), [](const NetShape& s) { return !s.layer.valid(); }),
                shapes_.end());
  sets_.reset(size_t(node));
}

// Along x (alongX) or y: merges shapes_[begin, end) (one layer) that have the same span across and
// overlap or abut along (a zero-width strip needs an overlap of positive length), uniting their
// nodes; the merged rect touches exactly what its pieces touch. Repeated or overlapping collinear
// wires become one shape, so the contact search below stays near linear. Returns the new end.
size_t NetChecker::mergeStrips(size_t begin, size_t end, bool alongX) {
  auto across = [&](const Rect& r) { return alongX ? std::make_pair(r.ylo, r.yhi) : std::make_pair(r.xlo, r.xhi); };
  auto lo = [&](const Rect& r) { return alongX ? r.xlo : r.ylo; };
  std::sort(shapes_.begin() + begin, shapes_.begin() + end, [&](const NetShape& a, const NetShape& b) {
    return std::make_pair(across(a.rect), lo(a.rect)) < std::make_pair(across(b.rect), lo(b.rect));
  });
  size_t out = begin;
  for (size_t i = begin; i < end; ++i) {
    const NetShape& s = shapes_[i];
    if (out > begin) {
      NetShape& last = shapes_[out - 1];
      const auto span = across(s.rect);
      Dbu& lastHi = alongX ? last.rect.xhi : last.rect.yhi;
      const bool joins = span.first < span.second ? lo(s.rect) <= lastHi : lo(s.rect) < lastHi;
      if (across(last.rect) == span && joins) {
        sets_.unite(last.node, s.node);
        lastHi = std::max(lastHi, alongX ? s.rect.xhi : s.rect.yhi);
        continue;
      }
    }
    shapes_[out++] = s;
  }
  return out;
}

// Unites the nodes of touching shapes in shapes_[begin, end) (one layer,
// sorted by xlo).
void NetChecker::connectLayer(size_t begin, size_t end) {
  if (end - begin <= kSweepLimit) {
    for (size_t i = begin; i < end; ++i) {
      const Rect& a = shapes_[i].rect;
      for (size_t j = i + 1; j < end && shapes_[j].rect.xlo <= a.xhi; ++j) {
        if (shapes_[i].node != shapes_[j].node && a.contacts(shapes_[j].rect)) sets_.unite(shapes_[i].node, shapes_[j].node);
      }
    }
    return;
  }
  std::vector<Rect> rects;
  rects.reserve(end - begin);
  for (size_t i = begin; i < end; ++i) rects.push_back(shapes_[i].rect);
  const BoxIndex index(std::move(rects));
  for (size_t i = begin; i < end; ++i) {
    const NetShape& a = shapes_[i];
    index.query(a.rect, [&](int32_t k) {
      const NetShape& b = shapes_[begin + k];
      if (begin + k > i && a.node != b.node && a.rect.contacts(b.rect)) sets_.unite(a.node, b.node);
    });
  }
}

NetConnectivity NetChecker::check(NetId net) {
  NetConnectivity out;
  out.net = net;
  out.pinCount = design_.pinCount(net);
  collect(net, out.pinCount);
  std::stable_sort(shapes_.begin(), shapes_.end(), [](const NetShape& a, const NetShape& b) { return a.layer < b.layer; });
  for (size_t b = 0, e = 0; b < shapes_.size(); b = e) {
    for (e = b + 1; e < shapes_.size() && shapes_[e].layer == shapes_[b].layer;) ++e;
    size_t end = mergeStrips(b, e, true);
    end = mergeStrips(b, end, false);
    std::sort(shapes_.begin() + b, shapes_.begin() + end,
              [](const NetShape& x, const NetShape& y) { return x.rect.xlo < y.rect.xlo; });
    connectLayer(b, end);
  }
  // Groups in the order of their first pin; then routing-only components.
  label_.assign(sets_.size(), -1);
  std::vector<std::vector<int32_t>> groups;
  const int32_t first = design_.netPinStart[*net];
  for (int32_t p = 0; p < out.pinCount; ++p) {
    const int32_t root = sets_.find(p);
    if (label_[root] < 0) {
      label_[root] = int32_t(groups.size());
      groups.emplace_back();
    }
    groups[label_[root]].push_back(first + p);
  }
  out.pinGroups = int32_t(groups.size());
  for (int32_t n = out.pinCount; n < int32_t(sets_.size()); ++n) {
    const int32_t root = sets_.find(n);
    if (label_[root] < 0) {
      label_[root] = out.pinGroups + out.floatingPieces;
      ++out.floatingPieces;
    }
  }
  out.open = out.pinGroups > 1;
  if (out.open) out.groups = std::move(groups);
  return out;
}

}  // namespace

ConnectivityReport checkConnectivity(const Tech& tech, const Design& design) {
  ConnectivityReport report;
  NetChecker checker(tech, design);
  for (int32_t n = 0; n < int32_t(design.nets.size()); ++n) {
    const NetId net(n);
    if (size_t(n + 1) >= design.netPinStart.size() || design.pinCount(net) < 2) {
      ++report.singlePinNets;
      continue;
    }
    NetConnectivity c = checker.check(net);
    ++report.netsChecked;
    report.openNets += c.open ? 1 : 0;
    report.unroutedNets += design.nets[n].routing.empty() ? 1 : 0;
    report.floatingPieces += c.floatingPieces;
    report.nets.push_back(std::move(c));
  }
  return report;
}

}  // namespace xroute
