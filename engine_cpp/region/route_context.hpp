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
#include "geom/box_index.hpp"
#include "grid/footprint.hpp"
#include "grid/gcell_grid.hpp"
#include "grid/tracks.hpp"
#include "grid/via_set.hpp"
#include "pa/pin_access.hpp"
#include "region/net_rules.hpp"
#include "route/maze.hpp"

namespace xroute {

// A routed metal or cut shape of a net, in design coordinates.
struct NetShape {
  LayerId layer;
  Rect rect;  // DBU
  bool taper = false;  // drawn to the default rule though the net has a rule (DrcShape::taper)
};

// The shapes of a net's routing: wires (extended by half width unless an
// extension is given), via shapes at their positions, patches. ndr: the net's
// rule (Net::ndr), for the taper flags; -1: none tapered.
void netRoutingShapes(const Tech& tech, const Design& design, const NetRouting& routing, std::vector<NetShape>& out,
                      int ndr = -1);

struct RouteContext {
  RouteContext(const Tech& tech, Design& design, int threads, int accessPointsPerPin = kAccessPointsPerPin);

  const Tech& tech;
  Design& design;
  TrackSet tracks;
  ViaSet vias;
  FootprintRules rules;
  PinAccessTable access;
  double soleShare = 0;              // soleViaShare(access): read by designCosts
  GCellGrid gcells;
  std::vector<int32_t> pinNet;      // per pinRef: its net id
  std::vector<DrcShape> fixedShapes;  // pins, OBS, special nets (DRC net ids: regular nets keep their id)
  BoxIndex fixedIndex;               // over fixedShapes' rects
  // Per fixed shape: its open cross ends (CrossEnd bits; a pin's other rects on the layer hold an
  // end), 0 on cut layers and for shapes wide across the tracks.
  std::vector<uint8_t> fixedCrossEnds;
  Dbu halo = 0;                      // DBU, how far outside a region shapes still matter
  NetRules netRules;                 // each net's NONDEFAULTRULE: widths, spacings, vias per layer
  // The design-rule options of the flow's checks: fixed-only pairs skipped, the nets' rule
  // spacings (as xroute check judges them).
  DrcOptions drcOptions() const;

  // GCell bucket -> nets with routing there (ascending net ids).
  std::vector<std::vector<int32_t>> bucketNets;
  std::vector<std::vector<int32_t>> netBuckets;  // net -> the buckets listing it (ascending)
  void rebuildRoutedIndex();
  // The index brought up to date for these nets, whose routing changed (the buckets a rebuild gives).
  void updateRoutedIndex(const std::vector<int32_t>& nets);
  // Nets with routing touching `window` (ascending, unique).
  std::vector<int32_t> netsNear(const Rect& window) const;

  int32_t gcellX(Dbu x) const;
  int32_t gcellY(Dbu y) const;
};

// The maze's costs for a run on this design: guideCosts, pitchCosts at the scorer's pitch
// (verify/scoring.hpp scorerPitch), and soleLandingCosts at soleShare.
MazeCosts designCosts(const MazeCosts& costs, const RouteContext& ctx);

}  // namespace xroute
