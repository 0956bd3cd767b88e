// Cut spacing (LEF cut layer "SPACING s [CENTERTOCENTER] [SAMENET]
// [ADJACENTCUTS n WITHIN w]").
//
// Plain rules apply to every pair of cuts, same net or not; a SAMENET rule,
// when present, replaces them for same-net pairs. Distance is edge to edge
// (Euclidean, or MAXXY), or centre to centre with CENTERTOCENTER; a pair
// closer than s violates (CutSpacing). Identical same-net cuts are one cut;
// other same-net cuts that overlap are a CutSpacing violation (distance 0);
// different-net overlaps are CutShort (short.cpp). ADJACENTCUTS: a cut with
// at least n other cuts closer than w needs s to each of them
// (AdjacentCuts), reported only for pairs that meet the plain rules.
// Marker box: the gap (or overlap) between the two cuts.
#include <algorithm>

#include "drc/layer_shapes.hpp"

namespace xroute::drc {

namespace {

// Is the distance between two cuts smaller than `space`?
bool cutsCloser(const Rect& a, const Rect& b, Dbu space, bool centerToCenter, bool euclidean) {
  if (centerToCenter) {
    const int64_t dx = std::abs(int64_t(a.xlo) + a.xhi - b.xlo - b.xhi);  // doubled
    const int64_t dy = std::abs(int64_t(a.ylo) + a.yhi - b.ylo - b.yhi);
    if (!euclidean) return std::max(dx, dy) < 2 * int64_t(space);
    return dx * dx + dy * dy < 4 * int64_t(space) * space;
  }
  return closerThan(gapX(a, b), gapY(a, b), space, euclidean);
}

bool sameCut(const LayerShapes& ls, int32_t a, int32_t b) {
  return !ls.isObs(a) && ls.nets[a] == ls.nets[b] && ls.rects[a] == ls.rects[b];
}

}  // namespace

void checkCutSpacing(const LayerShapes& ls, MarkerSink& out) {
  const std::vector<CutSpacingRule>& rules = ls.rules->cutSpacings;
  if (rules.empty()) return;
  Dbu range = 0;
  bool hasSameNetRule = false;
  for (const CutSpacingRule& r : rules) {
    range = std::max({range, r.space, r.cutWithin});
    hasSameNetRule = hasSameNetRule || (r.sameNet && r.adjacentCuts == 0);
  }
  // Pairs of cuts (a, b) that break a plain rule.
  auto plainViolation = [&](int32_t a, int32_t b) {
    const bool sameNet = !ls.conflicting(a, b) && !ls.isObs(a);
    for (const CutSpacingRule& r : rules) {
      if (r.adjacentCuts > 0) continue;
      if (r.sameNet ? !sameNet : (sameNet && hasSameNetRule)) continue;
      if (cutsCloser(ls.rects[a], ls.rects[b], r.space, r.centerToCenter, ls.euclidean)) return true;
    }
    return false;
  };

  std::vector<int32_t> near;
  for (size_t i = 0; i < ls.size(); ++i) {
    if (!ls.seed[i]) continue;
    const int32_t a = int32_t(i);
    const Rect& ra = ls.rects[a];
    near.clear();
    ls.index.query(expanded(ra, range + 1), [&](int32_t b) {
      if (b != a && !sameCut(ls, a, b)) near.push_back(b);
    });
    std::sort(near.begin(), near.end());
    for (int32_t b : near) {
      if (ls.seed[b] && b < a) continue;
      if (ls.isObs(a) && ls.isObs(b)) continue;
      if (ls.conflicting(a, b) && ls.rects[a].overlaps(ls.rects[b])) continue;  // CutShort
      if (plainViolation(a, b)) addPairMarker(out, ls, MarkerType::CutSpacing, gapBox(ra, ls.rects[b]), a, b);
    }
    for (const CutSpacingRule& r : rules) {
      if (r.adjacentCuts <= 0) continue;
      int count = 0;
      for (int32_t b : near)
        if (cutsCloser(ra, ls.rects[b], r.cutWithin, r.centerToCenter, ls.euclidean)) ++count;
      if (count < r.adjacentCuts) continue;
      for (int32_t b : near) {
        if (ls.isObs(a) && ls.isObs(b)) continue;
        if (ls.conflicting(a, b) && ls.rects[a].overlaps(ls.rects[b])) continue;
        if (!cutsCloser(ra, ls.rects[b], r.space, r.centerToCenter, ls.euclidean) || plainViolation(a, b)) continue;
        addPairMarker(out, ls, MarkerType::AdjacentCuts, gapBox(ra, ls.rects[b]), a, b);
      }
    }
  }
}

}  // namespace xroute::drc
