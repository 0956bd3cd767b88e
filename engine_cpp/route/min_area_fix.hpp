// Minimum-area repair of freshly routed metal: a piece of a net's new
// routing on one layer (wires and via metal that touch) whose area is below
// the layer's AREA gets a wire along the preferred direction, long enough to
// reach it. Pieces touching one of the net's anchors (pin access points,
// boundary terminals: pin metal or routing outside adds area) are left alone.
#pragma once

#include <utility>
#include <vector>

#include "db/design.hpp"
#include "grid/tracks.hpp"

namespace xroute {

struct MetalAnchor {
  Point at;   // DBU
  int z = 0;  // routing index
};

// Appends the repair wires to `added.wires`; returns how many it added.
int fixMinArea(const Tech& tech, const Design& design, const TrackSet& tracks, const Rect& box,
               const std::vector<MetalAnchor>& anchors, NetRouting& added);

// Area of the union of rects (DBU^2).
Area unionArea(const std::vector<Rect>& rects);

}  // namespace xroute
