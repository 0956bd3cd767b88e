// Everything the regions of one routing run share: tracks, vias, footprint
// rules, pin access, the GCell grid, the fixed shapes with their index, and
// which nets have routing near each GCell. Built once per run; the routed
// index is refreshed after each batch of regions is committed.
#pragma once

#include <cstdint>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"
#include "drc/drc.hpp"
#include "flow/regions.hpp"
#include "geom/box_index.hpp"
#include "grid/footprint.hpp"
#include "grid/tracks.hpp"
#include "pa/pin_access.hpp"
#include "grid/via_set.hpp"

namespace xroute {

// A routed metal or cut shape of a net, in design coordinates.
struct NetShape {
  LayerId layer;
  Rect rect;  // DBU
};

// The shapes of a net's routing: wires (extended by half width unless an
// extension is given), via shapes at their positions, patches.
void netRoutingShapes(const Tech& tech, const Design& design, const NetRouting& routing, std::vector<NetShape>& out);

struct RouteContext {
  RouteContext(const Tech& tech, Design& design, int threads, int accessPointsPerPin = kAccessPointsPerPin);

  const Tech& tech;
  Design& design;
  TrackSet tracks;
  ViaSet vias;
  FootprintRules rules;
  PinAccessTable access;
  GCellGrid gcells;
  std::vector<int32_t> pinNet;      // per pinRef: its net id
  std::vector<DrcShape> fixedShapes;  // pins, OBS, special nets (DRC net ids: regular nets keep their id)
  BoxIndex fixedIndex;               // over fixedShapes' rects
  Dbu halo = 0;                      // DBU, how far outside a region shapes still matter
  // NONDEFAULTRULE spacing by layer id and net id (DrcOptions::ndrSpacing; empty: no net has one).
  std::vector<std::vector<Dbu>> ndrSpacing;
  std::vector<Dbu> maxRuleSpacing;  // DBU per routing layer z: the largest of them (empty: none)

  // Net n's wire width on routing layer z by its NONDEFAULTRULE, DBU; 0 = the layer's default.
  Dbu ruleWidth(int32_t net, int z) const;
  // Net n's NONDEFAULTRULE spacing on routing layer z, DBU; 0 = the layer's rules only (also for
  // the ids of special nets and obstructions).
  Dbu ruleSpacing(int32_t net, int z) const;
  // True when net n's rule widens its wires or adds spacing on some routing layer.
  bool hasRule(int32_t net) const;
  // The design-rule options of the flow's checks: fixed-only pairs skipped, rule spacing as above.
  DrcOptions drcOptions() const;

  // GCell bucket -> nets with routing there (ascending net ids).
  std::vector<std::vector<int32_t>> bucketNets;
  void rebuildRoutedIndex();
  // Nets with routing touching `window` (ascending, unique).
  std::vector<int32_t> netsNear(const Rect& window) const;

  int32_t gcellX(Dbu x) const;
  int32_t gcellY(Dbu y) const;
};

}  // namespace xroute
