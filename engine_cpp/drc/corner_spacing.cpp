// Corner spacing (LEF58_CORNERSPACING "CORNERSPACING CONVEXCORNER [EXCEPTEOL
// eolWidth] WIDTH w1 SPACING s1 WIDTH w2 SPACING s2 ..."), convex corners only.
//
// For each convex corner of a component's merged metal, a shape of another
// net (or an obstruction) lying entirely in the corner's diagonal quadrant
// (no parallel run with the corner's two edges) must be at least s away from
// the corner point (Euclidean, or MAXXY). s is the SPACING of the last WIDTH
// row not larger than the width of the metal at the corner (the smaller side
// of the widest member rect having that corner). EXCEPTEOL: corners of a line
// end (an edge shorter than eolWidth with two convex corners) are exempt.
// Marker box: from the corner to the nearest corner of the offending shape.
#include <algorithm>

#include "drc/layer_shapes.hpp"

namespace xroute::drc {

namespace {

struct Corner {
  Dbu x, y;      // DBU
  int sx, sy;    // outward diagonal direction, +1 or -1
};

bool isLineEnd(const Edge& e, Dbu eolWidth) { return e.convexLo && e.convexHi && e.hi - e.lo < eolWidth; }

// The convex corners of one component with the EOL status of their edges.
void collectCorners(const std::vector<Edge>& edges, const CornerSpacingRule& rule, std::vector<Corner>& out) {
  // Each convex corner joins one horizontal and one vertical edge.
  struct End {
    Dbu x, y;
    int sx, sy;
    bool eol;
  };
  std::vector<End> horiz, vert;
  for (const Edge& e : edges) {
    const bool eol = rule.exceptEol && isLineEnd(e, rule.eolWidth);
    const bool horizontal = e.side == Side::Top || e.side == Side::Bottom;
    for (int end = 0; end < 2; ++end) {
      if (!(end == 0 ? e.convexLo : e.convexHi)) continue;
      const Dbu along = end == 0 ? e.lo : e.hi;
      const int dir = end == 0 ? -1 : +1;
      if (horizontal) horiz.push_back({along, e.coord, dir, e.side == Side::Top ? 1 : -1, eol});
      else vert.push_back({e.coord, along, e.side == Side::Right ? 1 : -1, dir, eol});
    }
  }
  auto key = [](const End& a) { return std::make_tuple(a.x, a.y, a.sx, a.sy); };
  std::sort(horiz.begin(), horiz.end(), [&](const End& a, const End& b) { return key(a) < key(b); });
  std::sort(vert.begin(), vert.end(), [&](const End& a, const End& b) { return key(a) < key(b); });
  for (const End& h : horiz) {
    auto it = std::lower_bound(vert.begin(), vert.end(), h, [&](const End& a, const End& b) { return key(a) < key(b); });
    const bool vertEol = it != vert.end() && key(*it) == key(h) && it->eol;
    if (!h.eol && !vertEol) out.push_back({h.x, h.y, h.sx, h.sy});
  }
}

}  // namespace

void checkCornerSpacing(const LayerShapes& ls, MarkerSink& out) {
  const int32_t comps = int32_t(ls.compStart.size()) - 1;
  std::vector<Corner> corners;
  for (const CornerSpacingRule& rule : ls.rules->cornerSpacings) {
    if (!rule.convexCorner || rule.widths.empty() || rule.widths.size() != rule.spacings.size()) continue;
    const Dbu maxSpace = *std::max_element(rule.spacings.begin(), rule.spacings.end());
    for (int32_t c = 0; c < comps; ++c) {
      const int32_t first = ls.compMembers[ls.compStart[c]];
      if (!ls.compSeed[c] || ls.isObs(first)) continue;
      corners.clear();
      collectCorners(componentEdges(ls, c), rule, corners);
      for (const Corner& k : corners) {
        // Width of the metal at the corner: the widest member having it as a corner.
        Dbu width = 0;
        ls.index.query(Rect{k.x, k.y, k.x, k.y}, [&](int32_t j) {
          const Rect& r = ls.rects[j];
          if (ls.comp[j] != c) return;
          if ((k.sx > 0 ? r.xhi : r.xlo) == k.x && (k.sy > 0 ? r.yhi : r.ylo) == k.y)
            width = std::max(width, std::min(r.width(), r.height()));
        });
        Dbu space = rule.spacings.front();
        for (size_t i = 0; i < rule.widths.size(); ++i)
          if (width >= rule.widths[i]) space = rule.spacings[i];
        const Rect quadrant = Rect::fromCorners({k.x, k.y}, {k.x + k.sx * maxSpace, k.y + k.sy * maxSpace});
        ls.index.query(quadrant, [&](int32_t j) {
          if (ls.comp[j] == c || (!ls.isObs(j) && ls.nets[j] == ls.nets[first])) return;
          const Rect& r = ls.rects[j];
          const Dbu dx = k.sx > 0 ? r.xlo - k.x : k.x - r.xhi;
          const Dbu dy = k.sy > 0 ? r.ylo - k.y : k.y - r.yhi;
          if (dx < 0 || dy < 0 || (dx == 0 && dy == 0)) return;  // parallel run, or touching
          if (!closerThan(dx, dy, space, ls.euclidean)) return;
          const Rect box = Rect::fromCorners({k.x, k.y}, {k.x + k.sx * dx, k.y + k.sy * dy});
          int32_t n1 = ls.nets[first], n2 = ls.isObs(j) ? -1 : ls.nets[j];
          if (n2 >= 0 && n2 < n1) std::swap(n1, n2);
          out.push_back({Marker{MarkerType::CornerSpacing, ls.layer, box, n1, n2}, ls.compFixed[c] && ls.fixed[j]});
        });
      }
    }
  }
}

}  // namespace xroute::drc
