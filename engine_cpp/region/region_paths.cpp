// Routing one candidate of a region: by the maze, or along a caller's node
// paths; either way applyPaths turns the paths into wires and vias, records
// the free crossings reached, repairs minimum area and marks the new metal.
#include "region/region_impl.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "region/patch_score.hpp"
#include "route/min_area_fix.hpp"

namespace xroute {

int32_t RegionRouter::Impl::nodeAt(Point p, int z) const {
  const int x = grid->xIndex(p.x), y = grid->yIndex(p.y);
  if (x < 0 || y < 0 || z < 0 || z >= grid->nz()) return -1;
  return grid->index(x, y, z);
}

NodeArray<uint8_t> RegionRouter::Impl::guideMask(int32_t net) const {
  const RegionGrid& g = *grid;
  const Design& d = ctx.design;
  NodeArray<uint8_t> mask(g.size(), 0);
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

void RegionRouter::Impl::addPathGeometry(int32_t net, const std::vector<int32_t>& path, NetRouting& out) {
  const RegionGrid& g = *grid;
  size_t i = 0;
  while (i + 1 < path.size()) {
    const int32_t u = path[i], v = path[i + 1];
    const int zu = g.zOf(u), zv = g.zOf(v);
    if (zu != zv) {
      const int zl = std::min(zu, zv);
      const int32_t lower = zu < zv ? u : v;
      const ViaId rule = ctx.netRules.via(net, zl);  // a NONDEFAULTRULE's via, else the default
      ViaId via = rule.valid() ? rule : ctx.vias.cuts[zl].via;
      auto it = apVia.find(lower);
      if (it != apVia.end() && g.accessNet(lower) == net) via = it->second;
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
    w.width = ctx.netRules.width(net, zu);  // a NONDEFAULTRULE's width (0: the layer's default)
    w.from = a;
    w.to = g.point(path[j]);
    // An end at one of the net's access points inside its pin stops there: the
    // pin holds it, and the usual half-width extension would only stick out of
    // the pin towards its neighbour (two stubs leaving facing pins of one cell
    // made line ends 100 apart where 120 is needed). Where the pin covers only a
    // part of the wire's width at the point, the end edge left bare meets the
    // pin at a concave corner: no line end either.
    const Dbu width = w.width > 0 ? w.width : ctx.tech.layer(w.layer).width;
    auto heldEnd = [&](int32_t node, int sign) {
      return (g.flags[node] & kAccess) && g.accessNet(node) == net && g.accessPin(node) >= 0 &&
             pinHoldsEnd(g.accessPin(node), w.layer, g.point(node), alongX, sign, width);
    };
    // (Not where the path turns on the layer: the corner's square needs the extensions.)
    const int fwd = (alongX ? w.to.x >= w.from.x : w.to.y >= w.from.y) ? 1 : -1;
    if ((i == 0 || g.zOf(path[i - 1]) != zu) && heldEnd(u, -fwd)) w.extFrom = 0;
    if ((j + 1 == path.size() || g.zOf(path[j + 1]) != zu) && heldEnd(path[j], fwd)) w.extTo = 0;
    out.wires.push_back(w);
    i = j;
  }
}

bool RegionRouter::Impl::pinHoldsEnd(int32_t pinRef, LayerId layer, Point at, bool alongX, int sign,
                                     Dbu width) const {
  const Dbu lo = width / 2, hi = width - width / 2;
  const Dbu reach = sign * lo;  // the default extension beyond `at`
  const Rect ext = alongX ? Rect{std::min(at.x, at.x + reach), at.y - lo, std::max(at.x, at.x + reach), at.y + hi}
                          : Rect{at.x - lo, std::min(at.y, at.y + reach), at.x + hi, std::max(at.y, at.y + reach)};
  std::vector<Rect> rects;
  pinRefRects(ctx.tech, ctx.design, pinRef, layer, rects);
  bool held = false;
  for (const Rect& r : rects) {
    if (r.xlo <= ext.xlo && ext.xhi <= r.xhi && r.ylo <= ext.ylo && ext.yhi <= r.yhi) return false;  // nothing to gain
    // The rect holds the point and reaches into the wire's body from it.
    if (!r.contains(at)) continue;
    held = held || (alongX ? (sign > 0 ? r.xlo < at.x : at.x < r.xhi) : (sign > 0 ? r.ylo < at.y : at.y < r.yhi));
  }
  return held;
}

void RegionRouter::Impl::markNewRouting(int32_t net, const NetRouting& added) {
  std::vector<NetShape> shapes;
  netRoutingShapes(ctx.tech, ctx.design, added, shapes);
  markShapes(ctx, net, shapes, grownBox(box(), ctx.halo), *grid, routedMetal);
}

MazeNet RegionRouter::Impl::mazeNet(const NetState& ns, std::vector<int32_t>& termOfSpec) const {
  const RegionGrid& g = *grid;
  MazeNet mn;
  mn.net = ns.task.net;
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t t = 0; t < ns.terms.size(); ++t) {
      const TermSpec& s = ns.terms[t];
      if (s.joined != (pass == 0)) continue;
      MazeTerminal mt;
      mt.joined = s.joined;
      mt.group = s.joined ? s.group : -1;
      std::vector<std::pair<int32_t, int64_t>> nodes;
      for (size_t k = 0; k < s.points.size(); ++k) {
        const int32_t v = nodeAt(s.points[k], s.zs[k]);
        if (v >= 0 && g.exists(v)) nodes.push_back({v, k < s.exitCost.size() ? s.exitCost[k] : 0});
      }
      for (size_t k = 0; k < s.touch.size(); ++k) {
        const int32_t v = nodeAt(s.touch[k], s.touchZs[k]);
        if (v >= 0 && g.exists(v)) nodes.push_back({v, 0});
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

// The net's access vias of another variant than the cut's default via: each pad that breaks a rule
// with another net's routed metal costs usePenalty at the access node (a via step pays the node
// costs of both its ends, so the landing carries nothing). The footprints of routed
// metal assume the default via's landing: on ispd19_test1 pin access chose VIA12_1C_H (wider than
// tall) at a pin, and its line end stayed 106 DBU from the next pin's access-via pad.
std::vector<std::pair<int32_t, int64_t>> RegionRouter::Impl::accessViaCosts(const NetState& ns) const {
  const RegionGrid& g = *grid;
  std::vector<std::pair<int32_t, int64_t>> out;
  for (const TermSpec& s : ns.terms) {
    if (s.pinRef < 0) continue;
    for (const AccessPoint* ap = ctx.access.begin(s.pinRef); ap != ctx.access.end(s.pinRef); ++ap) {
      if (!(ap->dirs & kAccessUp) || !ap->upVia.valid() || ap->z + 1 >= g.nz()) continue;
      if (ap->upVia == ctx.vias.cuts[ap->z].via) continue;
      const int32_t v = nodeAt(ap->at, ap->z);
      if (v < 0) continue;
      int conflicts = 0;  // pads that break a rule
      for (const ViaShape& sh : ctx.tech.vias[*ap->upVia].shapes) {
        const int z = ctx.tech.layer(sh.layer).routingIndex;
        if (z == ap->z || z == ap->z + 1)
          conflicts += breaksRoutedMetal(ctx, routedMetal, ns.task.net, z, sh.rect.translated(ap->at));
      }
      if (conflicts > 0) out.emplace_back(v, int64_t(conflicts) * task.costs.usePenalty);
    }
  }
  return out;
}

void RegionRouter::Impl::routeNet(int32_t index, MazeWorkspace& ws) {
  NetState& ns = nets[index];
  if (ns.routed) return;
  ns.routed = true;
  order.push_back(index);
  ns.result.routed = true;
  std::vector<int32_t> termOfSpec;
  MazeNet mn = mazeNet(ns, termOfSpec);
  if (mn.terminals.size() < 2) return;
  const NodeArray<uint8_t> mask = guideMask(ns.task.net);
  mn.inGuide = &mask;
  RuleCosts rule;
  if (ruleCosts(ns.task.net, rule)) {
    mn.ruleWire = &rule.wire;
    mn.ruleVia = &rule.via;
  }
  const std::vector<std::pair<int32_t, int64_t>> accessVia = accessViaCosts(ns);
  mn.accessVia = &accessVia;
  std::vector<std::vector<int32_t>> paths;
  ns.result.unreached = routeMaze(*grid, task.costs, mn, ws, paths);
  rounds += static_cast<int64_t>(paths.size());
  applyPaths(ns, mn, termOfSpec, std::move(paths));
}

// Turns a net's node paths into its routing: wires and vias, the free
// crossings they reach, the min-area fix, and the marks on the grid. The
// one way routing enters a region (the maze's and a caller's paths alike).
void RegionRouter::Impl::applyPaths(NetState& ns, const MazeNet& mn, const std::vector<int32_t>& termOfSpec,
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
  releaseLandings(ns);
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
  auto score = [&](int z, const Rect& r) { return patchScore(ctx, *grid, routedMetal, net, z, r); };
  fixMinArea(ctx.tech, ctx.design, ctx.tracks, box(), anchors, pinMetal, score, ns.result.added);
  markNewRouting(ns.task.net, ns.result.added);
  ns.paths = std::move(paths);
}

// The candidate's pins are joined: the landings above their access points
// that it holds alone are free for the nets after it (the one its via took is
// its routed metal now). Kept, they cost every later net the reserve penalty
// for passing on Metal2 above a routed pin's unused points.
void RegionRouter::Impl::releaseLandings(const NetState& ns) {
  RegionGrid& g = *grid;
  for (const TermSpec& s : ns.terms) {
    if (s.pinRef < 0) continue;
    for (const AccessPoint* ap = ctx.access.begin(s.pinRef); ap != ctx.access.end(s.pinRef); ++ap) {
      if (!(ap->dirs & kAccessUp) || ap->z + 1 >= g.nz()) continue;
      const int32_t above = nodeAt(ap->at, ap->z + 1);
      if (above >= 0 && g.reservedNet(above) == ns.task.net) g.flags[above] |= kReleased;
    }
  }
}

// A caller's node paths for net `index` (each step one maze edge), routed
// through applyPaths; unreached = terminals after the first (where the tree
// starts, as in the maze) that no path touches.
void RegionRouter::Impl::routeNetPaths(int32_t index, std::vector<std::vector<int32_t>> paths) {
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
  // As in the maze, the tree starts on the first terminal with nodes; a terminal is reached when a
  // path touches it or another terminal of its group (one conductor beyond the box).
  std::vector<uint8_t> hit(mn.terminals.size(), 0);
  std::vector<int32_t> groupsHit;
  bool first = true;
  for (size_t k = 0; k < mn.terminals.size(); ++k) {
    const MazeTerminal& t = mn.terminals[k];
    if (t.nodes.empty()) continue;
    hit[k] = first;
    first = false;
    for (const auto& p : paths)
      for (int32_t v : p) hit[k] = hit[k] || std::binary_search(t.nodes.begin(), t.nodes.end(), v);
    if (hit[k] && t.group >= 0) groupsHit.push_back(t.group);
  }
  int unreached = 0;
  for (size_t k = 0; k < mn.terminals.size(); ++k) {
    const MazeTerminal& t = mn.terminals[k];
    const bool viaGroup = t.group >= 0 && std::find(groupsHit.begin(), groupsHit.end(), t.group) != groupsHit.end();
    if (!t.nodes.empty() && !hit[k] && !viaGroup) ++unreached;
  }
  ns.result.unreached = mn.terminals.size() < 2 ? 0 : unreached;
  if (paths.empty() || mn.terminals.size() < 2) return;
  rounds += static_cast<int64_t>(paths.size());
  applyPaths(ns, mn, termOfSpec, std::move(paths));
}

void RegionRouter::Impl::moves(int32_t index, int32_t node, std::array<MazeMove, kMoveCount>& out) {
  NetState& ns = nets[index];
  if (node < 0 || static_cast<size_t>(node) >= grid->size() || !grid->exists(node))
    throw std::invalid_argument("node " + std::to_string(node) + " is not a node of the region grid");
  if (ns.guide.empty()) ns.guide = guideMask(ns.task.net);
  std::vector<int32_t> termOfSpec;
  MazeNet mn = mazeNet(ns, termOfSpec);
  mn.inGuide = &ns.guide;
  if (ns.ruleAt != order.size()) {  // the costs change as nets are routed
    ns.hasRule = ruleCosts(ns.task.net, ns.rule);
    ns.accessVia = accessViaCosts(ns);
    ns.ruleAt = order.size();
  }
  if (ns.hasRule) {
    mn.ruleWire = &ns.rule.wire;
    mn.ruleVia = &ns.rule.via;
  }
  mn.accessVia = &ns.accessVia;
  mazeMoves(*grid, task.costs, mn, node, out);
}

}  // namespace xroute
