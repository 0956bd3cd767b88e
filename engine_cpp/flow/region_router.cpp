#include "flow/region_router.hpp"

#include "drc/pair_rules.hpp"
#include "io/engine_errors.hpp"
#include "route/min_area_fix.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace xroute {

namespace {

constexpr int64_t kPatchConflict = 1000;  // a minimum-area patch score meaning "would break a spacing rule"

// True when another rect of the same net continues the edge of metal[i]
// that faces `r` (the merged edge is longer than the rect's side there), so
// that edge is no line end.
bool edgeContinues(const std::vector<std::pair<Rect, int32_t>>& metal, size_t i, const Rect& r) {
  const auto& [o, net] = metal[i];
  for (size_t j = 0; j < metal.size(); ++j) {
    const Rect& q = metal[j].first;
    if (j == i || metal[j].second != net || !q.overlaps(o)) continue;
    const bool sideways = q.xlo < o.xlo || q.xhi > o.xhi, upways = q.ylo < o.ylo || q.yhi > o.yhi;
    if (r.ylo >= o.yhi && q.yhi == o.yhi && sideways) return true;
    if (r.yhi <= o.ylo && q.ylo == o.ylo && sideways) return true;
    if (r.xlo >= o.xhi && q.xhi == o.xhi && upways) return true;
    if (r.xhi <= o.xlo && q.xlo == o.xlo && upways) return true;
  }
  return false;
}

struct TermSpec {
  std::vector<Point> points;  // DBU
  std::vector<int> zs;        // routing index per point
  std::vector<int64_t> exitCost;  // free crossings: per point, distance from where the far side wants it
  bool joined = true;
  int32_t pinRef = -1;        // pin terminals
  int32_t crossing = -1;      // free crossing terminals (iteration 0)
};

struct NetState {
  RegionNetTask task;
  std::vector<TermSpec> terms;
  NetRouting kept;  // rip-up: routing outside the box
  bool routed = false;
  RegionNetResult result;
  std::vector<std::vector<int32_t>> paths;  // the node paths its routing was made of
  std::vector<uint8_t> guide;               // guideMask, built on first use by moves()
};

// Grid index range of the closed interval [lo, hi] (first > last when empty).
void closedRange(const std::vector<Dbu>& v, Dbu lo, Dbu hi, int& first, int& last) {
  first = static_cast<int>(std::lower_bound(v.begin(), v.end(), lo) - v.begin());
  last = static_cast<int>(std::upper_bound(v.begin(), v.end(), hi) - v.begin()) - 1;
}

}  // namespace

struct RegionRouter::Impl {
  const RouteContext& ctx;
  const RegionTask& task;
  const CrossingPlan* plan;
  const RegionRepairSeed* seed;
  std::unique_ptr<RegionGrid> grid;
  std::vector<NetState> nets;
  std::vector<NetCandidate> candidates;
  std::unordered_map<int32_t, ViaId> apVia;  // access node -> via the pin access chose
  std::vector<CrossingChoice> choices;
  int64_t rounds = 0;
  std::vector<int32_t> order;
  // Per routing layer: routed metal (rect, net) of every net marked in the
  // grid (committed routing near the box and this region's new routing), so
  // a minimum-area patch is judged against real shapes.
  std::vector<std::vector<std::pair<Rect, int32_t>>> routedMetal;

  Impl(const RouteContext& c, const RegionTask& t, const CrossingPlan* p, const RegionRepairSeed* s)
      : ctx(c), task(t), plan(p), seed(s) {}

  bool kept(size_t i) const { return seed && i < seed->keep.size() && seed->keep[i]; }

  const Rect& box() const { return task.region.box; }
  int routingIndex(LayerId l) const { return ctx.tech.layer(l).routingIndex; }

