// How shapes make grid nodes costly. A shape on routing layer z claims the
// nodes where a default-width wire (or the metal of a via landing there)
// would come closer to it than the layer's spacing rules allow (or the
// NONDEFAULTRULE spacing of the shape's net, when larger); a cut claims
// the nodes where another via's cut would be too close. Fixed shapes (pins,
// obstructions, special nets) go into the fixed owner fields, routed shapes
// into the use counters. The net of the shape (-1 = obstruction) is recorded
// so that a net is never charged for its own metal. metalReach is the same
// reach for a wire of any width (a NONDEFAULTRULE net's, judged by the flow).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "db/tech.hpp"
#include "grid/region_grid.hpp"
#include "grid/via_set.hpp"

namespace xroute {

struct FootprintRules {
  const Tech* tech = nullptr;
  std::vector<const Layer*> layers;  // per z
  std::vector<Dbu> wireHalf;         // DBU, half the default wire width, per z
  std::vector<Rect> viaLanding;      // DBU, union of via metal on z (from below and above), per z
  std::vector<Rect> cutRect;         // DBU, cut of the via z -> z+1, per z (last unused)
  std::vector<Dbu> cutSpacing;       // DBU, smallest plain cut spacing of cut z -> z+1 (0 = none)
  std::vector<Dbu> eolSpace;         // DBU, largest end-of-line spacing of layer z (0 = no EOL rule)
  std::vector<Dbu> eolWithin;        // DBU, its sideways reach
  std::vector<Dbu> eolWidth;         // DBU, largest line-end width of layer z's EOL rules
  std::vector<uint8_t> horizontal;   // per z: preferred direction
};

FootprintRules makeFootprintRules(const Tech& tech, const TrackSet& tracks, const ViaSet& vias);

// The ends of a rect across its layer's preferred direction (left and right on a vertical
// layer, bottom and top on a horizontal one) that no other metal of its net continues: where a
// wrong-way stub or a patch across the tracks ends in a line end. Bit set = open.
enum CrossEnd : uint8_t { kCrossLow = 1, kCrossHigh = 2 };
// `r`'s open cross ends among `others`, the other rects of its net on the same layer (DBU):
// an end is closed by a rect that overlaps `r` and covers the end's edge or continues it.
uint8_t openCrossEnds(const Rect& r, bool horizontal, const std::vector<Rect>& others);
// Whether `r` on routing layer z can have line ends across the tracks at all: the layer has an
// end-of-line rule and `r` is narrower across than its EOL width.
bool narrowAcross(const FootprintRules& rules, int z, const Rect& r);

// Where metal `r` on routing layer z forbids a wire `half` wide through a node (wire: its line
// end, its side, its end of line, the end of line of `r`'s open cross ends) and a via's landing
// metal at a node (via: beside, end of line, cross ends), DBU; an unused rect is empty.
// minSpace (a NONDEFAULTRULE's SPACING of either net; 0 = none) raises the layer's spacing;
// landing: the via metal landing on z relative to the via origin (nullptr: rules.viaLanding[z]);
// crossEnds: CrossEnd bits of `r` (0: its cross ends are not modelled).
struct MetalReach {
  std::array<Rect, 4> wire;
  std::array<Rect, 3> via;
};
MetalReach metalReach(const FootprintRules& rules, int z, const Rect& r, Dbu half, Dbu minSpace = 0,
                      const Rect* landing = nullptr, uint8_t crossEnds = 0);
// Each node of layer z inside the reach: fn(node, false) once for the wire rects, fn(node, true)
// once for the via rects.
void forMetalReach(const RegionGrid& grid, const MetalReach& reach, int z,
                   const std::function<void(int32_t, bool)>& fn);

// Metal `r` on routing layer z owned by `net` (-1 = obstruction), marked for default-width
// wires; minSpace: the owner's NONDEFAULTRULE spacing on the layer (0 = none); crossEnds: as
// metalReach (routed metal only: a pin's short sides mostly lie inside its outline).
void markMetal(RegionGrid& grid, const FootprintRules& rules, int z, const Rect& r, int32_t net, bool fixed,
               Dbu minSpace = 0, uint8_t crossEnds = 0);
// A cut `r` on the cut layer between z and z+1, owned by `net`.
void markCut(RegionGrid& grid, const FootprintRules& rules, int z, const Rect& r, int32_t net);

}  // namespace xroute
