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

// True when some piece of `routing` lies inside the closed box.
bool routingTouches(const NetRouting& routing, const Rect& box);

}  // namespace xroute
