#include "loop/dangling.hpp"

#include <algorithm>
#include <vector>

#include "region/centre_lines.hpp"

namespace xroute {

namespace {

class Trimmer {
 public:
  Trimmer(const Tech& tech, Design& design, NetId n)
      : tech_(tech), design_(design), r_(design.nets[*n].routing), pinRects_(tech.routingLayers.size()) {
    for (const PlacedShape& s : netPinShapes(tech, design, n)) {
      if (!s.layer.valid()) continue;
      const int z = tech.layer(s.layer).routingIndex;
      if (z >= 0) pinRects_[z].push_back(s.rect);
    }
  }

  TrimCounts run() {
    TrimCounts out;
    wireZ_.clear();
    for (const RouteWire& w : r_.wires) wireZ_.push_back(w.layer.valid() ? tech_.layer(w.layer).routingIndex : -1);
    viaZ_.clear();
    for (const RouteVia& v : r_.vias) {
      if (!v.via.valid()) {
        viaZ_.push_back({-1, -1});
        continue;
      }
      const Via& via = design_.via(tech_, v.via);
      viaZ_.push_back({tech_.layer(via.bottom).routingIndex, tech_.layer(via.top).routingIndex});
    }
    wireAlive_.assign(r_.wires.size(), 1);
    viaAlive_.assign(r_.vias.size(), 1);
    for (bool changed = true; changed;) {
      changed = false;
      index();
      for (size_t j = 0; j < r_.vias.size(); ++j) {
        const auto [zb, zt] = viaZ_[j];
        if (!viaAlive_[j] || zb < 0 || zt < 0) continue;
        const int32_t self = piece(j);
        if (held(zb, r_.vias[j].at, self) && held(zt, r_.vias[j].at, self)) continue;
        viaAlive_[j] = 0;
        ++out.vias;
        changed = true;
      }
      if (changed) continue;  // the index is stale: a removed via may have held a wire's end
      for (size_t i = 0; i < r_.wires.size(); ++i) {
        const int z = wireZ_[i];
        if (!wireAlive_[i] || z < 0) continue;
        RouteWire& w = r_.wires[i];
        const bool holdFrom = held(z, w.from, int32_t(i)), holdTo = held(z, w.to, int32_t(i));
        if (holdFrom && holdTo) continue;
        changed = true;
        cutBack(i, holdFrom, holdTo, out);
        break;  // the index is stale
      }
    }
    finish(out);
    return out;
  }

 private:
  int32_t piece(size_t via) const { return int32_t(r_.wires.size() + via); }

  void index() {
    lines_ = CentreLineIndex();
    for (size_t i = 0; i < r_.wires.size(); ++i)
      if (wireAlive_[i] && wireZ_[i] >= 0) lines_.add(int32_t(i), wireZ_[i], r_.wires[i].from, r_.wires[i].to);
    for (size_t j = 0; j < r_.vias.size(); ++j) {
      if (!viaAlive_[j] || viaZ_[j].first < 0) continue;
      lines_.add(piece(j), viaZ_[j].first, r_.vias[j].at, r_.vias[j].at);
      lines_.add(piece(j), viaZ_[j].second, r_.vias[j].at, r_.vias[j].at);
    }
  }

  // Whether point p of layer z lies in a pin shape of the net or on a piece other than `self`.
  bool held(int z, Point p, int32_t self) const {
    for (const Rect& r : pinRects_[z])
      if (r.contains(p)) return true;
    bool any = false;
    lines_.at(z, p, [&](int32_t e) { any = any || e != self; });
    return any;
  }

