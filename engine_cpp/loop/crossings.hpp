// Initial routing (iteration 0) plan: for every net, the regions it must
// pass and the region edges it crosses. The net's guides, clipped to each
// region, fall into connected pieces; guides running across a region edge
// link pieces of neighbouring regions. Pins join the piece of their best
// access point. A Steiner tree over the pieces (the nearest pin piece joins
// by its cheapest path; steps the guides do not make cost more) gives the
// crossings and, per region, the net's parts.
#pragma once

#include <vector>

#include "loop/regions.hpp"
#include "region/crossing_plan.hpp"
#include "region/route_context.hpp"

namespace xroute {

CrossingPlan planCrossings(const RouteContext& ctx, const std::vector<Region>& regions, int size, int offset);

}  // namespace xroute
