// What each net's NONDEFAULTRULE asks of the router, per routing layer z: its wire width, its
// spacing, and its vias (a VIA the rule names that the LEF defines and that joins z and z+1; the
// router's default via of that cut otherwise). Built once per run; a net of no rule gets the
// defaults everywhere (width 0, spacing 0, the default via).
#pragma once

#include <cstdint>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"
#include "grid/tracks.hpp"
#include "grid/via_set.hpp"

namespace xroute {

class NetRules {
 public:
  NetRules() = default;
  NetRules(const Tech& tech, const Design& design, const TrackSet& tracks, const ViaSet& vias);

  // Net n's wire width on z, DBU; 0 = the layer's default (also when the rule's equals it).
  Dbu width(int32_t net, int z) const { return at(net, z) ? at(net, z)->width : 0; }
  // Net n's rule spacing on z, DBU; 0 = the layer's rules only (and for special nets, obstructions).
  Dbu spacing(int32_t net, int z) const { return at(net, z) ? at(net, z)->spacing : 0; }
  // The via net n's rule names from z to z+1; invalid: the router's default via of the cut.
  ViaId via(int32_t net, int z) const { return at(net, z) ? at(net, z)->via : ViaId(); }
  // The metal of net n's vias landing on z (from below and above), DBU, relative to the via
  // origin; nullptr for a net of no rule (FootprintRules::viaLanding holds).
  const Rect* landing(int32_t net, int z) const { return at(net, z) ? &at(net, z)->landing : nullptr; }
  // True when net n's rule differs from the defaults on some layer (width, spacing or via).
  bool any(int32_t net) const;
  // DBU: the largest rule spacing any net has on z.
  Dbu maxSpacing(int z) const { return maxSpacing_.empty() ? 0 : maxSpacing_[z]; }
  // DBU: the largest width + spacing of a rule some net names (0: none).
  Dbu reach() const { return reach_; }
  // DrcOptions::ndrSpacing of the design (by layer id and net id; empty: no net has a spacing).
  const std::vector<std::vector<Dbu>>& drcSpacing() const { return drcSpacing_; }

 private:
  struct Layer {
    Dbu width = 0;         // DBU, 0 = default
    Dbu spacing = 0;       // DBU, 0 = none
    ViaId via;             // the via up from this layer (invalid: the default)
    Rect landing;          // DBU, via metal landing here
    bool differs = false;  // any of the above differs from the defaults
  };
  const Layer* at(int32_t net, int z) const {
    if (net < 0 || static_cast<size_t>(net) >= netRule_.size() || netRule_[net] < 0) return nullptr;
    return &rules_[netRule_[net]][z];
  }

  std::vector<int> netRule_;                // per net: index into rules_ (Design::ndrs), -1 = none
  std::vector<std::vector<Layer>> rules_;   // per rule, per z
  std::vector<Dbu> maxSpacing_;             // per z (empty: no spacing anywhere)
  Dbu reach_ = 0;
  std::vector<std::vector<Dbu>> drcSpacing_;
};

}  // namespace xroute
