// The detailed-routing flow: iteration 0 routes every net region by region
// along its guides; each later iteration shifts the region boundaries, rips
// up the nets involved in design-rule markers inside each region and
// reroutes them with the markers as costs, until no marker is left or the
// iterations run out. Regions of one colour (never touching) run in
// parallel; results are committed in region order, so the outcome does not
// depend on the thread count.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "db/design.hpp"
#include "drc/drc.hpp"
#include "order/policy.hpp"
#include "region/route_context.hpp"
#include "route/maze.hpp"

namespace xroute {

// One iteration's region partition: regions of regionSize x regionSize GCells
// whose grid starts `offset` GCells before the first GCell.
struct ScheduleStep {
  int regionSize = 10;             // GCells per region side (C)
  int offset = 0;                  // GCells, 0 <= offset < regionSize
};

inline constexpr int kMaxIterations = 64;     // the most iterations one run may ask for
inline constexpr int kMaxRegionSize = 1000;   // GCells per region side at most (larger overflows int math)
inline constexpr int kMaxThreads = 1024;      // worker threads at most
inline constexpr int kMaxRepairRounds = 64;   // repair rounds per region at most

struct RouterSettings {
  // GCells per region side (C); 0 = 10, or more while most regions' grids stay within a node budget
  // (autoRegionSize, loop/regions.hpp): 15 on ispd18_test1, 16 on ispd19_test1, 10 on ispd19_test3.
  int regionSize = 0;
  // Iterations 0..iterations-1 at most (1..kMaxIterations); the flow stops at zero markers. 16 leaves room:
  // ispd19_test1 reaches zero in its iteration 8, ispd19_test3 in its iteration 7 (2026-11-27, 2 threads).
  int iterations = 16;
  int threads = 1;                 // worker threads for regions of one colour
  std::vector<ScheduleStep> schedule;  // per iteration, cycled; empty = regionSize with offsets 0, C/3, 2C/3, ...
  MazeCosts costs;                 // maze costs of iteration 0
  int64_t usePenaltyStep = 4000;   // added to costs.usePenalty at each later iteration
  int accessPointsPerPin = kAccessPointsPerPin;  // access points kept per pin
  // Cost units per node near a marker of the last iteration, times 1 + the marker's age (the checks in
  // a row before it that had it; counted when ripNeighboursOfPersistent).
  int64_t markerPenalty = 3000;
  int64_t historyPenalty = 1000;   // cost units per node near any earlier marker
  bool stopAtZero = true;          // stop when an iteration ends without markers
  // Check-and-reroute rounds inside each region before it is committed, in iterations after the
  // first (0..kMaxRepairRounds). 0 by default: on ispd18_test1 3 rounds end at 11 violations instead
  // of 13, on ispd19_test1 at 1,229 instead of 1,647, but ispd19_test1 takes 4.8x the time (2 threads).
  int repairRounds = 0;
  int firstRepairRounds = 0;       // the same in iteration 0 (0 measured best: later iterations mend as much, for a fraction of the time)
  int64_t repairPenalty = 3000;    // cost units per node near a region marker, times the repair round
  uint64_t searchSeed = 1;         // seeds the search of an iteration whose plan asks for one
  // A marker that survived its nets' reroute also rips up the other nets with metal near it
  // (farther the longer it lasts; an EndOfLine one of age 2+ also costs nodes farther out).
  bool ripNeighboursOfPersistent = true;
  // Once a check leaves lateSearchMarkers markers or fewer (and some), the next iterations order
  // their regions' nets by the victims search with lateSearchBudget trial routings per region
  // (IterationPlan::searchBudget), when the run's policy is the heuristic; 0 = never. Those regions
  // are few by then: on ispd19_test3 the search costs about 1 s an iteration (loop/README.md).
  int lateSearchMarkers = 50;
  int lateSearchBudget = 4;
  // After each iteration's routing, cut the routing of every net it rerouted back to what joins its pins
  // (loop/dangling.hpp): a rip-up whose terminals were joined beyond the box leaves ends that join
  // nothing.
  bool trimDangling = true;
  // After the first iteration, an iteration that changed at most this share of the nets is checked
  // again only where it changed (loop/incremental_check.hpp): the same markers as a whole check. 0:
  // every check is whole. On ispd19_test1 (2 threads) a partial check after 17% of the nets changed
  // cost about a whole one, after 37% 1.6 times one, after 8% 0.4.
  double partialCheckShare = 0.15;
  // A whole check of more shapes than this runs in bands of about this many (DrcOptions::bandShapes,
  // drc/design_check.hpp): the same markers, a fraction of the memory on a large design. 0: at once.
  int64_t checkBandShapes = kCheckBandShapes;
};

// What one iteration runs with, chosen before it starts: by the flow's rule (the settings' schedule,
// costs and repair rounds) or by an iteration planner that has seen the reports so far.
struct IterationPlan {
  int regionSize = 10;             // GCells per region side (1..kMaxRegionSize)
  int offset = 0;                  // GCells, 0 <= offset < regionSize
  int repairRounds = 0;            // check-and-reroute rounds inside each region (0..kMaxRepairRounds)
  MazeCosts costs;                 // the maze's costs (usePenalty: per shape of another net a step would violate)
  int64_t markerPenalty = 3000;    // cost units per node near a marker of the last iteration
  int64_t historyPenalty = 1000;   // what each marker this iteration leaves adds near it from then on
  bool stop = false;               // end the run instead of running this iteration
  // 0: the run's net-order policy orders each region's nets; 1..kMaxSearchBudget: the victims search
  // (order/search_policy.hpp) with this many trial routings per region does, in this iteration only.
  int searchBudget = 0;
};

// Wall seconds of an iteration's stages (they add up to about IterationReport::seconds).
struct StageSeconds {
  double setup = 0;                // regions, tasks and rip-ups made ready (incl. iteration 0's crossing plan)
  double route = 0;                // the regions' batches: pin access, grids, maze, in-region checks
  double commit = 0;               // the batches' routing written into the design
  double index = 0;                // the routed-shape index brought up to date after each colour
  double trim = 0;                 // rerouted nets' dangling routing cut back
  double check = 0;                // the whole design's rule check and the totals
};

struct IterationReport {
  int iteration = 0;
  int regionSize = 0;              // GCells per region side in this iteration
  int offset = 0;                  // GCells
  int regions = 0;                 // regions with work
  int netRoutes = 0;               // (net, region) pairs routed
  int unreached = 0;               // terminals the maze could not reach
  int64_t wirelength = 0;          // DBU, wires only
  int64_t vias = 0;
  std::array<int, kMarkerTypes> markersByType{};  // indexed by MarkerType
  int markers = 0;
  double seconds = 0;              // wall time of the iteration (routing + check)
  StageSeconds stages;             // where `seconds` went
  int64_t checkedShapes = 0;       // shapes the check after the iteration looked at (all, for a whole check)
  bool done = false;               // the check has run: markers, totals and seconds are final
  IterationPlan plan;              // what the iteration ran with (set with done)
};

// Asked before each iteration with the reports of the iterations done (oldest first) and the rule's
// plan for the next one; returns the plan to run, within the limits above (the bindings check the
// plans of a Python planner: bindings/settings_check.hpp). Empty: the rule's plan.
using IterationPlanner = std::function<IterationPlan(const std::vector<IterationReport>&, const IterationPlan&)>;

struct RouteOutcome {
  std::vector<IterationReport> iterations;
  std::vector<Marker> markers;     // of the final state
  MazeCosts costs;                 // the run's maze costs, designCosts applied (automatic values resolved)
};

// Called after every region batch: (iteration so far, regions done, regions with work).
using RouteProgress = std::function<void(const IterationReport&, int, int)>;

struct CrossingPlan;
struct RegionTask;
// Called in iteration 0 before each colour's regions are routed: (colour, the crossing plan with the
// choices of the colours before, that colour's region tasks); the design holds the routing of the
// colours before. What a replay of the first pass keeps (loop/first_pass.hpp).
using ColourHook = std::function<void(int, const CrossingPlan&, const std::vector<RegionTask>&)>;

// Routes every net of `design` (its Net::routing is replaced). With a planner, each iteration runs
// the plan it returns instead of the rule's.
RouteOutcome routeDesign(const Tech& tech, Design& design, const RouterSettings& settings, NetOrderPolicy& policy,
                         const RouteProgress& progress = {}, const ColourHook& beforeColour = {},
                         const IterationPlanner& planner = {});

// The rule's plan of `iteration`: the settings' schedule step (or the region size shifted by a
// third of a region each iteration), the iteration-0 costs plus usePenaltyStep per iteration, and
// the repair rounds of the first or the later iterations.
IterationPlan rulePlan(const RouterSettings& settings, int iteration);

// Wirelength (DBU, sum of wire lengths) and via count of the regular nets.
void routingTotals(const Design& design, int64_t& wirelength, int64_t& vias);

}  // namespace xroute
