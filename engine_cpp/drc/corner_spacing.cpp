// Corner spacing (LEF58_CORNERSPACING "CORNERSPACING CONVEXCORNER [EXCEPTEOL
// eolWidth] WIDTH w1 SPACING s1 WIDTH w2 SPACING s2 ..."), convex corners only.
//
// Corner to corner: a convex corner k of one conductor and a convex corner p
// of a conductor of another net (or an obstruction) facing it, p in k's
// closed diagonal quadrant (k's outward diagonal, p's the opposite one), so
// that the two pieces of metal have no parallel run. The pair violates when
// max(dx, dy) < s: the rule's spacing region is a square (a rectangle with
// the "SPACING sx sy" form), Euclidean only with CORNERTOCORNER, which we do
// not parse. s is the SPACING of the last WIDTH row not larger than the width
// of the metal at k (the smaller side of the widest member rect having k as
// its corner). EXCEPTEOL: a corner that ends an edge shorter than eolWidth
// with two convex corners (a line end) is exempt, on either side of the pair.
// The pair is fixed (the input's) when every rect having k on its boundary
// and every one having p on its boundary is fixed, even if routing joined
// either conductor elsewhere (as EndOfLine does). Marker box: k to p.
// drc/README.md says why (what drt and the LEF text do).
#include <algorithm>
#include <unordered_map>

#include "drc/layer_shapes.hpp"

namespace xroute::drc {

namespace {

struct Corner {
  Dbu x, y;      // DBU
  int sx, sy;    // outward diagonal direction, +1 or -1
  bool eol;      // one of its two edges is a line end (EXCEPTEOL)
};

bool isLineEnd(const Edge& e, Dbu eolWidth) { return e.convexLo && e.convexHi && e.hi - e.lo < eolWidth; }

// The convex corners of one component, each with the EOL status of its edges.
void collectCorners(const std::vector<Edge>& edges, const CornerSpacingRule& rule, std::vector<Corner>& out) {
  // Each convex corner joins one horizontal and one vertical edge.
  std::vector<Corner> horiz, vert;
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
  auto key = [](const Corner& a) { return std::make_tuple(a.x, a.y, a.sx, a.sy); };
  auto less = [&](const Corner& a, const Corner& b) { return key(a) < key(b); };
  std::sort(vert.begin(), vert.end(), less);
  for (Corner h : horiz) {
    auto it = std::lower_bound(vert.begin(), vert.end(), h, less);
    if (it != vert.end() && key(*it) == key(h)) h.eol = h.eol || it->eol;
    out.push_back(h);
  }
}

// Is corner (x, y) of component c carried by fixed rects only?
bool cornerFixed(const LayerShapes& ls, int32_t c, Dbu x, Dbu y) {
  bool fixed = true;
  ls.index.query(Rect{x, y, x, y}, [&](int32_t j) {
    if (ls.comp[j] == c && ls.rects[j].contains(Point{x, y}) && !ls.fixed[j]) fixed = false;
  });
  return fixed;
}

}  // namespace

void checkCornerSpacing(const LayerShapes& ls, MarkerSink& out) {
  const int32_t comps = int32_t(ls.compStart.size()) - 1;
  for (const CornerSpacingRule& rule : ls.rules->cornerSpacings) {
    if (!rule.convexCorner || rule.widths.empty() || rule.widths.size() != rule.spacings.size()) continue;
    // Corners per component, computed when first needed (offenders may lie
    // outside the window's seeds).
    std::unordered_map<int32_t, std::vector<Corner>> cache;
    auto cornersOf = [&](int32_t c) -> const std::vector<Corner>& {
      auto it = cache.find(c);
      if (it != cache.end()) return it->second;
      std::vector<Corner> cs;
      collectCorners(componentEdges(ls, c), rule, cs);
      return cache.emplace(c, std::move(cs)).first->second;
    };
    std::vector<int32_t> others;
    for (int32_t c = 0; c < comps; ++c) {
      const int32_t first = ls.compMembers[ls.compStart[c]];
      if (!ls.compSeed[c] || ls.isObs(first)) continue;
      const std::vector<Corner> mine = cornersOf(c);  // a copy: the cache may rehash below
      for (const Corner& k : mine) {
        if (k.eol) continue;
        // Width of the metal at the corner: the widest member having it as a corner.
        Dbu width = 0;
        ls.index.query(Rect{k.x, k.y, k.x, k.y}, [&](int32_t j) {
          const Rect& r = ls.rects[j];
          if (ls.comp[j] != c) return;
          if ((k.sx > 0 ? r.xhi : r.xlo) == k.x && (k.sy > 0 ? r.yhi : r.ylo) == k.y)
            width = std::max(width, r.minSide());
        });
        Dbu space = rule.spacings.front();
        for (size_t i = 0; i < rule.widths.size(); ++i)
          if (width >= rule.widths[i]) space = rule.spacings[i];
        // Conductors of other nets with metal in the quadrant.
        const Rect quadrant = Rect::fromCorners({k.x, k.y}, {k.x + k.sx * space, k.y + k.sy * space});
        others.clear();
        ls.index.queryExcept(quadrant, ls.nets[first], [&](int32_t j) {  // other nets only
          if (ls.comp[j] == c || (!ls.isObs(j) && ls.nets[j] == ls.nets[first])) return;
          others.push_back(ls.comp[j]);
        });
        std::sort(others.begin(), others.end());
        others.erase(std::unique(others.begin(), others.end()), others.end());
        for (int32_t o : others) {
          const int32_t oFirst = ls.compMembers[ls.compStart[o]];
          for (const Corner& p : cornersOf(o)) {
            if (p.sx != -k.sx || p.sy != -k.sy || p.eol) continue;
            const Dbu dx = (p.x - k.x) * k.sx, dy = (p.y - k.y) * k.sy;
            if (dx < 0 || dy < 0 || (dx == 0 && dy == 0)) continue;  // not diagonal, or touching (a short)
            if (std::max(dx, dy) >= space) continue;
            const Rect box = Rect::fromCorners({k.x, k.y}, {p.x, p.y});
            int32_t n1 = ls.nets[first], n2 = ls.isObs(oFirst) ? -1 : ls.nets[oFirst];
            if (n2 >= 0 && n2 < n1) std::swap(n1, n2);
            const bool fixed = cornerFixed(ls, c, k.x, k.y) && cornerFixed(ls, o, p.x, p.y);
            out.push_back({Marker{MarkerType::CornerSpacing, ls.layer, box, n1, n2}, fixed});
          }
        }
      }
    }
  }
}

}  // namespace xroute::drc
