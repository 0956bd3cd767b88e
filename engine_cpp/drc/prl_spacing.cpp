// Metal spacing between shapes of different nets (or a net and an
// obstruction) that do not touch.
//
// SPACINGTABLE PARALLELRUNLENGTH (LEF 5.8): take the larger of the two widths
// (width = the smaller side of a rect; an obstruction counts as min-width
// under USEMINSPACING OBS ON); the row is the last one whose WIDTH is
// strictly smaller than that width (the first row otherwise); the column is
// the last one whose PARALLELRUNLENGTH is strictly smaller than the parallel
// run length (the first column otherwise). Shapes whose projections overlap
// on neither axis have a negative run length (minus the smaller gap) and are
// measured corner to corner (Euclidean, or MAXXY). Without a table, plain
// "SPACING s" applies to all pairs and "SPACING s RANGE lo hi" when either
// width lies in [lo, hi]; SAMENET rules are not checked (same-net metal is
// never checked for spacing). Marker box: the gap between the two rects.
#include <algorithm>

#include "drc/layer_shapes.hpp"
#include "geom/polygon.hpp"

namespace xroute::drc {

namespace {

Dbu tableSpacing(const PrlSpacingTable& t, Dbu width, Dbu prl) {
  size_t row = 0, col = 0;
  for (size_t i = 1; i < t.widths.size(); ++i)
    if (width > t.widths[i]) row = i;
  for (size_t j = 1; j < t.prls.size(); ++j)
    if (prl > t.prls[j]) col = j;
  return t.at(row, col);
}

Dbu layerSpacing(const Layer& l, Dbu w1, Dbu w2, Dbu prl) {
  if (!l.prlTable.empty() && !l.prlTable.prls.empty()) return tableSpacing(l.prlTable, std::max(w1, w2), prl);
  Dbu s = 0;
  for (const SpacingRule& r : l.spacings) {
    if (r.sameNet) continue;
    const bool applies = !r.hasRange || (w1 >= r.rangeLo && w1 <= r.rangeHi) || (w2 >= r.rangeLo && w2 <= r.rangeHi);
    if (applies) s = std::max(s, r.space);
  }
  return s;
}

}  // namespace


void checkPrlSpacing(const LayerShapes& ls, const DrcOptions& options, MarkerSink& out) {
  const Layer& l = *ls.rules;
  Dbu maxSpace = 0;
  for (Dbu s : l.prlTable.spacing) maxSpace = std::max(maxSpace, s);
  for (const SpacingRule& r : l.spacings)
    if (!r.sameNet) maxSpace = std::max(maxSpace, r.space);
  // A NONDEFAULTRULE's SPACING: the gap its net's routing needs on this layer, whichever net is beside
  // it; not around the net's pins (fixed) nor its tapered routing (DrcOptions::ndrSpacing).
  const std::vector<Dbu>* ndr = size_t(*ls.layer) < options.ndrSpacing.size() && !options.ndrSpacing[*ls.layer].empty()
                                    ? &options.ndrSpacing[*ls.layer]
                                    : nullptr;
  // Per shape: the rule's gap (0: none). Routing that lies wholly on the net's own pins adds no
  // metal to them: OpenROAD's checker judges the union of a net's metal by its maximal rectangles,
  // and those of a pin with a via pad inside it are the pin's own (fixed) ones.
  std::vector<Dbu> ndrNeed;
  if (ndr != nullptr) {
    ndrNeed.assign(ls.size(), 0);
    std::vector<Rect> left, next;
    for (size_t i = 0; i < ls.size(); ++i) {
      const int32_t n = ls.nets[i];
      if (n < 0 || size_t(n) >= ndr->size() || (*ndr)[n] <= 0 || ls.fixed[i] || ls.taper[i]) continue;
      left.assign(1, ls.rects[i]);
      ls.index.query(ls.rects[i], [&](int32_t j) {
        if (left.empty() || ls.nets[j] != n || !ls.fixed[j]) return;
        next.clear();
        for (const Rect& r : left) subtractRect(r, ls.rects[j], next);
        left.swap(next);
      });
      if (!left.empty()) ndrNeed[i] = (*ndr)[n];
    }
    maxSpace = std::max(maxSpace, *std::max_element(ndr->begin(), ndr->end()));
  }
  auto ndrOf = [&](int32_t i) { return ndrNeed.empty() ? Dbu(0) : ndrNeed[i]; };
  if (maxSpace <= 0) return;
  const Dbu minWidth = l.minWidth > 0 ? l.minWidth : l.width;

  auto widthOf = [&](int32_t i) {
    if (ls.isObs(i) && options.obsAsMinWidth) return minWidth;
    return ls.rects[i].minSide();
  };

  for (size_t i = 0; i < ls.size(); ++i) {
    if (!ls.seed[i]) continue;
    const int32_t a = int32_t(i);
    const Rect& ra = ls.rects[a];
    ls.index.queryExcept(expanded(ra, maxSpace), ls.nets[a], [&](int32_t b) {  // same net never conflicts
      if (b == a || (ls.seed[b] && b < a) || !ls.conflicting(a, b)) return;
      const Rect& rb = ls.rects[b];
      const Dbu dx = gapX(ra, rb), dy = gapY(ra, rb);
      if (dx == 0 && dy == 0) return;  // touching or overlapping: a short
      const Dbu overlapX = std::min(ra.xhi, rb.xhi) - std::max(ra.xlo, rb.xlo);
      const Dbu overlapY = std::min(ra.yhi, rb.yhi) - std::max(ra.ylo, rb.ylo);
      const Dbu prl = std::max(overlapX, overlapY);
      const Dbu need = std::max({layerSpacing(l, widthOf(a), widthOf(b), prl), ndrOf(a), ndrOf(b)});
      if (closerThan(dx, dy, need, ls.euclidean)) addPairMarker(out, ls, MarkerType::MetalSpacing, gapBox(ra, rb), a, b);
    });
  }
}

}  // namespace xroute::drc

namespace xroute {

Dbu requiredSpacing(const Layer& layer, Dbu w1, Dbu w2, Dbu prl) { return drc::layerSpacing(layer, w1, w2, prl); }

}  // namespace xroute
