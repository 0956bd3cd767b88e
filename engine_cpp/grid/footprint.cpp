#include "grid/footprint.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

#include "drc/drc.hpp"

namespace xroute {

FootprintRules makeFootprintRules(const Tech& tech, const TrackSet& tracks, const ViaSet& vias) {
  FootprintRules r;
  r.tech = &tech;
  const size_t nz = tracks.layers.size();
  r.layers.resize(nz);
  r.wireHalf.resize(nz);
  r.viaLanding.assign(nz, Rect{0, 0, 0, 0});
  r.cutRect.assign(nz, Rect{0, 0, 0, 0});
  r.cutSpacing.assign(nz, 0);
  r.eolSpace.assign(nz, 0);
  r.eolWithin.assign(nz, 0);
  r.eolWidth.assign(nz, 0);
  r.horizontal.assign(nz, 0);
  for (size_t z = 0; z < nz; ++z) {
    r.layers[z] = &tech.layer(tracks.layers[z].layer);
    r.wireHalf[z] = tracks.layers[z].wireWidth / 2;
    r.horizontal[z] = tracks.layers[z].horizontal ? 1 : 0;
    for (const EolRule& e : r.layers[z]->eolRules) {
      r.eolSpace[z] = std::max(r.eolSpace[z], e.space);
      r.eolWithin[z] = std::max(r.eolWithin[z], e.within);
      r.eolWidth[z] = std::max(r.eolWidth[z], e.eolWidth);
    }
  }
  for (size_t z = 0; z + 1 < nz; ++z) {
    const CutVia& cv = vias.cuts[z];
    r.viaLanding[z].expandToInclude(cv.bottomMetal);
    r.viaLanding[z + 1].expandToInclude(cv.topMetal);
    r.cutRect[z] = cv.cut;
    const Via& via = tech.vias[*cv.via];
    Dbu s = 0;
    for (const CutSpacingRule& c : tech.layer(via.cut).cutSpacings) {
      if (c.adjacentCuts > 0 || c.sameNet) continue;
      // Centre-to-centre rules become edge-to-edge for equal square cuts.
      const Dbu edge = c.centerToCenter ? c.space - cv.cut.width() : c.space;
      s = std::max(s, edge);
    }
    r.cutSpacing[z] = s;
  }
  return r;
}

namespace {

// Nodes of layer z whose (x, y) lies strictly inside `region`.
template <class Fn>
void forNodesInside(const RegionGrid& g, int z, const Rect& region, Fn&& fn) {
  int x0, x1, y0, y1;
  g.xRangeOpen(region.xlo, region.xhi, x0, x1);
  g.yRangeOpen(region.ylo, region.yhi, y0, y1);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) fn(g.index(x, y, z));
}

void bump(uint16_t& counter) {
  if (counter < std::numeric_limits<uint16_t>::max()) ++counter;
}

}  // namespace

uint8_t openCrossEnds(const Rect& r, bool horizontal, const std::vector<Rect>& others) {
  // Along the cross axis (y on a horizontal layer, x on a vertical one): [lo, hi]; the ends'
  // edges span [a, b] along the other axis.
  const Dbu lo = horizontal ? r.ylo : r.xlo, hi = horizontal ? r.yhi : r.xhi;
  const Dbu a = horizontal ? r.xlo : r.ylo, b = horizontal ? r.xhi : r.yhi;
  uint8_t open = kCrossLow | kCrossHigh;
  for (const Rect& q : others) {
    const Dbu qlo = horizontal ? q.ylo : q.xlo, qhi = horizontal ? q.yhi : q.xhi;
    const Dbu qa = horizontal ? q.xlo : q.ylo, qb = horizontal ? q.xhi : q.yhi;
    if (qa >= b || qb <= a || qhi < lo || qlo > hi) continue;  // apart (or a corner only)
    const bool wider = qa < a || qb > b;  // the end's edge goes on along q
    // q goes on past the end, or holds it and its edge goes on along q.
    if ((qlo < lo && qhi >= lo) || (qlo <= lo && qhi > lo && wider)) open &= ~kCrossLow;
    if ((qhi > hi && qlo <= hi) || (qhi >= hi && qlo < hi && wider)) open &= ~kCrossHigh;
  }
  return open;
}

