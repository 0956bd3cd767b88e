#include "region/clip.hpp"

#include <algorithm>

#include "geom/union_find.hpp"
#include "region/centre_lines.hpp"

namespace xroute {

namespace {

bool insideOpen(const Rect& b, Point p) { return p.x > b.xlo && p.x < b.xhi && p.y > b.ylo && p.y < b.yhi; }

void addTerminal(std::vector<BoundaryTerminal>* out, Point p, int zLo, int zHi) {
  if (!out) return;
  const BoundaryTerminal t{p, zLo, zHi};
  if (std::find(out->begin(), out->end(), t) == out->end()) out->push_back(t);
}

// Clips one axis-aligned wire. `along` picks the coordinate that varies.
void clipWire(const RouteWire& w, int z, const Rect& box, NetRouting& kept, std::vector<BoundaryTerminal>* terms) {
  const bool horizontal = w.from.y == w.to.y && w.from.x != w.to.x;
  const bool vertical = w.from.x == w.to.x && w.from.y != w.to.y;
  if (!horizontal && !vertical) {  // a point wire
    if (!box.contains(w.from)) kept.wires.push_back(w);
    return;
  }
  const Dbu fixedCoord = horizontal ? w.from.y : w.from.x;
  const Dbu fixLo = horizontal ? box.ylo : box.xlo, fixHi = horizontal ? box.yhi : box.xhi;
  const Dbu a = horizontal ? w.from.x : w.from.y, b = horizontal ? w.to.x : w.to.y;
  const Dbu lo = std::min(a, b), hi = std::max(a, b);
  const Dbu boxLo = horizontal ? box.xlo : box.ylo, boxHi = horizontal ? box.xhi : box.yhi;
  auto pointAt = [&](Dbu v) { return horizontal ? Point{v, fixedCoord} : Point{fixedCoord, v}; };
  if (fixedCoord < fixLo || fixedCoord > fixHi || hi < boxLo || lo > boxHi) {
    kept.wires.push_back(w);
    if (fixedCoord >= fixLo && fixedCoord <= fixHi) {  // may touch the box at an end
      if (hi == boxLo) addTerminal(terms, pointAt(hi), z, z);
      if (lo == boxHi) addTerminal(terms, pointAt(lo), z, z);
    }
    return;
  }
  const bool forward = a <= b;  // from is the low end
  if (lo < boxLo) {
    RouteWire piece = w;
    if (forward) {
      piece.to = pointAt(boxLo);
      piece.extTo = -1;
    } else {
      piece.from = pointAt(boxLo);
      piece.extFrom = -1;
    }
    kept.wires.push_back(piece);
    addTerminal(terms, pointAt(boxLo), z, z);
  }
  if (hi > boxHi) {
    RouteWire piece = w;
    if (forward) {
      piece.from = pointAt(boxHi);
      piece.extFrom = -1;
    } else {
      piece.to = pointAt(boxHi);
      piece.extTo = -1;
    }
    kept.wires.push_back(piece);
    addTerminal(terms, pointAt(boxHi), z, z);
  }
}

}  // namespace

NetRouting clipOutside(const Tech& tech, const Design& design, const NetRouting& routing, const Rect& box,
                       std::vector<BoundaryTerminal>* terminals) {
  NetRouting kept;
  for (const RouteWire& w : routing.wires) clipWire(w, tech.layer(w.layer).routingIndex, box, kept, terminals);
  for (const RouteVia& v : routing.vias) {
    if (insideOpen(box, v.at)) continue;
    kept.vias.push_back(v);
    if (box.contains(v.at)) {
      const Via& via = design.via(tech, v.via);
      addTerminal(terminals, v.at, tech.layer(via.bottom).routingIndex, tech.layer(via.top).routingIndex);
    }
  }
  for (const RoutePatch& p : routing.patches) {
    const Point c{(p.rect.xlo + p.rect.xhi) / 2, (p.rect.ylo + p.rect.yhi) / 2};
    if (!box.contains(c)) kept.patches.push_back(p);
  }
  return kept;
}

std::vector<int32_t> keptConductors(const Tech& tech, const Design& design, int32_t pins, const NetRouting& kept,
                                    const std::vector<PinContact>& contacts,
                                    const std::vector<ConductorQuery>& queries) {
  // Nodes: the pins, then one per kept wire and via; a via is a point wire on each of its layers.
  CentreLineIndex index;
  std::vector<LayerPoint> ends;  // the pieces' vertices
  std::vector<int32_t> endPiece;
  int32_t node = pins;
  for (const RouteWire& w : kept.wires) {
    const int z = tech.layer(w.layer).routingIndex;
    if (z < 0) continue;
    index.add(node, z, w.from, w.to);
    for (const Point& p : {w.from, w.to}) {
      ends.push_back({z, p});
      endPiece.push_back(node);
    }
    ++node;
  }
  for (const RouteVia& v : kept.vias) {
    if (!v.via.valid()) continue;
    const Via& via = design.via(tech, v.via);
    for (const LayerId l : {via.bottom, via.top}) {
      const int z = tech.layer(l).routingIndex;
      if (z < 0) continue;
      index.add(node, z, v.at, v.at);
      ends.push_back({z, v.at});
      endPiece.push_back(node);
    }
    ++node;
  }
  UnionFind sets(static_cast<size_t>(node));
  for (size_t k = 0; k < ends.size(); ++k)
    index.at(ends[k].z, ends[k].at, [&](int32_t e) { sets.unite(endPiece[k], e); });
  for (const PinContact& c : contacts) {
    if (c.pin < 0 || c.pin >= pins) continue;
    index.at(c.point.z, c.point.at, [&](int32_t e) { sets.unite(c.pin, e); });
  }
  std::vector<int32_t> out;
  out.reserve(queries.size());
  for (const ConductorQuery& q : queries) {
    int32_t found = q.pin >= 0 && q.pin < pins ? q.pin : -1;
    if (q.pin < 0) index.at(q.point.z, q.point.at, [&](int32_t e) { found = found < 0 ? e : found; });
    out.push_back(found < 0 ? -1 : sets.find(found));
  }
  return out;
}

bool routingTouches(const NetRouting& routing, const Rect& box) {
  for (const RouteWire& w : routing.wires) {
    if (Rect::fromCorners(w.from, w.to).overlaps(box)) return true;
  }
  for (const RouteVia& v : routing.vias) {
    if (box.contains(v.at)) return true;
  }
  return false;
}

}  // namespace xroute
