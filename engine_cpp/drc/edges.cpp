// Boundary edges of the union of one component's rects, with the convexity of
// each edge's two corners: the merged-metal view that EOL and corner rules use.
#include <algorithm>
#include <tuple>

#include "drc/layer_shapes.hpp"

namespace xroute::drc {

bool compCovers(const LayerShapes& ls, int32_t c, int64_t x2, int64_t y2) {
  const Rect probe{Dbu(x2 >> 1), Dbu(y2 >> 1), Dbu((x2 + 1) >> 1), Dbu((y2 + 1) >> 1)};
  bool hit = false;
  ls.index.query(probe, [&](int32_t j) {
    if (hit || ls.comp[j] != c) return;
    const Rect& r = ls.rects[j];
    hit = 2 * int64_t(r.xlo) < x2 && x2 < 2 * int64_t(r.xhi) && 2 * int64_t(r.ylo) < y2 && y2 < 2 * int64_t(r.yhi);
  });
  return hit;
}

namespace {

struct Piece {
  Side side;
  Dbu coord, lo, hi;
};

// Appends the parts of [lo, hi] not covered by `cover` (closed intervals).
void subtract(Dbu lo, Dbu hi, std::vector<std::pair<Dbu, Dbu>>& cover, Side side, Dbu coord, std::vector<Piece>& out) {
  std::sort(cover.begin(), cover.end());
  Dbu at = lo;
  for (const auto& [clo, chi] : cover) {
    if (chi <= at) continue;
    if (clo >= hi) break;
    if (clo > at) out.push_back({side, coord, at, clo});
    at = std::max(at, chi);
    if (at >= hi) return;
  }
  if (at < hi) out.push_back({side, coord, at, hi});
}

// The edges (convexity not set yet) by one index query per side of each member.
std::vector<Edge> edgesByQuery(const LayerShapes& ls, int32_t c) {
  std::vector<Piece> pieces;
  std::vector<std::pair<Dbu, Dbu>> cover;
  for (int32_t k = ls.compStart[c]; k < ls.compStart[c + 1]; ++k) {
    const int32_t i = ls.compMembers[k];
    const Rect& r = ls.rects[i];
    // For each side, other members that continue the metal past that side.
    for (Side side : {Side::Bottom, Side::Top, Side::Left, Side::Right}) {
      const bool horizontal = side == Side::Bottom || side == Side::Top;
      const Dbu coord = side == Side::Bottom ? r.ylo : side == Side::Top ? r.yhi : side == Side::Left ? r.xlo : r.xhi;
      const Rect line = horizontal ? Rect{r.xlo, coord, r.xhi, coord} : Rect{coord, r.ylo, coord, r.yhi};
      cover.clear();
      ls.index.query(line, [&](int32_t j) {
        if (j == i || ls.comp[j] != c) return;
        const Rect& o = ls.rects[j];
        switch (side) {
          case Side::Top: if (o.ylo <= coord && coord < o.yhi) cover.push_back({o.xlo, o.xhi}); break;
          case Side::Bottom: if (o.ylo < coord && coord <= o.yhi) cover.push_back({o.xlo, o.xhi}); break;
          case Side::Right: if (o.xlo <= coord && coord < o.xhi) cover.push_back({o.ylo, o.yhi}); break;
          case Side::Left: if (o.xlo < coord && coord <= o.xhi) cover.push_back({o.ylo, o.yhi}); break;
        }
      });
      if (horizontal) subtract(r.xlo, r.xhi, cover, side, coord, pieces);
      else subtract(r.ylo, r.yhi, cover, side, coord, pieces);
    }
  }
  std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) {
    return std::tie(a.side, a.coord, a.lo, a.hi) < std::tie(b.side, b.coord, b.lo, b.hi);
  });
  std::vector<Edge> edges;
  for (const Piece& p : pieces) {
    if (!edges.empty() && edges.back().side == p.side && edges.back().coord == p.coord && p.lo <= edges.back().hi) {
      edges.back().hi = std::max(edges.back().hi, p.hi);
      continue;
    }
    edges.push_back({p.side, p.coord, p.lo, p.hi, false, false});
  }
  return edges;
}

}  // namespace

std::vector<Edge> componentEdges(const LayerShapes& ls, int32_t c) {
  std::vector<Edge> edges = ls.compStart[c + 1] - ls.compStart[c] > kSweepMembers ? componentEdgesBySweep(ls, c)
                                                                                  : edgesByQuery(ls, c);
  // A corner is concave when the metal continues diagonally inside it.
  for (Edge& e : edges) {
    const int64_t c2 = 2 * int64_t(e.coord), lo2 = 2 * int64_t(e.lo) - 1, hi2 = 2 * int64_t(e.hi) + 1;
    switch (e.side) {
      case Side::Top:
        e.convexLo = !compCovers(ls, c, lo2, c2 - 1);
        e.convexHi = !compCovers(ls, c, hi2, c2 - 1);
        break;
      case Side::Bottom:
        e.convexLo = !compCovers(ls, c, lo2, c2 + 1);
        e.convexHi = !compCovers(ls, c, hi2, c2 + 1);
        break;
      case Side::Right:
        e.convexLo = !compCovers(ls, c, c2 - 1, lo2);
        e.convexHi = !compCovers(ls, c, c2 - 1, hi2);
        break;
      case Side::Left:
        e.convexLo = !compCovers(ls, c, c2 + 1, lo2);
        e.convexHi = !compCovers(ls, c, c2 + 1, hi2);
        break;
    }
  }
  return edges;
}

}  // namespace xroute::drc
