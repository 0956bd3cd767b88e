// The GCell grid's partition into routing regions of C x C GCells, coloured so that regions of one
// colour never touch, and the default region size.
#pragma once

#include <vector>

#include "db/design.hpp"
#include "grid/gcell_grid.hpp"
#include "grid/tracks.hpp"
#include "pa/pin_access.hpp"
#include "region/region.hpp"

namespace xroute {

// The default region (RouterSettings::regionSize 0): kRegionGCells GCells a side, or more while the
// grids of most regions stay within kRegionGridNodes nodes a layer. A region's grid has a line at
// every track of every layer and at every terminal in it, so its memory and the maze's work follow
// its tracks and pins, not its GCells; larger regions cut fewer nets. loop/README.md has the
// measurement (15 GCells on ispd18_test1, 16 on ispd19_test1, 10 on ispd19_test3).
inline constexpr int kRegionGCells = 10;
inline constexpr double kRegionGridNodes = 90000;
// Where kRegionGCells' grids are over the budget (fine tracks over large GCells: OpenROAD's gcd on
// asap7 and on sky130hs, 234,304 and 216,361 nodes a layer), the default shrinks to the largest size
// within it, down to kLeastRegionGCells.
inline constexpr int kLeastRegionGCells = 5;

// The upper quartile over the regions of `size` GCells a side (offset 0) that hold a terminal of a
// region's grid nodes a layer: the lines in x times those in y, at its edges, every layer's tracks
// and the `terminals` (access points) in it (regionGridLines). 0 when no region holds one.
double regionGridNodes(const GCellGrid& grid, const TrackSet& tracks, const std::vector<AccessPoint>& terminals,
                       int size);

// GCells per region side of the default region: from kRegionGCells up while the next size's
// regionGridNodes stays within kRegionGridNodes and the region does not yet cover the die; or, when
// kRegionGCells' is over it, down while it is, to kLeastRegionGCells; in 1..maxSize.
int autoRegionSize(const GCellGrid& grid, const TrackSet& tracks, const std::vector<AccessPoint>& terminals,
                   int maxSize);

// Regions of `size` GCells, the first column/row shortened by `offset`
// (0 <= offset < size) so that the boundaries shift between iterations.
std::vector<Region> partitionRegions(const GCellGrid& grid, int size, int offset);

// The region containing point p (half-open: the low edge belongs to a region).
int32_t regionAt(const std::vector<Region>& regions, const GCellGrid& grid, int size, int offset, Point p);

}  // namespace xroute
