// A routing region: a block of GCells of one iteration's partition (loop/regions.hpp).
#pragma once

#include <cstdint>

#include "geom/geom.hpp"

namespace xroute {

struct Region {
  int32_t id = 0;
  int gx0 = 0, gy0 = 0, gx1 = 0, gy1 = 0;  // GCell index range [gx0, gx1) x [gy0, gy1)
  int rx = 0, ry = 0;                      // region column and row
  Rect box;                                // DBU, closed
  int color = 0;                           // 0..3: regions of one colour never touch
};

}  // namespace xroute
