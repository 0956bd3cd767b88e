#include "loop/router.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <unordered_map>

#include "grid/node_array.hpp"
#include "loop/crossings.hpp"
#include "loop/dangling.hpp"
#include "loop/incremental_check.hpp"
#include "loop/regions.hpp"
#include "order/search_policy.hpp"
#include "region/region_router.hpp"
#include "region/route_context.hpp"

namespace xroute {

void routingTotals(const Design& design, int64_t& wirelength, int64_t& vias) {
  wirelength = 0;
  vias = 0;
  for (const Net& n : design.nets) {
    wirelength += n.routing.wirelength();
    vias += static_cast<int64_t>(n.routing.vias.size());
  }
}

namespace {

using Clock = std::chrono::steady_clock;

// Seconds since `mark`, and `mark` moved to now.
double lap(Clock::time_point& mark) {
  const Clock::time_point now = Clock::now();
  const double s = std::chrono::duration<double>(now - mark).count();
  mark = now;
  return s;
}

// The partition of `iteration`: the schedule's step (cycled), or the default
// region size shifted by a third of a region each iteration.
ScheduleStep stepFor(const RouterSettings& s, int iteration) {
  if (!s.schedule.empty()) {
    ScheduleStep step = s.schedule[iteration % s.schedule.size()];
    step.regionSize = std::max(1, step.regionSize);
    step.offset = ((step.offset % step.regionSize) + step.regionSize) % step.regionSize;
    return step;
  }
  const int c = std::max(1, s.regionSize);
  return ScheduleStep{c, ((iteration % 3) * c) / 3};
}

// Runs a whole region: prepare, route in the policy's order, the task's repair rounds, finish.
RegionResult routeRegion(const RouteContext& ctx, const RegionTask& task, const CrossingPlan* plan,
                         NetOrderPolicy& policy, MazeWorkspace& ws) {
  RegionRouter rr(ctx, task, plan);
  rr.prepare();
  routeInOrder(rr, policy, ws);
  return rr.finishWithRepairs(ws);
}

// The widest neighbourhood (in pitches of the marker's layer) a persistent marker rips up.
constexpr int kMaxReachPitches = 8;

class Flow {
 public:
  Flow(const Tech& tech, Design& design, const RouterSettings& s, NetOrderPolicy& policy, const RouteProgress& progress,
       const ColourHook& beforeColour, const IterationPlanner& planner)
      : tech_(tech), design_(design), s_(s), policy_(policy), progress_(progress), beforeColour_(beforeColour),
        planner_(planner), ctx_(tech, design, s.threads, s.accessPointsPerPin), check_(ctx_, checkOptions()) {
    if (s_.regionSize <= 0)
      s_.regionSize = autoRegionSize(ctx_.gcells, ctx_.tracks, ctx_.access.points, kMaxRegionSize);
    s_.costs = designCosts(s_.costs, ctx_);
  }

  // The design's routing is empty (routeDesign cleared it before the context was made).
  RouteOutcome run() {
    RouteOutcome out;
    out.costs = s_.costs;
    const int iterations = std::clamp(s_.iterations, 1, kMaxIterations);
    for (int it = 0; it < iterations; ++it) {
      IterationPlan rule = rulePlan(s_, it);
      if (lateSearch(it)) rule.searchBudget = std::clamp(s_.lateSearchBudget, 1, kMaxSearchBudget);
      plan_ = planner_ ? planner_(out.iterations, rule) : rule;  // the planner checks its plans
      if (plan_.stop && it > 0) break;  // iteration 0 always runs: it routes every net
      search_.reset();
      if (plan_.searchBudget > 0) {
        SearchSettings search;
        search.budget = plan_.searchBudget;
        search.seed = s_.searchSeed;
        search_ = makeBuiltinPolicy("victims", search);
      }
      const auto t0 = Clock::now();
      IterationReport rep;
      rep.iteration = it;
      rep.regionSize = plan_.regionSize;
      rep.offset = plan_.offset;
      runIteration(it, rep);
      auto mark = Clock::now();
      if (s_.trimDangling) trimRerouted();
      rep.stages.trim = lap(mark);
      prevMarkers_ = std::move(markers_);
      prevAges_ = std::move(ages_);
      markers_ = it == 0 || s_.partialCheckShare <= 0 || wholeCheck_ ? check_.full() : check_.update(s_.partialCheckShare);
      wholeCheck_ = false;
      rep.checkedShapes = check_.lastShapes();
      ages_.assign(markers_.size(), 0);
      if (s_.ripNeighboursOfPersistent)
        for (size_t i = 0; i < markers_.size(); ++i) ages_[i] = age(markers_[i]);
      for (const Marker& m : markers_) ++rep.markersByType[static_cast<int>(m.type)];
      rep.markers = static_cast<int>(markers_.size());
      routingTotals(design_, rep.wirelength, rep.vias);
      rep.stages.check = lap(mark);
      rep.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      rep.done = true;
      rep.plan = plan_;
      out.iterations.push_back(rep);
      if (progress_) progress_(rep, rep.regions, rep.regions);
      for (const Marker& m : markers_) history_.push_back({m.layer, m.box, plan_.historyPenalty});
      if (markers_.empty() && s_.stopAtZero) break;
    }
    out.markers = markers_;
    return out;
  }

