// Initial routing (iteration 0) plan: for every net, the regions it must
// pass and the region edges it crosses. Pins are assigned to the region of
// their best access point; guides link regions; a Steiner tree of the
// net's regions over those links (the nearest pin region joins by its
// shortest path) gives the crossings. Where the guides do not link two pin
// regions, an L-shaped chain of regions does.
#pragma once

#include <vector>

#include "flow/regions.hpp"
#include "flow/route_context.hpp"

namespace xroute {

struct Crossing {
  int32_t net = -1;
  int32_t regionA = -1, regionB = -1;  // A left of / below B
  bool vertical = true;                // the shared edge is a vertical line x = coord
  Dbu coord = 0;                       // DBU
  Dbu lo = 0, hi = 0;                  // DBU, span along the edge
  uint32_t layerMask = 0;              // routing layers (bit z) of guides crossing here; 0 = any
  // Where along the edge the net's nearby pins on the far side lie, as seen
  // from region A ([0]) and from region B ([1]): the crossing is best there.
  bool hasWant[2] = {false, false};
  Dbu wantLo[2] = {0, 0}, wantHi[2] = {0, 0};  // DBU
  // Set when the first of the two regions routes the net through it.
  bool chosen = false;
  Point at;                            // DBU
  int z = -1;                          // routing index
};

struct CrossingPlan {
  std::vector<Crossing> crossings;
  std::vector<std::vector<int32_t>> regionCrossings;  // region -> crossing ids
  std::vector<std::vector<int32_t>> regionPins;       // region -> pinRefs assigned to it
  std::vector<std::vector<int32_t>> regionNets;       // region -> nets with pins or crossings there (ascending)
};

CrossingPlan planCrossings(const RouteContext& ctx, const std::vector<Region>& regions, int size, int offset);

}  // namespace xroute
