// Quick pairwise judgements of two rects on one layer, for the router's own
// decisions (minimum-area patches, access vias among neighbouring cells):
// what the checker (drc/) would ask of them, read without merging conductors,
// so erring towards more spacing (corner gaps by the larger axis gap, any
// short rect side a possible line end).
#pragma once

#include <algorithm>

#include "db/tech.hpp"
#include "drc/drc.hpp"
#include "drc/layer_shapes.hpp"

namespace xroute::drc {

// Distance between two rects (0 when they touch or overlap): the larger of the
// axis gaps, which is never more than the checker's Euclidean corner distance.
inline Dbu rectGap(const Rect& a, const Rect& b) { return std::max(gapX(a, b), gapY(a, b)); }

// Parallel run length of two rects: their overlap along the axis where they
// face each other (0 when they only face diagonally).
inline Dbu runLength(const Rect& a, const Rect& b) {
  const Dbu dx = gapX(a, b), dy = gapY(a, b);
  if (dx > 0 && dy > 0) return 0;
  return dx > 0 ? std::min(a.yhi, b.yhi) - std::max(a.ylo, b.ylo) : std::min(a.xhi, b.xhi) - std::max(a.xlo, b.xlo);
}

// The end-of-line spacing `b` needs from `a` (0 if none): b lies beyond an
// edge of `a` shorter than a rule's eolWidth, within the rule's reach of the
// edge's ends. PARALLELEDGE conditions are taken as met.
inline Dbu eolNeed(const Layer& layer, const Rect& a, const Rect& b) {
  Dbu need = 0;
  for (const EolRule& e : layer.eolRules) {
    const bool pastX = (b.xlo >= a.xhi || b.xhi <= a.xlo) && b.ylo < a.yhi + e.within && b.yhi > a.ylo - e.within;
    const bool pastY = (b.ylo >= a.yhi || b.yhi <= a.ylo) && b.xlo < a.xhi + e.within && b.xhi > a.xlo - e.within;
    if ((pastX && a.height() < e.eolWidth) || (pastY && a.width() < e.eolWidth)) need = std::max(need, e.space);
  }
  return need;
}

// The spacing two metal rects of different nets need on a routing layer:
// the spacing table by widths and run length, and end-of-line spacing where
// a short side of either faces the other (`aEnds`/`bEnds`: whether that side
// of a / b may be a line end).
inline Dbu metalNeed(const Layer& layer, const Rect& a, const Rect& b, bool aEnds = true, bool bEnds = true) {
  Dbu need = requiredSpacing(layer, a.minSide(), b.minSide(), runLength(a, b));
  if (aEnds) need = std::max(need, eolNeed(layer, a, b));
  if (bEnds) need = std::max(need, eolNeed(layer, b, a));
  return need;
}

}  // namespace xroute::drc