bool narrowAcross(const FootprintRules& rules, int z, const Rect& r) {
  return rules.eolSpace[z] > 0 && (rules.horizontal[z] ? r.width() : r.height()) < rules.eolWidth[z];
}

MetalReach metalReach(const FootprintRules& rules, int z, const Rect& r, Dbu half, Dbu minSpace,
                      const Rect* landing, uint8_t crossEnds) {
  const Layer& layer = *rules.layers[z];
  const Dbu width = r.minSide();
  const bool hz = rules.horizontal[z] != 0;
  // Spacing depends on the parallel run length. A wire along the preferred
  // direction beside the shape runs parallel at most the shape's extent in
  // that direction; a wire ending towards the shape (or passing a corner)
  // runs parallel at most its own width. Wide shapes (pads, macros, stripes)
  // need their wide-metal row only beside them. A NONDEFAULTRULE spacing
  // (minSpace) raises all three.
  const Dbu sSide = std::max(minSpace, requiredSpacing(layer, width, 2 * half, hz ? r.width() : r.height()));
  const Dbu sEnd = std::max(minSpace, requiredSpacing(layer, width, 2 * half, 2 * half));
  const Rect& m = landing != nullptr ? *landing : rules.viaLanding[z];
  const Dbu sVia = std::max(
      minSpace, requiredSpacing(layer, width, m.minSide(), std::max(m.width(), m.height())));
  MetalReach out;
  // A wire through the node: its square [x-half, x+half] must stay away.
  const Rect wireEnd{r.xlo - sEnd - half, r.ylo - sEnd - half, r.xhi + sEnd + half, r.yhi + sEnd + half};
  const Rect wireSide = hz ? Rect{r.xlo - half, r.ylo - sSide - half, r.xhi + half, r.yhi + sSide + half}
                           : Rect{r.xlo - sSide - half, r.ylo - half, r.xhi + sSide + half, r.yhi + half};
  // A via landing: its metal rect at the node must stay sVia away.
  const Rect viaRegion{r.xlo - sVia - m.xhi, r.ylo - sVia - m.yhi, r.xhi + sVia - m.xlo, r.yhi + sVia - m.ylo};
  // End of line: a wire or via metal ending at the node faces the shape
  // along the preferred direction and needs the EOL spacing within a
  // narrow band beside the shape.
  const Dbu e = std::max(rules.eolSpace[z], sEnd), w = rules.eolWithin[z];
  Rect wireEol = wireEnd, viaEol = viaRegion;
  if (rules.eolSpace[z] > 0) {
    if (hz) {
      wireEol = {r.xlo - e - half, r.ylo - w - half, r.xhi + e + half, r.yhi + w + half};
    } else {
      wireEol = {r.xlo - w - half, r.ylo - e - half, r.xhi + w + half, r.yhi + e + half};
    }
    // Via metal has its line ends across its long axis, which need not be
    // the layer's preferred direction.
    const bool viaAlongX = m.width() != m.height() ? m.width() > m.height() : hz;
    const Dbu ev = std::max(rules.eolSpace[z], sVia);
    if (viaAlongX) {
      viaEol = {r.xlo - ev - m.xhi, r.ylo - w - m.yhi, r.xhi + ev - m.xlo, r.yhi + w - m.ylo};
    } else {
      viaEol = {r.xlo - w - m.xhi, r.ylo - ev - m.yhi, r.xhi + w - m.xlo, r.yhi + ev - m.ylo};
    }
  }
  // Open line ends of `r` across the preferred direction (a wrong-way stub's
  // end, a patch across the tracks): a wire or via metal in their EOL window,
  // on the next track or end to end on the same line, breaks the rule.
  Rect wireCross{0, 0, 0, 0}, viaCross{0, 0, 0, 0};
  if (crossEnds != 0 && rules.eolSpace[z] > 0 && (hz ? r.width() : r.height()) < rules.eolWidth[z]) {
    const Dbu ev = std::max(rules.eolSpace[z], sVia);
    const bool low = (crossEnds & kCrossLow) != 0, high = (crossEnds & kCrossHigh) != 0;
    // Cross axis c: the node's metal [c - below, c + above] meets [r's end, e beyond it).
    auto span = [&](Dbu lo, Dbu hi, Dbu below, Dbu above, Dbu reach) {
      return std::pair<Dbu, Dbu>{low ? lo - reach - above : hi - above, high ? hi + reach + below : lo + below};
    };
    if (hz) {
      const auto [w0, w1] = span(r.ylo, r.yhi, half, half, e);
      const auto [v0, v1] = span(r.ylo, r.yhi, -m.ylo, m.yhi, ev);
      wireCross = {r.xlo - w - half, w0, r.xhi + w + half, w1};
      viaCross = {r.xlo - w - m.xhi, v0, r.xhi + w - m.xlo, v1};
    } else {
      const auto [w0, w1] = span(r.xlo, r.xhi, half, half, e);
      const auto [v0, v1] = span(r.xlo, r.xhi, -m.xlo, m.xhi, ev);
      wireCross = {w0, r.ylo - w - half, w1, r.yhi + w + half};
      viaCross = {v0, r.ylo - w - m.yhi, v1, r.yhi + w - m.ylo};
    }
  }
  out.wire = {wireEnd, wireSide, wireEol, wireCross};
  out.via = {viaRegion, viaEol, viaCross};
  return out;
}

