#include "grid/footprint.hpp"

#include <algorithm>
#include <limits>

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
  r.horizontal.assign(nz, 0);
  for (size_t z = 0; z < nz; ++z) {
    r.layers[z] = &tech.layer(tracks.layers[z].layer);
    r.wireHalf[z] = tracks.layers[z].wireWidth / 2;
    r.horizontal[z] = tracks.layers[z].horizontal ? 1 : 0;
    for (const EolRule& e : r.layers[z]->eolRules) {
      r.eolSpace[z] = std::max(r.eolSpace[z], e.space);
      r.eolWithin[z] = std::max(r.eolWithin[z], e.within);
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

void markMetal(RegionGrid& g, const FootprintRules& rules, int z, const Rect& r, int32_t net, bool fixed) {
  const Layer& layer = *rules.layers[z];
  const Dbu half = rules.wireHalf[z];
  const Dbu width = std::min(r.width(), r.height());
  const Dbu runLength = std::max(r.width(), r.height());
  const Dbu s = requiredSpacing(layer, width, 2 * half, runLength);
  const Rect& m = rules.viaLanding[z];
  // A wire through the node: its square [x-half, x+half] must stay s away.
  const Rect wireRegion{r.xlo - s - half, r.ylo - s - half, r.xhi + s + half, r.yhi + s + half};
  // A via landing: its metal rect at the node must stay s away.
  const Rect viaRegion{r.xlo - s - m.xhi, r.ylo - s - m.yhi, r.xhi + s - m.xlo, r.yhi + s - m.ylo};
  // End of line: a wire or via metal ending at the node faces the shape
  // along the preferred direction and needs the EOL spacing within a
  // narrow band beside the shape.
  const Dbu e = std::max(rules.eolSpace[z], s), w = rules.eolWithin[z];
  Rect wireEol = wireRegion, viaEol = viaRegion;
  if (rules.eolSpace[z] > 0) {
    if (rules.horizontal[z]) {
      wireEol = {r.xlo - e - half, r.ylo - w - half, r.xhi + e + half, r.yhi + w + half};
    } else {
      wireEol = {r.xlo - w - half, r.ylo - e - half, r.xhi + w + half, r.yhi + e + half};
    }
    // Via metal has its line ends across its long axis, which need not be
    // the layer's preferred direction.
    const bool viaAlongX = m.width() != m.height() ? m.width() > m.height() : bool(rules.horizontal[z]);
    if (viaAlongX) {
      viaEol = {r.xlo - e - m.xhi, r.ylo - w - m.yhi, r.xhi + e - m.xlo, r.yhi + w - m.ylo};
    } else {
      viaEol = {r.xlo - w - m.xhi, r.ylo - e - m.yhi, r.xhi + w - m.xlo, r.yhi + e - m.ylo};
    }
  }
  const int32_t owner = net < 0 ? kOwnerMixed : net;
  auto each = [&](const Rect& a, const Rect& b, auto&& fn) {
    forNodesInside(g, z, a, fn);
    // Nodes of b not already in a.
    forNodesInside(g, z, b, [&](int32_t n) {
      const Point p = g.point(n);
      if (!(p.x > a.xlo && p.x < a.xhi && p.y > a.ylo && p.y < a.yhi)) fn(n);
    });
  };
  if (fixed) {
    each(wireRegion, wireEol, [&](int32_t n) { claimOwner(g.fixedOwner[n], owner); });
    each(viaRegion, viaEol, [&](int32_t n) { claimOwner(g.viaFixedOwner[n], owner); });
  } else {
    each(wireRegion, wireEol, [&](int32_t n) {
      bump(g.wireUse[n]);
      claimOwner(g.wireUseOwner[n], owner);
    });
    each(viaRegion, viaEol, [&](int32_t n) {
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
