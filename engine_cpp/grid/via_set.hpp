// The vias the router places: for each cut between routing layers z and
// z+1, one LEF via chosen once (DEFAULT vias first, metal oriented along
// each layer's preferred direction, then the smallest metal), with the
// extents of its metal on both layers.
#pragma once

#include <vector>

#include "db/tech.hpp"
#include "grid/tracks.hpp"

namespace xroute {

struct CutVia {
  ViaId via;         // LEF via for the cut between z and z+1
  Rect bottomMetal;  // DBU, relative to the via origin, on layer z (bounding box)
  Rect topMetal;     // DBU, on layer z+1
  Rect cut;          // DBU, on the cut layer (bounding box)
};

struct ViaSet {
  std::vector<CutVia> cuts;  // index z: the via from routing layer z to z+1 (size layers-1)
};

// Throws InputError (naming the LEF) when a pair of adjacent routing layers
// has no via at all.
ViaSet chooseVias(const Tech& tech, const TrackSet& tracks);

// Bounding box of a via's shapes on `layer`, relative to its origin ({0,0,0,0} if none).
Rect viaMetal(const Tech& tech, const Via& via, LayerId layer);

}  // namespace xroute
