// Rip-up inside a region: a net's routing split at the region's closed box.
// What lies inside goes; wires crossing the box edge are cut there; a via
// on the edge stays (it is outside the open interior). Every point where a
// kept piece touches the box becomes a boundary terminal that the net's new
// route inside must reach.
#pragma once

#include <vector>

#include "db/design.hpp"

namespace xroute {

struct BoundaryTerminal {
  Point at;        // DBU, on the box edge
  int zLo = 0;     // routing index of the layer (a via: its bottom layer)
  int zHi = 0;     // a via: its top layer; a wire: zLo
  friend bool operator==(const BoundaryTerminal&, const BoundaryTerminal&) = default;
};

// The part of `routing` outside `box`; appends the boundary terminals
// (deduplicated) to `terminals` when it is not null.
NetRouting clipOutside(const Tech& tech, const Design& design, const NetRouting& routing, const Rect& box,
                       std::vector<BoundaryTerminal>* terminals);

// A point on a routing layer (z: routing index).
struct LayerPoint {
  int z = 0;
  Point at;  // DBU
};

// A pin's contact: routing that has a vertex or a centre line at `at` on layer z joins pin `pin`
// (an index into the net's pins, 0..pinCount-1). The access points are where routes join pins.
struct PinContact {
  int32_t pin = 0;
  LayerPoint point;
};

// What keptConductors places: a pin (pin >= 0, an index into the net's pins) or a point (pin < 0).
struct ConductorQuery {
  int32_t pin = -1;
  LayerPoint point;
};

// Per query, the conductor of a net's `kept` routing (its routing outside a region) and pins that
// it lies on; equal ids are one conductor, -1 is none. Joins are read from the routing's centre
// lines, as routes are made: a wire's end or a via on another piece's centre line (same layer), a
// piece through a pin contact. Metal that merely overlaps joins nothing here: a region that
// reroutes that metal later keeps only its own terminals joined, and could take such a join away.
std::vector<int32_t> keptConductors(const Tech& tech, const Design& design, int32_t pins, const NetRouting& kept,
                                    const std::vector<PinContact>& contacts,
                                    const std::vector<ConductorQuery>& queries);

// True when some piece of `routing` lies inside the closed box.
bool routingTouches(const NetRouting& routing, const Rect& box);

}  // namespace xroute
