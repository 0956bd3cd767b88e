// The GCell grid and its partition into routing regions of C x C GCells.
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

// The default region (RouterSettings::regionSize 0): kRegionGCells GCells a side, widened to span
// kRegionTracks tracks where GCells are small. 10 GCells of ispd18_test1's GCells (15 tracks each)
// measured best there; ispd19_test1's GCells span 10 tracks, and its regions of 10 GCells left
// wirelength and vias that regions of 150 tracks do not. A region's grid grows with its tracks, so
// the region is not widened in GCells of more tracks. flow/README.md has the measurement.
inline constexpr int kRegionGCells = 10;
inline constexpr int kRegionTracks = 150;

// GCells per region side of the default region: kRegionTracks over the tracks a GCell spans (per axis
// the median GCell side over the median pitch of the layers whose tracks cross it, averaged over x
// and y), rounded, and at least kRegionGCells; in 1..maxSize.
int autoRegionSize(const GCellGrid& grid, const TrackSet& tracks, int maxSize);

struct Region {
  int32_t id = 0;
  int gx0 = 0, gy0 = 0, gx1 = 0, gy1 = 0;  // GCell index range [gx0, gx1) x [gy0, gy1)
  int rx = 0, ry = 0;                      // region column and row
  Rect box;                                // DBU, closed
  int color = 0;                           // 0..3: regions of one colour never touch
};

// Regions of `size` GCells, the first column/row shortened by `offset`
// (0 <= offset < size) so that the boundaries shift between iterations.
std::vector<Region> partitionRegions(const GCellGrid& grid, int size, int offset);

// The region containing point p (half-open: the low edge belongs to a region).
int32_t regionAt(const std::vector<Region>& regions, const GCellGrid& grid, int size, int offset, Point p);

}  // namespace xroute
