// A region routed on its own (a learning environment's episode, a static
// region): every net with pins or routing inside the box, or whose guides
// cross its edges, becomes a candidate. Nets with routing are ripped up
// inside the box (their routing outside gives the boundary terminals);
// unrouted nets get a free crossing on each box edge their guides cross.
#pragma once

#include "region/crossing_plan.hpp"
#include "region/region_router.hpp"
#include "region/route_context.hpp"

namespace xroute {

// Fills `plan` with the free crossings the task refers to (regionA / regionB
// of a crossing name `regionId` on this box's side and -1 outside).
RegionTask makeStandaloneTask(const RouteContext& ctx, const Rect& box, int32_t regionId, int32_t iteration,
                              const MazeCosts& costs, CrossingPlan& plan);

}  // namespace xroute
