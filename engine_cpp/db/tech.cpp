#include "db/tech.hpp"

#include <algorithm>

namespace xroute {

namespace {
template <class IdT>
IdT lookup(const StringMap<IdT>& map, std::string_view name) {
  auto it = map.find(name);
  return it == map.end() ? IdT() : it->second;
}
}  // namespace

Dbu Layer::minSpacing() const {
  if (!prlTable.empty() && !prlTable.spacing.empty()) return prlTable.spacing.front();
  Dbu best = 0;
  for (const SpacingRule& r : spacings) {
    if (r.hasRange || r.sameNet) continue;
    if (best == 0 || r.space < best) best = r.space;
  }
  return best;
}

LayerId Tech::findLayer(std::string_view name) const { return lookup(layerIndex, name); }
ViaId Tech::findVia(std::string_view name) const { return lookup(viaIndex, name); }
MacroId Tech::findMacro(std::string_view name) const { return lookup(macroIndex, name); }
ViaRuleId Tech::findViaRule(std::string_view name) const { return lookup(viaRuleIndex, name); }

}  // namespace xroute
