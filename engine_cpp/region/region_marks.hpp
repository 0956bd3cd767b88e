// What a region's grid is told before and while its nets are routed: fixed
// shapes, other nets' routed metal and cuts (with the owning net, so nobody
// pays for its own metal), the nodes a net's new routing runs through, and
// markers of earlier checks as node costs.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "grid/region_grid.hpp"
#include "region/route_context.hpp"

namespace xroute {

// A DRC marker from an earlier pass, as a cost on the nodes around it.
struct MarkerCost {
  LayerId layer;
  Rect box;         // DBU
  int64_t cost = 0; // cost units added to each node near the box
  Dbu reach = 0;    // DBU beyond the usual pitch that "near" extends (see markerReach)
};

// How much farther than a pitch the nodes that caused marker `m` may lie from its box: the farthest
// a via's metal on the marker's layer reaches from the via's node (FootprintRules::viaLanding: a
// long landing pad's corner or end may be the marker's shape), and for an EndOfLine marker at least
// the largest end-of-line spacing of its layer (FootprintRules::eolSpace: its box is in front of the
// line end, which lies up to that far away); 0 on a cut layer.
Dbu markerReach(const RouteContext& ctx, const Marker& m);

// Per routing layer: routed metal (rect in DBU, net) of every net marked in
// the grid (committed routing near the box and the region's new routing), so
// that a minimum-area patch is judged against real shapes.
using RoutedMetal = std::vector<std::vector<std::pair<Rect, int32_t>>>;

// The box grown by `halo` DBU on every side.
Rect grownBox(const Rect& box, Dbu halo);
// Grid index range of the closed interval [lo, hi] (first > last when empty).
void closedRange(const std::vector<Dbu>& v, Dbu lo, Dbu hi, int& first, int& last);
// The routing index below a cut layer, -1 if unknown.
int cutBelow(const RouteContext& ctx, LayerId cut);

// Fixed shapes (pins, OBS, special nets) within the halo around `box`.
void markFixed(const RouteContext& ctx, const Rect& box, RegionGrid& g);
// A net's routed shapes overlapping `win`: footprints on the grid, metal kept in `metal`.
void markShapes(const RouteContext& ctx, int32_t net, const std::vector<NetShape>& shapes, const Rect& win,
                RegionGrid& g, RoutedMetal& metal);
// The grid nodes a net's new wires run through (routedNet).
void markRoutedNodes(const RouteContext& ctx, int32_t net, const NetRouting& r, RegionGrid& g);
// A marker's cost on the nodes within a pitch of its box (both layers of a cut marker).
void markMarker(const RouteContext& ctx, const MarkerCost& m, RegionGrid& g);

}  // namespace xroute
