#include "region/net_rules.hpp"

#include <algorithm>

#include "drc/drc.hpp"

namespace xroute {

namespace {

// The first VIA the rule names that the LEF defines and that joins layers lo and hi.
ViaId ruleVia(const Tech& tech, const NonDefaultRule& rule, LayerId lo, LayerId hi) {
  for (const std::string& name : rule.vias) {
    const ViaId id = tech.findVia(name);
    if (!id.valid()) continue;
    const Via& v = tech.vias[*id];
    if ((v.bottom == lo && v.top == hi) || (v.bottom == hi && v.top == lo)) return id;
  }
  return ViaId();
}

}  // namespace

NetRules::NetRules(const Tech& tech, const Design& design, const TrackSet& tracks, const ViaSet& vias) {
  const size_t nz = tracks.layers.size();
  netRule_.reserve(design.nets.size());
  bool anyNet = false;
  for (const Net& n : design.nets) {
    netRule_.push_back(n.ndr);
    anyNet = anyNet || n.ndr >= 0;
  }
  if (!anyNet) {
    netRule_.clear();
    return;
  }
  std::vector<Rect> defaultLanding(nz, Rect{0, 0, 0, 0});  // as FootprintRules::viaLanding
  for (size_t z = 0; z + 1 < nz; ++z) {
    defaultLanding[z].expandToInclude(vias.cuts[z].bottomMetal);
    defaultLanding[z + 1].expandToInclude(vias.cuts[z].topMetal);
  }
  for (const NonDefaultRule& rule : design.ndrs) {
    std::vector<Layer>& layers = rules_.emplace_back(nz);
    for (size_t z = 0; z < nz; ++z) {
      const LayerTracks& lt = tracks.layers[z];
      if (const NdrLayer* l = rule.find(lt.layer)) {
        layers[z].width = l->width != lt.wireWidth ? l->width : 0;
        layers[z].spacing = l->spacing;
      }
      if (z + 1 < nz) layers[z].via = ruleVia(tech, rule, lt.layer, tracks.layers[z + 1].layer);
    }
    for (size_t z = 0; z < nz; ++z) {
      Rect& landing = layers[z].landing;
      landing = Rect{0, 0, 0, 0};
      if (z + 1 < nz) {
        landing.expandToInclude(layers[z].via.valid() ? viaMetal(tech, tech.vias[*layers[z].via], tracks.layers[z].layer)
                                                      : vias.cuts[z].bottomMetal);
      }
      if (z > 0) {
        landing.expandToInclude(layers[z - 1].via.valid()
                                    ? viaMetal(tech, tech.vias[*layers[z - 1].via], tracks.layers[z].layer)
                                    : vias.cuts[z - 1].topMetal);
      }
      layers[z].differs = layers[z].width > 0 || layers[z].spacing > 0 || layers[z].via.valid() ||
                          landing != defaultLanding[z];
    }
  }
  std::vector<uint8_t> used(design.ndrs.size(), 0);
  for (int r : netRule_) {
    if (r >= 0) used[r] = 1;
  }
  for (size_t r = 0; r < design.ndrs.size(); ++r) {
    if (!used[r]) continue;
    for (const NdrLayer& l : design.ndrs[r].layers) reach_ = std::max(reach_, l.width + l.spacing);
  }
  drcSpacing_ = ndrSpacingByNet(tech, design);
  if (drcSpacing_.empty()) return;
  maxSpacing_.assign(nz, 0);
  for (size_t z = 0; z < nz; ++z) {
    for (Dbu v : drcSpacing_[*tracks.layers[z].layer]) maxSpacing_[z] = std::max(maxSpacing_[z], v);
  }
}

bool NetRules::any(int32_t net) const {
  if (net < 0 || static_cast<size_t>(net) >= netRule_.size() || netRule_[net] < 0) return false;
  for (const Layer& l : rules_[netRule_[net]]) {
    if (l.differs) return true;
  }
  return false;
}

}  // namespace xroute
