#include "db/design.hpp"

#include <algorithm>

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
