// RegionRouter::prepare: each candidate's terminals, the region's grid, the
// marks on it (fixed shapes, routing near the box, markers, access points),
// and the candidates' features.
#include "region/region_impl.hpp"

#include <algorithm>

namespace xroute {

void RegionRouter::Impl::gatherTerminals(std::vector<Dbu>& xs, std::vector<Dbu>& ys) {
  for (const RegionNetTask& t : task.nets) {
    NetState ns;
    ns.task = t;
    ns.result.net = t.net;
    ns.result.ripup = t.ripup;
    for (int32_t pin : t.pins) {
      TermSpec spec;
      spec.pinRef = pin;
      for (const AccessPoint* ap = ctx.access.begin(pin); ap != ctx.access.end(pin); ++ap) {
        if (!box().contains(ap->at)) continue;
        spec.points.push_back(ap->at);
        spec.zs.push_back(ap->z);
      }
      if (spec.points.empty()) continue;
      pinTouches(spec);
      ns.terms.push_back(std::move(spec));
    }
    if (t.ripup) {
      std::vector<BoundaryTerminal> bterms;
      ns.kept = clipOutside(ctx.tech, ctx.design, ctx.design.nets[t.net].routing, box(), &bterms);
      for (const BoundaryTerminal& b : bterms) {
        TermSpec spec;
        spec.points.push_back(b.at);
        spec.zs.push_back(b.zLo);
        if (b.zHi != b.zLo) {
          spec.points.push_back(b.at);
          spec.zs.push_back(b.zHi);
        }
        ns.terms.push_back(std::move(spec));
      }
      groupKeptTerminals(ns);
    }
    if (plan) {
      for (int32_t cid : t.crossings) {
        const Crossing& c = plan->crossings[cid];
        TermSpec spec;
        if (c.chosen) {
          spec.points.push_back(c.at);
          spec.zs.push_back(c.z);
        } else {
          spec.joined = false;
          spec.crossing = cid;
        }
        ns.terms.push_back(std::move(spec));
      }
    }
    for (const TermSpec& s : ns.terms) {
      for (const Point& p : s.points) {
        xs.push_back(p.x);
        ys.push_back(p.y);
      }
    }
    nets.push_back(std::move(ns));
  }
}

// TermSpec::group of a ripped-up net's terminals: a net passing the box twice, joined beyond it,
// has boundary terminals that its kept routing joins already; the new route joins only the rest.
void RegionRouter::Impl::groupKeptTerminals(NetState& ns) const {
  const int32_t net = ns.task.net;
  const int32_t first = ctx.design.netPinStart[net];
  const int32_t pins = ctx.design.netPinStart[net + 1] - first;
  std::vector<PinContact> contacts;
  for (int32_t p = 0; p < pins; ++p)
    for (const AccessPoint* ap = ctx.access.begin(first + p); ap != ctx.access.end(first + p); ++ap)
      contacts.push_back({p, {ap->z, ap->at}});
  std::vector<ConductorQuery> queries;
  for (const TermSpec& s : ns.terms) {
    ConductorQuery q;
    if (s.pinRef >= 0) q.pin = s.pinRef - first;
    else if (!s.points.empty()) q.point = {s.zs[0], s.points[0]};
    queries.push_back(q);
  }
  // The routing inside other regions rerouting the net now joins nothing.
  NetRouting clipped;
  const NetRouting* kept = &ns.kept;
  for (const Rect& other : ns.task.reroutedElsewhere) {
    clipped = clipOutside(ctx.tech, ctx.design, *kept, other, nullptr);
    kept = &clipped;
  }
  const std::vector<int32_t> groups = keptConductors(ctx.tech, ctx.design, pins, *kept, contacts, queries);
  for (size_t t = 0; t < ns.terms.size(); ++t) ns.terms[t].group = groups[t];
}

// TermSpec::touch of a pin terminal: on every layer but the access point's, where a rect of the pin
// holds the point and a wire's half width from it along the layer (so a wire ending there, with its
// extension, ends on the pin; across, the wire may overhang a narrower pin, as it may where it
// passes over one). A macro pin drawn on Metal1-4 with access points on Metal4 is then
// reached by a wire arriving on Metal3 without a via through the macro's cut obstruction.
void RegionRouter::Impl::pinTouches(TermSpec& spec) const {
  std::vector<Rect> rects;
  for (int z = 0; z < static_cast<int>(ctx.tracks.layers.size()); ++z) {
    rects.clear();
    pinRefRects(ctx.tech, ctx.design, spec.pinRef, ctx.tracks.layers[z].layer, rects);
    if (rects.empty()) continue;
    const Dbu half = ctx.rules.wireHalf[z];
    const bool h = ctx.tracks.layers[z].horizontal;
    const Dbu hx = h ? half : 0, hy = h ? 0 : half;
    for (size_t k = 0; k < spec.points.size(); ++k) {
      if (spec.zs[k] == z) continue;
      const Point p = spec.points[k];
      for (const Rect& r : rects) {
        if (r.contains(Point{p.x - hx, p.y - hy}) && r.contains(Point{p.x + hx, p.y + hy})) {
          spec.touch.push_back(p);
          spec.touchZs.push_back(z);
          break;
        }
      }
    }
  }
}

// Free crossing: nodes on the region edge within the span, on layers whose
// wires cross that edge (guide layers first; any such layer above the
// lowest when the guides name none).
void RegionRouter::Impl::freeCrossingNodes(const Crossing& c, TermSpec& spec) {
  const RegionGrid& g = *grid;
  const bool edgeIsX = c.vertical;  // vertical edge x = coord: horizontal layers cross it
  Dbu lo = c.lo, hi = c.hi;
  // Where along the edge the net's pins beyond it lie: crossing there
  // keeps the route short on the far side.
  const bool farIsHigh = c.regionA == task.region.id;
  const int side = farIsHigh ? 0 : 1;
  bool anyFar = c.hasWant[side];
  Dbu wantLo = c.wantLo[side], wantHi = c.wantHi[side];
  const Design& d = ctx.design;
  for (int32_t pin = d.netPinStart[c.net]; pin < d.netPinStart[c.net + 1] && !c.hasWant[side]; ++pin) {
    if (ctx.access.count(pin) == 0) continue;
    const Point p = ctx.access.begin(pin)->at;
    const Dbu across = c.vertical ? p.x : p.y, along = c.vertical ? p.y : p.x;
    if (farIsHigh ? across <= c.coord : across >= c.coord) continue;
    wantLo = anyFar ? std::min(wantLo, along) : along;
    wantHi = anyFar ? std::max(wantHi, along) : along;
    anyFar = true;
  }
  auto collect = [&](uint32_t mask) {
    for (int z = 0; z < g.nz(); ++z) {
      if (!(mask & (1u << z))) continue;
      if (g.horizontal(z) != edgeIsX) continue;
      const LayerTracks& lt = ctx.tracks.layers[z];
      for (Dbu t : tracksIn(lt.pref, lo, hi)) {
        spec.points.push_back(edgeIsX ? Point{c.coord, t} : Point{t, c.coord});
        spec.zs.push_back(z);
        const Dbu off = t < wantLo ? wantLo - t : (t > wantHi ? t - wantHi : 0);
        spec.exitCost.push_back(anyFar ? task.costs.crossingPull * off : 0);
      }
    }
  };
  collect(c.layerMask);
  if (spec.points.empty()) {
    uint32_t mask = 0;
    for (int z = 1; z < g.nz(); ++z) mask |= 1u << z;
    if (g.nz() == 1) mask = 1;
    collect(mask);
  }
  if (spec.points.empty()) {  // no track in the span: anywhere along the region's edge
    lo = c.vertical ? box().ylo : box().xlo;
    hi = c.vertical ? box().yhi : box().xhi;
    uint32_t mask = 0;
    for (int z = 0; z < g.nz(); ++z) mask |= 1u << z;
    collect(mask);
  }
}

void RegionRouter::Impl::markRouted() {
  const Rect win = grownBox(box(), ctx.halo);
  std::unordered_map<int32_t, const NetState*> ripped;
  for (const NetState& ns : nets) {
    if (ns.task.ripup) ripped[ns.task.net] = &ns;
  }
  std::vector<NetShape> shapes;
  for (int32_t n : ctx.netsNear(win)) {
    shapes.clear();
    auto it = ripped.find(n);
    const NetRouting& r = it != ripped.end() ? it->second->kept : ctx.design.nets[n].routing;
    netRoutingShapes(ctx.tech, ctx.design, r, shapes);
    markShapes(ctx, n, shapes, win, *grid, routedMetal);
  }
  // Repair round: the routing kept from the previous round is other nets' metal.
  for (size_t i = 0; i < nets.size(); ++i) {
    if (!kept(i)) continue;
    shapes.clear();
    netRoutingShapes(ctx.tech, ctx.design, nets[i].result.added, shapes);
    markShapes(ctx, nets[i].task.net, shapes, win, *grid, routedMetal);
    markRoutedNodes(ctx, nets[i].task.net, nets[i].result.added, *grid);
  }
}

void RegionRouter::Impl::markMarkers() {
  for (const MarkerCost& m : task.markers) markMarker(ctx, m, *grid);
  if (seed) {
    for (const MarkerCost& m : seed->markers) markMarker(ctx, m, *grid);
  }
}

// A repair round: the kept candidates are routed as in the previous round,
// with their crossing choices.
void RegionRouter::Impl::takeSeed() {
  for (size_t i = 0; i < nets.size(); ++i) {
    if (!kept(i)) continue;
    nets[i].routed = true;
    nets[i].result = seed->previous->nets[i];
  }
  for (const CrossingChoice& c : seed->previous->crossingChoices) {
    const int32_t net = plan->crossings[c.crossing].net;
    for (size_t i = 0; i < nets.size(); ++i) {
      if (kept(i) && nets[i].task.net == net) {
        choices.push_back(c);
        break;
      }
    }
  }
}

void RegionRouter::Impl::prepare() {
  std::vector<Dbu> xs, ys;
  gatherTerminals(xs, ys);
  if (seed && seed->previous) takeSeed();
  grid = std::make_unique<RegionGrid>(ctx.tracks, box(), std::move(xs), std::move(ys));
  routedMetal.assign(grid->nz(), {});
  markFixed(ctx, box(), *grid);
  markRouted();
  markMarkers();
  for (NetState& ns : nets) {
    markTerminals(ns);
    candidates.push_back(makeCandidate(ns));
  }
}

// A net's terminal nodes and its pins' access points: flags, owners, the
// planar exits pin access checked, the vias it chose, the landings above.
void RegionRouter::Impl::markTerminals(NetState& ns) {
  RegionGrid& g = *grid;
  for (TermSpec& s : ns.terms) {
    if (s.crossing >= 0) freeCrossingNodes(plan->crossings[s.crossing], s);
    for (size_t k = 0; k < s.points.size(); ++k) {
      const int32_t v = nodeAt(s.points[k], s.zs[k]);
      if (v < 0) continue;
      if (s.crossing < 0) {
        g.flags[v] |= s.pinRef >= 0 ? kAccess : kTerminal;
        g.setAccess(v, ns.task.net, s.pinRef);
      }
    }
  }
  for (const TermSpec& s : ns.terms) {
    if (s.pinRef < 0) continue;
    int vias = 0;  // the pin's points that offer a via up
    for (const AccessPoint* ap = ctx.access.begin(s.pinRef); ap != ctx.access.end(s.pinRef); ++ap)
      vias += (ap->dirs & kAccessUp) && ap->z + 1 < g.nz();
    for (const AccessPoint* ap = ctx.access.begin(s.pinRef); ap != ctx.access.end(s.pinRef); ++ap) {
      const int32_t v = nodeAt(ap->at, ap->z);
      if (v >= 0) {
        const uint8_t planar = ap->dirs & (kAccessEast | kAccessWest | kAccessNorth | kAccessSouth);
        g.addAccessExits(v, planar);
      }
      if (v >= 0 && ap->upVia.valid()) apVia.emplace(v, ap->upVia);
      if (v >= 0 && (ap->dirs & kAccessUp) && ap->z + 1 < g.nz()) {
        g.flags[v] |= kAccessVia;
        const int32_t above = nodeAt(ap->at, ap->z + 1);
        if (above >= 0) {
          g.flags[above] |= vias == 1 ? kLanding | kSoleLanding : kLanding;
          g.reserveLanding(above, ns.task.net);
        }
      }
    }
  }
}

// A net's static features (routedNearby is filled in by refreshNearby).
NetCandidate RegionRouter::Impl::makeCandidate(const NetState& ns) const {
  NetCandidate c;
  c.net = ns.task.net;
  c.netPins = ctx.design.pinCount(NetId(ns.task.net));
  bool first = true;
  for (const TermSpec& s : ns.terms) {
    if (s.pinRef >= 0) ++c.pins;
    else ++c.crossings;
    ++c.terminals;
    for (const Point& p : s.points) {
      ++c.accessPoints;
      const Rect r{p.x, p.y, p.x, p.y};
      if (first) c.bbox = r;
      else c.bbox.expandToInclude(r);
      first = false;
    }
  }
  c.guide = guideSpan(ns.task.net);
  return c;
}

// The bounding box of a net's guides clipped to the region; the region box when none overlaps it.
Rect RegionRouter::Impl::guideSpan(int32_t net) const {
  const Design& d = ctx.design;
  Rect span = box();
  bool any = false;
  for (int32_t gi = d.hasGuides() ? d.guideStart[net] : 0; d.hasGuides() && gi < d.guideStart[net + 1]; ++gi) {
    const Rect& r = d.guideRects[gi];
    if (!r.overlaps(box())) continue;
    const Rect clipped{std::max(r.xlo, box().xlo), std::max(r.ylo, box().ylo), std::min(r.xhi, box().xhi),
                       std::min(r.yhi, box().yhi)};
    if (any) span.expandToInclude(clipped);
    else span = clipped;
    any = true;
  }
  return span;
}

// routedNearby of each candidate: nodes in its terminal box that new routing uses (a 2-D
// prefix sum over the grid's (x, y) columns, all layers counted).
void RegionRouter::Impl::refreshNearby(std::vector<NetCandidate>& cands) const {
  const RegionGrid& g = *grid;
  const int nx = g.nx(), ny = g.ny();
  std::vector<int32_t> sum(size_t(nx + 1) * (ny + 1), 0);
  auto at = [&](int x, int y) -> int32_t& { return sum[size_t(y) * (nx + 1) + x]; };
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) {
      int32_t used = 0;
      for (int z = 0; z < g.nz(); ++z) used += g.routedNet[g.index(x, y, z)] >= 0 ? 1 : 0;
      at(x + 1, y + 1) = used + at(x, y + 1) + at(x + 1, y) - at(x, y);
    }
  for (NetCandidate& c : cands) {
    int x0, x1, y0, y1;
    closedRange(g.xs(), c.bbox.xlo, c.bbox.xhi, x0, x1);
    closedRange(g.ys(), c.bbox.ylo, c.bbox.yhi, y0, y1);
    c.routedNearby = x0 > x1 || y0 > y1 ? 0 : at(x1 + 1, y1 + 1) - at(x0, y1 + 1) - at(x1 + 1, y0) + at(x0, y0);
  }
}

}  // namespace xroute
