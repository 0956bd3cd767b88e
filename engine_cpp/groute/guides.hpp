// Turning a layer-assigned net into route guides (ISPD guide rows), and the
// guides into text or into the Design. Per net:
//  - each segment: the GCells from one end to the other on its layer;
//  - each node where segments meet or a pin sits: that GCell on every layer
//    from the lowest to the highest one attached there (the via stack); a
//    pin counts its own layer and the one above (a pin on M1 gets M1 and M2);
//  - each GCell a pin's shapes touch: the pin's layer and the one above;
// every rectangle grown by `slack` GCells on each side (clipped to the die).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "db/design.hpp"
#include "db/tech.hpp"
#include "groute/capacity.hpp"
#include "groute/layer_assign.hpp"
#include "groute/net_pins.hpp"

namespace xroute {

struct GuideSet {
  std::vector<int32_t> start;   // per net + 1: net n owns rows [start[n], start[n+1])
  std::vector<Rect> rects;      // DBU
  std::vector<LayerId> layers;  // routing layers
  int64_t vias = 0;             // layer changes the guides imply (via-stack heights, from pin layers)
};

GuideSet makeGuides(const GrGrid& grid, const std::vector<GrNet>& nets, const LayerAssignment& la, int slack);

// Replaces the design's guides with `g`.
void installGuides(Design& design, const GuideSet& g);

// The guides in the ISPD guide format (nets with guides only, in net order).
std::string guideText(const Tech& tech, const Design& design, const GuideSet& g);

}  // namespace xroute