 private:
  // The whole-design check's options: the run's threads check layers side by side.
  DrcOptions checkOptions() const {
    DrcOptions o = ctx_.drcOptions();
    o.threads = s_.threads;
    o.bandShapes = s_.checkBandShapes;
    return o;
  }

  // Whether iteration `it` runs the late search (RouterSettings::lateSearchBudget).
  bool lateSearch(int it) const {
    return it > 0 && s_.lateSearchBudget > 0 && !markers_.empty() &&
           static_cast<int>(markers_.size()) <= s_.lateSearchMarkers && policy_.builtinHeuristic();
  }

  // How many checks in a row before this one had a marker touching m on m's layer or between the
  // same two nets (an access-via conflict turns from a Metal1 EndOfLine into a Via1 CutSpacing and
  // back as its nets take turns); the previous check's markers carry their own ages.
  int age(const Marker& m) const {
    int best = 0;
    for (size_t j = 0; j < prevMarkers_.size(); ++j) {
      const Marker& p = prevMarkers_[j];
      const bool sameNets = m.net2 >= 0 && std::minmax(p.net1, p.net2) == std::minmax(m.net1, m.net2);
      if ((p.layer == m.layer || sameNets) && p.box.overlaps(m.box))
        best = std::max(best, 1 + prevAges_[j]);
    }
    return best;
  }

  std::vector<MarkerCost> markersNear(const Rect& box) const {
    std::vector<MarkerCost> out;
    const Rect win{box.xlo - ctx_.halo, box.ylo - ctx_.halo, box.xhi + ctx_.halo, box.yhi + ctx_.halo};
    // A marker costs more the longer it lasts. One that two reroutes in a row left (age 2) also
    // costs around the shapes that cause it beyond the pitch (markerReach: a via whose landing pad
    // reaches the box, the line end in front of an EndOfLine marker's box).
    for (size_t i = 0; i < markers_.size(); ++i) {
      const Marker& m = markers_[i];
      const Dbu reach = ages_[i] >= 2 ? markerReach(ctx_, m) : 0;
      if (m.box.overlaps(win)) out.push_back({m.layer, m.box, plan_.markerPenalty * (1 + ages_[i]), reach});
    }
    for (const MarkerCost& h : history_) {
      if (h.box.overlaps(win)) out.push_back(h);
    }
    return out;
  }

  // Iteration 0 tasks of one region from the crossing plan.
  RegionTask initialTask(const Region& r, const CrossingPlan& plan, int it) const {
    RegionTask t;
    t.region = r;
    t.iteration = it;
    t.costs = plan_.costs;
    t.repairRounds = plan_.repairRounds;
    t.repairPenalty = s_.repairPenalty;
    for (const NetPart& part : plan.regionParts[r.id]) {
      RegionNetTask nt;
      nt.net = part.net;
      nt.pins = part.pins;
      nt.crossings = part.crossings;
      t.nets.push_back(std::move(nt));
    }
    return t;
  }

