// Search as a net-order policy: a region's order chosen by routing trial
// orders on copies of the region (RegionRouter::clone) and scoring each by
// the region's cost. Deterministic: a region's trials use only its own task,
// so the routed result does not depend on the thread count.
//   rollout    - one-step lookahead, one net at a time: the unrouted nets that
//                the cheapest trial's markers name are each tried as the next
//                net, the rest finished in heuristic order; the cheapest first
//                choice is committed (no marker left to mend, or the budget
//                spent: the rest in heuristic order).
//   victims    - the nets the markers of the trials so far leave in violation
//                (the victims: of a two-net marker the net routed later, of a
//                one-net marker its net) routed first, the rest after them,
//                both in heuristic rank, until a trial names no new victim;
//                the budget's other trials route the victims first in seeded
//                random orders.
//   best-of-K  - the heuristic order plus K-1 seeded random orders.
// All count the heuristic's own order among their trials and keep the
// cheapest, so a region never ends costlier than the heuristic's routing.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <vector>

#include "drc/drc.hpp"
#include "order/policy.hpp"

namespace xroute {

class RegionRouter;

// The XRoute paper's cost of a region's routing: wirelength_um * wirelength + via * vias +
// violation * markers (new routing of the region's nets; markers from RegionRouter::check()).
struct RegionCostWeights {
  double wirelength = 0.5;  // per um of new wire
  double via = 4;           // per new via
  double violation = 500;   // per design-rule marker inside the region
};

inline constexpr int kMaxSearchBudget = 1024;  // trial routings per region at most

struct SearchSettings {
  // Trial routings per region: each routes the region's unrouted nets to the end in one order
  // and checks it (rollout, victims: at most this many; best-of-K: K). 1 = the heuristic alone.
  // Default 4: rollout's first pass (2 threads, loaded machine) took 3.6x the heuristic's time on
  // ispd18_test1 and 4.8x on ispd19_test1 (experiments/net_order/LOG.md).
  int budget = 4;
  // Rollout: candidates tried as the next net at each step, the first by heuristic rank
  // (0 = all of them); a smaller width spreads the budget over more steps.
  int width = 0;
  uint64_t seed = 1;        // best-of-K: seeds the random orders (with iteration, region and trial)
  RegionCostWeights weights;
};

// The cost of the region's routing as it is now (runs the region's rule check).
double regionCost(const RegionRouter& router, const RegionCostWeights& weights);
// The same with the check's markers given.
double regionCost(const RegionRouter& router, const RegionCostWeights& weights, const std::vector<Marker>& markers);

std::unique_ptr<NetOrderPolicy> makeRolloutPolicy(const SearchSettings& settings);
std::unique_ptr<NetOrderPolicy> makeBestOfPolicy(int k, const SearchSettings& settings);

// A built-in policy by name: heuristic, random (settings.seed), rollout, victims, bestof (K =
// settings.budget) or best-of-K. Throws std::invalid_argument (one line) for another name or a
// budget/K outside 1..kMaxSearchBudget.
std::unique_ptr<NetOrderPolicy> makeBuiltinPolicy(const std::string& name, const SearchSettings& settings);

}  // namespace xroute
