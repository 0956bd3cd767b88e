// The GCell grid: the global routing cells' boundaries, shared by the global router (groute/) and
// the detailed router's regions (loop/regions.hpp).
#pragma once

#include <vector>

#include "db/design.hpp"
#include "grid/tracks.hpp"

namespace xroute {

// GCell boundaries along x and y (DBU, sorted, first = die low edge, last =
// die high edge): from DEF GCELLGRID, else a regular grid at the guides' most
// common size, else every 15 pitches of the lowest layer with tracks in that
// direction.
struct GCellGrid {
  std::vector<Dbu> xs;
  std::vector<Dbu> ys;
  int nx() const { return static_cast<int>(xs.size()) - 1; }
  int ny() const { return static_cast<int>(ys.size()) - 1; }
};

GCellGrid makeGCellGrid(const Design& design, const TrackSet& tracks);

}  // namespace xroute