  // Later iterations: nets in markers touching the region are ripped up.
  RegionTask repairTask(const Region& r, int it) const {
    RegionTask t;
    t.region = r;
    t.iteration = it;
    t.costs = plan_.costs;
    t.repairRounds = plan_.repairRounds;
    t.repairPenalty = s_.repairPenalty;
    std::vector<int32_t> dirty;
    const int32_t nNets = static_cast<int32_t>(design_.nets.size());
    std::vector<NetShape> shapes;
    for (size_t i = 0; i < markers_.size(); ++i) {
      const Marker& m = markers_[i];
      if (!m.box.overlaps(r.box)) continue;
      if (m.net1 >= 0 && m.net1 < nNets) dirty.push_back(m.net1);
      if (m.net2 >= 0 && m.net2 < nNets) dirty.push_back(m.net2);
      // A piece below the minimum area that no patch could fit beside stays
      // short while its neighbours stay: they go too, so that the piece's
      // net can take the room and they come back around it (the marker's
      // cost keeps them off it). So do the neighbours of a marker that
      // survived the last reroute of its own nets (one of the last check
      // but one, on its layer, touching it): ripping up only its two nets
      // puts them back in the same spot. Neighbours: other nets with
      // metal on the layer (on a cut layer: on the layer below) within two
      // pitches of the marker per earlier check in a row that had it (two
      // for a fresh MinArea marker), kMaxReachPitches at most.
      if (m.type != MarkerType::MinArea && ages_[i] == 0) continue;
      const Layer& l = ctx_.tech.layer(m.layer);
      const LayerId below = l.routingIndex >= 0 || *m.layer == 0 ? m.layer : LayerId(*m.layer - 1);
      const Layer& pl = ctx_.tech.layer(below);
      const int pitches = std::min(kMaxReachPitches, 2 * std::max(1, ages_[i]));
      const Dbu reach = pitches * std::max(pl.pitchX, pl.pitchY);
      const Rect near{m.box.xlo - reach, m.box.ylo - reach, m.box.xhi + reach, m.box.yhi + reach};
      for (int32_t n : ctx_.netsNear(near)) {
        if (n == m.net1 || n == m.net2) continue;
        shapes.clear();
        netRoutingShapes(ctx_.tech, design_, design_.nets[n].routing, shapes);
        for (const NetShape& sh : shapes) {
          if ((sh.layer == m.layer || (l.routingIndex < 0 && sh.layer == below)) && sh.rect.overlaps(near)) {
            dirty.push_back(n);
            break;
          }
        }
      }
    }
    std::sort(dirty.begin(), dirty.end());
    dirty.erase(std::unique(dirty.begin(), dirty.end()), dirty.end());
    for (int32_t net : dirty) {
      RegionNetTask nt;
      nt.net = net;
      nt.ripup = true;
      for (int32_t pin = design_.netPinStart[net]; pin < design_.netPinStart[net + 1]; ++pin) {
        for (const AccessPoint* ap = ctx_.access.begin(pin); ap != ctx_.access.end(pin); ++ap) {
          if (r.box.contains(ap->at)) {
            nt.pins.push_back(pin);
            break;
          }
        }
      }
      t.nets.push_back(std::move(nt));
    }
    if (!t.nets.empty()) t.markers = markersNear(r.box);
    return t;
  }

  // Regions that will have work in this iteration, known before any is routed (for progress): in
  // iteration 0 those with a part of a net, later those a marker with a net touches (repairTask's
  // rip-up starts from exactly those markers).
  int regionsWithWork(int it, const std::vector<Region>& regions, const CrossingPlan& plan) const {
    const int32_t nNets = static_cast<int32_t>(design_.nets.size());
    auto valid = [nNets](int32_t n) { return n >= 0 && n < nNets; };
    int count = 0;
    for (const Region& r : regions) {
      if (it == 0) {
        count += !plan.regionParts[r.id].empty();
        continue;
      }
      count += std::any_of(markers_.begin(), markers_.end(), [&](const Marker& m) {
        return m.box.overlaps(r.box) && (valid(m.net1) || valid(m.net2));
      });
    }
    return count;
  }