  // Wire i has an end that is not held: the wire is cut back to the nearest held points along it
  // (the span of everything else on its layer that meets its centre line), or removed.
  void cutBack(size_t i, bool holdFrom, bool holdTo, TrimCounts& out) {
    RouteWire& w = r_.wires[i];
    const int z = wireZ_[i];
    const bool horizontal = w.from.y == w.to.y;
    auto along = [&](Point p) { return horizontal ? p.x : p.y; };
    const Dbu fixed = horizontal ? w.from.y : w.from.x;
    const Dbu lo = std::min(along(w.from), along(w.to)), hi = std::max(along(w.from), along(w.to));
    // Held spans along the wire: [a, b] where something meets its centre line.
    Dbu first = hi + 1, last = lo - 1;
    auto meet = [&](Dbu a, Dbu b) {
      a = std::max(a, lo), b = std::min(b, hi);
      if (a > b) return;
      first = std::min(first, a);
      last = std::max(last, b);
    };
    auto meetRect = [&](const Rect& r) {  // a rect crossing the centre line
      if (horizontal ? (r.ylo <= fixed && fixed <= r.yhi) : (r.xlo <= fixed && fixed <= r.xhi))
        meet(horizontal ? r.xlo : r.ylo, horizontal ? r.xhi : r.yhi);
    };
    for (const Rect& r : pinRects_[z]) meetRect(r);
    for (size_t k = 0; k < r_.wires.size(); ++k) {
      if (k == i || !wireAlive_[k] || wireZ_[k] != z) continue;
      meetRect(Rect::fromCorners(r_.wires[k].from, r_.wires[k].to));
    }
    for (size_t j = 0; j < r_.vias.size(); ++j) {
      if (!viaAlive_[j] || (viaZ_[j].first != z && viaZ_[j].second != z)) continue;
      const Point p = r_.vias[j].at;
      meetRect(Rect{p.x, p.y, p.x, p.y});
    }
    const bool fromLow = along(w.from) <= along(w.to);
    Dbu newLo = lo, newHi = hi;
    const bool holdLo = fromLow ? holdFrom : holdTo, holdHi = fromLow ? holdTo : holdFrom;
    if (!holdLo) newLo = first;
    if (!holdHi) newHi = last;
    if (first > last || newLo >= newHi) {
      wireAlive_[i] = 0;
      ++out.wires;
      out.length += hi - lo;
      return;
    }
    out.length += (newLo - lo) + (hi - newHi);
    ++out.shortened;
    auto at = [&](Dbu v) { return horizontal ? Point{v, fixed} : Point{fixed, v}; };
    Point& pLo = fromLow ? w.from : w.to;
    Point& pHi = fromLow ? w.to : w.from;
    Dbu& eLo = fromLow ? w.extFrom : w.extTo;
    Dbu& eHi = fromLow ? w.extTo : w.extFrom;
    if (newLo != lo) {
      pLo = at(newLo);
      eLo = -1;
    }
    if (newHi != hi) {
      pHi = at(newHi);
      eHi = -1;
    }
  }

  // Drops the removed pieces, then the patches that touch none of the metal left.
  void finish(TrimCounts& out) {
    if (!out.any()) return;
    NetRouting kept;
    for (size_t i = 0; i < r_.wires.size(); ++i)
      if (wireAlive_[i]) kept.wires.push_back(r_.wires[i]);
    for (size_t j = 0; j < r_.vias.size(); ++j)
      if (viaAlive_[j]) kept.vias.push_back(r_.vias[j]);
    std::vector<std::pair<LayerId, Rect>> metal;
    for (const RouteWire& w : kept.wires) {
      Rect r;
      if (routeWireRect(tech_, w, r)) metal.push_back({w.layer, r});
    }
    for (const RouteVia& v : kept.vias) {
      if (!v.via.valid()) continue;
      for (const ViaShape& s : design_.via(tech_, v.via).shapes) metal.push_back({s.layer, s.rect.translated(v.at)});
    }
    for (const RoutePatch& p : r_.patches) {
      const bool touches = std::any_of(metal.begin(), metal.end(), [&](const auto& m) {
        return m.first == p.layer && m.second.contacts(p.rect);
      });
      if (touches) kept.patches.push_back(p);
      else ++out.patches;
    }
    r_ = std::move(kept);
  }

  const Tech& tech_;
  Design& design_;
  NetRouting& r_;
  std::vector<std::vector<Rect>> pinRects_;  // per routing index
  std::vector<int> wireZ_;
  std::vector<std::pair<int, int>> viaZ_;
  std::vector<uint8_t> wireAlive_, viaAlive_;
  CentreLineIndex lines_;
};

}  // namespace

TrimCounts trimDangling(const Tech& tech, Design& design, NetId n) {
  if (design.nets[*n].routing.empty()) return {};
  return Trimmer(tech, design, n).run();
}

TrimCounts trimDanglingAll(const Tech& tech, Design& design) {
  TrimCounts sum;
  for (int32_t n = 0; n < static_cast<int32_t>(design.nets.size()); ++n) sum += trimDangling(tech, design, NetId(n));
  return sum;
}

}  // namespace xroute
