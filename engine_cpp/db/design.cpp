#include "db/design.hpp"

#include <algorithm>

#include "geom/polygon.hpp"

namespace xroute {

CompId Design::findComponent(std::string_view name) const {
  auto it = compIndex.find(name);
  return it == compIndex.end() ? CompId() : it->second;
}

NetId Design::findNet(std::string_view name) const {
  auto it = netIndex.find(name);
  return it == netIndex.end() ? NetId() : it->second;
}

Transform componentTransform(const Tech& tech, const Component& comp) {
  const Macro& m = tech.macros[*comp.macro];
  return Transform{comp.location, comp.orient, m.width, m.height};
}

std::vector<PlacedShape> netPinShapes(const Tech& tech, const Design& design, NetId n) {
  std::vector<PlacedShape> out;
  for (int32_t r = design.netPinStart[*n]; r < design.netPinStart[*n + 1]; ++r) {
    const PinRef& ref = design.pinRefs[r];
    if (ref.isIo()) {
      const IoPin& pin = design.ioPins[ref.pin];
      const Transform t{pin.location, pin.orient, 0, 0};
      for (const IoPinShape& s : pin.shapes) out.push_back({r, s.layer, t.apply(s.rect)});
    } else {
      const Component& comp = design.components[*ref.comp];
      const Transform t = componentTransform(tech, comp);
      const MacroPin& pin = tech.macros[*comp.macro].pins[ref.pin];
      for (const MacroShape& s : pin.shapes) out.push_back({r, s.layer, t.apply(s.rect)});
    }
  }
  return out;
}

bool routeWireRect(const Tech& tech, const RouteWire& w, Rect& out) {
  if (w.from == w.to || !w.layer.valid()) return false;
  const Dbu width = w.width > 0 ? w.width : tech.layer(w.layer).width;
  const Dbu lo = width / 2, hi = width - width / 2;
  const Dbu extFrom = w.extFrom >= 0 ? w.extFrom : lo, extTo = w.extTo >= 0 ? w.extTo : lo;
  if (w.from.y == w.to.y) {
    const bool fwd = w.from.x <= w.to.x;
    const Dbu x0 = fwd ? w.from.x - extFrom : w.to.x - extTo, x1 = fwd ? w.to.x + extTo : w.from.x + extFrom;
    out = {x0, w.from.y - lo, x1, w.from.y + hi};
    return true;
  }
  if (w.from.x == w.to.x) {
    const bool fwd = w.from.y <= w.to.y;
    const Dbu y0 = fwd ? w.from.y - extFrom : w.to.y - extTo, y1 = fwd ? w.to.y + extTo : w.from.y + extFrom;
    out = {w.from.x - lo, y0, w.from.x + hi, y1};
    return true;
  }
  return false;
}

void pinRefRects(const Tech& tech, const Design& design, int32_t pinRef, LayerId layer, std::vector<Rect>& out) {
  const PinRef& ref = design.pinRefs[pinRef];
  if (ref.isIo()) {
    const IoPin& pin = design.ioPins[ref.pin];
    const Transform t{pin.location, pin.orient, 0, 0};
    for (const IoPinShape& s : pin.shapes)
      if (s.layer == layer) out.push_back(t.apply(s.rect));
    return;
  }
  const Component& comp = design.components[*ref.comp];
  const Transform t = componentTransform(tech, comp);
  for (const MacroShape& s : tech.macros[*comp.macro].pins[ref.pin].shapes)
    if (s.layer == layer) placedShapeRects(s, t, out);
}

const NdrLayer* netRuleLayer(const Design& design, int32_t net, LayerId layer) {
  if (net < 0 || static_cast<size_t>(net) >= design.nets.size()) return nullptr;
  const int rule = design.nets[net].ndr;
  return rule < 0 ? nullptr : design.ndrs[rule].find(layer);
}

bool taperedWire(const Tech& tech, const Design& design, int ndr, const RouteWire& w) {
  if (ndr < 0 || size_t(ndr) >= design.ndrs.size() || !w.layer.valid()) return false;
  const NdrLayer* l = design.ndrs[ndr].find(w.layer);
  const Dbu standard = tech.layer(w.layer).width;
  return l != nullptr && l->width != standard && (w.width > 0 ? w.width : standard) == standard;
}

void placedShapeRects(const MacroShape& shape, const Transform& t, std::vector<Rect>& out) {
  if (shape.polygon.empty()) {
    out.push_back(t.apply(shape.rect));
    return;
  }
  std::vector<Point> pts;
  pts.reserve(shape.polygon.size());
  for (const Point& p : shape.polygon) pts.push_back(t.apply(p));
  polygonRects(pts, out);
}

std::vector<Dbu> gcellLines(const Design& design, bool isX) {
  std::vector<Dbu> lines;
  for (const GCellPattern& g : design.gcellGrid) {
    if (g.isX != isX) continue;
    for (int i = 0; i < g.count; ++i) lines.push_back(g.start + Dbu(i) * g.step);
  }
  std::sort(lines.begin(), lines.end());
  lines.erase(std::unique(lines.begin(), lines.end()), lines.end());
  return lines;
}

}  // namespace xroute