  void runIteration(int it, IterationReport& rep) {
    auto mark = Clock::now();
    const std::vector<Region> regions = partitionRegions(ctx_.gcells, rep.regionSize, rep.offset);
    CrossingPlan plan;
    if (it == 0) plan = planCrossings(ctx_, regions, rep.regionSize, rep.offset);
    const int total = progress_ ? regionsWithWork(it, regions, plan) : 0;
    for (int color = 0; color < 4; ++color) {
      std::vector<RegionTask> tasks;
      for (const Region& r : regions) {
        if (r.color != color) continue;
        RegionTask t = it == 0 ? initialTask(r, plan, it) : repairTask(r, it);
        if (!t.nets.empty()) tasks.push_back(std::move(t));
      }
      if (it > 0) markReroutedElsewhere(tasks);
      if (it > 0 && s_.partialCheckShare > 0)
        for (const RegionTask& t : tasks)
          for (const RegionNetTask& nt : t.nets) check_.remember(nt.net);
      if (it == 0 && beforeColour_) beforeColour_(color, plan, tasks);
      rep.stages.setup += lap(mark);
      std::vector<RegionResult> results = runBatch(tasks, it == 0 ? &plan : nullptr);
      rep.stages.route += lap(mark);
      for (size_t i = 0; i < results.size(); ++i) commit(tasks[i], results[i], plan, rep);
      rep.regions += static_cast<int>(tasks.size());
      rep.stages.commit += lap(mark);
      // Iteration 0 routes every net: the index is built again; later only the committed nets move.
      if (it == 0) {
        ctx_.rebuildRoutedIndex();
      } else {
        std::vector<int32_t> nets;
        for (const RegionResult& r : results)
          for (const RegionNetResult& nr : r.nets) nets.push_back(nr.net);
        std::sort(nets.begin(), nets.end());
        nets.erase(std::unique(nets.begin(), nets.end()), nets.end());
        ctx_.updateRoutedIndex(nets);
      }
#ifdef __GLIBC__
      malloc_trim(0);
#endif
      rep.stages.index += lap(mark);
      if (progress_) progress_(rep, rep.regions, total);
      mark = Clock::now();
    }
  }

  // Routing that joins nothing (loop/dangling.hpp) goes before the check. Only the nets this
  // iteration rerouted can have any: the others were cut back when they were last rerouted.
  void trimRerouted() {
    std::vector<int32_t> trimmed;
    for (int32_t n = 0; n < static_cast<int32_t>(rerouted_.size()); ++n) {
      if (!rerouted_[n]) continue;
      rerouted_[n] = 0;
      if (trimDangling(tech_, design_, NetId(n)).any()) trimmed.push_back(n);
    }
    ctx_.updateRoutedIndex(trimmed);
  }

  // Each ripped-up net of a colour's tasks learns the boxes of the other tasks that reroute it too.
  static void markReroutedElsewhere(std::vector<RegionTask>& tasks) {
    std::unordered_map<int32_t, std::vector<size_t>> where;
    for (size_t i = 0; i < tasks.size(); ++i)
      for (const RegionNetTask& nt : tasks[i].nets)
        if (nt.ripup) where[nt.net].push_back(i);
    for (size_t i = 0; i < tasks.size(); ++i) {
      for (RegionNetTask& nt : tasks[i].nets) {
        if (!nt.ripup) continue;
        for (size_t j : where[nt.net])
          if (j != i) nt.reroutedElsewhere.push_back(tasks[j].region.box);
      }
    }
  }

