// Minimum-area repair of freshly routed metal: a piece of a net's new
// routing on one layer (wires and via metal that touch) whose area is below
// the layer's AREA gets a patch of wire width along the preferred direction
// (or across it, where that conflicts less), long enough to reach it; where
// every such patch meets another net's metal, a thicker and shorter one or
// one off the wire's centre line (still along the preferred direction). Pin
// metal of the net joins the pieces it touches and counts in their area;
// pieces touching an anchor (a boundary terminal: the routing outside adds
// area) are left alone.
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include "db/design.hpp"
#include "grid/tracks.hpp"

namespace xroute {

struct MetalAnchor {
  Point at;   // DBU
  int z = 0;  // routing index
};

// Appends the repairs to `added.patches` (metal patches, as DEF RECTs: they
// are not wires and do not count as wirelength); returns how many it added.
struct PinMetal {
  int z = 0;   // routing index
  Rect rect;   // DBU
};

// How bad a repair rect on layer z would be (0 = harmless, >= 1000 = it
// would meet another net's metal: then no repair is made); the repair picks
// the least bad of a few placements (along and across the preferred
// direction, centred or shifted; then thicker or off-centre ones).
using RepairScore = std::function<int64_t(int z, const Rect& rect)>;

int fixMinArea(const Tech& tech, const Design& design, const TrackSet& tracks, const Rect& box,
               const std::vector<MetalAnchor>& anchors, const std::vector<PinMetal>& pins, const RepairScore& score,
               NetRouting& added);

// Area of the union of rects (DBU^2).
Area unionArea(const std::vector<Rect>& rects);

}  // namespace xroute
