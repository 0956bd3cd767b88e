// Layer assignment: each net's 2D tree is cut into straight segments (at
// bends, branches and ends), and each segment goes to one layer of its
// direction. Nets go in the given order; a net's segments go outward from
// its first pin (breadth-first). A segment's layer minimises
//   overflowCost x (edges where the layer is already full, at capacityPercent
//   of its free tracks) + congestionCost x (sum over its edges of usage /
//   capacity) + viaCost x (layers between it and what is already attached at
//   its two ends),
// ties to the lowest layer: short segments stay low, long ones rise to
// emptier layers when that saves more than the vias cost. Layers below
// `minLayer` carry no segment.
#pragma once

#include <cstdint>
#include <vector>

#include "groute/capacity.hpp"
#include "groute/net_pins.hpp"

namespace xroute {

struct GrSegment {
  int32_t a = -1, b = -1;  // GCell indices of the ends (a below/left of b)
  bool horizontal = true;
  int z = 0;               // routing index
};

struct LayerAssignSettings {
  int minLayer = 1;          // routing index
  int64_t viaCost = 2;       // cost units per layer crossed
  double congestionCost = 0; // cost units per edge at full use (scaled by usage / capacity)
  int64_t overflowCost = 50; // cost units per full edge
  int capacityPercent = 100; // a layer edge counts as full at this share of its free tracks, percent
};

struct LayerAssignment {
  std::vector<std::vector<GrSegment>> segments;  // per net (index = net id)
  int64_t overflow = 0;                          // sum over layer edges of max(0, usage - capacity), tracks
};

// routes[n]: net n's 2D edges (graph2d edge ids); order: the nets to assign, in order.
LayerAssignment assignLayers(const GrGrid& grid, const std::vector<GrNet>& nets,
                             const std::vector<std::vector<int32_t>>& routes, const std::vector<int32_t>& order,
                             const LayerAssignSettings& settings);

}  // namespace xroute