  std::vector<RegionResult> runBatch(const std::vector<RegionTask>& tasks, const CrossingPlan* plan) {
    const BlockReuse reuse;  // the regions' arrays reuse each other's pages; all handed back at the end
    std::vector<RegionResult> results(tasks.size());
    const int workers = std::max(1, std::min<int>(s_.threads, static_cast<int>(tasks.size())));
    // The threads take the regions with the most terminals first, so that a big region does not
    // start last and keep one thread busy alone at the batch's end. The results do not depend on
    // the order: a colour's regions never touch, and they are committed in region order.
    std::vector<size_t> order(tasks.size());
    std::vector<size_t> weight(tasks.size(), 0);
    for (size_t i = 0; i < tasks.size(); ++i) {
      order[i] = i;
      for (const RegionNetTask& nt : tasks[i].nets) weight[i] += 1 + nt.pins.size() + nt.crossings.size();
    }
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return weight[a] > weight[b]; });
    std::atomic<size_t> next{0};
    std::exception_ptr error;
    std::mutex errorMutex;
    auto work = [&]() {
      MazeWorkspace ws;
      while (true) {
        const size_t k = next.fetch_add(1);
        if (k >= tasks.size()) return;
        const size_t i = order[k];
        try {
          results[i] = routeRegion(ctx_, tasks[i], plan, search_ ? *search_ : policy_, ws);
        } catch (...) {
          std::lock_guard<std::mutex> lock(errorMutex);
          if (!error) error = std::current_exception();
          next = tasks.size();
          return;
        }
      }
    };
    if (workers == 1) {
      work();
    } else {
      std::vector<std::thread> pool;
      for (int w = 0; w < workers; ++w) pool.emplace_back(work);
      for (std::thread& t : pool) t.join();
    }
    if (error) std::rethrow_exception(error);
    return results;
  }

  void commit(const RegionTask& task, const RegionResult& res, CrossingPlan& plan, IterationReport& rep) {
    commitRegion(tech_, design_, task.region.box, res);
    for (const RegionNetResult& nr : res.nets) {
      rerouted_[nr.net] = 1;
      if (!check_.remembered(nr.net)) wholeCheck_ = true;  // changed unseen: the next check is whole
      if (!nr.routed) continue;
      ++rep.netRoutes;
      rep.unreached += nr.unreached;
    }
    for (const CrossingChoice& c : res.crossingChoices) {
      Crossing& cr = plan.crossings[c.crossing];
      if (cr.chosen) continue;
      cr.chosen = true;
      cr.at = c.at;
      cr.z = c.z;
    }
  }

  const Tech& tech_;
  Design& design_;
  RouterSettings s_;  // regionSize 0 and the out-of-guide factor resolved for the design
  NetOrderPolicy& policy_;
  const RouteProgress& progress_;
  const ColourHook& beforeColour_;
  const IterationPlanner& planner_;
  IterationPlan plan_;  // the running iteration's
  std::unique_ptr<NetOrderPolicy> search_;  // the running iteration's search, when its plan asks for one
  RouteContext ctx_;
  IncrementalCheck check_;  // the check after each iteration
  bool wholeCheck_ = false;  // a net changed that check_ was not told of
  std::vector<Marker> markers_;
  std::vector<Marker> prevMarkers_;  // the check before markers_'s
  std::vector<int> ages_;            // per marker of markers_: age()
  std::vector<int> prevAges_;        // per marker of prevMarkers_
  std::vector<MarkerCost> history_;
  std::vector<uint8_t> rerouted_ = std::vector<uint8_t>(design_.nets.size(), 0);  // per net, this iteration
};

}  // namespace

IterationPlan rulePlan(const RouterSettings& s, int iteration) {
  const ScheduleStep step = stepFor(s, iteration);
  IterationPlan p;
  p.regionSize = step.regionSize;
  p.offset = step.offset;
  p.repairRounds = iteration == 0 ? s.firstRepairRounds : s.repairRounds;
  p.costs = s.costs;
  p.costs.usePenalty += s.usePenaltyStep * iteration;
  p.markerPenalty = s.markerPenalty;
  p.historyPenalty = s.historyPenalty;
  return p;
}

RouteOutcome routeDesign(const Tech& tech, Design& design, const RouterSettings& settings, NetOrderPolicy& policy,
                         const RouteProgress& progress, const ColourHook& beforeColour,
                         const IterationPlanner& planner) {
  // The routing is replaced: cleared before the context is made, whose pin access judges IO pins
  // (and access vias among the neighbours) against every shape of the design. Routing left from an
  // earlier run, or read from the DEF, gave a second route of the same design other access points.
  for (Net& n : design.nets) n.routing = NetRouting{};
  RouteOutcome out = Flow(tech, design, settings, policy, progress, beforeColour, planner).run();
#ifdef __GLIBC__
  // The flow's context and checks are freed: hand their memory back before the caller writes the
  // routed DEF and checks it again (on the 8x8 tiles of ispd18_test1, that check is the peak).
  malloc_trim(0);
#endif
  return out;
}

}  // namespace xroute
