// The crossings of iteration 0's plan (loop/crossings.hpp makes it): where each net passes from
// one region to its neighbour, and per region the parts of each net that route there. A region's
// router reads the crossings that touch it and reports the point it chose on each.
#pragma once

#include <cstdint>
#include <vector>

#include "geom/geom.hpp"

namespace xroute {

struct Crossing {
  int32_t net = -1;
  int32_t regionA = -1, regionB = -1;  // A left of / below B
  bool vertical = true;                // the shared edge is a vertical line x = coord
  Dbu coord = 0;                       // DBU
  Dbu lo = 0, hi = 0;                  // DBU, span along the edge
  uint32_t layerMask = 0;              // routing layers (bit z) of guides crossing here; 0 = any
  // Where along the edge the net's nearby pins on the far side lie, as seen
  // from region A ([0]) and from region B ([1]): the crossing is best there.
  bool hasWant[2] = {false, false};
  Dbu wantLo[2] = {0, 0}, wantHi[2] = {0, 0};  // DBU
  // Set when the first of the two regions routes the net through it.
  bool chosen = false;
  Point at;                            // DBU
  int z = -1;                          // routing index
};

// What a net routes in one region: its pins there and the crossings of its
// tree that touch the region. A net whose guides pass a region in two
// pieces that its tree does not join there has two parts in that region,
// routed as two trees (the guides join them elsewhere).
struct NetPart {
  int32_t net = -1;
  std::vector<int32_t> pins;       // pinRefs
  std::vector<int32_t> crossings;  // crossing ids
};

struct CrossingPlan {
  std::vector<Crossing> crossings;
  std::vector<std::vector<NetPart>> regionParts;  // region -> parts, by net (ascending)
};

}  // namespace xroute
