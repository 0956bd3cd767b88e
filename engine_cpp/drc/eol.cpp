// End-of-line spacing (LEF "SPACING s ENDOFLINE w WITHIN d [PARALLELEDGE p
// WITHIN q [TWOEDGES]]"), on the merged metal of each same-net component.
//
// A line end is a boundary edge shorter than w whose two corners are convex.
// It needs spacing >= s to any shape of another net (or an obstruction) in
// the window that extends s outward from the edge and d sideways beyond both
// ends (open box: a shape exactly s away, or exactly d to the side, is
// legal). With PARALLELEDGE the rule applies only when some metal other than
// the line's own component lies within p of a side edge (open box from the
// side edge p outward, from q behind the line end to d beyond it); TWOEDGES
// needs such metal on both sides. A shape that touches the line's own metal
// is a short, not an EOL violation. Marker box: the window clipped to the
// offending shape; net1 is the line end's net. The marker counts as fixed
// (input-only) when the line end is carried by fixed rects only and the
// offender is fixed, even if routing has joined the line's conductor.
#include <algorithm>

#include "drc/layer_shapes.hpp"

namespace xroute::drc {

namespace {

// The EOL window of an edge (outward s, sideways d), as an open box.
Rect eolWindow(const Edge& e, Dbu s, Dbu d) {
  switch (e.side) {
    case Side::Top: return {e.lo - d, e.coord, e.hi + d, e.coord + s};
    case Side::Bottom: return {e.lo - d, e.coord - s, e.hi + d, e.coord};
    case Side::Right: return {e.coord, e.lo - d, e.coord + s, e.hi + d};
    case Side::Left: return {e.coord - s, e.lo - d, e.coord, e.hi + d};
  }
  return {};
}

// The PARALLELEDGE search box beside the `low` (or high) end of the edge.
Rect parallelBox(const Edge& e, bool low, const EolRule& r) {
  const Dbu p = r.parSpace, q = r.parWithin, d = r.within;
  switch (e.side) {
    case Side::Top:
      return low ? Rect{e.lo - p, e.coord - q, e.lo, e.coord + d} : Rect{e.hi, e.coord - q, e.hi + p, e.coord + d};
    case Side::Bottom:
      return low ? Rect{e.lo - p, e.coord - d, e.lo, e.coord + q} : Rect{e.hi, e.coord - d, e.hi + p, e.coord + q};
    case Side::Right:
      return low ? Rect{e.coord - q, e.lo - p, e.coord + d, e.lo} : Rect{e.coord - q, e.hi, e.coord + d, e.hi + p};
    case Side::Left:
      return low ? Rect{e.coord - d, e.lo - p, e.coord + q, e.lo} : Rect{e.coord - d, e.hi, e.coord + q, e.hi + p};
  }
  return {};
}

bool hasOtherMetal(const LayerShapes& ls, int32_t c, const Rect& box) {
  bool found = false;
  ls.index.query(box, [&](int32_t j) {
    if (!found && ls.comp[j] != c && overlapsOpen(ls.rects[j], box)) found = true;
  });
  return found;
}

bool touchesComponent(const LayerShapes& ls, int32_t c, const Rect& r) {
  bool found = false;
  ls.index.query(r, [&](int32_t j) { found = found || ls.comp[j] == c; });
  return found;
}

// True when every member rect of component c that carries a piece of edge e
// is fixed: the line end is the input's own (a pin's end), not the router's.
bool edgeFixed(const LayerShapes& ls, int32_t c, const Edge& e) {
  for (int32_t k = ls.compStart[c]; k < ls.compStart[c + 1]; ++k) {
    const int32_t i = ls.compMembers[k];
    const Rect& r = ls.rects[i];
    bool carries = false;
    switch (e.side) {
      case Side::Top: carries = r.yhi == e.coord && r.xlo < e.hi && r.xhi > e.lo; break;
      case Side::Bottom: carries = r.ylo == e.coord && r.xlo < e.hi && r.xhi > e.lo; break;
      case Side::Right: carries = r.xhi == e.coord && r.ylo < e.hi && r.yhi > e.lo; break;
      case Side::Left: carries = r.xlo == e.coord && r.ylo < e.hi && r.yhi > e.lo; break;
    }
    if (carries && !ls.fixed[i]) return false;
  }
  return true;
}

Rect clip(const Rect& a, const Rect& b) {
  return {std::max(a.xlo, b.xlo), std::max(a.ylo, b.ylo), std::min(a.xhi, b.xhi), std::min(a.yhi, b.yhi)};
}

}  // namespace

void checkEndOfLine(const LayerShapes& ls, MarkerSink& out) {
  const std::vector<EolRule>& rules = ls.rules->eolRules;
  if (rules.empty()) return;
  Dbu maxEolWidth = 0;
  for (const EolRule& r : rules) maxEolWidth = std::max(maxEolWidth, r.eolWidth);
  const int32_t comps = int32_t(ls.compStart.size()) - 1;
  for (int32_t c = 0; c < comps; ++c) {
    const int32_t first = ls.compMembers[ls.compStart[c]];
    if (!ls.compSeed[c] || ls.isObs(first)) continue;
    // Only components with some rect side shorter than the widest eolWidth
    // can have a line end.
    bool candidate = false;
    for (int32_t k = ls.compStart[c]; k < ls.compStart[c + 1] && !candidate; ++k) {
      const Rect& r = ls.rects[ls.compMembers[k]];
      candidate = r.minSide() < maxEolWidth;
    }
    if (!candidate) continue;
    for (const Edge& e : componentEdges(ls, c)) {
      if (!e.convexLo || !e.convexHi) continue;
      for (const EolRule& rule : rules) {
        if (e.hi - e.lo >= rule.eolWidth) continue;
        if (rule.parallelEdge) {
          const bool lowSide = hasOtherMetal(ls, c, parallelBox(e, true, rule));
          const bool highSide = hasOtherMetal(ls, c, parallelBox(e, false, rule));
          if (rule.twoEdges ? !(lowSide && highSide) : !(lowSide || highSide)) continue;
        }
        const Rect window = eolWindow(e, rule.space, rule.within);
        const bool fixedEdge = edgeFixed(ls, c, e);
        ls.index.queryExcept(window, ls.nets[first], [&](int32_t j) {  // the same net is not checked
          if (ls.comp[j] == c || !overlapsOpen(ls.rects[j], window)) return;
          if (!ls.isObs(j) && ls.nets[j] == ls.nets[first]) return;  // same net: not checked
          if (touchesComponent(ls, c, ls.rects[j])) return;           // a short
          const int32_t net2 = ls.isObs(j) ? -1 : ls.nets[j];
          out.push_back({Marker{MarkerType::EndOfLine, ls.layer, clip(window, ls.rects[j]), ls.nets[first], net2},
                         fixedEdge && ls.fixed[j]});
        });
      }
    }
  }
}

}  // namespace xroute::drc