  void gatherTerminals(std::vector<Dbu>& xs, std::vector<Dbu>& ys) {
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
        if (!spec.points.empty()) ns.terms.push_back(std::move(spec));
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

  // Free crossing: nodes on the region edge within the span, on layers whose
  // wires cross that edge (guide layers first; any such layer above the
  // lowest when the guides name none).
  void freeCrossingNodes(const Crossing& c, TermSpec& spec) {
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

  void markFixed() {
    RegionGrid& g = *grid;
    const Rect win{box().xlo - ctx.halo, box().ylo - ctx.halo, box().xhi + ctx.halo, box().yhi + ctx.halo};
    ctx.fixedIndex.query(win, [&](int32_t id) {
      const DrcShape& s = ctx.fixedShapes[id];
      const Layer& l = ctx.tech.layer(s.layer);
      if (l.routingIndex >= 0) {
        markMetal(g, ctx.rules, l.routingIndex, s.rect, s.net, true);
      } else if (l.cutIndex >= 0) {
        const int z = cutBelow(s.layer);
        if (z >= 0) markCut(g, ctx.rules, z, s.rect, s.net);
      }
    });
  }

  // The routing index below a cut layer, -1 if unknown.
  int cutBelow(LayerId cut) const {
    for (size_t z = 0; z < ctx.vias.cuts.size(); ++z) {
      if (ctx.tech.vias[*ctx.vias.cuts[z].via].cut == cut) return static_cast<int>(z);
    }
    return -1;
  }

  void markShapes(int32_t net, const std::vector<NetShape>& shapes, const Rect& win) {
    RegionGrid& g = *grid;
    for (const NetShape& s : shapes) {
      if (!s.rect.overlaps(win)) continue;
      const Layer& l = ctx.tech.layer(s.layer);
      if (l.routingIndex >= 0) {
        markMetal(g, ctx.rules, l.routingIndex, s.rect, net, false);
        routedMetal[l.routingIndex].emplace_back(s.rect, net);
      }
      else if (l.cutIndex >= 0) {
        const int z = cutBelow(s.layer);
        if (z >= 0) markCut(g, ctx.rules, z, s.rect, net);
      }
    }
  }

  void markRouted() {
    const Rect win{box().xlo - ctx.halo, box().ylo - ctx.halo, box().xhi + ctx.halo, box().yhi + ctx.halo};
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
      markShapes(n, shapes, win);
    }
    // Repair round: the routing kept from the previous round is other nets' metal.
    for (size_t i = 0; i < nets.size(); ++i) {
      if (!kept(i)) continue;
      shapes.clear();
      netRoutingShapes(ctx.tech, ctx.design, nets[i].result.added, shapes);
      markShapes(nets[i].task.net, shapes, win);
      markRoutedNodes(nets[i].task.net, nets[i].result.added);
    }
  }

  // The grid nodes a net's new wires and vias run through (routedNet).
  void markRoutedNodes(int32_t net, const NetRouting& r) {
    RegionGrid& g = *grid;
    for (const RouteWire& w : r.wires) {
      const int z = routingIndex(w.layer);
      if (z < 0 || z >= g.nz()) continue;
      int x0, x1, y0, y1;
      closedRange(g.xs(), std::min(w.from.x, w.to.x), std::max(w.from.x, w.to.x), x0, x1);
      closedRange(g.ys(), std::min(w.from.y, w.to.y), std::max(w.from.y, w.to.y), y0, y1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) g.routedNet[g.index(x, y, z)] = net;
    }
  }

  void markMarkers() {
    for (const MarkerCost& m : task.markers) markMarker(m);
    if (seed) {
      for (const MarkerCost& m : seed->markers) markMarker(m);
    }
  }

  void markMarker(const MarkerCost& m) {
    RegionGrid& g = *grid;
    {
      const Layer& l = ctx.tech.layer(m.layer);
      int zlo = l.routingIndex, zhi = l.routingIndex;
      if (zlo < 0) {
        zlo = cutBelow(m.layer);
        zhi = zlo + 1;
        if (zlo < 0) return;
      }
      for (int z = zlo; z <= zhi && z < g.nz(); ++z) {
        const Dbu grow = ctx.tracks.layers[z].pitch;
        int x0, x1, y0, y1;
        closedRange(g.xs(), m.box.xlo - grow, m.box.xhi + grow, x0, x1);
        closedRange(g.ys(), m.box.ylo - grow, m.box.yhi + grow, y0, y1);
        for (int y = y0; y <= y1; ++y)
          for (int x = x0; x <= x1; ++x) {
            int32_t& c = g.markerCost[g.index(x, y, z)];
            c = static_cast<int32_t>(std::min<int64_t>(int64_t(c) + m.cost, std::numeric_limits<int32_t>::max() / 2));
          }
      }
    }
  }

  int32_t nodeAt(Point p, int z) const {
    const int x = grid->xIndex(p.x), y = grid->yIndex(p.y);
    if (x < 0 || y < 0 || z < 0 || z >= grid->nz()) return -1;
    return grid->index(x, y, z);
  }

  void prepare() {
    std::vector<Dbu> xs, ys;
    gatherTerminals(xs, ys);
    if (seed && seed->previous) {
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
    grid = std::make_unique<RegionGrid>(ctx.tracks, box(), std::move(xs), std::move(ys));
    RegionGrid& g = *grid;
    routedMetal.assign(g.nz(), {});
    markFixed();
    markRouted();
    markMarkers();
    for (NetState& ns : nets) {
      for (TermSpec& s : ns.terms) {
        if (s.crossing >= 0) freeCrossingNodes(plan->crossings[s.crossing], s);
        for (size_t k = 0; k < s.points.size(); ++k) {
          const int32_t v = nodeAt(s.points[k], s.zs[k]);
          if (v < 0) continue;
          if (s.crossing < 0) {
            g.flags[v] |= s.pinRef >= 0 ? kAccess : kTerminal;
            g.accessNet[v] = ns.task.net;
            if (s.pinRef >= 0) g.accessPin[v] = s.pinRef;
          }
        }
      }
      for (const TermSpec& s : ns.terms) {
        if (s.pinRef < 0) continue;
        for (const AccessPoint* ap = ctx.access.begin(s.pinRef); ap != ctx.access.end(s.pinRef); ++ap) {
          const int32_t v = nodeAt(ap->at, ap->z);
          if (v >= 0) {
            const uint8_t planar = ap->dirs & (kAccessEast | kAccessWest | kAccessNorth | kAccessSouth);
            g.accessExits[v] = g.accessExits[v] == kAnyExit ? planar : uint8_t(g.accessExits[v] | planar);
          }
          if (v >= 0 && ap->upVia.valid()) apVia.emplace(v, ap->upVia);
          if (v >= 0 && (ap->dirs & kAccessUp) && ap->z + 1 < g.nz()) {
            g.flags[v] |= kAccessVia;
            const int32_t above = nodeAt(ap->at, ap->z + 1);
            if (above >= 0) {
              g.flags[above] |= kLanding;
              claimOwner(g.reservedNet[above], ns.task.net);
            }
          }
        }
      }
      candidates.push_back(makeCandidate(ns));
    }
  }

  // A net's static features (routedNearby is filled in by refreshNearby).
  NetCandidate makeCandidate(const NetState& ns) const {
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
  Rect guideSpan(int32_t net) const {
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
  void refreshNearby(std::vector<NetCandidate>& cands) const {
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

  std::vector<uint8_t> guideMask(int32_t net) const {
    const RegionGrid& g = *grid;
    const Design& d = ctx.design;
    std::vector<uint8_t> mask(g.size(), 0);
    if (!d.hasGuides() || d.guideStart[net] == d.guideStart[net + 1]) {
      std::fill(mask.begin(), mask.end(), 1);
      return mask;
    }
    for (int32_t gi = d.guideStart[net]; gi < d.guideStart[net + 1]; ++gi) {
      const Rect& r = d.guideRects[gi];
      if (!r.overlaps(box())) continue;
      const int z = routingIndex(d.guideLayers[gi]);
      if (z < 0) continue;
      int x0, x1, y0, y1;
      closedRange(g.xs(), r.xlo, r.xhi, x0, x1);
      closedRange(g.ys(), r.ylo, r.yhi, y0, y1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) mask[g.index(x, y, z)] = 1;
    }
    return mask;
  }

  void addPathGeometry(int32_t net, const std::vector<int32_t>& path, NetRouting& out) {
    const RegionGrid& g = *grid;
    size_t i = 0;
    while (i + 1 < path.size()) {
      const int32_t u = path[i], v = path[i + 1];
      const int zu = g.zOf(u), zv = g.zOf(v);
      if (zu != zv) {
        const int zl = std::min(zu, zv);
        const int32_t lower = zu < zv ? u : v;
        ViaId via = ctx.vias.cuts[zl].via;
        auto it = apVia.find(lower);
        if (it != apVia.end() && g.accessNet[lower] == net) via = it->second;
        out.vias.push_back({ViaRef{*via, false}, g.point(u)});
        ++i;
        continue;
      }
      // A straight run on one layer.
      const Point a = g.point(u);
      const bool alongX = g.point(v).y == a.y;
      size_t j = i + 1;
      while (j + 1 < path.size() && g.zOf(path[j + 1]) == zu && (g.point(path[j + 1]).y == a.y) == alongX &&
             (alongX ? g.point(path[j + 1]).y == a.y : g.point(path[j + 1]).x == a.x)) {
        ++j;
      }
      RouteWire w;
      w.layer = ctx.tracks.layers[zu].layer;
      w.from = a;
      w.to = g.point(path[j]);
      out.wires.push_back(w);
      i = j;
    }
  }

  void markNewRouting(int32_t net, const NetRouting& added) {
    std::vector<NetShape> shapes;
    netRoutingShapes(ctx.tech, ctx.design, added, shapes);
    const Rect win{box().xlo - ctx.halo, box().ylo - ctx.halo, box().xhi + ctx.halo, box().yhi + ctx.halo};
    markShapes(net, shapes, win);
  }

  // The maze's view of a net: its terminals (joined ones first, so the tree
  // starts on metal) as grid nodes; termOfSpec maps them back to ns.terms.
  MazeNet mazeNet(const NetState& ns, std::vector<int32_t>& termOfSpec) const {
    const RegionGrid& g = *grid;
    MazeNet mn;
    mn.net = ns.task.net;
    for (int pass = 0; pass < 2; ++pass) {
      for (size_t t = 0; t < ns.terms.size(); ++t) {
        const TermSpec& s = ns.terms[t];
        if (s.joined != (pass == 0)) continue;
        MazeTerminal mt;
        mt.joined = s.joined;
        std::vector<std::pair<int32_t, int64_t>> nodes;
        for (size_t k = 0; k < s.points.size(); ++k) {
          const int32_t v = nodeAt(s.points[k], s.zs[k]);
          if (v >= 0 && g.exists(v)) nodes.push_back({v, k < s.exitCost.size() ? s.exitCost[k] : 0});
        }
        std::sort(nodes.begin(), nodes.end());
        nodes.erase(std::unique(nodes.begin(), nodes.end(),
                                [](const auto& a, const auto& b) { return a.first == b.first; }),
                    nodes.end());
        for (const auto& [v, cost] : nodes) {
          mt.nodes.push_back(v);
          mt.exitCost.push_back(cost);
        }
        mn.terminals.push_back(std::move(mt));
        termOfSpec.push_back(static_cast<int32_t>(t));
      }
    }
    return mn;
  }

  void routeNet(int32_t index, MazeWorkspace& ws) {
    NetState& ns = nets[index];
    if (ns.routed) return;
    ns.routed = true;
    order.push_back(index);
    ns.result.routed = true;
    std::vector<int32_t> termOfSpec;
    MazeNet mn = mazeNet(ns, termOfSpec);
    if (mn.terminals.size() < 2) return;
    const std::vector<uint8_t> mask = guideMask(ns.task.net);
    mn.inGuide = &mask;
    std::vector<std::vector<int32_t>> paths;
    ns.result.unreached = routeMaze(*grid, task.costs, mn, ws, paths);
    rounds += static_cast<int64_t>(paths.size());
    applyPaths(ns, mn, termOfSpec, std::move(paths));
  }

  // Turns a net's node paths into its routing: wires and vias, the free
  // crossings they reach, the min-area fix, and the marks on the grid. The
  // one way routing enters a region (the maze's and a caller's paths alike).
  void applyPaths(NetState& ns, const MazeNet& mn, const std::vector<int32_t>& termOfSpec,
                  std::vector<std::vector<int32_t>> paths) {
    RegionGrid& g = *grid;
    for (const auto& p : paths) {
      addPathGeometry(ns.task.net, p, ns.result.added);
      for (int32_t v : p) g.routedNet[v] = ns.task.net;
    }
    // Record where the free crossings were reached.
    for (size_t k = 0; k < mn.terminals.size(); ++k) {
      const TermSpec& s = ns.terms[termOfSpec[k]];
      if (s.crossing < 0) continue;
      const auto& nodes = mn.terminals[k].nodes;
      bool done = false;
      for (const auto& p : paths) {
        for (int32_t v : p) {
          if (std::binary_search(nodes.begin(), nodes.end(), v)) {
            choices.push_back({s.crossing, g.point(v), g.zOf(v)});
            done = true;
            break;
          }
        }
        if (done) break;
      }
    }
    std::vector<MetalAnchor> anchors;
    std::vector<PinMetal> pinMetal;
    for (const TermSpec& s : ns.terms) {
      if (s.crossing >= 0) continue;  // a free crossing is no metal
      if (s.pinRef >= 0) continue;    // pins count by their shapes below
      for (size_t k = 0; k < s.points.size(); ++k) anchors.push_back({s.points[k], s.zs[k]});
    }
    for (const PlacedShape& ps : netPinShapes(ctx.tech, ctx.design, NetId(ns.task.net))) {
      const int z = routingIndex(ps.layer);
      if (z >= 0 && ps.rect.overlaps(box())) pinMetal.push_back({z, ps.rect});
    }
    for (const CrossingChoice& c : choices) {
      if (plan && plan->crossings[c.crossing].net == ns.task.net) anchors.push_back({c.at, c.z});
    }
    const int32_t net = ns.task.net;
    auto score = [&](int z, const Rect& r) { return patchScore(net, z, r); };
    fixMinArea(ctx.tech, ctx.design, ctx.tracks, box(), anchors, pinMetal, score, ns.result.added);
    markNewRouting(ns.task.net, ns.result.added);
    ns.paths = std::move(paths);
  }

  // How bad a minimum-area patch `r` of `net` on layer z would be (RepairScore):
  // kPatchConflict and more when it would break a spacing rule with another
  // net's metal, small sums for metal merely near it. Fixed shapes and routed
  // metal by the spacing table with the run length (a patch runs along them,
  // so a wide one, a power rail, may need its wide-metal row), and the
  // end-of-line spacing where a line end of either faces the other.
  int64_t patchScore(int32_t net, int z, const Rect& r) const {
    const Layer& layer = *ctx.rules.layers[z];
    const Dbu pw = std::min(r.width(), r.height());
    const Dbu s = std::max(layer.minSpacing(), ctx.rules.eolSpace[z]);
    const Dbu reach = std::max(s, requiredSpacing(layer, std::numeric_limits<Dbu>::max() / 4, pw,
                                                  std::numeric_limits<Dbu>::max() / 4));
    const Rect grown{r.xlo - s, r.ylo - s, r.xhi + s, r.yhi + s};
    const Rect far{r.xlo - reach, r.ylo - reach, r.xhi + reach, r.yhi + reach};
    int64_t bad = 0;
    // `lineEnd`: whether o's edge facing the patch may be a line end.
    auto judge = [&](const Rect& o, bool lineEnd) {
      if (drc::rectGap(o, r) < drc::metalNeed(layer, r, o, true, lineEnd)) bad += kPatchConflict;
      else if (o.overlaps(grown)) bad += 10;
    };
    ctx.fixedIndex.query(far, [&](int32_t id) {
      const DrcShape& sh = ctx.fixedShapes[id];
      if (sh.net != net && routingIndex(sh.layer) == z) judge(sh.rect, true);
    });
    const auto& metal = routedMetal[z];
    for (size_t i = 0; i < metal.size(); ++i) {
      if (metal[i].second != net && metal[i].first.overlaps(far)) judge(metal[i].first, !edgeContinues(metal, i, r));
    }
    const RegionGrid& g = *grid;
    int x0, x1, y0, y1;
    g.xRangeOpen(grown.xlo, grown.xhi, x0, x1);
    g.yRangeOpen(grown.ylo, grown.yhi, y0, y1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const int32_t v = g.index(x, y, z);
        if (g.accessNet[v] >= 0 && g.accessNet[v] != net) bad += 5;  // keep clear of others' pin access
      }
    return bad;
  }

  // A caller's node paths for net `index` (each step one maze edge), routed
  // through applyPaths; unreached = terminals after the first (where the tree
  // starts, as in the maze) that no path touches.
  void routeNetPaths(int32_t index, std::vector<std::vector<int32_t>> paths) {
    NetState& ns = nets[index];
    if (ns.routed) throw std::invalid_argument("candidate " + std::to_string(index) + " is already routed");
    std::vector<int32_t> termOfSpec;
    const MazeNet mn = mazeNet(ns, termOfSpec);
    for (const auto& p : paths) {
      for (size_t k = 0; k < p.size(); ++k) {
        if (p[k] < 0 || static_cast<size_t>(p[k]) >= grid->size() || !grid->exists(p[k]))
          throw std::invalid_argument("path node " + std::to_string(p[k]) + " is not a node of the region grid");
        if (k == 0) continue;
        std::array<MazeMove, kMoveCount> mv;
        mazeMoves(*grid, task.costs, mn, p[k - 1], mv);
        bool edge = false;
        for (const MazeMove& m : mv) edge = edge || m.node == p[k];
        if (!edge)
          throw std::invalid_argument("path step " + std::to_string(p[k - 1]) + " -> " + std::to_string(p[k]) +
                                      " is not an edge of the region grid");
      }
    }
    ns.routed = true;
    order.push_back(index);
    ns.result.routed = true;
    int unreached = 0;
    bool first = true;  // as in the maze, the tree starts on the first terminal with nodes
    for (const MazeTerminal& t : mn.terminals) {
      if (t.nodes.empty()) continue;
      if (first) {
        first = false;
        continue;
      }
      bool hit = false;
      for (const auto& p : paths)
        for (int32_t v : p) hit = hit || std::binary_search(t.nodes.begin(), t.nodes.end(), v);
      if (!hit) ++unreached;
    }
    ns.result.unreached = mn.terminals.size() < 2 ? 0 : unreached;
    if (paths.empty() || mn.terminals.size() < 2) return;
    rounds += static_cast<int64_t>(paths.size());
    applyPaths(ns, mn, termOfSpec, std::move(paths));
  }

  void moves(int32_t index, int32_t node, std::array<MazeMove, kMoveCount>& out) {
    NetState& ns = nets[index];
    if (node < 0 || static_cast<size_t>(node) >= grid->size() || !grid->exists(node))
      throw std::invalid_argument("node " + std::to_string(node) + " is not a node of the region grid");
    if (ns.guide.empty()) ns.guide = guideMask(ns.task.net);
    std::vector<int32_t> termOfSpec;
    MazeNet mn = mazeNet(ns, termOfSpec);
    mn.inGuide = &ns.guide;
    mazeMoves(*grid, task.costs, mn, node, out);
  }
};

RegionRouter::RegionRouter(const RouteContext& ctx, const RegionTask& task, const CrossingPlan* plan,
                           const RegionRepairSeed* seed)
    : impl_(std::make_unique<Impl>(ctx, task, plan, seed)) {}
RegionRouter::~RegionRouter() = default;

void RegionRouter::prepare() { impl_->prepare(); }
const RegionGrid& RegionRouter::grid() const { return *impl_->grid; }
const std::vector<NetCandidate>& RegionRouter::candidates() const { return impl_->candidates; }
bool RegionRouter::isRouted(int32_t candidate) const { return impl_->nets[candidate].routed; }
const std::vector<int32_t>& RegionRouter::routedOrder() const { return impl_->order; }
void RegionRouter::routeNet(int32_t index, MazeWorkspace& ws) { impl_->routeNet(index, ws); }
void RegionRouter::routeNetPaths(int32_t index, std::vector<std::vector<int32_t>> paths) {
  impl_->routeNetPaths(index, std::move(paths));
}
const std::vector<std::vector<int32_t>>& RegionRouter::paths(int32_t candidate) const {
  return impl_->nets[candidate].paths;
}
std::vector<std::vector<int32_t>> RegionRouter::terminalNodes(int32_t candidate) const {
  std::vector<int32_t> termOfSpec;
  const MazeNet mn = impl_->mazeNet(impl_->nets[candidate], termOfSpec);
  std::vector<std::vector<int32_t>> out;
  for (const MazeTerminal& t : mn.terminals) out.push_back(t.nodes);
  return out;
}
std::vector<bool> RegionRouter::terminalJoined(int32_t candidate) const {
  std::vector<int32_t> termOfSpec;
  const MazeNet mn = impl_->mazeNet(impl_->nets[candidate], termOfSpec);
  std::vector<bool> out;
  for (const MazeTerminal& t : mn.terminals) out.push_back(t.joined);
  return out;
}
void RegionRouter::moves(int32_t candidate, int32_t node, std::array<MazeMove, kMoveCount>& out) const {
  impl_->moves(candidate, node, out);
}

std::vector<NetCandidate> RegionRouter::unrouted(std::vector<int32_t>& index) const {
  index.clear();
  std::vector<NetCandidate> cands;
  for (size_t i = 0; i < impl_->candidates.size(); ++i) {
    if (impl_->nets[i].routed) continue;
    index.push_back(static_cast<int32_t>(i));
    cands.push_back(impl_->candidates[i]);
  }
  if (!cands.empty()) impl_->refreshNearby(cands);
  return cands;
}

std::vector<NetCandidate> RegionRouter::candidatesNow() const {
  std::vector<NetCandidate> cands = impl_->candidates;
  if (!cands.empty()) impl_->refreshNearby(cands);
  return cands;
}

std::unique_ptr<RegionRouter> RegionRouter::clone() const {
  const Impl& s = *impl_;
  std::unique_ptr<RegionRouter> out(new RegionRouter(s.ctx, s.task, s.plan, s.seed));
  Impl& d = *out->impl_;
  if (s.grid) d.grid = std::make_unique<RegionGrid>(*s.grid);
  d.nets = s.nets;
  d.candidates = s.candidates;
  d.apVia = s.apVia;
  d.choices = s.choices;
  d.rounds = s.rounds;
  d.order = s.order;
  d.routedMetal = s.routedMetal;
  return out;
}

void RegionRouter::adopt(std::unique_ptr<RegionRouter> other) {
  if (&other->impl_->task != &impl_->task) throw std::logic_error("RegionRouter::adopt: not a copy of this region");
  std::swap(impl_, other->impl_);
}

const RouteContext& RegionRouter::context() const { return impl_->ctx; }
RegionInfo RegionRouter::info() const {
  return RegionInfo{impl_->task.iteration, impl_->task.region.id, impl_->task.region.box};
}

// A sequential policy: one net at a time, the candidates' features refreshed after each.
void RegionRouter::routeSequential(NetOrderPolicy& policy, MazeWorkspace& ws) {
  const RegionInfo region = info();
  std::vector<int32_t> pending;
  for (std::vector<NetCandidate> cands = unrouted(pending); !pending.empty(); cands = unrouted(pending)) {
    const int32_t k = policy.next(*this, region, cands);
    if (k < 0 || static_cast<size_t>(k) >= cands.size()) {
      throw PolicyOrderError("net-order policy '" + policy.name() + "' chose candidate " + std::to_string(k) +
                             ", outside 0.." + std::to_string(cands.size() - 1));
    }
    if (!isRouted(pending[k])) routeNet(pending[k], ws);  // the policy may have routed it itself
  }
}

void RegionRouter::routeAll(NetOrderPolicy& policy, MazeWorkspace& ws) {
  if (policy.sequential()) {
    routeSequential(policy, ws);
    return;
  }
  std::vector<int32_t> pending;
  const std::vector<NetCandidate> cands = unrouted(pending);
  if (pending.empty()) return;
  const RegionInfo info = this->info();
  const std::vector<int32_t> order = policy.orderRegion(*this, info, cands);
  if (!isPermutation(order, cands.size())) {
    throw PolicyOrderError("net-order policy '" + policy.name() + "' returned an order that is not a permutation of " +
                                std::to_string(cands.size()) + " candidates");
  }
  for (int32_t k : order) {
    if (!isRouted(pending[k])) routeNet(pending[k], ws);  // the policy may have routed some itself
  }
}

const RegionNetResult& RegionRouter::result(int32_t candidate) const { return impl_->nets[candidate].result; }

std::vector<Marker> RegionRouter::check() const {
  const Impl& im = *impl_;
  const Rect& box = im.task.region.box;
  const Dbu reach = 2 * im.ctx.halo;
  const Rect win{box.xlo - reach, box.ylo - reach, box.xhi + reach, box.yhi + reach};
  std::vector<DrcShape> shapes;
  im.ctx.fixedIndex.query(win, [&](int32_t id) { shapes.push_back(im.ctx.fixedShapes[id]); });
  std::unordered_map<int32_t, std::vector<const NetState*>> mine;  // a net may have parts
  for (const NetState& ns : im.nets) mine[ns.task.net].push_back(&ns);
  std::vector<NetShape> ns;
  auto add = [&](int32_t net, const NetRouting& r, ShapeOrigin origin) {
    ns.clear();
    netRoutingShapes(im.ctx.tech, im.ctx.design, r, ns);
    for (const NetShape& s : ns) {
      if (s.rect.overlaps(win)) shapes.push_back({s.layer, s.rect, net, origin});
    }
  };
  std::vector<int32_t> nets = im.ctx.netsNear(win);
  for (const auto& [n, st] : mine) nets.push_back(n);
  std::sort(nets.begin(), nets.end());
  nets.erase(std::unique(nets.begin(), nets.end()), nets.end());
  for (int32_t n : nets) {
    auto it = mine.find(n);
    if (it == mine.end()) {
      add(n, im.ctx.design.nets[n].routing, ShapeOrigin::Wire);
      continue;
    }
    const NetState& first = *it->second.front();
    add(n, first.task.ripup ? first.kept : im.ctx.design.nets[n].routing, ShapeOrigin::Wire);
    for (const NetState* part : it->second) add(n, part->result.added, ShapeOrigin::Wire);
  }
  DrcOptions o;
  o.skipFixedPairs = true;
  o.window = box;
  return checkShapes(im.ctx.tech, std::move(shapes), o);
}

void commitRegion(const Tech& tech, Design& design, const Rect& box, const RegionResult& result) {
  for (const RegionNetResult& nr : result.nets) {
    if (!nr.routed) continue;
    NetRouting& routing = design.nets[nr.net].routing;
    if (nr.ripup) routing = clipOutside(tech, design, routing, box, nullptr);
    routing.wires.insert(routing.wires.end(), nr.added.wires.begin(), nr.added.wires.end());
    routing.vias.insert(routing.vias.end(), nr.added.vias.begin(), nr.added.vias.end());
    routing.patches.insert(routing.patches.end(), nr.added.patches.begin(), nr.added.patches.end());
  }
}

RegionResult RegionRouter::finish() {
  RegionResult r;
  r.regionId = impl_->task.region.id;
  for (NetState& ns : impl_->nets) r.nets.push_back(std::move(ns.result));
  r.crossingChoices = std::move(impl_->choices);
  r.gridNodes = impl_->grid ? static_cast<int64_t>(impl_->grid->size()) : 0;
  r.mazeRounds = impl_->rounds;
  r.order = std::move(impl_->order);
  return r;
}

RegionResult routeRegion(const RouteContext& ctx, const RegionTask& task, const CrossingPlan* plan,
                         NetOrderPolicy& policy, MazeWorkspace& ws) {
  RegionRouter rr(ctx, task, plan);
  rr.prepare();
  rr.routeAll(policy, ws);
  if (task.repairRounds <= 0) return rr.finish();
  std::vector<Marker> markers = rr.check();
  RegionResult best = rr.finish();
  // Repair: rip up the region's nets named in its markers and reroute them
  // (in their first order) around everything else, with the markers found
  // so far as rising node costs; keep the round with the fewest markers.
  RegionRepairSeed seed;
  std::unordered_map<int32_t, std::vector<int32_t>> candidatesOf;  // net -> its candidates (a net may have parts)
  for (size_t i = 0; i < task.nets.size(); ++i) candidatesOf[task.nets[i].net].push_back(static_cast<int32_t>(i));
  std::vector<Marker> current = markers;
  RegionResult currentResult = best;
  size_t bestCount = markers.size();
  for (int round = 1; round <= task.repairRounds && !current.empty(); ++round) {
    seed.keep.assign(task.nets.size(), 1);
    bool any = false;
    for (const Marker& m : current) {
      for (int32_t n : {m.net1, m.net2}) {
        auto it = candidatesOf.find(n);
        if (it == candidatesOf.end()) continue;
        for (int32_t c : it->second) {
          if (!currentResult.nets[c].routed) continue;
          seed.keep[c] = 0;
          any = true;
        }
      }
      seed.markers.push_back({m.layer, m.box, task.repairPenalty * round});
    }
    if (!any) break;
    seed.previous = &currentResult;
    RegionRouter again(ctx, task, plan, &seed);
    again.prepare();
    for (int32_t c : currentResult.order) {
      if (!seed.keep[c]) again.routeNet(c, ws);
    }
    std::vector<Marker> next = again.check();
    RegionResult res = again.finish();
    // Keep the first order for the next round's reroutes.
    std::vector<int32_t> ord = currentResult.order;
    res.order = std::move(ord);
    res.gridNodes = std::max(res.gridNodes, currentResult.gridNodes);
    res.mazeRounds += currentResult.mazeRounds;
    res.repairRounds = round;
    currentResult = std::move(res);
    current = std::move(next);
    if (current.size() >= bestCount) break;  // no better: stop here (keeps the time bounded)
    bestCount = current.size();
    best = currentResult;
  }
  best.repairRounds = currentResult.repairRounds;
  return best;
}

}  // namespace xroute
