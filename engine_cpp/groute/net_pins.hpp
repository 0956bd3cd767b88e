// Net decomposition, step 1: each pin of a net becomes GCells. A pin's
// anchor is the GCell holding the centre of its largest routing-layer shape
// (where the net's tree attaches); its cover is every GCell its shapes touch
// on its lowest routing layer (those get guides, so the detailed router may
// reach the pin from any side).
#pragma once

#include <cstdint>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"
#include "groute/capacity.hpp"

namespace xroute {

struct GrPin {
  int32_t anchor = -1;           // GCell index (y*nx + x)
  int z = 0;                     // routing index of the pin's lowest routing layer
  std::vector<int32_t> cover;    // GCell indices, sorted unique (anchor included)
};

struct GrNet {
  int32_t net = -1;              // design net id
  std::vector<GrPin> pins;       // pins with at least one routing-layer shape, in net pin order
  std::vector<int32_t> anchors;  // distinct anchor GCells, sorted
};

// One GrNet per design net (index = net id). Pins without routing-layer
// shapes (unplaced, or only on cut/masterslice layers) are left out.
std::vector<GrNet> collectGrNets(const Tech& tech, const Design& design, const GrGrid& grid);

}  // namespace xroute
