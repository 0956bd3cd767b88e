// How bad a minimum-area patch would be where it is placed: the score
// route/min_area_fix minimises over a piece's candidate patches.
#pragma once

#include <cstdint>

#include "grid/region_grid.hpp"
#include "region/region_marks.hpp"
#include "region/route_context.hpp"

namespace xroute {

// The score of a patch `r` of `net` on routing layer z (RepairScore): 1000
// and more when it would break a spacing rule with another net's metal
// (fixed shapes, and `metal`: the routed metal marked in the region's grid),
// small sums for metal merely near it or other nets' access points in `g`.
int64_t patchScore(const RouteContext& ctx, const RegionGrid& g, const RoutedMetal& metal, int32_t net, int z,
                   const Rect& r);

// Whether other nets' routed metal (`metal`) on layer z breaks a spacing rule with `r` of `net`
// (as patchScore judges it; fixed shapes not counted).
bool breaksRoutedMetal(const RouteContext& ctx, const RoutedMetal& metal, int32_t net, int z, const Rect& r);

}  // namespace xroute
