// Routing tracks per routing layer, from DEF TRACKS. A layer's preferred
// tracks carry its wires: for a HORIZONTAL layer they are the y coordinates
// of its "TRACKS Y" lines, for a VERTICAL layer the x coordinates of its
// "TRACKS X" lines. Its cross tracks are the other axis (where vias and
// crossing wires land).
#pragma once

#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"

namespace xroute {

struct LayerTracks {
  LayerId layer;
  bool horizontal = true;     // preferred direction
  std::vector<Dbu> pref;      // DBU, sorted unique: y of tracks if horizontal, else x
  std::vector<Dbu> cross;     // DBU, sorted unique: the other axis
  Dbu wireWidth = 0;          // DBU, default wire width
  Dbu pitch = 0;              // DBU, smallest step between pref tracks (0 if < 2 tracks)
};

struct TrackSet {
  std::vector<LayerTracks> layers;  // indexed by routing index (z)
};

// Builds the track set; throws InputError (on the DEF) when a routing layer
// has no tracks at all in its preferred direction.
TrackSet buildTracks(const Tech& tech, const Design& design);

// Sorted coordinates of `tracks` inside [lo, hi].
std::vector<Dbu> tracksIn(const std::vector<Dbu>& tracks, Dbu lo, Dbu hi);

// True when `v` is one of the sorted `tracks`.
bool onTrack(const std::vector<Dbu>& tracks, Dbu v);

}  // namespace xroute
