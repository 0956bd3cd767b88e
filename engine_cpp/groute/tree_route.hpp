// Routing one net on the 2D graph. A net's route is the sorted set of 2D
// edges its tree uses (see graph2d.hpp); its own edges cost nothing to reuse.
//  - patternRoute: a minimum spanning tree over the pin GCells (Prim,
//    Manhattan distance, ties to the lower GCell index), each tree edge as
//    the cheapest of its two L shapes and its Z shapes (one bend column or
//    row anywhere between the ends).
//  - mazeRoute: grows a Steiner tree from the first pin GCell, each time
//    joining the pin GCell nearest to the tree in cost (Dijkstra from every
//    tree node at once) by that cheapest path, inside the pins' bounding box
//    grown by `margin` GCells.
// Both are deterministic: equal costs go to the first candidate in a fixed order.
#pragma once

#include <cstdint>
#include <vector>

#include "groute/graph2d.hpp"

namespace xroute {

// Reusable buffers for mazeRoute (one per thread of work).
struct MazeScratch {
  std::vector<double> dist;
  std::vector<int32_t> from;     // predecessor cell, -1 = a source
  std::vector<uint32_t> stamp;   // dist/from valid when stamp == round
  std::vector<uint8_t> inTree;
  uint32_t round = 0;
};

std::vector<int32_t> patternRoute(const Graph2d& g, const std::vector<int32_t>& pins, double presentFactor);

std::vector<int32_t> mazeRoute(const Graph2d& g, const std::vector<int32_t>& pins, double presentFactor, int margin,
                               MazeScratch& scratch);

}  // namespace xroute