namespace {

// Every node of layer z strictly inside one of the rects, once.
template <size_t N, class Fn>
void eachNodeOnce(const RegionGrid& g, int z, const std::array<Rect, N>& rects, Fn&& fn) {
  for (size_t a = 0; a < N; ++a) {
    forNodesInside(g, z, rects[a], [&](int32_t n) {
      const Point p = g.point(n);
      for (size_t b = 0; b < a; ++b) {
        const Rect& q = rects[b];
        if (p.x > q.xlo && p.x < q.xhi && p.y > q.ylo && p.y < q.yhi) return;
      }
      fn(n);
    });
  }
}

}  // namespace

void forMetalReach(const RegionGrid& g, const MetalReach& reach, int z, const std::function<void(int32_t, bool)>& fn) {
  eachNodeOnce(g, z, reach.wire, [&](int32_t n) { fn(n, false); });
  eachNodeOnce(g, z, reach.via, [&](int32_t n) { fn(n, true); });
}

void markMetal(RegionGrid& g, const FootprintRules& rules, int z, const Rect& r, int32_t net, bool fixed,
               Dbu minSpace, uint8_t crossEnds) {
  const MetalReach reach = metalReach(rules, z, r, rules.wireHalf[z], minSpace, nullptr, crossEnds);
  const int32_t owner = net < 0 ? kOwnerMixed : net;
  if (fixed) {
    eachNodeOnce(g, z, reach.wire, [&](int32_t n) { claimOwner(g.fixedOwner[n], owner); });
    eachNodeOnce(g, z, reach.via, [&](int32_t n) { claimOwner(g.viaFixedOwner[n], owner); });
  } else {
    eachNodeOnce(g, z, reach.wire, [&](int32_t n) {
      bump(g.wireUse[n]);
      claimOwner(g.wireUseOwner[n], owner);
    });
    eachNodeOnce(g, z, reach.via, [&](int32_t n) {
      bump(g.viaUse[n]);
      claimOwner(g.viaUseOwner[n], owner);
    });
  }
}

void markCut(RegionGrid& g, const FootprintRules& rules, int z, const Rect& r, int32_t net) {
  if (z < 0 || z + 1 >= g.nz()) return;
  const Dbu s = rules.cutSpacing[z];
  const Rect& c = rules.cutRect[z];
  const Rect region{r.xlo - s - c.xhi, r.ylo - s - c.yhi, r.xhi + s - c.xlo, r.yhi + s - c.ylo};
  const int32_t owner = net < 0 ? kOwnerMixed : net;
  forNodesInside(g, z, region, [&](int32_t n) {
    bump(g.cutUse[n]);
    claimOwner(g.cutUseOwner[n], owner);
  });
}

}  // namespace xroute
