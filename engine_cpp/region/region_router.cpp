// RegionRouter's public steps over its Impl (region_impl.hpp), the
// region's design-rule check, commit, and its repair rounds.
#include "region/region_router.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "region/region_impl.hpp"

namespace xroute {

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
    const int ndr = net >= 0 && size_t(net) < im.ctx.design.nets.size() ? im.ctx.design.nets[net].ndr : -1;
    netRoutingShapes(im.ctx.tech, im.ctx.design, r, ns, ndr);
    for (const NetShape& s : ns) {
      if (s.rect.overlaps(win)) shapes.push_back({s.layer, s.rect, net, origin, s.taper});
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
  DrcOptions o = im.ctx.drcOptions();
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

RegionResult RegionRouter::finishWithRepairs(MazeWorkspace& ws) {
  const RouteContext& ctx = impl_->ctx;
  const RegionTask& task = impl_->task;
  const CrossingPlan* plan = impl_->plan;
  if (task.repairRounds <= 0) return finish();
  std::vector<Marker> markers = check();
  RegionResult best = finish();
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
