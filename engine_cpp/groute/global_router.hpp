// The built-in global router: guides for a placed design without any.
//   1. grid and capacities (capacity.hpp), pins to GCells (net_pins.hpp);
//   2. every net pattern-routed on the 2D graph (tree_route.hpp), smaller
//      nets first;
//   3. negotiated congestion: while edges overflow (at most `iterations`
//      rounds), overflowed edges gain history cost and every net using one is
//      ripped up and maze-routed again, the present-congestion factor growing
//      each round;
//   4. layer assignment (layer_assign.hpp) and guides (guides.hpp).
// Deterministic: no randomness, every order fixed by sizes and net ids.
#pragma once

#include <cstdint>

#include "db/design.hpp"
#include "db/tech.hpp"
#include "groute/guides.hpp"

namespace xroute {

struct GlobalRouteSettings {
  int iterations = 30;          // rip-up-and-reroute rounds at most
  int capacityPercent = 70;     // share of each edge's free tracks the router may fill, percent
  int minLayer = 1;             // lowest routing index carrying routes (0 = the pin layer M1 too)
  int margin = 10;              // maze search box: pins' bounding box grown by this many GCells
  double presentFactor = 1.0;   // cost per track of overflow in round 1 (x1.5 each round)
  double historyStep = 1.0;     // history added per track of overflow per round
  int64_t viaCost = 2;          // layer assignment: cost of one layer change (in edge units)
  double congestionCost = 0;    // layer assignment: cost of one edge at full use (see layer_assign.hpp)
  int slack = 0;                // GCells each guide rectangle is grown by on every side
};

struct GlobalRouteStats {
  int nx = 0, ny = 0, nz = 0;   // GCells along x, y; routing layers
  int64_t nets = 0;             // nets routed (with >= 2 pin GCells)
  int64_t initialOverflow = 0;  // 2D overflow after pattern routing, tracks
  int64_t overflow = 0;         // 2D overflow at the end, tracks
  int64_t overflowEdges = 0;    // 2D edges over capacity at the end
  int64_t overflow3d = 0;       // overflow per layer after layer assignment, tracks
  int64_t wirelength = 0;       // 2D edges used, summed over nets (GCells)
  int64_t vias = 0;             // via-stack heights (see guides.hpp)
  int64_t guides = 0;           // guide rectangles
  int iterations = 0;           // rip-up rounds run
  int64_t reroutes = 0;         // nets maze-routed, summed over rounds
  double seconds = 0;
};

struct GlobalRouteResult {
  GlobalRouteStats stats;
  GuideSet guides;
};

GlobalRouteResult globalRoute(const Tech& tech, const Design& design, const GlobalRouteSettings& settings);

}  // namespace xroute
