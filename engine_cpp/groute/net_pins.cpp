#include "groute/net_pins.hpp"

#include <algorithm>

namespace xroute {

std::vector<GrNet> collectGrNets(const Tech& tech, const Design& design, const GrGrid& grid) {
  std::vector<GrNet> nets(design.nets.size());
  for (size_t n = 0; n < design.nets.size(); ++n) {
    GrNet& gn = nets[n];
    gn.net = static_cast<int32_t>(n);
    const std::vector<PlacedShape> shapes = netPinShapes(tech, design, NetId(static_cast<int32_t>(n)));
    size_t i = 0;
    while (i < shapes.size()) {
      size_t j = i;
      while (j < shapes.size() && shapes[j].pinRef == shapes[i].pinRef) ++j;
      // Shapes [i, j) belong to one pin.
      GrPin pin;
      pin.z = 1 << 20;
      Area bestArea = -1;
      Rect best;
      for (size_t k = i; k < j; ++k) {
        const int z = tech.layer(shapes[k].layer).routingIndex;
        if (z < 0) continue;
        if (z < pin.z) {
          pin.z = z;
          bestArea = -1;
        }
        if (z == pin.z && shapes[k].rect.area() > bestArea) {
          bestArea = shapes[k].rect.area();
          best = shapes[k].rect;
        }
      }
      if (bestArea >= 0) {
        pin.anchor = grid.cell(grid.gcellX((best.xlo + best.xhi) / 2), grid.gcellY((best.ylo + best.yhi) / 2));
        for (size_t k = i; k < j; ++k) {
          if (tech.layer(shapes[k].layer).routingIndex != pin.z) continue;
          const Rect& r = shapes[k].rect;
          for (int y = grid.gcellY(r.ylo); y <= grid.gcellY(r.yhi); ++y) {
            for (int x = grid.gcellX(r.xlo); x <= grid.gcellX(r.xhi); ++x) pin.cover.push_back(grid.cell(x, y));
          }
        }
        pin.cover.push_back(pin.anchor);
        std::sort(pin.cover.begin(), pin.cover.end());
        pin.cover.erase(std::unique(pin.cover.begin(), pin.cover.end()), pin.cover.end());
        gn.anchors.push_back(pin.anchor);
        gn.pins.push_back(std::move(pin));
      }
      i = j;
    }
    std::sort(gn.anchors.begin(), gn.anchors.end());
    gn.anchors.erase(std::unique(gn.anchors.begin(), gn.anchors.end()), gn.anchors.end());
  }
  return nets;
}

}  // namespace xroute
