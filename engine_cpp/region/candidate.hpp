// What a region tells its caller about itself and its candidate nets: the features a net-order
// policy (order/policy.hpp) orders the nets by, one row per net.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geom/geom.hpp"

namespace xroute {

// Which region, of which iteration, a net-order policy orders.
struct RegionInfo {
  int32_t iteration = 0;
  int32_t regionId = 0;
  Rect box;  // DBU
};

// What a region tells about one of its candidate nets (what a net-order policy sees of it).
struct NetCandidate {
  int32_t net = -1;          // net id
  int32_t pins = 0;          // pins of the net inside the region
  int32_t terminals = 0;     // all terminals (pins + boundary crossings)
  int32_t accessPoints = 0;  // terminal nodes in the grid
  Rect bbox;                 // DBU, bounding box of the terminal nodes
  int32_t netPins = 0;       // pins of the whole net
  int32_t crossings = 0;     // terminals on the region edge (boundary cuts and planned crossings)
  Rect guide;                // DBU, bounding box of the net's guides clipped to the region (the box: no guide there)
  int32_t routedNearby = 0;  // updated state: grid nodes (all layers) in `bbox` that routing of this region
                             // already uses (other nets' new routing); 0 until nets are routed
};

// The candidates as a flat row-major table, one row of kFeatureCount int32
// per candidate, columns named by kFeatureColumns (what Python policies see).
// New columns go at the end: Python policies read them by name, old ones keep their place.
inline constexpr const char* kFeatureColumns[] = {
    "net",       "pins",      "terminals", "access_points", "bbox_xlo",  "bbox_ylo",     "bbox_xhi", "bbox_yhi",
    "net_pins",  "crossings", "guide_xlo", "guide_ylo",     "guide_xhi", "guide_yhi", "routed_nearby"};
inline constexpr size_t kFeatureCount = sizeof(kFeatureColumns) / sizeof(kFeatureColumns[0]);
std::vector<int32_t> featureRows(const std::vector<NetCandidate>& candidates);

}  // namespace xroute
