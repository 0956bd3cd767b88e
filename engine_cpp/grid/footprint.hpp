// How shapes make grid nodes costly. A shape on routing layer z claims the
// nodes where a default-width wire (or the metal of a via landing there)
// would come closer to it than the layer's spacing rules allow; a cut claims
// the nodes where another via's cut would be too close. Fixed shapes (pins,
// obstructions, special nets) go into the fixed owner fields, routed shapes
// into the use counters. The net of the shape (-1 = obstruction) is recorded
// so that a net is never charged for its own metal.
#pragma once

#include <vector>

#include "db/tech.hpp"
#include "grid/region_grid.hpp"
#include "grid/via_set.hpp"

namespace xroute {

struct FootprintRules {
  const Tech* tech = nullptr;
  std::vector<const Layer*> layers;  // per z
  std::vector<Dbu> wireHalf;         // DBU, half the default wire width, per z
  std::vector<Rect> viaLanding;      // DBU, union of via metal on z (from below and above), per z
  std::vector<Rect> cutRect;         // DBU, cut of the via z -> z+1, per z (last unused)
  std::vector<Dbu> cutSpacing;       // DBU, smallest plain cut spacing of cut z -> z+1 (0 = none)
  std::vector<Dbu> eolSpace;         // DBU, largest end-of-line spacing of layer z (0 = no EOL rule)
  std::vector<Dbu> eolWithin;        // DBU, its sideways reach
  std::vector<uint8_t> horizontal;   // per z: preferred direction
};

FootprintRules makeFootprintRules(const Tech& tech, const TrackSet& tracks, const ViaSet& vias);

// Metal `r` on routing layer z owned by `net` (-1 = obstruction).
void markMetal(RegionGrid& grid, const FootprintRules& rules, int z, const Rect& r, int32_t net, bool fixed);
// A cut `r` on the cut layer between z and z+1, owned by `net`.
void markCut(RegionGrid& grid, const FootprintRules& rules, int z, const Rect& r, int32_t net);

}  // namespace xroute
